// What the PDF report shows, section by section, from the report's JSON; the layout
// itself (pages, tables, pictures, footers) is plugin/cli/pdf_document.h's. Optional
// keys that are absent, null or of another type leave their section or cell out ("–").
#include "plugin/cli/pdf_report.h"

#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "plugin/cli/pdf_document.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

namespace dynrad::cli {
namespace {

using json = nlohmann::json;

const PdfColour kMetText{0.0, 0.42, 0.1}, kMetFill{0.87, 0.96, 0.87};
const PdfColour kFailText{0.72, 0.0, 0.0}, kFailFill{0.99, 0.88, 0.88};
const PdfColour kTotalFill{0.94, 0.94, 0.95}, kNote{0.33, 0.33, 0.36};
constexpr const char* kNone = "–";

// obj[key] when obj is an object holding it, not null.
const json* field(const json& obj, const char* key) {
  if (!obj.is_object()) return nullptr;
  const auto it = obj.find(key);
  return it == obj.end() || it->is_null() ? nullptr : &*it;
}

std::string text(const json& obj, const char* key, const std::string& fallback = "") {
  const json* v = field(obj, key);
  if (!v) return fallback;
  return v->is_string() ? v->get<std::string>() : v->dump();
}

std::optional<double> number(const json& obj, const char* key) {
  const json* v = field(obj, key);
  if (!v || !v->is_number()) return std::nullopt;
  return v->get<double>();
}

std::optional<bool> flag(const json& obj, const char* key) {
  const json* v = field(obj, key);
  if (!v || !v->is_boolean()) return std::nullopt;
  return v->get<bool>();
}

// A non-empty array under `key`, or nullptr.
const json* list(const json& obj, const char* key) {
  const json* v = field(obj, key);
  return v && v->is_array() && !v->empty() ? v : nullptr;
}

// Three significant figures, without an exponent: 127.6 -> "128", 0.04567 -> "0.0457",
// 12345 -> "12300".
std::string significant(double x) {
  if (!std::isfinite(x)) return kNone;
  if (x == 0) return "0";
  int digits = static_cast<int>(std::floor(std::log10(std::abs(x)))) + 1;  // before the point
  // Rounding can carry into one more digit: 999.7 -> 1000.
  if (std::round(std::abs(x) * std::pow(10.0, 3 - digits)) >= 1000) ++digits;
  if (digits >= 3) {
    const double unit = std::pow(10.0, digits - 3);
    return fmt::format("{:.0f}", std::round(x / unit) * unit);
  }
  return fmt::format("{:.{}f}", x, 3 - digits);
}

std::string fixed(const std::optional<double>& x, int decimals) {
  return x ? fmt::format("{:.{}f}", *x, decimals) : kNone;
}
std::string significant(const std::optional<double>& x) { return x ? significant(*x) : kNone; }

std::string vec3(const json& obj, const char* key) {
  const json* v = field(obj, key);
  if (!v || !v->is_array() || v->size() != 3) return kNone;
  for (const json& c : *v)
    if (!c.is_number()) return kNone;
  return fmt::format("({:.2f}, {:.2f}, {:.2f})", (*v)[0].get<double>(), (*v)[1].get<double>(), (*v)[2].get<double>());
}

// "met" in green, "not met" in red, "–" when unknown.
PdfCell verdict(std::optional<bool> met) {
  PdfCell cell(met ? (*met ? "met" : "not met") : kNone);
  if (met) {
    cell.colour = *met ? kMetText : kFailText;
    cell.fill = *met ? kMetFill : kFailFill;
    cell.bold = !*met;
  }
  return cell;
}

// The local time now in strftime's `format`.
std::string local_time(const char* format) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, format, &local);
  return buffer;
}

// A check's number as its quantity is usually given: UGR to one decimal, ratios (no
// unit) to two, illuminances and luminances to three significant figures.
std::string check_number(double v, const std::string& quantity, const std::string& unit) {
  if (quantity == "UGR") return fmt::format("{:.1f}", v);
  if (unit.empty()) return fmt::format("{:.2f}", v);
  return significant(v);
}

std::string with_unit(const std::string& value, const std::string& unit) {
  return unit.empty() || value == kNone ? value : value + " " + unit;
}

