// Light scenes: named dimming levels of the luminaires' control groups ("group" in the
// scene file), combined from one solve by superposition, since light is linear in its
// sources.
//
// How one solve keeps each group's light apart: the solver carries three channels (red,
// green, blue). With light scenes, every source is white and every material grey, so
// the channels do not mix; each group's luminaires then shoot into a channel of their
// own, scaled by 1 / (the channel's luminance weight) so that the luminance the solver
// steers by (refinement, error estimate) is the one of the scene with every group at
// full output. A group's light at a point is that channel's value times its weight; a
// scene's is the sum over groups times their levels. Light sources outside any group
// (and emitting surfaces) share a channel of their own, always at full output. So at
// most three channels: three groups, or two and the ungrouped sources.
//
// The scene file's top-level "scenes": [{"name": "evening", "levels": {"day": 0.3,
// "night": 1}}, ...], levels from 0 to 1; a group a scene does not list stays at 1.
#pragma once

#include "radiosity/analysis/grid.h"
#include "radiosity/sources/luminaire.h"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace dynrad::rad {

struct LightScene {
  std::string name;
  std::vector<std::pair<std::string, double>> levels;  // group, 0..1
};

// The channel each source's light goes to.
struct ChannelPlan {
  std::vector<std::string> channels;  // the group of each channel; "" for sources in none
  int channel(const std::string& group) const;  // -1 when none holds it
};

// "scenes" of the scene file; every group named must be some luminaire's. Empty when
// the scene has none. Throws InputError naming the file and the entry.
std::vector<LightScene> read_light_scenes(const std::string& scene_path, const std::vector<Luminaire>& luminaires);

// The channels for `luminaires` and, when `emitting_surfaces`, the model's own emitters.
// Throws InputError (naming the scene file) with more than three, or with daylight.
ChannelPlan plan_channels(const std::string& scene_path, const std::vector<Luminaire>& luminaires,
                          bool emitting_surfaces);

// Channel k alone, scaled to luminance 1.
Rgb channel_colour(int k);

// Sets every luminaire's colour to its group's channel colour.
void assign_channels(std::vector<Luminaire>& luminaires, const ChannelPlan& plan);

// The luminance each channel carries in a value of a channelled solve.
std::array<double, 3> channel_luminances(const Rgb& channelled);

// The value as a white-light solve gives it: its luminance in every channel.
Rgb grey(const Rgb& channelled);

// Each channel's level in `scene` (1 for groups it does not list and for "").
std::array<double, 3> channel_levels(const LightScene& scene, const ChannelPlan& plan);

// A grid's figures in one light scene, from its points gathered from the channelled
// solve (GridPointResult::colour).
struct SceneGrid {
  std::string name;
  std::size_t count = 0;
  double e_avg = 0, e_min = 0, e_max = 0, u0 = 0;
  bool meets_target = true;
};
SceneGrid scene_grid(const GridResult& channelled, const std::array<double, 3>& levels);

}  // namespace dynrad::rad
