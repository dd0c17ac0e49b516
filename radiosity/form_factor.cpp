#include "radiosity/form_factor.h"

#include <cmath>

namespace dynrad::rad {

double point_to_polygon(const Vec3d& x, const Vec3d& n, const Vec3d* corners, int count, const Vec3d& front) {
  if (OpenMesh::dot(front, x - corners[0]) <= 0) return 0.0;  // x is behind the sender

  // Clip to x's upper hemisphere: keep the part with (p - x) . n >= 0 (Sutherland-Hodgman
  // against one plane; a convex polygon gains at most one corner).
  Vec3d clipped[9];
  int m = 0;
  for (int i = 0; i < count; ++i) {
    const Vec3d& p = corners[i];
    const Vec3d& q = corners[(i + 1) % count];
    const double dp = OpenMesh::dot(p - x, n), dq = OpenMesh::dot(q - x, n);
    if (dp >= 0) clipped[m++] = p;
    if ((dp >= 0) != (dq >= 0)) clipped[m++] = p + (q - p) * (dp / (dp - dq));
  }
  if (m < 3) return 0.0;

  // Lambert: F = 1/(2 pi) sum_i gamma_i n . (R_i x R_i+1) / |R_i x R_i+1|, with gamma_i
  // the angle between the directions R_i, R_i+1 from x to consecutive corners.
  double sum = 0;
  for (int i = 0; i < m; ++i) {
    const Vec3d r0 = clipped[i] - x;
    const Vec3d r1 = clipped[(i + 1) % m] - x;
    const Vec3d c = OpenMesh::cross(r0, r1);
    const double length = c.norm();
    if (length <= 0) continue;  // x on the line of this edge: it subtends no angle
    const double gamma = std::atan2(length, OpenMesh::dot(r0, r1));
    sum += gamma * OpenMesh::dot(n, c) / length;
  }
  return std::abs(sum) / (2.0 * M_PI);
}

}  // namespace dynrad::rad
