// Calculation grids: illuminance at points in mid-air (a work plane), as lighting
// designers read it, gathered from a solved scene.
//
// A grid is a polygon in a horizontal plane at a height above the model's floor level
// (the plane of the two axes other than `up`), cut into square cells of a spacing
// (EN 12464-1's automatic rule p = 0.2 x 5^log10(d), d the longer side of the polygon's
// bounding rectangle, at most 10 m), with a point at the centre of every cell whose
// centre lies inside the polygon and at least `border` from its edges.
//
// At each point, facing up, the illuminance is gathered:
//   direct, exact: each luminaire's I(C, gamma) cos(theta) / d^2 with a shadow ray (its
//     opening sampled when near: luminaire_illuminance), and each emitting triangle's
//     exitance times Lambert's closed form to it times the fraction of 16 seeded rays
//     that reach it;
//   indirect: the solved radiosity seen over the hemisphere, B - emission at the first
//     surface each ray meets, by stratified cosine-weighted rays (seeded: the same
//     answer for any thread count); the mean of B over cosine-weighted directions is the
//     illuminance it gives.
// A point inside a solid (most of 6 axis rays meet the backs of faces) is masked: no
// value, counted.
#pragma once

#include "mesh/core/default_seed.h"
#include "radiosity/analysis/lit_scene.h"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dynrad::rad {

// EN 12464-1:2021 requirements of the room a grid's task area lies in, beyond the task
// area's own Eavg and U0 (design/room_checks.h evaluates them); every one off unless the
// scene file's "target" asks for it. Defaults are the standard's general values.
struct RoomTargets {
  // The immediate surrounding: a band this wide just outside the task area, inside the
  // polygon (between border - surrounding and border from its edges). 0: not checked.
  double surrounding = 0;
  double surrounding_eavg = 0;  // 0: from the task's target by EN 12464-1's table
  double surrounding_u0 = 0.4;
  // Walls and ceiling of the room (the polygon raised from the floor to the ceiling).
  bool walls = false, ceiling = false;
  double walls_eavg = 75, walls_u0 = 0.1, ceiling_eavg = 50, ceiling_u0 = 0.1;
  // Mean cylindrical illuminance over the task area at `ez_height` above the floor
  // (1.2 m seated, 1.6 m standing), its uniformity, and modelling Ez / Eh within
  // [modelling_low, modelling_high]. 0: not checked.
  double ez = 0, ez_u0 = 0.1, ez_height = 1.2, modelling_low = 0.3, modelling_high = 0.6;
  // UGR limit for the observers standing in the room. 0: not checked.
  double ugr = 0;
  bool any() const { return surrounding > 0 || walls || ceiling || ez > 0 || ugr > 0; }
};

// The surrounding's Em for a task's by EN 12464-1's table: 500 lx for tasks of 750 lx
// and above, 300 for 500, 200 for 300, 150 for 200, and the task's own below that.
double surrounding_illuminance(double task_eavg);

struct GridSpec {
  std::string name;
  std::vector<std::array<double, 2>> polygon;  // in the plane's axes (x, y for z up), counter-clockwise or not
  double height = 0.8;    // along `up`, model units
  double spacing = 0;     // model units; 0: the automatic rule (metres assumed)
  double border = 0;      // band along the edges left out
  int up = 2;             // axis: 0 x, 1 y, 2 z
  // Requirements to check (0: none): the average illuminance at least target_eavg,
  // U0 at least target_u0.
  double target_eavg = 0, target_u0 = 0;
  RoomTargets room;
};

// The automatic spacing for a longer side d: 0.2 x 5^log10(d), at most 10.
double automatic_spacing(double longer_side);

// Whether (x, y) lies inside `polygon` (even-odd rule).
bool inside_polygon(const std::vector<std::array<double, 2>>& polygon, double x, double y);

// Shortest distance from (x, y) to the polygon's edges.
double polygon_edge_distance(const std::vector<std::array<double, 2>>& polygon, double x, double y);

// The cells: nx x ny over the rectangle [x0, x0 + nx w] x [y0, y0 + ny h] (the polygon's
// bounding rectangle less the border), in the plane's two axes.
struct GridCells {
  long nx = 0, ny = 0;
  double x0 = 0, y0 = 0, w = 0, h = 0;
};

// Cell centres of `spec` (before masking), in row order; `cells` gets each point's
// (i, j) and `layout` the cells.
std::vector<Vec3d> grid_points(const GridSpec& spec, double* spacing_used = nullptr,
                               std::vector<std::array<long, 2>>* cells = nullptr, GridCells* layout = nullptr);

