// The lighting report as one HTML file: the solve's facts (method, time, elements,
// estimated error, energy), the luminaires, each calculation grid's figures and
// false-colour plan, and each view in true and false colour. Pictures are embedded
// (PNG as base64 data URIs), so the file can be mailed or archived alone.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace dynrad::report {

// `report`: the JSON report of the solve (plugin/cli/cmd_solve.cpp, or the C ABI's dynrad_result_write_report), whose "grids" and "views"
// entries name their PNG files; those are read and embedded. Written atomically;
// OutputError when it cannot be.
void write_html_report(const std::string& path, const nlohmann::json& report);

// Text made safe inside HTML elements and attributes.
std::string html_escape(const std::string& text);

// Standard base64 with '=' padding.
std::string base64(const std::string& bytes);

}  // namespace dynrad::report
