// The sky and the sun as sources (see daylight.h).
#include "radiosity/daylight.h"

#include "mesh/load.h"
#include "mesh/ray_cast.h"
#include "radiosity/luminaire.h"
#include "radiosity/random.h"
#include "radiosity/visibility.h"

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

namespace {

std::vector<Vec3d> glazing_points(const std::vector<GlazingTriangle>& triangles) {
  std::vector<Vec3d> points;
  for (const GlazingTriangle& t : triangles)
    for (const Vec3d& c : t.corners) points.push_back(c);
  return points;
}

std::vector<std::array<std::uint32_t, 3>> glazing_indices(std::size_t count) {
  std::vector<std::array<std::uint32_t, 3>> out(count);
  for (std::size_t i = 0; i < count; ++i)
    out[i] = {static_cast<std::uint32_t>(3 * i), static_cast<std::uint32_t>(3 * i + 1), static_cast<std::uint32_t>(3 * i + 2)};
  return out;
}

}  // namespace

Glazing::Glazing(const std::vector<GlazingTriangle>& triangles) {
  for (const GlazingTriangle& t : triangles) {
    corners_.push_back(t.corners);
    transmittance_.push_back(t.transmittance.luminance());
  }
  if (!triangles.empty())
    caster_ = std::make_unique<RayCaster>(glazing_points(triangles), glazing_indices(triangles.size()));
}

Glazing::~Glazing() = default;

double Glazing::along(const Vec3d& origin, const Vec3d& direction) const {
  if (!caster_) return 1;
  double t = 1;
  Vec3d o = origin;
  // Each pane crossed, nearest first; the ray restarts just past it (a pane met twice,
  // as both faces of a thick glass model, counts twice).
  for (int crossing = 0; crossing < 16; ++crossing) {
    const long hit = caster_->first_hit(o, direction);
    if (hit < 0) break;
    const auto& c = corners_[static_cast<std::size_t>(hit)];
    const Vec3d n = OpenMesh::cross(c[1] - c[0], c[2] - c[0]);
    const double denominator = OpenMesh::dot(n, direction);
    if (denominator == 0) break;
    const double distance = OpenMesh::dot(n, c[0] - o) / denominator;
    t *= transmittance_[static_cast<std::size_t>(hit)];
    if (!(t > 0)) return 0;
    const double size = std::max({(c[1] - c[0]).norm(), (c[2] - c[0]).norm(), 1e-300});
    o += direction * (std::max(distance, 0.0) + 1e-6 * size);
  }
  return t;
}

double daylight_illuminance(const Visibility* visibility, const Luminaire& l, const Vec3d& x, const Vec3d& n,
                            double* unoccluded, int side, double* ground) {
  const Daylight& day = *l.daylight;
  if (ground) *ground = 0;
  if (l.kind == Luminaire::Kind::sun) {
    const double c = OpenMesh::dot(n, day.sun);
    const double open = c > 0 ? day.direct_normal * c : 0.0;
    if (unoccluded) *unoccluded = open;
    if (!visibility || open <= 0) return open;
    if (visibility->trace(x, n, day.sun) != Visibility::Hit::nothing) return 0;
    return open * (day.glazing ? day.glazing->along(x, day.sun) : 1.0);
  }
  // The sky: stratified cosine-weighted directions about n, one jitter per source.
  const int k = side > 0 ? side : day.side;
  // Unobstructed, the value depends on n alone: remembered per normal (the solver asks
  // for it at every edge midpoint and centroid it examines).
  const auto key = std::make_tuple(std::llround(n[0] * 1e9), std::llround(n[1] * 1e9), std::llround(n[2] * 1e9), k);
  if (!visibility) {
    std::lock_guard<std::mutex> lock(day.cache_mutex);
    const auto found = day.unobstructed.find(key);
    if (found != day.unobstructed.end()) {
      if (unoccluded) *unoccluded = found->second;
      return found->second;
    }
  }
  const Vec3d t = OpenMesh::cross(std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0), n).normalized();
  const Vec3d b = OpenMesh::cross(n, t);
  std::uint64_t state = mix(day.seed ^ 0x5C1D0000ull);
  double open = 0, seen = 0, below = 0;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const double u = (i + uniform(state)) / k, v = (j + uniform(state)) / k;
      const double r = std::sqrt(u), phi = 2 * M_PI * v;
      const Vec3d d = (t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - u))).normalized();
      const double L = day.sky.luminance(d);
      if (!(L > 0)) continue;
      open += L;
      if (!visibility) continue;
      if (visibility->trace(x, n, d) != Visibility::Hit::nothing) continue;
      const double through = L * (day.glazing ? day.glazing->along(x, d) : 1.0);
      seen += through;
      if (OpenMesh::dot(d, day.sky.up) <= 0) below += through;
    }
  const double scale = M_PI / (static_cast<double>(k) * k);
  if (unoccluded) *unoccluded = open * scale;
  if (!visibility) {
    std::lock_guard<std::mutex> lock(day.cache_mutex);
    day.unobstructed.emplace(key, open * scale);
    return open * scale;
  }
  if (ground) *ground = below * scale;
  return seen * scale;
}

}  // namespace dynrad::rad
