// The solve's part of the JSON report (`dynrad solve --report`, the C ABI's
// dynrad_result_report_json): the method, the settings the model chose, what the solve
// did and why it stopped, its energy balance and estimated error. Hosts add what is
// theirs (files written, views, the designer's checks). Every field: docs/report.md.
#pragma once

#include "radiosity/pipeline/pipeline.h"

#include <nlohmann/json.hpp>

namespace dynrad::rad {

// `exposure`: the display exposure the host used (0: none).
nlohmann::json solve_report_json(const PreparedScene& prepared, const SolvedScene& solved, double exposure);

// Per grid of `solved`: name, points, masked, Eavg, Emin, Emax, U0 (lx, or W/m^2 in
// radiometric solves), and the daylight factors when the sky is the only source.
nlohmann::json grid_summary_json(const SolvedScene& solved);

}  // namespace dynrad::rad
