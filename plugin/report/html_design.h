// The designer's checks (plugin/report/design_output.h) as sections of the HTML report:
// EN 12464-1 per room, light scenes, UGR per observer, EN 1838 emergency lighting.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace dynrad::report {

// The HTML of the report's "rooms", "scenes", "observers" and "emergency" sections (empty when it
// has none).
std::string html_design_sections(const nlohmann::json& report);

// A check's row cells (area, quantity, value, target, verdict, margin, note).
std::string html_check_row(const nlohmann::json& check);

}  // namespace dynrad::report
