// The sky and the sun as sources (see daylight.h).
#include "radiosity/daylight.h"

#include "mesh/load.h"
#include "mesh/ray_cast.h"
#include "radiosity/luminaire.h"
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
  // The sky: stratified cosine-weighted directions about n, the same for every point.
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
  // (u, v) in [0, 1)^2 to a direction: r = sqrt(u), phi = 2 pi v, cosine-weighted: equal
  // areas of (u, v) carry equal shares of pi.
  auto direction = [&](double u, double v) {
    const double r = std::sqrt(u), phi = 2 * M_PI * v;
    return (t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - u))).normalized();
  };
  struct Sample {
    double seen = 0, below = 0;
    int code = -1;  // -1 blocked; else the transmittance it crossed, in millionths
  };
  auto sample = [&](double u, double v) {
    Sample out;
    const Vec3d d = direction(u, v);
    const double L = day.sky.luminance(d);
    if (visibility->trace(x, n, d) != Visibility::Hit::nothing) return out;
    const double through = day.glazing ? day.glazing->along(x, d) : 1.0;
    const bool under = OpenMesh::dot(d, day.sky.up) <= 0;
    out.seen = L * through;
    out.below = under ? out.seen : 0.0;
    out.code = static_cast<int>(std::lround(through * 1e6));
    return out;
  };
  // The unobstructed sum: computed once per normal (the cache above), not again for
  // every point that asks with rays.
  double open = 0;
  if (visibility) {
    open = daylight_illuminance(nullptr, l, x, n, nullptr, k) / (M_PI / (static_cast<double>(k) * k));
  } else {
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) open += day.sky.luminance(direction((i + 0.5) / k, (j + 0.5) / k));
  }
  double seen = 0, below = 0;
  if (visibility) {
    // Stratum centres first. Where a stratum's neighbour (v wraps around) sees otherwise
    // (an opening's edge, a pane's), it is evaluated again with 8 x 8 sub-strata: the
    // edges of what the point sees are resolved 8 times finer than the rest, where most
    // of the error of the centres is. (The horizon, where the sky's luminance steps to
    // the ground's, is left to the centres: refining it would double the rays of every
    // point that sees it, for a fraction of a percent.)
    std::vector<Sample> grid(static_cast<std::size_t>(k) * k);
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) grid[static_cast<std::size_t>(i * k + j)] = sample((i + 0.5) / k, (j + 0.5) / k);
    const int m = 8;
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) {
        const Sample& c = grid[static_cast<std::size_t>(i * k + j)];
        bool edge = false;
        for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
          const int i2 = i + di, j2 = (j + dj + k) % k;
          if (i2 < 0 || i2 >= k) continue;
          edge = edge || grid[static_cast<std::size_t>(i2 * k + j2)].code != c.code;
        }
        if (!edge) {
          seen += c.seen;
          below += c.below;
          continue;
        }
        double sub_seen = 0, sub_below = 0;
        for (int a = 0; a < m; ++a)
          for (int e = 0; e < m; ++e) {
            const Sample s = sample((i + (a + 0.5) / m) / k, (j + (e + 0.5) / m) / k);
            sub_seen += s.seen;
            sub_below += s.below;
          }
        seen += sub_seen / (m * m);
        below += sub_below / (m * m);
      }
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
