// The sky and the sun as sources (see daylight.h).
#include "radiosity/sources/daylight.h"

#include "mesh/load.h"
#include "mesh/core/ray_cast.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/transfer/visibility.h"

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

namespace {

std::vector<Vec3d> pane_points(const std::vector<std::array<Vec3d, 3>>& panes) {
  std::vector<Vec3d> points;
  for (const auto& t : panes)
    for (const Vec3d& c : t) points.push_back(c);
  return points;
}

std::vector<std::array<std::uint32_t, 3>> pane_indices(std::size_t count) {
  std::vector<std::array<std::uint32_t, 3>> out(count);
  for (std::size_t i = 0; i < count; ++i)
    out[i] = {static_cast<std::uint32_t>(3 * i), static_cast<std::uint32_t>(3 * i + 1), static_cast<std::uint32_t>(3 * i + 2)};
  return out;
}

// Distance along `direction` from `origin` to the plane of triangle c (negative behind).
double plane_distance(const std::array<Vec3d, 3>& c, const Vec3d& origin, const Vec3d& direction) {
  const Vec3d n = OpenMesh::cross(c[1] - c[0], c[2] - c[0]);
  const double denominator = OpenMesh::dot(n, direction);
  return denominator == 0 ? -1 : OpenMesh::dot(n, c[0] - origin) / denominator;
}

// A triangle seen from a point, as the spherical triangle of unit directions (a, b, c)
// to its corners, and Arvo's (1995) map from the unit square onto it, uniform in solid
// angle: the first coordinate picks the share of the area cut off along the edge from
// a, the second the point along the arc from b.
struct SphericalTriangle {
  Vec3d a, b, c;
  double area = 0;  // solid angle (sr)
  double alpha = 0, cos_alpha = 1, sin_alpha = 0, cos_ab = 1;
  Vec3d c_off_a;    // the unit tangent at a towards c

  SphericalTriangle(const Vec3d& a_, const Vec3d& b_, const Vec3d& c_) : a(a_), b(b_), c(c_) {
    // Van Oosterom and Strackee's solid angle: tan(area / 2) = |a.(b x c)| / (1 + a.b + b.c + c.a).
    area = 2 * std::atan2(std::abs(OpenMesh::dot(a, OpenMesh::cross(b, c))),
                          1 + OpenMesh::dot(a, b) + OpenMesh::dot(b, c) + OpenMesh::dot(c, a));
    const Vec3d to_b = b - a * OpenMesh::dot(a, b);
    const Vec3d to_c = c - a * OpenMesh::dot(a, c);
    if (!(to_b.norm() > 0) || !(to_c.norm() > 0)) {
      area = 0;
      return;
    }
    c_off_a = to_c.normalized();
    cos_alpha = std::clamp(OpenMesh::dot(to_b.normalized(), c_off_a), -1.0, 1.0);
    alpha = std::acos(cos_alpha);
    sin_alpha = std::sin(alpha);
    cos_ab = OpenMesh::dot(a, b);
  }

  Vec3d sample(double u, double v) const {
    const double cut = u * area - alpha;  // the cut-off part's area, less alpha
    const double s = std::sin(cut), t = std::cos(cut);
    const double p = t - cos_alpha, q = s + sin_alpha * cos_ab;
    const double denominator = (q * s + p * t) * sin_alpha;
    const double w = denominator != 0 ? std::clamp(((q * t - p * s) * cos_alpha - q) / denominator, -1.0, 1.0) : 1.0;
    // The cut's third corner, on the arc from a to c; then a point on the arc from b to it.
    const Vec3d c_cut = a * w + c_off_a * std::sqrt(std::max(0.0, 1 - w * w));
    const double z = 1 - v * (1 - OpenMesh::dot(c_cut, b));
    const Vec3d off_b = c_cut - b * OpenMesh::dot(c_cut, b);
    const double off = off_b.norm();
    if (!(off > 0)) return b;
    return (b * z + off_b * (std::sqrt(std::max(0.0, 1 - z * z)) / off)).normalized();
  }
};

}  // namespace

