// The annual daylight report as one HTML file (dynrad annual): the site and the
// conventions, each grid's metrics (LM-83, UDI, DA, EN 17037 per level) and its plans,
// embedded, so the file can be mailed or archived alone.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace dynrad::cli {

// `report`: the annual JSON report (cmd_annual.cpp). `plans`: per grid, in the report's
// order, its plans as (caption, PNG bytes). Written atomically; OutputError when it
// cannot be.
void write_annual_html(const std::string& path, const nlohmann::json& report,
                       const std::vector<std::vector<std::pair<std::string, std::string>>>& plans);

}  // namespace dynrad::cli
