// Point-to-polygon form factors (no occlusion): the fraction of the power leaving a
// Lambertian polygon that arrives at a small area at a point, equivalently the
// polygon's share of the point's cosine-weighted hemisphere.
#pragma once

#include "mesh/types.h"

namespace dynrad::rad {

// Form factor from a differential area at `x` with unit normal `n` to a convex polygon
// (`count` <= 8 corners, counter-clockwise seen from its front, unit front normal
// `front`). Lambert's contour integral over the part of the polygon above x's tangent
// plane (the rest cannot reach x). Zero when x lies behind the polygon's plane: a
// polygon sends light only from its front.
double point_to_polygon(const Vec3d& x, const Vec3d& n, const Vec3d* corners, int count, const Vec3d& front);

// std::atan2(y, x) for y >= 0 (the angle between two directions from the length of
// their cross product and their dot product), within 1e-14, faster.
double angle_between(double y, double x);

inline double point_to_triangle(const Vec3d& x, const Vec3d& n, const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                const Vec3d& front) {
  const Vec3d corners[3] = {a, b, c};
  return point_to_polygon(x, n, corners, 3, front);
}

}  // namespace dynrad::rad