std::string check_target(const json& check) {
  const std::string quantity = text(check, "quantity"), unit = text(check, "unit"), relation = text(check, "relation");
  const json* target = field(check, "target");
  if (!target) return kNone;
  if (target->is_array() && target->size() == 2 && (*target)[0].is_number() && (*target)[1].is_number())
    return with_unit(check_number((*target)[0].get<double>(), quantity, unit) + " – " +
                         check_number((*target)[1].get<double>(), quantity, unit),
                     unit);
  if (!target->is_number()) return target->dump();
  const std::string sign = relation == ">=" ? "≥ " : relation == "<=" ? "≤ " : relation.empty() ? "" : relation + " ";
  return sign + with_unit(check_number(target->get<double>(), quantity, unit), unit);
}

PdfTable checks_table(const json& checks) {
  bool notes = false;
  for (const json& c : checks) notes = notes || !text(c, "note").empty();
  PdfTable t;
  t.header = {"Area", "Quantity", "Value", "Target", "Result", "Margin"};
  t.right_aligned = {false, false, true, true, false, true};
  if (notes) t.header.push_back("Note");
  for (const json& c : checks) {
    const std::string quantity = text(c, "quantity"), unit = text(c, "unit");
    const std::optional<double> value = number(c, "value");
    std::vector<PdfCell> row = {text(c, "area", kNone),
                                text(c, "quantity", kNone),
                                value ? with_unit(check_number(*value, quantity, unit), unit) : kNone,
                                check_target(c),
                                verdict(flag(c, "met")),
                                text(c, "margin", kNone)};
    if (notes) row.emplace_back(text(c, "note"));
    t.rows.push_back(std::move(row));
  }
  return t;
}

// Checks met and the overall verdict of a list of checks: all met.
std::vector<PdfCell> summary_row(const std::string& name, const json* checks) {
  std::size_t met = 0, total = 0;
  if (checks)
    for (const json& c : *checks) {
      ++total;
      met += flag(c, "met").value_or(false) ? 1 : 0;
    }
  return {name, fmt::format("{} / {}", met, total), verdict(total ? std::optional<bool>(met == total) : std::nullopt)};
}

void title_block(PdfDocument& doc, const json& r, const std::string& name) {
  const json empty = json::object();
  const json& project = field(r, "project") && r["project"].is_object() ? r["project"] : empty;
  doc.heading(name, 0);
  doc.paragraph("Lighting report", 13, kNote);
  std::string facts;
  for (const auto& [label, key] : {std::pair{"Client", "client"}, {"Author", "author"}})
    if (!text(project, key).empty()) facts += std::string(label) + ": " + text(project, key) + "\n";
  facts += "Date: " + text(project, "date", local_time("%Y-%m-%d"));
  doc.paragraph(facts, 10);
  if (!text(project, "description").empty()) doc.paragraph(text(project, "description"), 10);
  const std::string units = text(r, "units");
  std::string line = "Model: " + text(r, "input", kNone) + " · dynrad " + text(r, "dynrad_version", kNone);
  if (!units.empty())
    line += " · units: " + (units == "photometric"   ? std::string("photometric (lm, lx, cd/m²)")
                            : units == "radiometric" ? "radiometric (W, W/m², W/(m² sr))"
                                                     : units);
  doc.paragraph(line, 8.5, kNote);
}

void compliance_summary(PdfDocument& doc, const json& r) {
  const json* rooms = list(r, "rooms");
  const json* emergency = field(r, "emergency");
  const json* areas = emergency ? list(*emergency, "areas") : nullptr;
  if (!rooms && !areas) return;
  doc.heading("Summary");
  PdfTable t;
  t.header = {"Room or area", "Checks met", "Overall"};
  t.right_aligned = {false, true, false};
  if (rooms)
    for (const json& room : *rooms) t.rows.push_back(summary_row(text(room, "name", kNone), list(room, "checks")));
  if (areas)
    for (const json& a : *areas)
      t.rows.push_back(summary_row("Emergency: " + text(a, "name", kNone), list(a, "checks")));
  doc.table(t);
}

// Luminaires of one type: the same photometry, flux, power, maintenance factor and
// emergency role.
struct LuminaireType {
  std::vector<std::string> names;
  std::string photometry_name, file, kind;
  double flux = 0;
  std::optional<double> watts, maintenance, emergency_flux;
  bool emergency = false;
  std::set<std::string> groups;
};

