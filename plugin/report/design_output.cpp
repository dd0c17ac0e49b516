// The designer's checks as report sections (see design_output.h).
#include "plugin/report/design_output.h"

#include "mesh/core/error.h"
#include "plugin/report/grid_output.h"
#include "radiosity/design/emergency.h"
#include "radiosity/design/glare.h"
#include "radiosity/design/room_checks.h"
#include "radiosity/sources/scene_json.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <ctime>
#include <set>

namespace dynrad::report {

namespace {

using json = nlohmann::json;

json vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

json check_json(const rad::Check& c) {
  json j = {{"area", c.area},   {"quantity", c.quantity}, {"unit", c.unit},
            {"met", c.met()},   {"note", c.note}};
  j["value"] = c.defined && std::isfinite(c.value) ? json(c.value) : json(nullptr);
  switch (c.relation) {
    case rad::Check::Relation::at_least: j["relation"] = ">="; j["target"] = c.target; break;
    case rad::Check::Relation::at_most: j["relation"] = "<="; j["target"] = c.target; break;
    case rad::Check::Relation::within: j["relation"] = "in"; j["target"] = {c.target, c.target_high}; break;
  }
  j["margin"] = c.defined && std::isfinite(c.value) ? fmt::format("{:+.1f}%", 100 * c.margin()) : "";
  return j;
}

json checks_json(const std::vector<rad::Check>& checks) {
  json out = json::array();
  for (const rad::Check& c : checks) out.push_back(check_json(c));
  return out;
}

std::string verdicts(const std::vector<rad::Check>& checks) {
  std::string out;
  for (const rad::Check& c : checks)
    out += fmt::format("{}{} {} {}: {}", out.empty() ? "" : "; ", c.area, c.quantity,
                       c.defined ? fmt::format("{:.3g}", c.value) : "undefined", c.met() ? "met" : "NOT met");
  return out;
}

// The "project" block: title-block strings; the date defaults to today's (UTC).
json read_project(const std::string& scene_path) {
  const json p = rad::scene_section(scene_path, "project");
  json out = json::object();
  if (!p.is_null()) {
    if (!p.is_object()) throw InputError(scene_path, 0, "\"project\" must be an object of strings.");
    static const std::set<std::string> known = {"name", "author", "date", "client", "description"};
    for (const auto& item : p.items()) {
      if (!known.count(item.key()))
        throw InputError(scene_path, 0,
                         "unknown key \"" + item.key() + "\" in project (known keys: author, client, date, description, name).");
      if (!item.value().is_string())
        throw InputError(scene_path, 0, "project." + item.key() + " must be a string.");
      out[item.key()] = item.value();
    }
  }
  if (!out.contains("date")) {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[16];
    std::strftime(text, sizeof text, "%Y-%m-%d", &utc);
    out["date"] = text;
  }
  return out;
}

}  // namespace

json light_scene_results(const std::vector<rad::LightScene>& scenes, const rad::ChannelPlan& plan,
                         const std::vector<rad::GridResult>& channelled) {
  json out = json::array();
  for (const rad::LightScene& scene : scenes) {
    const std::array<double, 3> levels = rad::channel_levels(scene, plan);
    json entry = {{"name", scene.name}, {"levels", json::object()}, {"grids", json::array()}};
    for (std::size_t k = 0; k < plan.channels.size(); ++k)
      if (!plan.channels[k].empty()) entry["levels"][plan.channels[k]] = levels[k];
    std::string figures;
    for (const rad::GridResult& g : channelled) {
      const rad::SceneGrid r = rad::scene_grid(g, levels);
      json grid = {{"name", r.name}, {"count", r.count}, {"Eavg", r.e_avg}, {"Emin", r.e_min},
                   {"Emax", r.e_max}, {"U0", r.u0},      {"meets_target", r.meets_target}};
      if (const json target = grid_target_json(g.spec); !target.empty()) grid["target"] = target;
      entry["grids"].push_back(grid);
      figures += fmt::format("{}{} Eavg {:.4g} U0 {:.3f}{}", figures.empty() ? "" : "; ", r.name, r.e_avg, r.u0,
                             grid.contains("target") ? (r.meets_target ? " (met)" : " (NOT met)") : "");
    }
    spdlog::info("light scene {}: {}", scene.name, figures.empty() ? "no grid" : figures);
    out.push_back(entry);
  }
  return out;
}

json luminaire_json(const rad::Luminaire& l) {
  json j = {{"name", l.name},
            {"type", l.kind == rad::Luminaire::Kind::sky   ? "sky"
                     : l.kind == rad::Luminaire::Kind::sun ? "sun"
                                                           : "luminaire"},
            {"flux", l.flux()},
            {"position", vec(l.position)},
            {"aim", vec(l.nadir)},
            {"description", l.describe()},
            {"maintenance_factor", l.maintenance_factor}};
  if (l.photometry) j["photometry"] = {{"file", l.photometry->file}, {"name", l.photometry->name}};
  if (!l.group.empty()) j["group"] = l.group;
  if (l.watts > 0) j["watts"] = l.watts;
  j["emergency"] = l.emergency > 0;
  if (l.emergency > 0) j["emergency_flux"] = l.emergency * l.flux();
  return j;
}

bool check_design_inputs(const std::string& scene_path) {
  read_project(scene_path);
  return !rad::read_observers(scene_path).empty() + !rad::read_emergency_areas(scene_path).empty() > 0;
}

void add_design_checks(json& report, const std::string& scene_path, const rad::LitScene& scene,
                       const std::vector<rad::GridResult>& grids) {
  report["project"] = read_project(scene_path);
  const rad::GatherOptions gather;

  // Glare first: the rooms take their observers' UGR.
  std::vector<rad::ObserverGlare> glare;
  json observers = json::array();
  for (const rad::Observer& o : rad::read_observers(scene_path)) {
    const rad::GlareResult g = rad::observer_glare(scene, o, gather);
    glare.push_back({o.name, o.eye, g.ugr, g.defined});
    json sources = json::array();
    for (const rad::GlareSource& s : g.sources)
      if (s.counted)
        sources.push_back({{"luminaire", s.luminaire},
                           {"luminance", s.luminance},
                           {"solid_angle", s.solid_angle},
                           {"position_index", s.position_index},
                           {"term", s.term}});
    json notes = g.notes;
    for (const rad::GlareSource& s : g.sources)
      if (!s.note.empty()) notes.push_back(s.luminaire + ": " + s.note);
    observers.push_back({{"name", o.name},
                         {"position", vec(o.eye)},
                         {"direction", vec(o.view)},
                         {"ugr", g.defined ? json(g.ugr) : json(nullptr)},
                         {"limit", o.limit > 0 ? json(o.limit) : json(nullptr)},
                         {"met", o.limit > 0 ? json(g.met()) : json(nullptr)},
                         {"background_luminance", g.background_luminance},
                         {"indirect_illuminance", g.indirect_illuminance},
                         {"counted", g.counted},
                         {"sources", sources},
                         {"notes", notes}});
    spdlog::info("observer {}: UGR {}{} (Lb {:.3g} cd/m2, {} luminaires in view)", o.name,
                 g.defined ? (g.ugr < 10 ? "< 10" : fmt::format("{:.1f}", g.ugr)) : "undefined",
                 o.limit > 0 ? fmt::format(", limit {:g}: {}", o.limit, g.met() ? "met" : "NOT met") : "",
                 g.background_luminance, g.counted);
  }
  if (!observers.empty()) report["observers"] = observers;

  // EN 12464-1 per room: every grid with a target.
  json rooms = json::array();
  for (const rad::GridResult& grid : grids) {
    const rad::GridSpec& spec = grid.spec;
    if (!(spec.target_eavg > 0 || spec.target_u0 > 0 || spec.room.any())) continue;
    const rad::RoomResult room = rad::check_room(scene, grid, glare, gather);
    json r = {{"name", room.name},
              {"floor", room.floor},
              {"ceiling", room.ceiling},
              {"observers", room.observers},
              {"checks", checks_json(room.checks)},
              {"met", room.met()}};
    if (report.contains("grids"))
      for (const json& g : report["grids"])
        if (g.value("name", "") == spec.name && g.contains("picture")) r["picture"] = g["picture"];
    if (spec.room.ez > 0)
      r["modelling"] = {{"mean", room.modelling}, {"min", room.modelling_min}, {"max", room.modelling_max}};
    rooms.push_back(r);
    spdlog::info("room {}: {} ({})", room.name, room.met() ? "meets EN 12464-1" : "does NOT meet EN 12464-1",
                 verdicts(room.checks));
  }
  if (!rooms.empty()) report["rooms"] = rooms;

  // EN 1838.
  const std::vector<rad::EmergencyArea> areas = rad::read_emergency_areas(scene_path);
  if (!areas.empty()) {
    json e = {{"note", "EN 1838 convention: direct light only, on the floor, from the emergency luminaires at their "
                       "flux on emergency supply"},
              {"areas", json::array()}};
    std::vector<std::string> names;
    for (const rad::Luminaire& l : scene.luminaires)
      if (l.emergency > 0) names.push_back(l.name);
    e["luminaires"] = names;
    for (const rad::EmergencyArea& a : areas) {
      const rad::EmergencyResult r = rad::check_emergency(scene, a);
      e["areas"].push_back({{"name", r.name},
                            {"kind", a.kind == rad::EmergencyArea::Kind::route ? "escape route" : "open area"},
                            {"points", r.points},
                            {"length", r.length},
                            {"width", a.width},
                            {"Emin", r.e_min},
                            {"Emax", r.e_max},
                            {"checks", checks_json(r.checks)},
                            {"met", r.met()}});
      spdlog::info("emergency {} {}: {} ({})", a.kind == rad::EmergencyArea::Kind::route ? "route" : "open area",
                   r.name, r.met() ? "meets EN 1838" : "does NOT meet EN 1838", verdicts(r.checks));
    }
    if (names.empty())
      spdlog::warn("the scene declares escape routes or open areas but no luminaire is marked \"emergency\": they get "
                   "no emergency light.");
    report["emergency"] = e;
  }
}

}  // namespace dynrad::report
