// Calculation grids (see grid.h).
#include "radiosity/analysis/grid.h"

#include "radiosity/sources/daylight.h"
#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/random.h"
#include "radiosity/analysis/rooms.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dynrad::rad {

namespace {

double edge_distance(const std::vector<std::array<double, 2>>& poly, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const double ax = poly[j][0], ay = poly[j][1], bx = poly[i][0], by = poly[i][1];
    const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(x - (ax + t * dx), y - (ay + t * dy)));
  }
  return best;
}

// Unit vectors t, b with (t, b, n) right-handed.
void frame(const Vec3d& n, Vec3d& t, Vec3d& b) {
  t = OpenMesh::cross(std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0), n).normalized();
  b = OpenMesh::cross(n, t);
}

}  // namespace

Rgb radiosity_at(const LitScene& scene, const Visibility::Intersection& hit) {
  const auto& tri = scene.triangles[static_cast<std::size_t>(hit.face)];
  return scene.radiosity[tri[0]] * (1 - hit.u - hit.v) + scene.radiosity[tri[1]] * hit.u +
         scene.radiosity[tri[2]] * hit.v;
}

int gather_rays(const LitScene& scene, const Vec3d& point, const Vec3d& normal, int side, std::uint64_t& state,
                const std::function<void(const Visibility::Intersection&)>& on_hit) {
  Vec3d t, bt;
  frame(normal, t, bt);
  side = std::max(1, side);
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const double u1 = (i + uniform(state)) / side, u2 = (j + uniform(state)) / side;
      const double r = std::sqrt(u1), phi = 2 * M_PI * u2;
      const Vec3d dir = t * (r * std::cos(phi)) + bt * (r * std::sin(phi)) + normal * std::sqrt(std::max(0.0, 1 - u1));
      // (from a hair above the point: a grid on a surface must not see that surface)
      const Visibility::Intersection hit = scene.visibility->intersect(point + normal * (1e-7 * scene.diagonal), dir);
      if (hit.hit && hit.front) on_hit(hit);
    }
  return side * side;
}

double polygon_edge_distance(const std::vector<std::array<double, 2>>& polygon, double x, double y) {
  return edge_distance(polygon, x, y);
}

bool inside_polygon(const std::vector<std::array<double, 2>>& poly, double x, double y) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) in = !in;
  }
  return in;
}

double surrounding_illuminance(double task_eavg) {
  if (task_eavg >= 750) return 500;
  if (task_eavg >= 500) return 300;
  if (task_eavg >= 300) return 200;
  if (task_eavg >= 200) return 150;
  return task_eavg;
}

double automatic_spacing(double longer_side) {
  if (!(longer_side > 0)) return 0.2;
  return std::min(10.0, 0.2 * std::pow(5.0, std::log10(longer_side)));
}

std::vector<Vec3d> grid_points(const GridSpec& spec, double* spacing_used, std::vector<std::array<long, 2>>* cells,
                               GridCells* layout) {
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (const auto& p : spec.polygon)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  const double width = hi[0] - lo[0], depth = hi[1] - lo[1];
  const double p = spec.spacing > 0 ? spec.spacing : automatic_spacing(std::max(width, depth));
  if (spacing_used) *spacing_used = p;
  // Whole cells over the rectangle the border leaves, each as close to p as fits.
  const double w = std::max(0.0, width - 2 * spec.border), d = std::max(0.0, depth - 2 * spec.border);
  const long nx = std::max(1L, static_cast<long>(std::ceil(w / p - 1e-9)));
  const long ny = std::max(1L, static_cast<long>(std::ceil(d / p - 1e-9)));
  if (layout) *layout = {nx, ny, lo[0] + spec.border, lo[1] + spec.border, w / nx, d / ny};
  std::vector<Vec3d> out;
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      const double x = lo[0] + spec.border + (i + 0.5) * w / nx;
      const double y = lo[1] + spec.border + (j + 0.5) * d / ny;
      if (!inside_polygon(spec.polygon, x, y)) continue;
      if (spec.border > 0 && edge_distance(spec.polygon, x, y) < spec.border - 1e-12) continue;
      out.push_back(plan_point(spec.up, x, y, spec.height));
      if (cells) cells->push_back({i, j});
    }
  return out;
}

bool inside_solid(const Visibility& visibility, const Vec3d& point) {
  int backs = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      Vec3d d(0.0);
      d[axis] = sign;
      backs += visibility.trace(point, d, d) == Visibility::Hit::back;
    }
  return backs >= 4;
}

