// The lighting report as a printable PDF (A4 portrait), drawn with cairo: a title
// block, the luminaire schedule, the rooms' EN 12464-1 checks with their plans, the
// calculation grids, glare observers, light scenes, emergency lighting (EN 1838), the
// views, and the solve's facts. Each section appears only when the report holds it.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace dynrad::cli {

// `report`: the JSON report of a solve or a grid run (the same object write_html_report
// gets, plugin/report/html_report.h). PNG pictures it names are read and drawn scaled to
// the text width. Written atomically (no partial file on failure); OutputError when it
// cannot be.
void write_pdf_report(const std::string& path, const nlohmann::json& report);

}  // namespace dynrad::cli