Glazing::Glazing(const std::vector<GlazingTriangle>& triangles, const std::vector<std::array<Vec3d, 3>>& openings) {
  for (const GlazingTriangle& t : triangles) {
    corners_.push_back(t.corners);
    glass_panes_.emplace_back(t.transmittance.luminance());
  }
  if (!openings.empty()) {
    // An opening is covered when glass lies in its plane across its centroid.
    std::unique_ptr<RayCaster> glass;
    if (!corners_.empty()) glass = std::make_unique<RayCaster>(pane_points(corners_), pane_indices(corners_.size()));
    for (const auto& o : openings) {
      const Vec3d normal = OpenMesh::cross(o[1] - o[0], o[2] - o[0]);
      const double size = std::max({(o[1] - o[0]).norm(), (o[2] - o[0]).norm(), (o[2] - o[1]).norm()});
      if (!(normal.norm() > 0)) continue;
      const Vec3d m = normal.normalized();
      const Vec3d centroid = (o[0] + o[1] + o[2]) / 3.0;
      bool covered = false;
      if (glass) {
        const Vec3d from = centroid + m * (1e-3 * size);
        const long hit = glass->first_hit(from, -m);
        covered = hit >= 0 && plane_distance(corners_[static_cast<std::size_t>(hit)], from, -m) < 2e-3 * size;
      }
      if (!covered) corners_.push_back(o);
    }
  }
  for (const auto& c : corners_) {
    const Vec3d normal = OpenMesh::cross(c[1] - c[0], c[2] - c[0]);
    normals_.push_back(normal.norm() > 0 ? normal.normalized() : Vec3d(0, 0, 0));
    centres_.push_back((c[0] + c[1] + c[2]) / 3.0);
    radii_.push_back(std::max({(c[0] - centres_.back()).norm(), (c[1] - centres_.back()).norm(),
                               (c[2] - centres_.back()).norm()}));
  }
  if (!corners_.empty()) caster_ = std::make_unique<RayCaster>(pane_points(corners_), pane_indices(corners_.size()));
}

long Glazing::first(const Vec3d& origin, const Vec3d& direction) const {
  return caster_ ? caster_->first_hit(origin, direction) : -1;
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
    const auto i = static_cast<std::size_t>(hit);
    const auto& c = corners_[i];
    const double facing = OpenMesh::dot(normals_[i], direction);
    if (facing == 0) break;
    const double distance = OpenMesh::dot(normals_[i], c[0] - o) / facing;
    if (i < glass_panes_.size()) t *= glass_panes_[i].transmittance(std::abs(facing));
    if (!(t > 0)) return 0;
    const double size = std::max({(c[1] - c[0]).norm(), (c[2] - c[0]).norm(), 1e-300});
    o += direction * (std::max(distance, 0.0) + 1e-6 * size);
  }
  return t;
}