// The solved radiosity where a ray met a face, interpolated from its corners.
Rgb radiosity_at(const LitScene& scene, const Visibility::Intersection& hit);

// The indirect part of a gather: side x side stratified cosine-weighted rays about
// `normal` from a hair above `point` (jittered from `state`); `on_hit` receives each that
// lands on a front face. Returns the number of rays cast (the divisor of the mean).
int gather_rays(const LitScene& scene, const Vec3d& point, const Vec3d& normal, int side, std::uint64_t& state,
                const std::function<void(const Visibility::Intersection&)>& on_hit);

// Whether `point` lies inside a solid: most of six rays along the axes meet the backs of
// faces (grid points there are masked).
bool inside_solid(const Visibility& visibility, const Vec3d& point);

struct GatherOptions {
  // Indirect rays per point: side x side strata of the cosine-weighted hemisphere.
  // 48 x 48 = 2304 gives about 0.5% noise (one standard deviation) on the indirect
  // part in a room of even walls (tests/grid_test.cpp measures it).
  int side = 48;
  int emitter_rays = 16;   // per emitting triangle and point
  std::uint64_t seed = default_seed();
};

struct GridPointResult {
  Vec3d position;
  std::array<long, 2> cell{0, 0};  // (i, j) in GridResult::cells
  bool masked = false;      // inside a solid
  double illuminance = 0;   // direct + indirect, luminance-weighted (lx or W/m^2)
  double direct = 0, indirect = 0;
  Rgb colour;               // direct + indirect per channel (illuminance is its luminance)
  // Of `direct`, what the sky gives from above the horizon (sky component) and from
  // below it (the ground outside: externally reflected), lx.
  double sky = 0, ground = 0;
};

// Figures over a set of gathered points, the masked ones left out and counted: average,
// minimum, maximum and U0 = Emin / Eavg (all 0 with no point).
struct PointStatistics {
  std::size_t count = 0, masked = 0;
  double e_avg = 0, e_min = 0, e_max = 0, u0 = 0;
};
PointStatistics point_statistics(const std::vector<GridPointResult>& points);

// The point statistics (count, masked, e_avg, e_min, e_max, u0) are over its points.
struct GridResult : PointStatistics {
  GridSpec spec;
  double spacing = 0;
  GridCells cells;
  std::vector<GridPointResult> points;
  double min_over_max = 0;  // Emin / Emax over the unmasked points
  int indirect_rays = 0;  // per point
  // With a sky: its unobstructed horizontal illuminance (lx) and the daylight factors
  // over the unmasked points, DF = 100 E / outside (%): average, minimum, maximum, and
  // the average's three parts: sky component, externally reflected (the ground seen
  // through openings) and internally reflected (everything the solution's surfaces
  // send, reflections from outside obstructions included). All 0 unless the sky is
  // the only source.
  double outside = 0;
  double df_avg = 0, df_min = 0, df_max = 0;
  double sky_component = 0, externally_reflected = 0, internally_reflected = 0;
  // Whether the spec's targets are met (true when it has none).
  bool meets_target() const {
    return (spec.target_eavg <= 0 || e_avg >= spec.target_eavg) && (spec.target_u0 <= 0 || u0 >= spec.target_u0);
  }
};

// The cylindrical illuminance at `point` about the axis `up` (EN 12464-1's Ez: the mean
// of the vertical illuminance over all directions around): luminaires and the sun exact
// (I sin(theta) / (pi d^2), one shadow ray, openings sampled as for grids), a sky as
// the mean of eight vertical illuminances, surfaces by side x side stratified
// directions uniform over the sphere. In `illuminance`, split into direct and indirect.
GridPointResult gather_cylindrical(const LitScene& scene, const Vec3d& point, const Vec3d& up,
                                   const GatherOptions& options, std::uint64_t point_seed);

GridResult gather_grid(const LitScene& scene, const GridSpec& spec, const GatherOptions& options = {});
// Each of `specs`, in order.
std::vector<GridResult> gather_grids(const LitScene& scene, const std::vector<GridSpec>& specs,
                                     const GatherOptions& options = {});

// The illuminance at one point facing `normal` (for tests and probes): direct and
// indirect as above. `masked` is set when the point is inside a solid.
GridPointResult gather_point(const LitScene& scene, const Vec3d& point, const Vec3d& normal,
                             const GatherOptions& options, std::uint64_t point_seed);

}  // namespace dynrad::rad
