// `dynrad validate --html FILE`: the validation as one HTML page a designer can attach
// to a project: how points are judged, a table per section of CIE 171, and per run its
// figures, the choices made, a chart of its points' errors (SVG) and the false-colour
// plan of its work plane (embedded PNG).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace dynrad::cli {

// `runs`: what `validate --json` writes, each run with "picture" (a PNG path, or null)
// added. `quality`: what the solves ran at. Written atomically; OutputError when it
// cannot be.
void write_validation_report(const std::string& path, const nlohmann::json& runs, const std::string& quality);

}  // namespace dynrad::cli
