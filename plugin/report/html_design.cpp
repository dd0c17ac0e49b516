// The designer's checks in the HTML report (see html_design.h).
#include "plugin/report/html_design.h"

#include "plugin/report/html_report.h"

#include <fmt/format.h>

#include <sstream>

namespace dynrad::report {

namespace {

using json = nlohmann::json;

std::string value_text(const json& v, const std::string& unit, const char* format = "{:.3g}") {
  if (!v.is_number()) return "–";
  return fmt::format(fmt::runtime(format), v.get<double>()) + (unit.empty() ? "" : " " + unit);
}

// UGR is printed to one decimal, or "< 10" below the formula's range.
std::string ugr_text(const json& v) {
  if (!v.is_number()) return "–";
  return v.get<double>() < 10 ? "&lt; 10" : fmt::format("{:.1f}", v.get<double>());
}

std::string verdict(bool met) {
  return std::string("<td style=\"color:") + (met ? "#070\">met" : "#b00\"><b>not met</b>") + "</td>";
}

const char* kHeader =
    "<tr><th>Area</th><th>Quantity</th><th>Value</th><th>Target</th><th>Result</th><th>Margin</th><th>Note</th></tr>\n";

std::string checks_table(const json& checks) {
  std::string out = std::string("<table>\n") + kHeader;
  for (const json& c : checks) out += html_check_row(c);
  return out + "</table>\n";
}

}  // namespace

std::string html_check_row(const json& c) {
  const std::string unit = c.value("unit", "");
  const bool ugr = c.value("quantity", "") == "UGR";
  std::string target;
  const std::string relation = c.value("relation", "");
  if (relation == "in" && c["target"].is_array() && c["target"].size() == 2)
    target = fmt::format("{:.2f} – {:.2f}", c["target"][0].get<double>(), c["target"][1].get<double>());
  else
    target = (relation == "<=" ? "≤ " : "≥ ") + value_text(c["target"], unit, "{:g}");
  return "<tr><td>" + html_escape(c.value("area", "")) + "</td><td>" + html_escape(c.value("quantity", "")) +
         "</td><td class=\"n\">" + (ugr ? ugr_text(c["value"]) : value_text(c["value"], unit)) + "</td><td class=\"n\">" +
         target + "</td>" + verdict(c.value("met", false)) + "<td class=\"n\">" + html_escape(c.value("margin", "")) +
         "</td><td class=\"note\">" + html_escape(c.value("note", "")) + "</td></tr>\n";
}

std::string html_design_sections(const json& r) {
  std::ostringstream h;
  if (r.contains("rooms") && !r["rooms"].empty()) {
    h << "<h2>Rooms: EN 12464-1:2021</h2>\n<p class=\"note\">Each room is a grid with a target: its task area "
         "(the grid's points), the surrounding band, the walls and ceiling (the grid's polygon raised from the floor "
         "to the ceiling, points 1 cm from them), cylindrical illuminance E<sub>z</sub> and modelling "
         "E<sub>z</sub>/E<sub>h</sub> over the task area at eye height, and the largest UGR of the observers in the "
         "room. Margins are relative to the target; negative fails.</p>\n";
    h << "<table>\n<tr><th>Room</th><th>Checks met</th><th>Result</th></tr>\n";
    for (const json& room : r["rooms"]) {
      std::size_t met = 0;
      for (const json& c : room["checks"]) met += c.value("met", false);
      h << "<tr><td>" << html_escape(room.value("name", "")) << "</td><td class=\"n\">" << met << " / "
        << room["checks"].size() << "</td>" << verdict(room.value("met", false)) << "</tr>\n";
    }
    h << "</table>\n";
    for (const json& room : r["rooms"])
      h << "<h3>" << html_escape(room.value("name", "")) << "</h3>\n" << checks_table(room["checks"]);
  }
  if (r.contains("scenes") && !r["scenes"].empty()) {
    h << "<h2>Light scenes</h2>\n<p class=\"note\">Each control group's light is kept apart in one solve (light "
         "is linear); a scene is the groups' light times their levels. Groups a scene does not list, and light "
         "sources in no group, are at full output. The grids and rooms above are the solve with every group at "
         "full output.</p>\n";
    for (const json& s : r["scenes"]) {
      std::string levels;
      for (const auto& item : s["levels"].items())
        levels += (levels.empty() ? "" : ", ") + html_escape(item.key()) + fmt::format(" {:.0f}%", 100 * item.value().get<double>());
      h << "<h3>" << html_escape(s.value("name", "")) << "</h3>\n<p>" << levels << "</p>\n<table>\n<tr><th>Grid</th>"
           "<th>E<sub>avg</sub></th><th>E<sub>min</sub></th><th>E<sub>max</sub></th><th>U<sub>0</sub></th>"
           "<th>Target</th></tr>\n";
      for (const json& g : s["grids"]) {
        std::string target = "<td>–</td>";
        if (g.contains("target")) {
          std::string wanted;
          if (g["target"].contains("Eavg")) wanted = "E<sub>avg</sub> ≥ " + value_text(g["target"]["Eavg"], "", "{:g}");
          if (g["target"].contains("U0"))
            wanted += (wanted.empty() ? "" : ", ") + std::string("U<sub>0</sub> ≥ ") + value_text(g["target"]["U0"], "", "{:g}");
          target = verdict(g.value("meets_target", false));
          target.insert(target.find('>') + 1, wanted + ": ");
        }
        h << "<tr><td>" << html_escape(g.value("name", "")) << "</td><td class=\"n\">" << value_text(g["Eavg"], "")
          << "</td><td class=\"n\">" << value_text(g["Emin"], "") << "</td><td class=\"n\">"
          << value_text(g["Emax"], "") << "</td><td class=\"n\">" << value_text(g["U0"], "", "{:.2f}") << "</td>"
          << target << "</tr>\n";
      }
      h << "</table>\n";
    }
  }
  if (r.contains("observers") && !r["observers"].empty()) {
    h << "<h2>Glare: UGR (CIE 117)</h2>\n<table>\n<tr><th>Observer</th><th>Eye</th><th>Line of sight</th>"
         "<th>UGR</th><th>Limit</th><th>Result</th><th>L<sub>b</sub> (cd/m²)</th><th>Luminaires counted</th></tr>\n";
    auto vec = [](const json& v) {
      return v.is_array() && v.size() == 3
                 ? fmt::format("({:.3g}, {:.3g}, {:.3g})", v[0].get<double>(), v[1].get<double>(), v[2].get<double>())
                 : std::string("–");
    };
    for (const json& o : r["observers"]) {
      h << "<tr><td>" << html_escape(o.value("name", "")) << "</td><td>" << vec(o["position"]) << "</td><td>"
        << vec(o["direction"]) << "</td><td class=\"n\">" << ugr_text(o["ugr"]) << "</td><td class=\"n\">"
        << value_text(o["limit"], "", "{:g}") << "</td>"
        << (o["met"].is_boolean() ? verdict(o["met"].get<bool>()) : std::string("<td>–</td>")) << "<td class=\"n\">"
        << value_text(o["background_luminance"], "") << "</td><td class=\"n\">" << o.value("counted", 0) << "</td></tr>\n";
    }
    h << "</table>\n";
    for (const json& o : r["observers"])
      if (o.contains("notes") && !o["notes"].empty()) {
        h << "<p class=\"note\">" << html_escape(o.value("name", "")) << ":";
        for (const json& n : o["notes"]) h << " " << html_escape(n.get<std::string>()) << ";";
        h << "</p>\n";
      }
  }
  if (r.contains("emergency") && r["emergency"].contains("areas")) {
    const json& e = r["emergency"];
    h << "<h2>Emergency lighting: EN 1838</h2>\n<p class=\"note\">" << html_escape(e.value("note", ""))
      << ". Emergency luminaires: ";
    std::string names;
    for (const json& n : e["luminaires"]) names += (names.empty() ? "" : ", ") + n.get<std::string>();
    h << html_escape(names.empty() ? "none" : names) << ".</p>\n";
    for (const json& a : e["areas"])
      h << "<h3>" << html_escape(a.value("name", "")) << " (" << html_escape(a.value("kind", "")) << ")</h3>\n"
        << checks_table(a["checks"]);
  }
  return h.str();
}

}  // namespace dynrad::report