void luminaire_schedule(PdfDocument& doc, const json& r) {
  const json* luminaires = list(r, "luminaires");
  if (!luminaires) return;
  std::vector<LuminaireType> types;
  std::map<std::string, std::size_t> index;
  bool any_watts = false, all_watts = true, any_maintenance = false, any_group = false, any_file = false,
       any_emergency = false;
  for (const json& l : *luminaires) {
    LuminaireType t;
    const json* photometry = field(l, "photometry");
    t.file = photometry ? std::filesystem::path(text(*photometry, "file")).filename().string() : "";
    t.photometry_name = photometry ? text(*photometry, "name") : "";
    t.kind = text(l, "type");
    t.flux = number(l, "flux").value_or(0);
    t.watts = number(l, "watts");
    t.maintenance = number(l, "maintenance_factor");
    t.emergency = flag(l, "emergency").value_or(false);
    t.emergency_flux = number(l, "emergency_flux");
    const std::string key =
        fmt::format("{}|{}|{}|{:.1f}|{}|{}|{}|{}", t.kind, t.file, t.photometry_name, t.flux, fixed(t.watts, 2),
                    fixed(t.maintenance, 3), t.emergency, fixed(t.emergency_flux, 1));
    auto [it, added] = index.emplace(key, types.size());
    if (added) types.push_back(t);
    LuminaireType& type = types[it->second];
    type.names.push_back(text(l, "name", kNone));
    // "group": one name, or a list of them.
    if (const json* group = field(l, "group"); group && group->is_array()) {
      for (const json& g : *group) type.groups.insert(g.is_string() ? g.get<std::string>() : g.dump());
    } else if (group) {
      type.groups.insert(text(l, "group"));
    }
    any_watts = any_watts || t.watts;
    all_watts = all_watts && t.watts;
    any_maintenance = any_maintenance || t.maintenance;
    any_group = any_group || field(l, "group");
    any_file = any_file || !t.file.empty();
    any_emergency = any_emergency || t.emergency;
  }
  doc.heading("Luminaire schedule");
  PdfTable t;
  t.header = {"Count", "Type / luminaires"};
  if (any_file) t.header.push_back("Photometry file");
  t.header.push_back("Flux per luminaire (lm)");
  if (any_watts) t.header.push_back("Power (W)");
  if (any_maintenance) t.header.push_back("Maintenance factor");
  if (any_group) t.header.push_back("Group");
  if (any_emergency) t.header.push_back("Emergency");
  for (const std::string& h : t.header)
    t.right_aligned.push_back(h == "Count" || h.find('(') != std::string::npos || h == "Maintenance factor");
  double total_flux = 0, total_watts = 0;
  std::size_t total_count = 0;
  for (const LuminaireType& type : types) {
    std::string names;
    for (std::size_t i = 0; i < type.names.size() && i < 8; ++i) names += (i ? ", " : "") + type.names[i];
    if (type.names.size() > 8) names += fmt::format(" and {} more", type.names.size() - 8);
    std::string label = !type.photometry_name.empty()              ? type.photometry_name + ": " + names
                        : type.kind == "sky" || type.kind == "sun" ? type.kind + " (flux reaching the model)"
                                                                   : names;
    std::vector<PdfCell> row = {std::to_string(type.names.size()), label};
    if (any_file) row.emplace_back(type.file.empty() ? kNone : type.file);
    row.emplace_back(fmt::format("{:.0f}", type.flux));
    if (any_watts) row.emplace_back(fixed(type.watts, 1));
    if (any_maintenance) row.emplace_back(fixed(type.maintenance, 2));
    if (any_group) {
      std::string groups;
      for (const std::string& g : type.groups) groups += (groups.empty() ? "" : ", ") + g;
      row.emplace_back(groups.empty() ? kNone : groups);
    }
    if (any_emergency)
      row.emplace_back(!type.emergency       ? "no"
                       : type.emergency_flux ? fmt::format("yes, {:.0f} lm", *type.emergency_flux)
                                             : std::string("yes"));
    t.rows.push_back(std::move(row));
    total_count += type.names.size();
    total_flux += type.flux * type.names.size();
    if (type.watts) total_watts += *type.watts * type.names.size();
  }
  std::vector<PdfCell> total = {std::to_string(total_count), "Total"};
  if (any_file) total.emplace_back("");
  total.emplace_back(fmt::format("{:.0f}", total_flux));
  if (any_watts) total.emplace_back(all_watts ? fmt::format("{:.1f}", total_watts) : kNone);
  while (total.size() < t.header.size()) total.emplace_back("");
  for (PdfCell& c : total) {
    c.bold = true;
    c.fill = kTotalFill;
  }
  t.rows.push_back(std::move(total));
  doc.table(t);
}

