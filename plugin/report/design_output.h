// The lighting designer's checks of a lit scene as sections of the report (JSON, then
// HTML and PDF): the project's title block, EN 12464-1 per room (the grids with
// targets), UGR per observer, EN 1838 emergency routes and open areas. Shared by `solve`
// and `grid`.
#pragma once

#include "radiosity/design/light_scenes.h"
#include "radiosity/analysis/grid.h"
#include "radiosity/analysis/lit_scene.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dynrad::report {

// Reads every section the checks need from the scene file, so that bad input stops the
// run before any work (InputError naming the file and the entry). True when it declares
// observers or emergency areas (checks that need the lit scene even without grids).
bool check_design_inputs(const std::string& scene_path);

// Adds "project", "rooms", "observers" and "emergency" to `report` (each only when the
// scene declares what it needs), computed from `scene` and the gathered `grids`, and
// logs each verdict.
void add_design_checks(nlohmann::json& report, const std::string& scene_path, const rad::LitScene& scene,
                       const std::vector<rad::GridResult>& grids);

// The report's "scenes": every grid in every light scene, from `channelled`, the grids
// gathered from a solve whose groups travel in channels of their own (radiosity/design/
// light_scenes.h); each verdict logged.
nlohmann::json light_scene_results(const std::vector<rad::LightScene>& scenes, const rad::ChannelPlan& plan,
                                   const std::vector<rad::GridResult>& channelled);

// A luminaire's entry in the report: name, kind, flux, place, aim, description, and the
// schedule's facts (file, group, watts, maintenance factor, emergency share).
nlohmann::json luminaire_json(const rad::Luminaire& l);

}  // namespace dynrad::report
