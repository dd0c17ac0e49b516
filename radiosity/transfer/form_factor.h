// Point-to-polygon form factors (no occlusion): the fraction of the power leaving a
// Lambertian polygon that arrives at a small area at a point, equivalently the
// polygon's share of the point's cosine-weighted hemisphere.
#pragma once

#include "mesh/core/types.h"

#include <array>
#include <cmath>

namespace dynrad::rad {

// Form factor from a differential area at `x` with unit normal `n` to a convex polygon
// (`count` <= 8 corners, counter-clockwise seen from its front, unit front normal
// `front`). Lambert's contour integral over the part of the polygon above x's tangent
// plane (the rest cannot reach x). Zero when x lies behind the polygon's plane: a
// polygon sends light only from its front.
double point_to_polygon(const Vec3d& x, const Vec3d& n, const Vec3d* corners, int count, const Vec3d& front);

// The sum over the four parts of a triangle cut at its edge midpoints of weight[s]
// times the form factor from x to part s: parts 0-2 the corner triangles (corner s and
// the midpoints of its two edges), part 3 the middle one. The parts share their inner
// edges, whose Lambert terms cancel between neighbours of equal weight, so where no part
// needs clipping at x's horizon this takes nine edge terms instead of four polygons'
// twelve; otherwise it sums the four polygons. `corners` counter-clockwise seen from
// the front, as for point_to_polygon.
double point_to_quartered_triangle(const Vec3d& x, const Vec3d& n, const Vec3d* corners, const double* weight,
                                   const Vec3d& front);

// A triangle cut into kTriangleParts = 16 equal parts: its edges in quarters, the grid
// lines through the cuts parallel to the edges. Nodes are c0 + i/4 (c1 - c0) + j/4
// (c2 - c0) for i + j <= 4; the parts (each counter-clockwise when the triangle is)
// are first the ten with a corner's orientation, (i, j), (i + 1, j), (i, j + 1) for
// i + j <= 3, then the six turned over, (i + 1, j), (i + 1, j + 1), (i, j + 1) for
// i + j <= 2, each in order of i then j.
inline constexpr int kTriangleParts = 16;
void triangle_parts(const Vec3d* corners, Vec3d (*parts)[3]);
// Per part, the indices of its three nodes in the order (i, j) by i then j.
const std::array<std::array<int, 3>, kTriangleParts>& triangle_part_nodes();
inline constexpr int kTriangleNodes = 15;
// The grid's nodes, c0 + i/4 (c1 - c0) + j/4 (c2 - c0), in the order (i, j) by i then j,
// the corners exactly: node[kGridCorners[k]] is corners[k].
void triangle_nodes(const Vec3d* corners, Vec3d* node);
inline constexpr int kGridCorners[3] = {0, 14, 4};
// The grid's nodes that are neither corners nor edge midpoints, each with the two of
// those it lies halfway between: {node, end, end}.
inline constexpr int kGridHalfway[9][3] = {{5, 0, 9},    {12, 9, 14}, {1, 0, 2},  {3, 2, 4}, {6, 9, 2},
                                           {13, 14, 11}, {8, 11, 4},  {10, 9, 11}, {7, 2, 11}};
// The four parts cut at the edge midpoints (point_to_quartered_triangle's), by their
// corner nodes: the corner parts of corners 0, 1 and 2, then the middle one.
inline constexpr int kMidpointParts[4][3] = {{0, 9, 2}, {9, 14, 11}, {2, 11, 4}, {9, 11, 2}};

// The sum over triangle_parts() of weight[s] times the form factor from x to part s
// (`corners` counter-clockwise seen from the front, as for point_to_polygon). The parts
// wholly above x's horizon by one Lambert term per grid edge they bound (30 at most):
// an edge two of them share is walked once each way, so it counts for the difference
// of their weights and cancels where they are equal. Parts across the horizon are
// clipped, each on its own; parts below it add nothing.
double point_to_parted_triangle(const Vec3d& x, const Vec3d& n, const Vec3d* corners, const double* weight,
                                const Vec3d& front);

// The point-to-area approximation: a polygon of `area` around `centre` (unit front
// normal `front`) seen from x as if it were a differential area, A cos cos / (pi r^2).
// Its error relative to the exact form factor is of order (R / r)^2, R the polygon's
// radius and r its distance; no clipping at x's horizon (the caller checks that none is
// needed). Zero when either side faces away.
inline double point_to_area(const Vec3d& x, const Vec3d& n, const Vec3d& centre, const Vec3d& front, double area) {
  const Vec3d d = centre - x;
  const double r2 = d.sqrnorm(), cos_x = OpenMesh::dot(n, d), cos_s = -OpenMesh::dot(front, d);
  if (!(cos_x > 0 && cos_s > 0 && r2 > 0)) return 0.0;
  return area * cos_x * cos_s / (M_PI * r2 * r2);
}

// std::atan2(y, x) for y >= 0 (the angle between two directions from the length of
// their cross product and their dot product), within 1e-14, faster.
double angle_between(double y, double x);

inline double point_to_triangle(const Vec3d& x, const Vec3d& n, const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                const Vec3d& front) {
  const Vec3d corners[3] = {a, b, c};
  return point_to_polygon(x, n, corners, 3, front);
}

}  // namespace dynrad::rad
