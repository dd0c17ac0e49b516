// The annual daylight report as one HTML file (see html_annual.h).
#include "plugin/cli/html_annual.h"

#include "mesh/io/atomic_file.h"
#include "plugin/report/html_report.h"

#include <fmt/format.h>

#include <sstream>

namespace dynrad::cli {
using namespace dynrad::report;  // the report's writers (plugin/report/)

namespace {

using json = nlohmann::json;

std::string text(const json& v) { return html_escape(v.is_string() ? v.get<std::string>() : v.dump()); }

std::string percent(const json& v) { return v.is_number() ? fmt::format("{:.1f}%", v.get<double>()) : "-"; }

}  // namespace

void write_annual_html(const std::string& path, const json& r,
                       const std::vector<std::vector<std::pair<std::string, std::string>>>& plans) {
  std::ostringstream h;
  const json& w = r["weather"];
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>dynrad annual daylight: "
    << text(w["city"]) << "</title>\n<style>\n"
    << "body{font-family:sans-serif;margin:2em auto;max-width:1400px;color:#222}\n"
    << "table{border-collapse:collapse;margin:0.5em 0 1.5em}\n"
    << "th,td{border:1px solid #bbb;padding:0.25em 0.6em;text-align:left}\n"
    << "td.n{text-align:right;font-variant-numeric:tabular-nums}\nth{background:#eee}\n"
    << "img{max-width:100%;border:1px solid #ccc}\nfigure{display:inline-block;margin:0 1em 1.5em 0;"
    << "vertical-align:top;max-width:48%}\n.note{color:#555;font-size:0.9em}\n</style>\n</head>\n<body>\n";
  h << "<h1>Annual daylight: " << text(w["city"]) << ", " << text(w["country"]) << "</h1>\n";
  if (r.value("interrupted", false))
    h << "<p><strong>Interrupted:</strong> the year was computed from the light the solve had shot when it was "
         "stopped; the figures are low.</p>\n";
  h << "<table>\n<tr><th>Weather file</th><td>" << text(w["file"]) << "</td></tr>\n"
    << fmt::format("<tr><th>Site</th><td>latitude {:.3f}, longitude {:.3f}, UTC{:+g}, elevation {:.0f} m</td></tr>\n",
                   w["latitude"].get<double>(), w["longitude"].get<double>(), w["timezone"].get<double>(),
                   w["elevation"].get<double>());
  const json& c = r["conventions"];
  for (const auto& [key, label] : std::vector<std::pair<const char*, const char*>>{
           {"time", "Time"},
           {"sky", "Sky"},
           {"occupied", "Analysis hours (LM-83, UDI, DA)"},
           {"en17037_daylight_hours", "EN 17037 daylight hours"},
           {"blinds", "Blinds"},
           {"coefficients", "Daylight coefficients"}})
    if (c.contains(key)) h << "<tr><th>" << label << "</th><td>" << text(c[key]) << "</td></tr>\n";
  h << fmt::format("<tr><th>Ground reflectance</th><td>{:.2f}</td></tr>\n", c["ground_reflectance"].get<double>())
    << fmt::format("<tr><th>Median diffuse horizontal illuminance</th><td>{:.0f} lx (EN 17037's E<sub>v,d,med</sub>)"
                   "</td></tr>\n",
                   c["median_diffuse_illuminance"].get<double>())
    << "</table>\n";
  std::size_t k = 0;
  for (const json& g : r["grids"]) {
    h << "<h2>Grid " << text(g["name"]) << "</h2>\n<table>\n"
      << "<tr><th>Points</th><td class=\"n\">" << g["points"].get<std::size_t>() << " (" << g["masked"].get<std::size_t>()
      << " inside solids, left out)</td></tr>\n"
      << "<tr><th>sDA<sub>300/50%</sub> (LM-83)</th><td class=\"n\">" << percent(g["sDA300_50"]) << "</td></tr>\n"
      << "<tr><th>ASE<sub>1000,250h</sub> (LM-83)</th><td class=\"n\">" << percent(g["ASE1000_250h"]) << "</td></tr>\n"
      << "<tr><th>UDI below 100 / 100-3000 / above 3000 lx</th><td class=\"n\">" << percent(g["UDI_below_100"])
      << " / " << percent(g["UDI_100_3000"]) << " / " << percent(g["UDI_above_3000"]) << "</td></tr>\n"
      << "<tr><th>Mean DA<sub>300</sub> / cDA<sub>300</sub></th><td class=\"n\">" << percent(g["DA300_mean"]) << " / "
      << percent(g["cDA300_mean"]) << "</td></tr>\n</table>\n";
    if (g.contains("EN17037")) {
      const json& e = g["EN17037"];
      h << "<p>EN 17037 daylight provision over " << e["daylight_hours"].get<std::size_t>()
        << " daylight hours: level achieved <strong>" << text(e["achieved"]) << "</strong>.</p>\n<table>\n"
        << "<tr><th>Level</th><th>Target over 50% of the plane</th><th>Hours reached</th>"
        << "<th>Minimum over 95%</th><th>Hours reached</th><th>Met</th></tr>\n";
      for (const json& l : e["levels"])
        h << "<tr><td>" << text(l["level"]) << "</td><td class=\"n\">" << l["target_lux"].get<double>()
          << " lx</td><td class=\"n\">" << percent(l["target_hours_percent"]) << "</td><td class=\"n\">"
          << l["minimum_lux"].get<double>() << " lx</td><td class=\"n\">" << percent(l["minimum_hours_percent"])
          << "</td><td>" << (l["met"].get<bool>() ? "yes" : "no") << "</td></tr>\n";
      h << "</table>\n";
    }
    for (const json& note : g["notes"]) h << "<p class=\"note\">" << text(note) << "</p>\n";
    if (k < plans.size())
      for (const auto& [caption, png] : plans[k])
        h << "<figure><img alt=\"" << html_escape(caption) << "\" src=\"data:image/png;base64," << base64(png)
          << "\"><figcaption>" << html_escape(caption) << "</figcaption></figure>\n";
    ++k;
  }
  h << "<p class=\"note\">Written by dynrad annual in " << fmt::format("{:.0f}", r["seconds"].get<double>())
    << " s. The hourly illuminance of every point is in the grids' _hourly.npy files, the metrics per point in "
       "their _points.csv files.</p>\n</body>\n</html>\n";
  AtomicFile file(path, std::ios::out);
  file.stream() << h.str();
  file.commit();
}

}  // namespace dynrad::cli
