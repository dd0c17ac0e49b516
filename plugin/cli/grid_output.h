// Calculation grids' results as files: PREFIX_grids.json (per grid: Eavg, Emin, Emax,
// U0, Emin/Emax, count, ...), PREFIX_grid_NAME.csv (per point) and PREFIX_grid_NAME.png
// (a false-colour plan), shared by `solve` and `grid`.
#pragma once

#include "radiosity/grid.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dynrad::cli {

// Each file the grids will write can be written (OutputError otherwise), before any work.
void check_grid_outputs(const std::string& prefix, const std::vector<rad::GridSpec>& grids);

// Gathers every grid, writes its files and PREFIX_grids.json; returns the per-grid
// figures (also logged). `input` names the model in the JSON. `gathered`, when given,
// receives each grid's result (for the room checks).
nlohmann::json write_grid_results(const std::string& prefix, const std::string& input,
                                  const std::vector<rad::GridSpec>& grids, const rad::LitScene& scene,
                                  std::vector<rad::GridResult>* gathered = nullptr);

}  // namespace dynrad::cli
