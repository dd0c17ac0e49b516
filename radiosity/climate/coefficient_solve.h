// Daylight coefficients with interreflection, from one solve.
//
// The solve is steered by a uniform sky of luminance 1 over a ground of luminance
// `ground` (a sky that is the sum of every patch's, each at luminance 1, and of the
// ground's), and carries one coefficient channel per sky patch of `indirect` and one
// for the ground (Solver::carry_coefficients). After it, a patch holds its radiosity
// per unit luminance of each sky patch: the interreflected light of any sky is their
// sum weighted by its sky vector.
//
// At a point (point_coefficients):
//   direct: the sky's directions binned on the fine patches (direct_sky_coefficients);
//     the sun by a shadow ray per hour (sun_illuminance);
//   indirect: the gather of grid.h (cosine-weighted rays that take the radiosity where
//     they land), each ray taking the coefficients of the patch it lands on, scaled by
//     the steering sky's radiosity there over that patch's mean: the shape across the
//     patch from the refined mesh, the mix of skies from the patch.
// The sun's interreflected light has channels of its own, one per sun position: the
// nodes of a grid of altitude and azimuth (every `sun_spacing` degrees) around the
// hours' suns; an hour takes its sun's four nodes, bilinearly. (Through the Tregenza
// patch it lies in, as a patch of luminance E_n / (its solid angle), a sun low in a
// south window gave 10-25% too much interreflected light: the patch's 12 degrees meet
// the glass and an overhang at other angles than the sun. At the nearest of positions
// about 3 degrees apart, 3%: the overhang's shadow on the window moves 2% of its height
// per half degree.) A receiver takes a sun's light itself, not as a share of the
// steering sky's: its mean illuminance over sun_points x sun_points points, shadow
// rays and glass included.
// Channels: the indirect sky patches, the ground, then the sun positions.
#pragma once

#include "radiosity/climate/daylight_coefficients.h"
#include "radiosity/climate/sky_patches.h"
#include "radiosity/analysis/grid.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/solver/solver.h"

#include <array>
#include <memory>
#include <cstdint>
#include <vector>

namespace dynrad {
class SceneMesh;
}

namespace dynrad::rad {

struct LitScene;

struct CoefficientOptions {
  int fine_subdivision = 4;      // Reinhart MF:n of the direct coefficients at points (2305 patches)
  // MF:n of the solve's channels. (Tregenza's 145, MF:1, left interreflection under an
  // overcast sky 1.5% high: a patch's mean luminance weighs the horizon's band as much
  // as its top.)
  int indirect_subdivision = 2;
  int mix_side = 16;             // sky directions (side x side) per point splitting a patch's light into channels
  int point_side = 48;           // sky directions and indirect rays per grid point (GatherOptions::side)
  double sun_spacing = 6;        // degrees between sun positions, in altitude and in azimuth
  // The steering sky's ground luminance, relative to its sky's. (0.2, the ground of a
  // uniform sky, left hours whose ground outshines their sky 2% high deep in a room: a
  // ceiling lit through a window by the ground keeps the steering sky's shape, which is
  // the floor's reflection.)
  double steering_ground = 0.6;
  // The solve's patch size, times this: each patch keeps the steering sky's shape, so
  // the smaller they are the less it matters (a south room: 2.1% at the automatic 0.78 m,
  // 0.9% at 0.5 m).
  double patch_factor = 0.6;
  int sun_points = 6;            // sun_points^2 points per receiving patch for its share of each sun
};

// The steering sky's light from per-channel values (the sky's channels at luminance 1,
// the ground's at `ground`; the suns' after them are no part of it).
template <typename T>
double steering_light(const T* values, std::size_t sky_count, double ground) {
  double sum = 0;
  for (std::size_t j = 0; j + 1 < sky_count; ++j) sum += values[j];
  return sum + ground * values[sky_count - 1];
}

// An hour's sun as weights of up to four sun positions (index -1: none).
struct SunNodes {
  std::array<int, 4> position{-1, -1, -1, -1};
  std::array<float, 4> weight{0, 0, 0, 0};
};
// The sun positions for hours whose suns are `hour_suns` (unit; below the horizon:
// none): the grid nodes (altitude and azimuth in `frame`'s up and north, every
// `spacing` degrees) of the cells the suns lie in, in grid order. `nodes` receives
// each hour's.
std::vector<Vec3d> sun_positions(const SkyPatches& frame, double spacing, const std::vector<Vec3d>& hour_suns,
                                 std::vector<SunNodes>* nodes);

// The steering sky: uniform luminance 1 through `glazing` (the windows and openings),
// and the ground at `ground_luminance` (not 0, so that the ground's channel is carried).
Luminaire steering_sky(std::shared_ptr<const Glazing> glazing, const Vec3d& up, double ground_luminance);

// The channels for the solve (count: indirect.size() + 1 + suns.size()). `visibility`,
// `steering`, `indirect` and `suns` must outlive it.
Solver::CoefficientChannels coefficient_channels(const Visibility& visibility, const Luminaire& steering,
                                                 const SkyPatches& indirect, const std::vector<Vec3d>& suns,
                                                 const CoefficientOptions& options);

struct PointCoefficients {
  SkyCoefficients direct;     // on the fine patches, the ground last
  std::vector<float> indirect;  // per indirect patch, the ground, then per sun position
  bool masked = false;        // inside a solid (as GridPointResult::masked)
};

// A point's coefficients from a solved scene: `lit` the steering sky's lit scene (its
// triangles are `mesh`'s faces), `solver` the solve that carried the channels.
PointCoefficients point_coefficients(const LitScene& lit, const SceneMesh& mesh, const Solver& solver,
                                     const Luminaire& steering, const SkyPatches& fine, const SkyPatches& indirect,
                                     const Vec3d& point, const Vec3d& normal, const CoefficientOptions& options,
                                     std::uint64_t seed);

// One hour's sky for the coefficients: the sky vectors and the sun.
struct HourSky {
  std::vector<double> fine, indirect;  // sky_vector() of each (the ground last)
  Vec3d sun{0, 0, 1};
  double direct_normal = 0;  // lx; 0: no sun
  SunNodes nodes;            // its channels among the sun positions
};
// `sky` with its ground luminance set (its patches' means from 2 x 2 points each: the
// fine patches are 3 degrees, and the indirect ones their solid-angle-weighted means
// when they nest, as MF:2 in MF:4 do); the sun at `sun` (unit) with `direct_normal` lx,
// at sun positions `nodes` (none: then, should the sun shine, through its indirect
// patch as a patch of the same power).
HourSky hour_sky(const SkyModel& sky, const Vec3d& sun, double direct_normal, const SkyPatches& fine,
                 const SkyPatches& indirect, const SunNodes& nodes);

// Illuminance at a point for an hour; `sun_direct` its sun_illuminance().
struct HourIlluminance {
  double total = 0, sun = 0, sky_direct = 0, indirect = 0;
};
HourIlluminance hour_illuminance(const PointCoefficients& c, const HourSky& hour, double sun_direct);

}  // namespace dynrad::rad