std::string normal_path(const std::string& path) { return std::filesystem::path(path).lexically_normal().string(); }

// Draws a picture, or says in the text that it could not be read.
void picture(PdfDocument& doc, const std::string& path, const std::string& caption, double max_height) {
  if (path.empty()) return;
  if (!doc.picture(path, caption, max_height)) {
    spdlog::warn("the PDF report leaves out {}: it could not be read as a PNG", path);
    doc.paragraph("(" + caption + ": the picture " + path + " could not be read)", 8.5, kFailText);
  }
}

void rooms(PdfDocument& doc, const json& r, std::set<std::string>& shown) {
  const json* rooms = list(r, "rooms");
  if (!rooms) return;
  doc.heading("Rooms (EN 12464-1)");
  const double half = doc.text_height() / 2 - 30;
  for (const json& room : *rooms) {
    const std::string name = text(room, "name", kNone);
    doc.heading(name, 2);
    if (const json* checks = list(room, "checks"))
      doc.table(checks_table(*checks));
    else
      doc.paragraph("No checks.", 9, kNote);
    if (!text(room, "picture").empty()) {
      picture(doc, text(room, "picture"), name + ": plan", half);
      shown.insert(normal_path(text(room, "picture")));
    }
    if (const json* pictures = list(room, "pictures"))
      for (const json& p : *pictures) {
        picture(doc, text(p, "file"), name + ": " + text(p, "title", "plan"), half);
        if (!text(p, "file").empty()) shown.insert(normal_path(text(p, "file")));
      }
  }
}

void grids(PdfDocument& doc, const json& r, const std::set<std::string>& shown) {
  const json* grids = list(r, "grids");
  if (!grids) return;
  const std::string unit = text(r, "units", "photometric") == "photometric" ? "lx" : "W/m²";
  doc.heading("Calculation grids");
  PdfTable t;
  t.header = {"Grid", "Height", "Spacing",        "Points",    "Eavg (" + unit + ")",
              "Emin", "Emax",   "U0 = Emin/Eavg", "Emin/Emax", "Target"};
  t.right_aligned = {false, true, true, true, true, true, true, true, true, false};
  for (const json& g : *grids) {
    std::string wanted;
    const json* target = field(g, "target");
    if (target && target->is_object()) {
      if (number(*target, "Eavg")) wanted = "Eavg ≥ " + significant(number(*target, "Eavg"));
      if (number(*target, "U0"))
        wanted += (wanted.empty() ? "" : ", ") + std::string("U0 ≥ ") + fixed(number(*target, "U0"), 2);
    }
    PdfCell verdict_cell = verdict(wanted.empty() ? std::nullopt : flag(g, "meets_target"));
    if (!wanted.empty()) verdict_cell.text = wanted + ": " + verdict_cell.text;
    t.rows.push_back({text(g, "name", kNone), fixed(number(g, "height"), 2), fixed(number(g, "spacing"), 2),
                      fixed(number(g, "count"), 0), significant(number(g, "Eavg")), significant(number(g, "Emin")),
                      significant(number(g, "Emax")), fixed(number(g, "U0"), 2), fixed(number(g, "Emin/Emax"), 2),
                      verdict_cell});
  }
  doc.table(t);
  bool any_daylight = false;
  for (const json& g : *grids)
    any_daylight = any_daylight || (field(g, "daylight_factor") && g["daylight_factor"].is_object());
  if (any_daylight) {
    doc.heading("Daylight factors", 2);
    PdfTable d;
    d.header = {"Grid",
                "DFavg (%)",
                "DFmin (%)",
                "DFmax (%)",
                "Sky component",
                "Externally reflected",
                "Internally reflected",
                "Outside (lx)"};
    d.right_aligned = {false, true, true, true, true, true, true, true};
    for (const json& g : *grids) {
      const json* f = field(g, "daylight_factor");
      if (!f || !f->is_object()) continue;
      d.rows.push_back({text(g, "name", kNone), fixed(number(*f, "DFavg"), 2), fixed(number(*f, "DFmin"), 2),
                        fixed(number(*f, "DFmax"), 2), fixed(number(*f, "sky_component"), 2),
                        fixed(number(*f, "externally_reflected_component"), 2),
                        fixed(number(*f, "internally_reflected_component"), 2),
                        fixed(number(*f, "outside_horizontal_illuminance"), 0)});
    }
    doc.table(d);
  }
  const double half = doc.text_height() / 2 - 30;
  std::vector<std::string> with_rooms;
  for (const json& g : *grids) {
    const std::string file = text(g, "picture");
    if (file.empty()) continue;
    if (shown.count(normal_path(file))) {
      with_rooms.push_back(text(g, "name", kNone));
      continue;
    }
    std::string caption = text(g, "name", kNone) + ": illuminance (" + unit + ")";
    if (number(g, "height")) caption += " at height " + fixed(number(g, "height"), 2);
    picture(doc, file, caption, half);
  }
  if (!with_rooms.empty()) {
    std::string names;
    for (const std::string& n : with_rooms) names += (names.empty() ? "" : ", ") + n;
    doc.paragraph("The plans of " + names + " are shown with their rooms above.", 8.5, kNote);
  }
}