namespace {

// The sky's illuminance at x facing n through the windows and openings: each pane a
// portal, integrated over the solid angle it covers, by the centres of strata of
// Arvo's map (the same directions for a pane at every point: no noise). A direction
// counts for the first pane it crosses only, and only when nothing of the model stops
// it; the directions of the hemisphere that cross a pane are left out there. So the
// two parts add up to the whole sky, and a pane seen as a sliver from close beside it
// gets as many directions as one seen face on. Only panes that cover at least
// `least` sr are portals (`portals`, in pane order); the hemisphere keeps the
// directions through the others, as through no pane. `budget` directions are shared
// among the portals by their solid angle, at least 4 each; `elsewhere` is what x gets
// from the rest of the sky (the hemisphere's part), to judge whether a sliver matters.
struct Portal {
  std::size_t pane;
  SphericalTriangle triangle;
};

std::vector<Portal> portals_at(const Glazing& glazing, const Vec3d& x, const Vec3d& n, double least) {
  std::vector<Portal> out;
  for (std::size_t i = 0; i < glazing.size(); ++i) {
    const auto& c = glazing.pane(i);
    // A cheap bound first: the cap of the pane's bounding sphere.
    const double radius = glazing.radius(i), distance = (glazing.centre(i) - x).norm();
    if (distance > radius && 2 * M_PI * (1 - std::sqrt(1 - (radius / distance) * (radius / distance))) < least) continue;
    Vec3d to[3];
    double height = 0, size = 0;
    for (int k = 0; k < 3; ++k) {
      to[k] = c[k] - x;
      height = std::max(height, OpenMesh::dot(to[k], n));
      size = std::max(size, (c[k] - c[(k + 1) % 3]).norm());
    }
    if (height <= 1e-9 * size) continue;  // at or below x's horizon
    if (std::abs(OpenMesh::dot(glazing.normal(i), to[0])) <= 1e-9 * size) continue;  // x in its plane
    // The map starts at the pane's lowest corner (by x, then y, then z), so that the
    // strata do not depend on the order the model lists its corners in.
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (std::lexicographical_compare(c[k].data(), c[k].data() + 3, c[first].data(), c[first].data() + 3)) first = k;
    SphericalTriangle t(to[first].normalized(), to[(first + 1) % 3].normalized(), to[(first + 2) % 3].normalized());
    if (!(t.area >= least)) continue;
    out.push_back({i, t});
  }
  return out;
}

bool is_portal(const std::vector<Portal>& portals, long pane) {
  if (pane < 0) return false;
  const auto at = std::lower_bound(portals.begin(), portals.end(), static_cast<std::size_t>(pane),
                                   [](const Portal& p, std::size_t i) { return p.pane < i; });
  return at != portals.end() && at->pane == static_cast<std::size_t>(pane);
}

void portal_sky(const Visibility& visibility, const Daylight& day, const std::vector<Portal>& panes, const Vec3d& x,
                const Vec3d& n, int budget, double elsewhere, double& seen, double& below,
                const SkyDirectionSink* sink) {
  const Glazing& glazing = *day.glazing;
  double total = 0;
  for (const Portal& p : panes) total += p.triangle.area;
  struct Sample {
    double value = 0, below = 0;
    int code = -1;      // -1: counts nothing (blocked, another pane's, below x's plane); 1: seen
    bool edge = false;  // a neighbouring stratum's code differs
    Vec3d d;            // (for the sink) the direction, and its transmittance x cosine
    double geometric = 0;
  };
  struct Part {
    double value = 0, below = 0;  // the integral over the pane
    std::size_t seen = 0, strata = 0;
    std::vector<std::pair<Vec3d, double>> directions;  // for the sink: (direction, weight)
  };
  // The pane's integral on side x side strata (stratum centres of Arvo's map).
  auto integrate = [&](const Portal& p, int side) {
    auto sample = [&](double u, double v) {
      Sample out;
      const Vec3d d = p.triangle.sample(u, v);
      const double cosine = OpenMesh::dot(d, n);
      if (cosine <= 0) return out;
      if (glazing.first(x, d) != static_cast<long>(p.pane)) return out;
      if (visibility.trace(x, n, d) != Visibility::Hit::nothing) return out;
      const double through = glazing.along(x, d);
      out.value = day.sky.luminance(d) * through * cosine;
      out.below = OpenMesh::dot(d, day.sky.up) <= 0 ? out.value : 0.0;
      out.code = 1;
      out.d = d;
      out.geometric = through * cosine;
      return out;
    };
    Part part;
    part.strata = static_cast<std::size_t>(side) * side;
    std::vector<Sample> grid(part.strata);
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        Sample& s = grid[static_cast<std::size_t>(i * side + j)];
        s = sample((i + 0.5) / side, (j + 0.5) / side);
        part.seen += s.code == 1;
      }
    // Where a neighbouring stratum sees otherwise (a mask's or a mullion's edge across
    // the pane, the horizon of x's plane), m x m sub-strata, m chosen so that they add
    // at most as many directions as the strata themselves, from 2 to 8. (A fixed 2 x 2:
    // a grid point 0.125 m from a facade under an overhang was 1.1% off, CIE 171 test
    // 5.13; 4 x 4 everywhere took the IFC house's solve under an overcast sky to 64.6 s
    // against 52.7 s with 2 x 2. Few edge strata are a thin sliver of sky or a thin
    // mask, where each matters most; many are a large visible part, where 2 x 2 is
    // enough.)
    std::size_t edges = 0;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        Sample& c = grid[static_cast<std::size_t>(i * side + j)];
        for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
          const int i2 = i + di, j2 = j + dj;
          if (i2 < 0 || i2 >= side || j2 < 0 || j2 >= side) continue;
          c.edge = c.edge || grid[static_cast<std::size_t>(i2 * side + j2)].code != c.code;
        }
        edges += c.edge;
      }
    const int m = edges == 0 ? 1
                             : std::clamp(static_cast<int>(std::sqrt(static_cast<double>(side) * side / edges)), 2, 8);
    const double weight = p.triangle.area / static_cast<double>(part.strata);
    double sum = 0, sum_below = 0;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        const Sample& c = grid[static_cast<std::size_t>(i * side + j)];
        if (!c.edge) {
          sum += c.value;
          sum_below += c.below;
          if (sink && c.code == 1) part.directions.emplace_back(c.d, c.geometric * weight);
          continue;
        }
        for (int a = 0; a < m; ++a)
          for (int e = 0; e < m; ++e) {
            const Sample s = sample((i + (a + 0.5) / m) / side, (j + (e + 0.5) / m) / side);
            sum += s.value / (m * m);
            sum_below += s.below / (m * m);
            if (sink && s.code == 1) part.directions.emplace_back(s.d, s.geometric * weight / (m * m));
          }
      }
    part.value = sum * weight;
    part.below = sum_below * weight;
    return part;
  };
  // Whether x sees the sky through the pane just inside one of its corners: a gap past
  // a mask's end, where the mask's edge crosses the pane's, can be thinner than a
  // stratum.
  auto seen_at_a_corner = [&](const Portal& p) {
    const auto& c = glazing.pane(p.pane);
    const Vec3d& centre = glazing.centre(p.pane);
    for (int k = 0; k < 3; ++k) {
      const Vec3d on = c[k] + (centre - c[k]) * 1e-3;
      const Vec3d d = (on - x).normalized();
      if (OpenMesh::dot(d, n) > 0 && glazing.first(x, d) == static_cast<long>(p.pane) &&
          visibility.trace(x, n, d) == Visibility::Hit::nothing)
        return true;
    }
    return false;
  };
  std::vector<Part> parts;
  std::vector<int> sides;
  double estimate = elsewhere;
  for (const Portal& p : panes) {
    const int wanted = std::max(4, static_cast<int>(std::lround(budget * p.triangle.area / total)));
    sides.push_back(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(wanted)))));
    parts.push_back(integrate(p, sides.back()));
    estimate += parts.back().value;
  }
  // A pane seen through a gap in a mask, in a sliver of its strata (or in none, when
  // the sliver passes between their centres but a corner sees it), is integrated
  // again on strata twice as fine where it could matter: where a sixteenth of the pane,
  // seen whole, would give at least 2% of the point's light. (CIE 171 test 5.13: a
  // floor vertex under an overhang that saw the sky past its end in 1% of the pane's
  // strata was 20% low; with the pane's corners listed in another order, none of its
  // strata saw it and a floor point took half its light. The IFC house under an
  // overcast sky: looking along every such pane's outline, 8 points per edge, and
  // strata 3 times finer took its solve from 43 to 76 s; with the 2% and the corners
  // alone, 49 s; strata twice as fine, 44 s, and 5.13 within 1.3%.)
  for (std::size_t k = 0; k < panes.size(); ++k) {
    const Part& part = parts[k];
    if (part.seen * 16 >= part.strata) continue;
    const Vec3d centre = (glazing.centre(panes[k].pane) - x).normalized();
    const double whole = day.sky.luminance(centre) * std::max(0.0, OpenMesh::dot(centre, n)) * panes[k].triangle.area;
    if (std::max(part.value, whole / 16) < 0.02 * estimate) continue;
    if (part.seen == 0 && !seen_at_a_corner(panes[k])) continue;
    parts[k] = integrate(panes[k], 2 * sides[k]);
  }
  for (const Part& part : parts) {
    seen += part.value;
    below += part.below;
    if (sink)
      for (const auto& [d, w] : part.directions) (*sink)(d, w);
  }
}

}  // namespace

