// The lighting report as one JSON document: the solve's part (radiosity/pipeline/
// report_json.h) and the host's (what it read and wrote, the grids' results, the views'
// pictures, the luminaires, the designer's checks, the light scenes). `dynrad solve
// --report` writes it; the HTML and PDF reports, from the command line and from the C
// ABI (dynrad_result_write_report), are drawn from it.
#pragma once

#include "plugin/report/view_output.h"
#include "radiosity/pipeline/pipeline.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dynrad::report {

// What the host adds to the solve's part.
struct ReportHost {
  std::string version;  // dynrad's
  std::string input;    // the model or scene file (or what the host calls its arrays)
  std::string output;   // the lit mesh written, or what holds it
  nlohmann::json grids = nlohmann::json::array();   // write_grid_results()' answer
  nlohmann::json scenes = nlohmann::json::array();  // light_scene_results()' answer; empty: none
  std::vector<ViewPictures> pictures;               // write_views()' answer
};

// The document. The designer's checks are added where the solve built the lit scene
// from a scene file (SolvedScene::lit, SceneRequest::path).
nlohmann::json report_document(const rad::PreparedScene& prepared, const rad::SolvedScene& solved, double exposure,
                               const ReportHost& host);

}  // namespace dynrad::report
