// The lighting report of a C ABI solve (dynrad_result_write_report): the same HTML page
// `dynrad solve --html` writes, through the report library (plugin/report/).
#pragma once

#include "radiosity/pipeline/pipeline.h"

#include <nlohmann/json.hpp>

#include <string>

namespace dynrad::capi {

// What a report is made from: the solve's scene and result, kept by the dynrad_result.
struct ReportInputs {
  const rad::PreparedScene* prepared = nullptr;
  const rad::SolvedScene* solved = nullptr;
  double exposure = 0;      // of the views' true-colour pictures
  std::string input;        // the scene file, or "scene arrays"
  std::string version;      // dynrad's
};

// Writes the HTML report at `html` (any extension; usually .html) and, beside it and named
// after it as the command line names them after its output (REPORT_grid_NAME.csv and
// .png, REPORT_grids.json, REPORT_view_NAME.png), the grids' files and the views'
// pictures that the page embeds. Views and the designer's checks need the lit scene,
// which scene files have; a scene made from arrays gets the solve's facts only. Every
// path is checked before anything is written (OutputError naming it).
void write_report(const std::string& html, const ReportInputs& inputs);

}  // namespace dynrad::capi
