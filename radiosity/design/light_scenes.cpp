// Light scenes by superposition (see light_scenes.h).
#include "radiosity/design/light_scenes.h"

#include "mesh/core/error.h"
#include "radiosity/sources/scene_json.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace dynrad::rad {

namespace {

using json = nlohmann::json;

// Rgb::luminance's weights.
constexpr std::array<double, 3> kWeights = {0.2126, 0.7152, 0.0722};

}  // namespace

int ChannelPlan::channel(const std::string& group) const {
  for (std::size_t k = 0; k < channels.size(); ++k)
    if (channels[k] == group) return static_cast<int>(k);
  return -1;
}

std::vector<LightScene> read_light_scenes(const std::string& scene_path, const std::vector<Luminaire>& luminaires) {
  const json list = scene_section(scene_path, "scenes");
  if (list.is_null()) return {};
  auto fail = [&](const std::string& what) { throw InputError(scene_path, 0, what); };
  if (!list.is_array()) fail("\"scenes\" must be an array of {\"name\": ..., \"levels\": {group: level}}.");
  std::set<std::string> groups;
  for (const Luminaire& l : luminaires)
    if (!l.group.empty()) groups.insert(l.group);
  std::string known;
  for (const std::string& g : groups) known += (known.empty() ? "" : ", ") + g;
  std::vector<LightScene> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& e = list[i];
    const std::string where = "scenes[" + std::to_string(i) + "]";
    if (!e.is_object()) fail(where + " must be an object.");
    for (const auto& item : e.items())
      if (item.key() != "name" && item.key() != "levels")
        fail("unknown key \"" + item.key() + "\" in " + where + " (known keys: levels, name).");
    LightScene s;
    s.name = "scene" + std::to_string(i + 1);
    if (e.contains("name")) {
      if (!e["name"].is_string() || e["name"].get<std::string>().empty()) fail(where + ".name must be a non-empty string.");
      s.name = e["name"].get<std::string>();
    }
    if (!names.insert(s.name).second) fail("two scenes are named \"" + s.name + "\"; give each its own name.");
    const std::string named = where + " (\"" + s.name + "\")";
    if (!e.contains("levels") || !e["levels"].is_object())
      fail(named + " needs \"levels\": {group: level from 0 to 1}.");
    for (const auto& item : e["levels"].items()) {
      if (!groups.count(item.key()))
        fail(named + ".levels names group \"" + item.key() + "\", which no luminaire belongs to" +
             (known.empty() ? " (no luminaire has a \"group\")." : " (groups: " + known + ")."));
      const double level = scene_number(scene_path, item.value(), named + ".levels." + item.key());
      if (!(level >= 0 && level <= 1)) fail(named + ".levels." + item.key() + " must lie from 0 (off) to 1 (full).");
      s.levels.emplace_back(item.key(), level);
    }
    out.push_back(std::move(s));
  }
  if (groups.empty() && !out.empty())
    fail("\"scenes\" dim control groups, but no luminaire has a \"group\"; give the luminaires one.");
  return out;
}

ChannelPlan plan_channels(const std::string& scene_path, const std::vector<Luminaire>& luminaires,
                          bool emitting_surfaces) {
  ChannelPlan plan;
  bool ungrouped = emitting_surfaces;
  for (const Luminaire& l : luminaires) {
    if (l.directional())
      throw InputError(scene_path, 0,
                       "light scenes combine luminaires' groups; with a \"sky\" the daylight would have to be a group "
                       "too, which dynrad does not do yet. Solve the daylight and the light scenes apart.");
    if (std::abs(l.colour.r - 1) + std::abs(l.colour.g - 1) + std::abs(l.colour.b - 1) > 1e-12)
      throw InputError(scene_path, 0,
                       "light scenes need white luminaires (each group's light travels in a colour channel of its "
                       "own); luminaire \"" + l.name + "\" has a \"colour\". Remove it.");
    if (l.group.empty()) {
      ungrouped = true;
    } else if (plan.channel(l.group) < 0) {
      plan.channels.push_back(l.group);
    }
  }
  if (ungrouped) plan.channels.push_back("");
  if (plan.channels.size() > 3)
    throw InputError(scene_path, 0,
                     "light scenes keep each control group's light in one of the solver's three channels, so at most "
                     "three groups (or two, when some luminaires or emitting surfaces belong to none); this scene "
                     "needs " + std::to_string(plan.channels.size()) + ". Join groups, or give every luminaire a group.");
  return plan;
}

Rgb channel_colour(int k) {
  Rgb c;
  (k == 0 ? c.r : k == 1 ? c.g : c.b) = 1 / kWeights[static_cast<std::size_t>(k)];
  return c;
}

void assign_channels(std::vector<Luminaire>& luminaires, const ChannelPlan& plan) {
  for (Luminaire& l : luminaires) l.colour = channel_colour(plan.channel(l.group));
}

std::array<double, 3> channel_luminances(const Rgb& c) {
  return {kWeights[0] * c.r, kWeights[1] * c.g, kWeights[2] * c.b};
}

Rgb grey(const Rgb& c) {
  const double y = c.luminance();
  return Rgb(y, y, y);
}

std::array<double, 3> channel_levels(const LightScene& scene, const ChannelPlan& plan) {
  std::array<double, 3> levels = {1, 1, 1};
  for (const auto& [group, level] : scene.levels) {
    const int k = plan.channel(group);
    if (k >= 0) levels[static_cast<std::size_t>(k)] = level;
  }
  return levels;
}

SceneGrid scene_grid(const GridResult& channelled, const std::array<double, 3>& levels) {
  SceneGrid g;
  g.name = channelled.spec.name;
  double sum = 0;
  g.e_min = std::numeric_limits<double>::infinity();
  for (const GridPointResult& p : channelled.points) {
    if (p.masked) continue;
    const std::array<double, 3> y = channel_luminances(p.colour);
    const double e = levels[0] * y[0] + levels[1] * y[1] + levels[2] * y[2];
    ++g.count;
    sum += e;
    g.e_min = std::min(g.e_min, e);
    g.e_max = std::max(g.e_max, e);
  }
  if (g.count == 0) {
    g.e_min = 0;
    return g;
  }
  g.e_avg = sum / static_cast<double>(g.count);
  g.u0 = g.e_avg > 0 ? g.e_min / g.e_avg : 0;
  const GridSpec& s = channelled.spec;
  g.meets_target = (s.target_eavg <= 0 || g.e_avg >= s.target_eavg) && (s.target_u0 <= 0 || g.u0 >= s.target_u0);
  return g;
}

}  // namespace dynrad::rad
