// Direct light, exact: each emitter's form factor from a point, by Lambert's contour
// integral over the part of it above the point's horizon, less the parts that boxes
// hide, cut out as polygons (box_tracer.cpp's opening comment has the method).
#include "reference/box_tracer_internal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace dynrad_test::reference::detail {
namespace {

// A convex polygon, at most kMaxVertices corners.
struct Polygon {
  static constexpr int kMaxVertices = 64;
  std::array<Vec3, kMaxVertices> v;
  int count = 0;
};

// The part of p on the side q.(y - x) >= 0 of the plane through x with normal q.
Polygon clip(const Polygon& p, const Vec3& x, const Vec3& q) {
  Polygon out;
  for (int i = 0; i < p.count; ++i) {
    const Vec3& a = p.v[i];
    const Vec3& b = p.v[(i + 1) % p.count];
    const double da = dot(q, a - x), db = dot(q, b - x);
    if (out.count + 2 > Polygon::kMaxVertices) throw std::length_error("box tracer: too many overlapping blockers");
    if (da >= 0) out.v[out.count++] = a;
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) out.v[out.count++] = a + (b - a) * (da / (da - db));
  }
  return out;
}

// Point-to-polygon form factor (dimensionless) from the differential area at x with
// unit normal n to polygon p, which lies above x's horizon: Lambert's contour
// integral. The sign, set by the polygon's orientation, is dropped.
double form_factor(const Polygon& p, const Vec3& x, const Vec3& n) {
  double sum = 0;
  for (int i = 0; i < p.count; ++i) {
    const Vec3 a = p.v[i] - x, b = p.v[(i + 1) % p.count] - x;
    const Vec3 c = cross(a, b);
    const double c_length = length(c);
    if (c_length == 0) continue;
    const double gamma = std::atan2(c_length, dot(a, b));  // angle between a and b
    sum += gamma * dot(n, c) / c_length;
  }
  return std::abs(sum) / (2 * kPi);
}

// The cone of points that box b hides from x, as half-spaces q.(y - x) >= 0: one plane
// through x and each silhouette edge of b (an edge between a face that x sees and one
// it does not). x inside b (no face seen): no planes, b hides everything.
struct ShadowCone {
  std::array<Vec3, 12> planes;
  int count = 0;
};

ShadowCone shadow_cone(const Bounds& b, const Vec3& x) {
  bool sees[3][2];  // x sees face (axis, side): it is on or in front of the face's plane
  for (int a = 0; a < 3; ++a) {
    sees[a][0] = x[a] <= b.lo[a];
    sees[a][1] = x[a] >= b.hi[a];
  }
  const Vec3 center = (b.lo + b.hi) * 0.5;
  ShadowCone cone;
  for (int a = 0; a < 3; ++a) {  // edges along axis a, where faces of axes u and v meet
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    for (int su = 0; su < 2; ++su)
      for (int sv = 0; sv < 2; ++sv) {
        if (sees[u][su] == sees[v][sv]) continue;
        Vec3 p0, p1;
        p0[u] = p1[u] = su ? b.hi[u] : b.lo[u];
        p0[v] = p1[v] = sv ? b.hi[v] : b.lo[v];
        p0[a] = b.lo[a];
        p1[a] = b.hi[a];
        Vec3 q = cross(p0 - x, p1 - x);
        if (dot(q, q) == 0) continue;  // x in line with the edge: its neighbours bound the cone
        if (dot(q, center - x) < 0) q = q * -1.0;
        cone.planes[cone.count++] = q;
      }
  }
  return cone;
}

// Cone c covers all of polygon p.
bool covers(const ShadowCone& c, const Polygon& p, const Vec3& x) {
  for (int k = 0; k < c.count; ++k)
    for (int i = 0; i < p.count; ++i)
      if (dot(c.planes[k], p.v[i] - x) < 0) return false;
  return true;
}