void glare(PdfDocument& doc, const json& r) {
  const json* observers = list(r, "observers");
  if (!observers) return;
  doc.heading("Glare (UGR)");
  PdfTable t;
  t.header = {"Observer", "Position", "Direction", "UGR", "Limit", "Result", "Background (cd/m²)", "Sources"};
  t.right_aligned = {false, false, false, true, true, false, true, true};
  for (const json& o : *observers) {
    const json* sources = field(o, "sources");
    t.rows.push_back({text(o, "name", kNone), vec3(o, "position"), vec3(o, "direction"), fixed(number(o, "ugr"), 1),
                      fixed(number(o, "limit"), 1), verdict(flag(o, "met")),
                      significant(number(o, "background_luminance")),
                      sources && sources->is_array() ? std::to_string(sources->size()) : kNone});
  }
  doc.table(t);
  for (const json& o : *observers)
    if (const json* notes = list(o, "notes"))
      for (const json& n : *notes)
        doc.paragraph(text(o, "name", kNone) + ": " + (n.is_string() ? n.get<std::string>() : n.dump()), 9, kNote);
}

void scenes(PdfDocument& doc, const json& r) {
  const json* scenes = list(r, "scenes");
  if (!scenes) return;
  const std::string unit = text(r, "units", "photometric") == "photometric" ? "lx" : "W/m²";
  doc.heading("Light scenes");
  for (const json& s : *scenes) {
    doc.heading(text(s, "name", kNone), 2);
    const json* levels = field(s, "levels");
    if (levels && levels->is_object() && !levels->empty()) {
      std::string line = "Levels: ";
      bool first = true;
      for (const auto& [group, level] : levels->items()) {
        line += (first ? "" : ", ") + group + " " +
                (level.is_number() ? fmt::format("{:.0f}%", 100 * level.get<double>()) : std::string(kNone));
        first = false;
      }
      doc.paragraph(line, 9.5);
    }
    if (const json* grids = list(s, "grids")) {
      PdfTable t;
      t.header = {"Grid", "Eavg (" + unit + ")", "Emin (" + unit + ")", "U0", "Target"};
      t.right_aligned = {false, true, true, true, false};
      for (const json& g : *grids)
        t.rows.push_back({text(g, "name", kNone), significant(number(g, "Eavg")), significant(number(g, "Emin")),
                          fixed(number(g, "U0"), 2),
                          verdict(g.contains("target") ? flag(g, "meets_target") : std::nullopt)});
      doc.table(t);
    }
  }
}

void emergency(PdfDocument& doc, const json& r) {
  const json* e = field(r, "emergency");
  if (!e || !e->is_object() || e->empty()) return;
  doc.heading("Emergency lighting (EN 1838)");
  if (const json* names = list(*e, "luminaires")) {
    std::string line;
    for (const json& n : *names) line += (line.empty() ? "" : ", ") + (n.is_string() ? n.get<std::string>() : n.dump());
    doc.paragraph("Emergency luminaires: " + line + ".", 9.5);
  }
  if (!text(*e, "note").empty()) doc.paragraph(text(*e, "note"), 9, kNote);
  if (const json* areas = list(*e, "areas"))
    for (const json& a : *areas) {
      const std::string name = text(a, "name", kNone);
      doc.heading(text(a, "kind").empty() ? name : name + " (" + text(a, "kind") + ")", 2);
      if (const json* checks = list(a, "checks")) doc.table(checks_table(*checks));
      picture(doc, text(a, "picture"), name + ": emergency illuminance", doc.text_height() / 2 - 30);
    }
}

