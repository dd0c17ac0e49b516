// Calculation grids' results as files: PREFIX_grids.json (per grid: Eavg, Emin, Emax,
// U0, Emin/Emax, count, ...), PREFIX_grid_NAME.csv (per point) and PREFIX_grid_NAME.png
// (a false-colour plan), shared by `solve` and `grid`.
#pragma once

#include "radiosity/analysis/grid.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dynrad::report {

// Each file the grids will write can be written (OutputError otherwise), before any work.
void check_grid_outputs(const std::string& prefix, const std::vector<rad::GridSpec>& grids);

// Writes each gathered grid's files and PREFIX_grids.json; returns the per-grid figures
// (also logged). `input` names the model in the JSON; `photometric`: lx, else W/m2.
nlohmann::json write_grid_results(const std::string& prefix, const std::string& input,
                                  const std::vector<rad::GridResult>& grids, bool photometric);

// A grid's targets as the reports show them: {"Eavg": E, "U0": u}, either or both, or {}.
nlohmann::json grid_target_json(const rad::GridSpec& g);

}  // namespace dynrad::report