GridPointResult gather_point(const LitScene& scene, const Vec3d& point, const Vec3d& normal,
                             const GatherOptions& options, std::uint64_t point_seed) {
  const Visibility& vis = *scene.visibility;
  GridPointResult out;
  out.position = point;
  if (inside_solid(vis, point)) {
    out.masked = true;
    return out;
  }
  Rgb direct, indirect;
  std::uint64_t state = mix(point_seed);
  for (std::size_t k = 0; k < scene.luminaires.size(); ++k) {
    const Luminaire& l = scene.luminaires[k];
    if (l.kind == Luminaire::Kind::sky) {
      // The sky with the grid's own count of directions, its ground part apart.
      double ground = 0;
      const double e = daylight_illuminance(&vis, l, point, normal, nullptr, options.side, &ground);
      out.sky += e - ground;
      out.ground += ground;
      direct += l.colour * e;
      continue;
    }
    direct += l.colour * luminaire_illuminance(&vis, l, point, normal, mix(point_seed ^ mix(k + 1)), nullptr);
  }
  Vec3d targets[64];
  for (const std::uint32_t f : scene.emitting) {  // (a pass over every triangle per point grew with the square)
    const Rgb& m = scene.emission[f];
    const auto& t = scene.triangles[f];
    const Vec3d &a = scene.positions[t[0]], &b = scene.positions[t[1]], &c = scene.positions[t[2]];
    const Vec3d front = OpenMesh::cross(b - a, c - a).normalized();
    const double ff = point_to_triangle(point, normal, a, b, c, front);
    if (!(ff > 0)) continue;
    const int side = std::clamp(static_cast<int>(std::lround(std::sqrt(options.emitter_rays))), 1, 8);
    int n = 0;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        const double u = (i + uniform(state)) / side, v = (j + uniform(state)) / side;
        const double s = std::sqrt(u);
        const Vec3d p = a * (1 - s) + b * (s * (1 - v)) + c * (s * v);
        if (OpenMesh::dot(normal, p - point) > 0) targets[n++] = p;
      }
    if (n == 0) continue;
    direct += m * (ff * vis.visible_count(point, normal, targets, n, front) / n);
  }
  // Indirect: B - emission where cosine-weighted rays first land, stratified.
  const int rays = gather_rays(scene, point, normal, options.side, state, [&](const Visibility::Intersection& hit) {
    indirect += radiosity_at(scene, hit) - scene.emission[static_cast<std::size_t>(hit.face)];
  });
  indirect = indirect * (1.0 / rays);
  out.direct = direct.luminance();
  out.indirect = indirect.luminance();
  out.colour = direct + indirect;
  out.illuminance = out.direct + out.indirect;
  return out;
}

GridPointResult gather_cylindrical(const LitScene& scene, const Vec3d& point, const Vec3d& up,
                                   const GatherOptions& options, std::uint64_t point_seed) {
  // Ez = (1/pi) integral of L sin(theta) over the sphere, theta from `up`: the mean over
  // azimuths of the vertical illuminance.
  const Visibility& vis = *scene.visibility;
  GridPointResult out;
  out.position = point;
  Vec3d t, b;
  frame(up, t, b);
  std::uint64_t state = mix(point_seed);
  double direct = 0, indirect = 0;
  for (std::size_t k = 0; k < scene.luminaires.size(); ++k) {
    const Luminaire& l = scene.luminaires[k];
    if (l.kind == Luminaire::Kind::sky) {
      // A smooth sky: the mean of eight vertical illuminances (each a quarter of the
      // grid's directions).
      const int side = std::max(2, options.side / 2);
      double sum = 0;
      for (int a = 0; a < 8; ++a) {
        const double phi = a * M_PI / 4;
        sum += daylight_illuminance(&vis, l, point, t * std::cos(phi) + b * std::sin(phi), nullptr, side);
      }
      direct += l.colour.luminance() * sum / 8;
      continue;
    }
    // A point or the sun: I sin(theta) / (pi d^2), the illuminance on the vertical plane
    // facing it across, over pi. Straight above or below, nothing.
    const Vec3d towards = l.kind == Luminaire::Kind::sun ? l.daylight->sun : l.position - point;
    const Vec3d across = towards - up * OpenMesh::dot(towards, up);
    if (across.norm() <= 1e-9 * towards.norm()) continue;
    direct += l.colour.luminance() *
              luminaire_illuminance(&vis, l, point, across.normalized(), mix(point_seed ^ mix(k + 1)), nullptr) / M_PI;
  }
  // Surfaces, emitting or reflecting, by stratified directions uniform over the sphere:
  // each gives (4 / pi) B sin(theta).
  const int side = std::max(1, options.side);
  double emitted = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const double z = 1 - 2 * (i + uniform(state)) / side, phi = 2 * M_PI * (j + uniform(state)) / side;
      const double s = std::sqrt(std::max(0.0, 1 - z * z));
      const Vec3d dir = t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + up * z;
      const Visibility::Intersection hit = vis.intersect(point, dir);
      if (!hit.hit || !hit.front) continue;
      const Rgb radiosity = radiosity_at(scene, hit);
      const Rgb& emission = scene.emission[static_cast<std::size_t>(hit.face)];
      emitted += 4 / M_PI * s * emission.luminance();
      indirect += 4 / M_PI * s * (radiosity - emission).luminance();
    }
  const double n = static_cast<double>(side) * side;
  out.direct = direct + emitted / n;
  out.indirect = indirect / n;
  out.illuminance = out.direct + out.indirect;
  return out;
}