void views(PdfDocument& doc, const json& r) {
  const json* views = list(r, "views");
  if (!views) return;
  doc.page_break();
  doc.heading("Views");
  doc.paragraph("Each view in true colour, then its luminance in false colour (cd/m² for photometric units).", 9,
                kNote);
  // One view to a page: its true-colour picture over its luminance, each in half of
  // what the page leaves after the captions (and, on the first, the heading above).
  constexpr double kCaption = 2 * (4 + 8.5 * 1.3 + 10);
  const double half = (doc.text_height() - 60 - 2 * kCaption) / 2;
  for (const json& v : *views) {
    doc.keep(2 * (half + kCaption));
    const std::string name = text(v, "name", kNone), description = text(v, "description");
    picture(doc, text(v, "picture"), name + (description.empty() ? "" : " — " + description), half);
    picture(doc, text(v, "luminance_picture"), name + ": luminance", half);
  }
}

void solve_facts(PdfDocument& doc, const json& r) {
  if (!field(r, "method")) {
    if (list(r, "grids"))
      doc.paragraph("The grids light a mesh solved earlier; its solve's facts are in the report written with it.", 8.5,
                    kNote);
    return;
  }
  // The heading and its short table together on one page.
  doc.keep(180);
  doc.heading("Solve");
  PdfTable t;
  t.header = {"", ""};
  const json* settings = field(r, "settings");
  const std::string quality = settings ? text(*settings, "quality") : "";
  t.rows.push_back({"Method", text(r, "method") + (quality.empty() ? "" : ", quality " + quality)});
  t.rows.push_back({"Stopped by", text(r, "stopped_by", kNone)});
  t.rows.push_back({"Shots", fixed(number(r, "iterations"), 0)});
  t.rows.push_back({"Patches / elements", fixed(number(r, "patches"), 0) + " / " + fixed(number(r, "elements"), 0)});
  t.rows.push_back({"Time", with_unit(fixed(number(r, "seconds"), 2), "s")});
  if (const json* e = field(r, "estimated_error"); e && number(*e, "total"))
    t.rows.push_back(
        {"Estimated error",
         fmt::format("{:.2f}% (unshot light {:.2f}%, mesh {:.2f}%, shadows inside elements {:.2f}%)",
                     100 * number(*e, "total").value_or(0), 100 * number(*e, "unshot").value_or(0),
                     100 * number(*e, "discretisation").value_or(0), 100 * number(*e, "shadows").value_or(0))});
  for (auto& row : t.rows) row[0].bold = true;
  t.header = {"Fact", "Value"};
  doc.table(t);
}

}  // namespace

void write_pdf_report(const std::string& path, const json& r) {
  const json empty = json::object();
  const json& project = field(r, "project") && r["project"].is_object() ? r["project"] : empty;
  const std::string input = text(r, "input");
  std::string name = text(project, "name");
  if (name.empty()) name = input.empty() ? "dynrad lighting report" : std::filesystem::path(input).filename().string();
  std::string bytes;
  try {
    PdfDocument doc(name.size() > 80 ? name.substr(0, 77) + "..." : name);
    std::set<std::string> shown;
    title_block(doc, r, name);
    compliance_summary(doc, r);
    luminaire_schedule(doc, r);
    rooms(doc, r, shown);
    grids(doc, r, shown);
    glare(doc, r);
    scenes(doc, r);
    emergency(doc, r);
    views(doc, r);
    solve_facts(doc, r);
    PdfMetadata metadata;
    metadata.title = "Lighting report: " + name;
    metadata.author = text(project, "author");
    metadata.subject = input.empty() ? "" : "Lighting of " + input;
    metadata.creator = "dynrad " + text(r, "dynrad_version");
    metadata.created = local_time("%Y-%m-%dT%H:%M:%S");
    bytes = doc.finish(metadata);
  } catch (const std::runtime_error& e) {
    throw OutputError(path, e.what());
  }
  AtomicFile file(path);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

}  // namespace dynrad::cli
