// Triangulation of one planar polygon in its own plane (CGAL's constrained Delaunay
// triangulation), optionally with extra edges inside it. Used by cleanup (step 4) and by
// imprinting, which adds the lines where other surfaces meet the polygon.
#pragma once

#include "mesh/core/types.h"

#include <array>
#include <cstdint>
#include <vector>

namespace dynrad {

using Triangle = std::array<std::uint32_t, 3>;
using Segment = std::array<std::uint32_t, 2>;  // two point ids

// Triangulates the simple polygon `loop` (ids into `points`) in the plane through its
// corners with unit normal `normal`. Triangles are appended to `out`, counter-clockwise
// about `normal`. A corner repeated one after the other counts once. Without Steiner
// points: an n-gon gives n - 2 triangles. Returns false, appending nothing, when the
// loop intersects itself, has fewer than 3 corners, or two corners fall onto one point
// of the plane.
bool triangulate_polygon(const std::vector<Vec3d>& points, const std::vector<std::uint32_t>& loop, const Vec3d& normal,
                         std::vector<Triangle>& out);

// Triangulates again the flat region that `region` (triangles into `points`, in one
// plane, facing `normal`) covers, with the edges of `outline` (its boundary, possibly
// split at points on it) and `segments` (point id pairs inside it) as edges of the
// result. Where segments cross each other a new point is made: it is appended to
// `points`, on the plane through `plane_point` with unit normal `normal`. Triangles are
// appended to `out`, facing `normal`, and in `from` the index into `region` of the
// triangle that holds each. Returns false, appending nothing, when the new triangles
// do not cover the region's area (to 1e-9 relative): the caller keeps the old ones.
bool triangulate_region(std::vector<Vec3d>& points, const std::vector<Triangle>& region,
                        const std::vector<Segment>& outline, const std::vector<Segment>& segments, const Vec3d& normal,
                        const Vec3d& plane_point, std::vector<Triangle>& out, std::vector<std::uint32_t>& from);

// Twice the area vector of a closed loop (Newell's method): its direction is the
// loop's facing, robust for loops that are not quite planar.
Vec3d newell_normal(const std::vector<Vec3d>& points, const std::vector<std::uint32_t>& loop);

}  // namespace dynrad