PointStatistics point_statistics(const std::vector<GridPointResult>& points) {
  PointStatistics s;
  double sum = 0;
  s.e_min = std::numeric_limits<double>::infinity();
  for (const GridPointResult& p : points) {
    if (p.masked) {
      ++s.masked;
      continue;
    }
    ++s.count;
    sum += p.illuminance;
    s.e_min = std::min(s.e_min, p.illuminance);
    s.e_max = std::max(s.e_max, p.illuminance);
  }
  if (s.count == 0) {
    s.e_min = 0;
    return s;
  }
  s.e_avg = sum / static_cast<double>(s.count);
  s.u0 = s.e_avg > 0 ? s.e_min / s.e_avg : 0.0;
  return s;
}

GridResult gather_grid(const LitScene& scene, const GridSpec& spec, const GatherOptions& options) {
  GridResult result;
  result.spec = spec;
  std::vector<std::array<long, 2>> cells;
  const std::vector<Vec3d> points = grid_points(spec, &result.spacing, &cells, &result.cells);
  Vec3d up(0.0);
  up[spec.up] = 1;
  result.points.resize(points.size());
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
    result.points[k] = gather_point(scene, points[k], up, options, mix(options.seed ^ mix(0x6E1Dull + k)));
    result.points[k].cell = cells[k];
  });
  result.indirect_rays = options.side * options.side;
  static_cast<PointStatistics&>(result) = point_statistics(result.points);
  if (result.count == 0) return result;
  result.min_over_max = result.e_max > 0 ? result.e_min / result.e_max : 0.0;
  // Daylight factors, against the sky's unobstructed horizontal illuminance.
  // (Only under a sky alone: with the sun or luminaires the ratio is not a daylight factor.)
  for (const Luminaire& l : scene.luminaires)
    if (l.kind == Luminaire::Kind::sky && l.daylight && l.daylight->horizontal_sky > 0)
      result.outside = l.daylight->horizontal_sky;
  if (scene.luminaires.size() != 1) result.outside = 0;
  if (result.outside > 0) {
    const double to_percent = 100.0 / result.outside;
    result.df_min = std::numeric_limits<double>::infinity();
    for (const GridPointResult& p : result.points) {
      if (p.masked) continue;
      const double df = p.illuminance * to_percent;
      result.df_avg += df;
      result.df_min = std::min(result.df_min, df);
      result.df_max = std::max(result.df_max, df);
      result.sky_component += p.sky * to_percent;
      result.externally_reflected += p.ground * to_percent;
      result.internally_reflected += p.indirect * to_percent;
    }
    const double n = static_cast<double>(result.count);
    result.df_avg /= n;
    result.sky_component /= n;
    result.externally_reflected /= n;
    result.internally_reflected /= n;
  }
  return result;
}

std::vector<GridResult> gather_grids(const LitScene& scene, const std::vector<GridSpec>& specs,
                                     const GatherOptions& options) {
  std::vector<GridResult> out;
  for (const GridSpec& spec : specs) out.push_back(gather_grid(scene, spec, options));
  return out;
}

}  // namespace dynrad::rad
