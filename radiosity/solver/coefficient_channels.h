// The coefficient channels a solve can carry beside its colours (annual daylight).
#pragma once

#include "mesh/core/types.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace dynrad::rad {

// Coefficient channels (Solver::carry_coefficients, solver_coefficients.cpp): `count`
// values per patch carried beside the colours, each the light of one part of the sky
// (climate/daylight_coefficients.h), so that one solve gives the interreflection of
// every sky.
// Every transfer is linear, so each channel moves as the luminance does: a patch that
// shoots sends its channels' unshot with the same factors as its luminance, a
// receiver takes them with the same form factor and reflectance. The solve itself
// (which patch shoots, where the mesh refines, when to stop) is steered by the colours,
// whose sky is a sum of the channels' with positive weights, so that it holds every
// channel's light. The sky's first shot splits a receiver's light into channels by
// `sky_mix` over the receiver (climate/coefficient_solve.cpp samples a few points):
// for channel j, the light there per unit of channel j over the light of the
// steering sky, both direct (so that the channels' light sums to the steering sky's
// with the weights; CoefficientChannels::relative tells the channels that are light of
// their own instead). Materials must be grey, the only source one sky luminaire
// (throws std::invalid_argument otherwise).
struct CoefficientChannels {
  std::size_t count = 0;
  // Channels from `relative` on (when below count) are not shares of the steering
  // sky's light but the light itself: sky_mix writes their irradiance per unit area,
  // which a receiver takes once, whatever the steering sky brought it (a sun's
  // light, with its sharp shadows, is not a share of the sky's on the same patch).
  std::size_t relative = SIZE_MAX;
  // Writes `count` values to `mix` for a receiving triangle (facing n; a point when its
  // corners are one).
  std::function<void(const std::array<Vec3d, 3>& surface, const Vec3d& n, float* mix)> sky_mix;
};

}  // namespace dynrad::rad
