#include "plugin/report/html_report.h"

#include "plugin/report/html_design.h"

#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "mesh/io/io_util.h"

#include <boost/archive/iterators/base64_from_binary.hpp>
#include <boost/archive/iterators/transform_width.hpp>
#include <fmt/format.h>

#include <sstream>

namespace dynrad::report {

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64(const std::string& bytes) {
  using namespace boost::archive::iterators;
  using Encoder = base64_from_binary<transform_width<std::string::const_iterator, 6, 8>>;
  std::string out(Encoder(bytes.begin()), Encoder(bytes.end()));
  out.append((3 - bytes.size() % 3) % 3, '=');
  return out;
}

namespace {

using json = nlohmann::json;

std::string number(const json& v, const char* format = "{:.4g}") {
  return v.is_number() ? fmt::format(fmt::runtime(format), v.get<double>()) : "–";
}

std::string text(const json& v) {
  if (v.is_string()) return html_escape(v.get<std::string>());
  if (v.is_null()) return "–";
  return html_escape(v.dump());
}

std::string picture(const json& file, const std::string& alt) {
  if (!file.is_string()) return "";
  const std::string path = file.get<std::string>();
  return "<img alt=\"" + html_escape(alt) + "\" src=\"data:image/png;base64," + base64(detail::read_file(path)) + "\">";
}

std::string row(const std::string& name, const std::string& value) {
  return "<tr><th>" + html_escape(name) + "</th><td>" + value + "</td></tr>\n";
}

double channel_sum(const json& rgb) {
  double s = 0;
  if (rgb.is_array())
    for (const json& c : rgb) s += c.get<double>();
  return s;
}

// The grid's target and whether it is met, coloured.
std::string target_cell(const json& g) {
  if (!g.contains("target") || !g["target"].is_object() || g["target"].empty()) return "<td>–</td>";
  std::string wanted;
  if (g["target"].contains("Eavg")) wanted = "E<sub>avg</sub> ≥ " + number(g["target"]["Eavg"], "{:g}");
  if (g["target"].contains("U0"))
    wanted += std::string(wanted.empty() ? "" : ", ") + "U<sub>0</sub> ≥ " + number(g["target"]["U0"], "{:g}");
  const bool met = g.value("meets_target", false);
  return std::string("<td style=\"color:") + (met ? "#070\">" : "#b00\">") + wanted + (met ? ": met" : ": not met") +
         "</td>";
}

}  // namespace

void write_html_report(const std::string& path, const json& r) {
  const bool photometric = r.value("units", "") == "photometric";
  const std::string illuminance_unit = photometric ? "lx" : "W/m²";
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>dynrad lighting report: "
    << text(r["input"]) << "</title>\n<style>\n"
    << "body{font-family:sans-serif;margin:2em auto;max-width:1400px;color:#222}\n"
    << "table{border-collapse:collapse;margin:0.5em 0 1.5em}\n"
    << "th,td{border:1px solid #bbb;padding:0.25em 0.6em;text-align:left}\n"
    << "td.n{text-align:right;font-variant-numeric:tabular-nums}\n"
    << "th{background:#eee}\nimg{max-width:100%;border:1px solid #ccc;margin:0.3em 0.3em 0 0}\n"
    << "figure{display:inline-block;margin:0 1em 1.5em 0;vertical-align:top}\n"
    << ".pair img{max-width:48%}\n.note{color:#555;font-size:0.9em}\n</style>\n</head>\n<body>\n";
  const json project = r.contains("project") && r["project"].is_object() ? r["project"] : json::object();
  h << "<h1>Lighting report: " << (project.contains("name") ? text(project["name"]) : text(r["input"])) << "</h1>\n";
  std::string byline;
  for (const char* key : {"client", "author", "date"})
    if (project.contains(key))
      byline += (byline.empty() ? "" : " · ") + std::string(1, static_cast<char>(std::toupper(key[0]))) + (key + 1) +
                ": " + text(project[key]);
  if (!byline.empty()) h << "<p>" << byline << "</p>\n";
  if (project.contains("description")) h << "<p>" << text(project["description"]) << "</p>\n";
  h << "<p class=\"note\">Written by dynrad " << text(r["dynrad_version"]) << ". Lit mesh: " << text(r["output"])
    << ". Units: " << (photometric ? "photometric (lm, lx, cd/m²)" : "radiometric (W, W/m², W/(m² sr))")
    << ".</p>\n";

  // The solve.
  if (!r.contains("method")) {
    h << "<p class=\"note\">Grids and views of a lit mesh solved earlier; its solve's facts are in the report "
         "written with it (dynrad solve --report or --html).</p>\n";
  } else {
  h << "<h2>Solve</h2>\n<table>\n";
  h << row("Method", text(r["method"]) + (r.contains("settings") ? ", quality " + text(r["settings"]["quality"]) : ""));
  h << row("Stopped by", text(r["stopped_by"]));
  h << row("Time", number(r["seconds"], "{:.2f}") + " s");
  h << row("Shots", number(r["iterations"], "{:.0f}"));
  h << row("Patches / elements", number(r["patches"], "{:.0f}") + " / " + number(r["elements"], "{:.0f}"));
  if (r.contains("estimated_error")) {
    const json& e = r["estimated_error"];
    h << row("Estimated error",
             fmt::format("{:.2f}% (unshot light {:.2f}%, mesh {:.2f}%, shadows inside elements {:.2f}%)",
                         100 * e.value("total", 0.0), 100 * e.value("unshot", 0.0),
                         100 * e.value("discretisation", 0.0), 100 * e.value("shadows", 0.0)));
  }
  h << row("Unshot at the end", fmt::format("{:.3f}%", 100 * r.value("unshot_fraction", 0.0)));
  if (r.contains("energy")) {
    const json& e = r["energy"];
    const double emitted = channel_sum(e["emitted"]);
    const char* unit = photometric ? " lm" : "";
    h << row("Emitted", fmt::format("{:.4g}{} (sum over channels)", emitted, unit));
    for (const char* part : {"absorbed", "escaped", "unshot"})
      h << row(std::string("  ") + part,
               fmt::format("{:.4g}{} ({:.1f}%)", channel_sum(e[part]), unit,
                           emitted > 0 ? 100 * channel_sum(e[part]) / emitted : 0.0));
  }
  h << row("Visibility rays", number(r["visibility_rays"], "{:.0f}"));
  h << row("Exposure of the pictures", number(r["exposure"]));
  h << "</table>\n";
  }

  // Luminaires.
  if (r.contains("luminaires") && !r["luminaires"].empty()) {
    h << "<h2>Light sources</h2>\n<p class=\"note\">For the sky and the sun, the flux is what reaches the "
         "model's surfaces.</p>\n<table>\n<tr><th>Name</th><th>Flux (lm)</th><th>Position</th><th>Aim</th>"
         "<th>Group</th><th>W</th><th>Emergency (lm)</th><th>Description</th></tr>\n";
    for (const json& l : r["luminaires"]) {
      auto vec = [](const json& v) {
        return v.is_array() && v.size() == 3
                   ? fmt::format("({:.3g}, {:.3g}, {:.3g})", v[0].get<double>(), v[1].get<double>(), v[2].get<double>())
                   : std::string("–");
      };
      const bool daylight = l.value("type", "") == "sky" || l.value("type", "") == "sun";
      h << "<tr><td>" << text(l["name"]) << "</td><td class=\"n\">" << number(l["flux"], "{:.0f}") << "</td><td>"
        << (daylight ? "–" : vec(l["position"])) << "</td><td>" << (daylight ? "–" : vec(l["aim"])) << "</td><td>"
        << text(l.value("group", json())) << "</td><td class=\"n\">" << number(l.value("watts", json()), "{:g}")
        << "</td><td class=\"n\">" << number(l.value("emergency_flux", json()), "{:.0f}") << "</td><td>"
        << text(l["description"]) << "</td></tr>\n";
    }
    h << "</table>\n";
  }

  // Grids.
  if (r.contains("grids") && !r["grids"].empty()) {
    h << "<h2>Calculation grids</h2>\n<table>\n<tr><th>Grid</th><th>Height</th><th>Spacing</th><th>Points</th>"
         "<th>Inside solids</th><th>E<sub>avg</sub> ("
      << illuminance_unit << ")</th><th>E<sub>min</sub></th><th>E<sub>max</sub></th><th>U<sub>0</sub> = "
         "E<sub>min</sub>/E<sub>avg</sub></th><th>E<sub>min</sub>/E<sub>max</sub></th><th>Target</th></tr>\n";
    for (const json& g : r["grids"])
      h << "<tr><td>" << text(g["name"]) << "</td><td class=\"n\">" << number(g["height"], "{:.3g}")
        << "</td><td class=\"n\">" << number(g["spacing"], "{:.3g}") << "</td><td class=\"n\">"
        << number(g["count"], "{:.0f}") << "</td><td class=\"n\">" << number(g["masked"], "{:.0f}")
        << "</td><td class=\"n\">" << number(g["Eavg"], "{:.1f}") << "</td><td class=\"n\">"
        << number(g["Emin"], "{:.1f}") << "</td><td class=\"n\">" << number(g["Emax"], "{:.1f}")
        << "</td><td class=\"n\">" << number(g["U0"], "{:.2f}") << "</td><td class=\"n\">"
        << number(g["Emin/Emax"], "{:.2f}") << "</td>" << target_cell(g) << "</tr>\n";
    h << "</table>\n";
    bool any_df = false;
    for (const json& g : r["grids"]) any_df = any_df || (g.contains("daylight_factor") && g["daylight_factor"].is_object());
    if (any_df) {
      h << "<h3>Daylight factors</h3>\n<table>\n<tr><th>Grid</th><th>DF<sub>avg</sub> (%)</th><th>DF<sub>min</sub></th>"
           "<th>DF<sub>max</sub></th><th>Sky component</th><th>Externally reflected</th><th>Internally reflected</th>"
           "<th>Outside (lx)</th></tr>\n";
      for (const json& g : r["grids"]) {
        if (!g.contains("daylight_factor") || !g["daylight_factor"].is_object()) continue;
        const json& d = g["daylight_factor"];
        h << "<tr><td>" << text(g["name"]) << "</td><td class=\"n\">" << number(d["DFavg"], "{:.2f}")
          << "</td><td class=\"n\">" << number(d["DFmin"], "{:.2f}") << "</td><td class=\"n\">"
          << number(d["DFmax"], "{:.2f}") << "</td><td class=\"n\">" << number(d["sky_component"], "{:.2f}")
          << "</td><td class=\"n\">" << number(d["externally_reflected_component"], "{:.2f}")
          << "</td><td class=\"n\">" << number(d["internally_reflected_component"], "{:.2f}")
          << "</td><td class=\"n\">" << number(d["outside_horizontal_illuminance"], "{:.0f}") << "</td></tr>\n";
      }
      h << "</table>\n<p class=\"note\">DF = 100 E / E<sub>outside</sub> under the sky alone, E<sub>outside</sub> "
           "its unobstructed horizontal illuminance. The externally reflected component is the ground seen through "
           "openings; light reflected by obstructions outside counts as internally reflected.</p>\n";
    }
    const int rays = r["grids"].front().value("indirect_rays_per_point", 0);
    h << "<p class=\"note\">Each point faces up. Direct light is exact (luminaires' photometry, emitting surfaces' "
         "closed form, with shadow rays); light from surfaces is gathered from the solution by "
      << rays << " stratified cosine-weighted rays per point. Points inside solids are left out and counted.</p>\n";
    for (const json& g : r["grids"])
      h << "<figure>" << picture(g["picture"], "grid " + g.value("name", "")) << "<figcaption>" << text(g["name"])
        << ", CSV per point: " << text(g["csv"]) << "</figcaption></figure>\n";
  }

  h << html_design_sections(r);

  // Views.
  if (r.contains("views") && !r["views"].empty()) {
    h << "<h2>Views</h2>\n<p class=\"note\">True colour at the exposure above, and luminance in false colour "
         "(cd/m² for photometric units). In plans the cut through walls shows dark; in views the back of a face "
         "shows dark red.</p>\n";
    for (const json& v : r["views"])
      h << "<h3>" << text(v["name"]) << "</h3>\n<p class=\"note\">" << text(v["description"]) << "</p>\n<div class=\"pair\">"
        << picture(v["picture"], v.value("name", "") + " in true colour")
        << picture(v["luminance_picture"], v.value("name", "") + " luminance") << "</div>\n";
  }
  h << "</body>\n</html>\n";
  AtomicFile file(path, std::ios::out);
  file.stream() << h.str();
  file.commit();
}

}  // namespace dynrad::report
