// EN 1838 escape-route and open-area checks (see emergency.h).
#include "radiosity/design/emergency.h"

#include "radiosity/analysis/grid.h"
#include "radiosity/transfer/random.h"
#include "radiosity/analysis/rooms.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dynrad::rad {

namespace {

constexpr double kAboveFloor = 0.01;

Vec3d floor_point(const EmergencyArea& area, double x, double y) {
  return plan_point(area.up, x, y, area.floor + kAboveFloor);
}

// Direct illuminance from the emergency luminaires, each at its emergency share.
std::vector<double> direct_emergency(const LitScene& scene, const std::vector<Vec3d>& points, const Vec3d& up,
                                     std::uint64_t seed) {
  std::vector<double> out(points.size(), 0.0);
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
    double e = 0;
    for (std::size_t i = 0; i < scene.luminaires.size(); ++i) {
      const Luminaire& l = scene.luminaires[i];
      if (!(l.emergency > 0) || l.directional()) continue;
      e += l.emergency * l.colour.luminance() *
           luminaire_illuminance(scene.visibility.get(), l, points[k], up, mix(seed ^ mix(k * 7919 + i + 1)), nullptr);
    }
    out[k] = e;
  });
  return out;
}

void min_max(const std::vector<double>& values, std::size_t from, std::size_t to, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = 0;
  for (std::size_t k = from; k < to; ++k) {
    lo = std::min(lo, values[k]);
    hi = std::max(hi, values[k]);
  }
  if (from == to) lo = 0;
}

}  // namespace

EmergencyResult check_emergency(const LitScene& scene, const EmergencyArea& area, std::uint64_t seed) {
  EmergencyResult r;
  r.name = area.name;
  r.kind = area.kind;
  for (const Luminaire& l : scene.luminaires)
    if (l.emergency > 0 && !l.directional()) r.luminaires.push_back(l.name);
  const Vec3d up = axis_vector(area.up);
  const std::string clause = "EN 1838:2013, escape routes";
  std::vector<Vec3d> points;
  if (area.kind == EmergencyArea::Kind::route) {
    // The centre line first (every 0.1 m, both ends included), then the band's lines.
    std::vector<std::array<double, 4>> line;  // x, y and the unit normal across
    for (std::size_t i = 0; i + 1 < area.points.size(); ++i) {
      const auto& p = area.points[i];
      const auto& q = area.points[i + 1];
      const double dx = q[0] - p[0], dy = q[1] - p[1], length = std::hypot(dx, dy);
      if (!(length > 0)) continue;
      r.length += length;
      const long n = std::max(1L, static_cast<long>(std::ceil(length / 0.1)));
      for (long s = 0; s <= n; ++s) {
        if (s == 0 && i > 0) continue;  // (the corner, already the last point of the leg before)
        const double t = static_cast<double>(s) / n;
        line.push_back({p[0] + t * dx, p[1] + t * dy, -dy / length, dx / length});
      }
    }
    for (const auto& c : line) points.push_back(floor_point(area, c[0], c[1]));
    const std::size_t centre = points.size();
    for (double f : {-0.25, -0.125, 0.125, 0.25})
      for (const auto& c : line) points.push_back(floor_point(area, c[0] + f * area.width * c[2], c[1] + f * area.width * c[3]));
    const std::vector<double> e = direct_emergency(scene, points, up, seed);
    double band_hi = 0;
    min_max(e, 0, centre, r.e_min, r.e_max);
    min_max(e, 0, e.size(), r.band_min, band_hi);
    r.points = points.size();
    r.checks.push_back({"centre line", "Emin", r.e_min, centre > 0, "lx", Check::Relation::at_least, area.e_min, 0,
                        clause});
    r.checks.push_back({"central band", "Emin", r.band_min, centre > 0, "lx", Check::Relation::at_least,
                        area.band_min, 0, fmt::format("{}; the band of half the width, {:g} m", clause, area.width / 2)});
    Check ratio{"centre line", "Emax/Emin", r.e_min > 0 ? r.e_max / r.e_min : INFINITY, r.e_min > 0, "",
                Check::Relation::at_most, area.max_ratio, 0, clause};
    if (!(r.e_min > 0)) ratio.note = "a point of the centre line gets no emergency light";
    r.checks.push_back(ratio);
    if (area.width > 2 + 1e-9)
      r.checks.front().note = fmt::format("the route is {:g} m wide; EN 1838 treats wider routes as several 2 m strips or as "
                                          "an open area", area.width);
    return r;
  }
  // An open area: the polygon less a 0.5 m border.
  GridSpec core;
  core.polygon = area.points;
  core.border = 0.5;
  core.up = area.up;
  core.height = area.floor + kAboveFloor;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (const auto& p : area.points)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  core.spacing = std::min(0.5, automatic_spacing(std::max(hi[0] - lo[0], hi[1] - lo[1])));
  points = grid_points(core);
  const std::vector<double> e = direct_emergency(scene, points, up, seed);
  min_max(e, 0, e.size(), r.e_min, r.e_max);
  r.points = points.size();
  const bool any = !points.empty();
  Check minimum{"open area less 0.5 m", "Emin", r.e_min, any, "lx", Check::Relation::at_least, area.band_min, 0,
                "EN 1838:2013, open areas"};
  if (!any) minimum.note = "the 0.5 m border leaves no floor";
  r.checks.push_back(minimum);
  Check ratio{"open area less 0.5 m", "Emax/Emin", r.e_min > 0 ? r.e_max / r.e_min : INFINITY, r.e_min > 0, "",
              Check::Relation::at_most, area.max_ratio, 0, "EN 1838:2013, open areas"};
  if (any && !(r.e_min > 0)) ratio.note = "a point gets no emergency light";
  r.checks.push_back(ratio);
  return r;
}

}  // namespace dynrad::rad