double daylight_illuminance(const Visibility* visibility, const Luminaire& l, const Vec3d& x, const Vec3d& n,
                            double* unoccluded, int side, double* ground, const SkyDirectionSink* sink) {
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
  // Panes that cover at least one hemisphere stratum's share (pi / k^2 sr) are
  // portals; smaller ones (far, or many) are left to the hemisphere's directions.
  std::vector<Portal> portals;
  if (visibility && day.glazing) portals = portals_at(*day.glazing, x, n, M_PI / (static_cast<double>(k) * k));
  struct Sample {
    double seen = 0, below = 0;
    // -1 blocked (or a portal's); else 0 open, or 1 + the first pane it crosses (not its
    // transmittance, which changes with the angle from one stratum to the next)
    long code = -1;
    Vec3d d;             // (for the sink) the direction and its transmittance
    double through = 0;
  };
  auto sample = [&](double u, double v) {
    Sample out;
    const Vec3d d = direction(u, v);
    const double L = day.sky.luminance(d);
    // Directions through a portal are the portals' (below).
    const long pane = day.glazing ? day.glazing->first(x, d) : -1;
    if (!portals.empty() && is_portal(portals, pane)) return out;
    if (visibility->trace(x, n, d) != Visibility::Hit::nothing) return out;
    const double through = pane >= 0 ? day.glazing->along(x, d) : 1.0;
    const bool under = OpenMesh::dot(d, day.sky.up) <= 0;
    out.seen = L * through;
    out.below = under ? out.seen : 0.0;
    out.code = pane + 1;
    out.d = d;
    out.through = through;
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
        const double stratum = M_PI / (static_cast<double>(k) * k);
        if (!edge) {
          seen += c.seen;
          below += c.below;
          if (sink && c.code >= 0) (*sink)(c.d, c.through * stratum);
          continue;
        }
        double sub_seen = 0, sub_below = 0;
        for (int a = 0; a < m; ++a)
          for (int e = 0; e < m; ++e) {
            const Sample s = sample((i + (a + 0.5) / m) / k, (j + (e + 0.5) / m) / k);
            sub_seen += s.seen;
            sub_below += s.below;
            if (sink && s.code >= 0) (*sink)(s.d, s.through * stratum / (m * m));
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
  double through_seen = 0, through_below = 0;
  if (!portals.empty())
    portal_sky(*visibility, day, portals, x, n, k * k, seen * scale, through_seen, through_below, sink);
  if (ground) *ground = below * scale + through_below;
  return seen * scale + through_seen;
}

}  // namespace dynrad::rad

