// Triangulation of one planar polygon in its own plane (CGAL's constrained Delaunay
// triangulation), optionally with extra edges inside it. Used by cleanup (step 4) and by
// imprinting, which adds the lines where other surfaces meet the polygon.
#pragma once

#include "mesh/types.h"

#include <array>
#include <cstdint>
#include <vector>

namespace dynrad {

using Triangle = std::array<std::uint32_t, 3>;
using Segment = std::array<std::uint32_t, 2>;  // two point ids

// Triangulates the simple polygon `loop` (ids into `points`) in the plane through its
// corners with unit normal `normal`. Triangles are appended to `out`, counter-clockwise
// about `normal`. Without Steiner points: an n-gon gives n - 2 triangles. Returns false,
// appending nothing, when the loop intersects itself or two corners fall onto one point
// of the plane.
bool triangulate_polygon(const std::vector<Vec3d>& points, const std::vector<std::uint32_t>& loop,
                         const Vec3d& normal, std::vector<Triangle>& out);

// The same with `segments` (point id pairs, their ends on or inside the polygon) as
// edges of the result. Where segments cross each other a new point is made: it is
// appended to `points`, on the plane through `plane_point` with unit normal `normal`.
// Triangles outside the loop are dropped. Returns false, appending nothing, when the
// triangles made do not cover the polygon's area (to 1e-9 relative): the caller keeps
// its old triangulation.
bool triangulate_polygon_with_segments(std::vector<Vec3d>& points, const std::vector<std::uint32_t>& loop,
                                       const Vec3d& normal, const Vec3d& plane_point,
                                       const std::vector<Segment>& segments, std::vector<Triangle>& out);

// Twice the area vector of a closed loop (Newell's method): its direction is the
// loop's facing, robust for loops that are not quite planar.
Vec3d newell_normal(const std::vector<Vec3d>& points, const std::vector<std::uint32_t>& loop);

}  // namespace dynrad