// Form factor from x (normal n) to the part of polygon p outside cones[first...].
double unblocked_form_factor(const Polygon& p, const std::vector<ShadowCone>& cones, std::size_t first, const Vec3& x,
                             const Vec3& n) {
  for (std::size_t j = first; j < cones.size(); ++j)
    if (covers(cones[j], p, x)) return 0;  // the common case in a shadow: no integral
  double f = form_factor(p, x, n);
  for (std::size_t j = first; j < cones.size(); ++j) {
    Polygon hidden = p;
    for (int k = 0; k < cones[j].count && hidden.count >= 3; ++k) hidden = clip(hidden, x, cones[j].planes[k]);
    if (hidden.count >= 3) f -= unblocked_form_factor(hidden, cones, j + 1, x, n);
  }
  return f;
}

// Form factor from x (unit normal n) to the part of emitter e that x sees.
double visible_form_factor(const Scene& scene, const EmitterInfo& e, const Vec3& x, const Vec3& n) {
  const double height = (x[e.axis] - e.plane) * e.sign;  // x above the emitter's front
  if (!(height > 0)) return 0;
  const int u = (e.axis + 1) % 3, v = (e.axis + 2) % 3;
  Polygon p;
  p.count = 4;
  for (int k = 0; k < 4; ++k) {
    p.v[k][e.axis] = e.plane;
    p.v[k][u] = (k == 1 || k == 2) ? e.hi[u] : e.lo[u];
    p.v[k][v] = (k >= 2) ? e.hi[v] : e.lo[v];
  }
  p = clip(p, x, n);  // above x's horizon
  if (p.count < 3) return 0;

  Bounds hull{x, x};  // of x and what it may see of the emitter
  for (int k = 0; k < p.count; ++k)
    for (int c = 0; c < 3; ++c) {
      hull.lo[c] = std::min(hull.lo[c], p.v[k][c]);
      hull.hi[c] = std::max(hull.hi[c], p.v[k][c]);
    }
  // A box can hide part of the emitter only if it reaches strictly between the two
  // planes (emitter's and x's, along the emitter's axis) and into the hull's box; only
  // that slice of it matters.
  std::vector<ShadowCone> cones;
  const double near = std::min(e.plane, x[e.axis]), far = std::max(e.plane, x[e.axis]);
  auto add_blocker = [&](const Bounds& b) {
    if (!(b.lo[e.axis] < far && b.hi[e.axis] > near)) return;
    for (int c = 0; c < 3; ++c) {
      if (c != e.axis && !(b.lo[c] < hull.hi[c] && b.hi[c] > hull.lo[c])) return;
      if (b.lo[c] == b.hi[c] && x[c] == b.lo[c]) return;  // a wall in a plane through x
    }
    Bounds slice = b;
    slice.lo[e.axis] = std::max(b.lo[e.axis], near);
    slice.hi[e.axis] = std::min(b.hi[e.axis], far);
    cones.push_back(shadow_cone(slice, x));
  };
  for (const BoxScene::Box& box : scene.boxes) {
    if (!box.room) {
      add_blocker({box.lo, box.hi});
      continue;
    }
    bool hull_inside = true;  // then the room's faces hide nothing
    for (int c = 0; c < 3; ++c) hull_inside = hull_inside && box.lo[c] <= hull.lo[c] && hull.hi[c] <= box.hi[c];
    if (hull_inside) continue;
    for (int f = 0; f < 6; ++f) {  // each face as a box of zero thickness
      const int a = axis_of(static_cast<Face>(f));
      Bounds wall{box.lo, box.hi};
      wall.lo[a] = wall.hi[a] = on_plus_side(static_cast<Face>(f)) ? box.hi[a] : box.lo[a];
      add_blocker(wall);
    }
  }
  return std::max(0.0, unblocked_form_factor(p, cones, 0, x, n));
}

}  // namespace

// Direct irradiance (W/m^2) at x, unit normal n, from every emitter.
double direct(const Scene& scene, const Vec3& x, const Vec3& n) {
  double h = 0;
  for (const EmitterInfo& e : scene.emitters)
    if (e.exitance > 0) h += e.exitance * visible_form_factor(scene, e, x, n);
  return h;
}

}  // namespace dynrad_test::reference::detail
