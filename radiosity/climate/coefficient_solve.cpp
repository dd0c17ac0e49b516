// Daylight coefficients with interreflection from one solve (see coefficient_solve.h).
#include "radiosity/climate/coefficient_solve.h"

#include "mesh/core/scene_mesh.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/analysis/lit_scene.h"
#include "radiosity/transfer/random.h"
#include "radiosity/transfer/visibility.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace dynrad::rad {

Luminaire steering_sky(std::shared_ptr<const Glazing> glazing, const Vec3d& up, double ground_luminance) {
  auto day = std::make_shared<Daylight>();
  day->sky.type = SkyModel::Type::uniform;
  day->sky.up = up;
  day->sky.zenith_luminance = 1;
  day->sky.ground_luminance = ground_luminance;
  day->glazing = std::move(glazing);
  day->horizontal_sky = M_PI;
  day->sky_summary = "the steering sky of daylight coefficients: uniform, luminance 1, the ground " +
                     std::to_string(ground_luminance);
  Luminaire l;
  l.kind = Luminaire::Kind::sky;
  l.name = "sky";
  l.daylight = day;
  return l;
}

std::vector<Vec3d> sun_positions(const SkyPatches& frame, double spacing, const std::vector<Vec3d>& hour_suns,
                                 std::vector<SunNodes>* nodes) {
  const double step = spacing * M_PI / 180;
  const int rows = static_cast<int>(std::ceil(M_PI / 2 / step)) + 1;
  const int columns = static_cast<int>(std::ceil(2 * M_PI / step));
  // Each sun's cell (row, column of its lower-left node) and place in it.
  struct Cell {
    int row = -1, column = 0;
    double fa = 0, fb = 0;
  };
  std::vector<Cell> cells;
  std::vector<int> node(static_cast<std::size_t>(rows) * columns, -1);
  for (const Vec3d& s : hour_suns) {
    Cell c;
    if (OpenMesh::dot(s, frame.up()) > 0) {
      const auto [altitude, azimuth] = frame.altitude_azimuth(s);
      const double a = altitude / step;
      double b = azimuth / step;
      if (b < 0) b += columns;
      c.row = std::min(static_cast<int>(a), rows - 2);
      c.column = static_cast<int>(b) % columns;
      c.fa = a - c.row;
      c.fb = b - std::floor(b);
      for (int da = 0; da < 2; ++da)
        for (int db = 0; db < 2; ++db)
          node[static_cast<std::size_t>((c.row + da) * columns + (c.column + db) % columns)] = 0;
    }
    cells.push_back(c);
  }
  std::vector<Vec3d> out;
  for (int r = 0; r < rows; ++r)
    for (int k = 0; k < columns; ++k) {
      int& n = node[static_cast<std::size_t>(r * columns + k)];
      if (n < 0) continue;
      n = static_cast<int>(out.size());
      out.push_back(frame.direction(std::min(r * step, M_PI / 2), k * step));
    }
  if (nodes) {
    nodes->clear();
    for (const Cell& c : cells) {
      SunNodes h;
      if (c.row >= 0)
        for (int da = 0; da < 2; ++da)
          for (int db = 0; db < 2; ++db) {
            const int k = da * 2 + db;
            h.position[static_cast<std::size_t>(k)] =
                node[static_cast<std::size_t>((c.row + da) * columns + (c.column + db) % columns)];
            h.weight[static_cast<std::size_t>(k)] =
                static_cast<float>((da ? c.fa : 1 - c.fa) * (db ? c.fb : 1 - c.fb));
          }
      nodes->push_back(h);
    }
  }
  return out;
}

Solver::CoefficientChannels coefficient_channels(const Visibility& visibility, const Luminaire& steering,
                                                 const SkyPatches& indirect, const std::vector<Vec3d>& suns,
                                                 const CoefficientOptions& options) {
  Solver::CoefficientChannels c;
  const std::size_t sky_count = indirect.size() + 1;
  c.count = sky_count + suns.size();
  c.relative = sky_count;  // the suns' channels hold their irradiance itself
  const double ground = steering.daylight->sky.ground_luminance;
  const Glazing* glazing = steering.daylight->glazing.get();
  c.sky_mix = [&visibility, &steering, &indirect, &suns, options, ground, glazing, sky_count](
                  const std::array<Vec3d, 3>& surface, const Vec3d& n, float* mix) {
    const Vec3d centre = (surface[0] + surface[1] + surface[2]) / 3.0;
    const bool point = (surface[1] - surface[0]).sqrnorm() == 0 && (surface[2] - surface[0]).sqrnorm() == 0;
    // The sky: binned at the centre and halfway to each corner (the mean of the four).
    std::vector<double> bins(sky_count, 0.0);
    const SkyDirectionSink sink = [&](const Vec3d& d, double weight) { bins[indirect.index(d)] += weight; };
    for (int k = point ? 3 : 0; k < 4; ++k) {
      const Vec3d x = k == 3 ? centre : (centre + surface[static_cast<std::size_t>(k)]) / 2.0;
      daylight_illuminance(&visibility, steering, x, n, nullptr, options.mix_side, nullptr, &sink);
    }
    const double light = steering_light(bins.data(), sky_count, ground);
    for (std::size_t j = 0; j < sky_count; ++j)
      mix[j] = light > 0 ? static_cast<float>(bins[j] / light)
                         : static_cast<float>(1.0 / (static_cast<double>(sky_count - 1) + ground));
    if (suns.empty()) return;
    // The suns: the mean illuminance over stratified points of the triangle.
    const int m = point ? 1 : std::max(1, options.sun_points);
    std::vector<Vec3d> at;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) at.push_back(point ? centre : point_on_triangle(surface, (i + 0.5) / m, (j + 0.5) / m));
    for (std::size_t k = 0; k < suns.size(); ++k) {
      double sum = 0;
      for (const Vec3d& x : at) sum += sun_illuminance(visibility, glazing, x, n, suns[k], 1.0);
      mix[sky_count + k] = static_cast<float>(sum / static_cast<double>(at.size()));
    }
  };
  return c;
}

PointCoefficients point_coefficients(const LitScene& lit, const SceneMesh& mesh, const Solver& solver,
                                     const Luminaire& steering, const SkyPatches& fine, const SkyPatches& indirect,
                                     const Vec3d& point, const Vec3d& normal, const CoefficientOptions& options,
                                     std::uint64_t seed) {
  const Visibility& vis = *lit.visibility;
  PointCoefficients out;
  if (inside_solid(vis, point)) {
    out.masked = true;
    return out;
  }
  out.direct = direct_sky_coefficients(vis, steering, fine, point, normal, options.point_side);
  const std::size_t count = solver.coefficient_count(), sky_count = indirect.size() + 1;
  const double ground = steering.daylight->sky.ground_luminance;
  std::vector<double> sum(count, 0.0);
  std::uint64_t state = mix(seed);
  const int rays = gather_rays(lit, point, normal, options.point_side, state, [&](const Visibility::Intersection& hit) {
    const float* c = solver.patch_coefficients(mesh.patch(FaceHandle(hit.face)));
    const double mean = steering_light(c, sky_count, ground);  // the patch's, under the steering sky
    if (!(mean > 0)) return;
    const double shape = radiosity_at(lit, hit).luminance() / mean;
    for (std::size_t k = 0; k < count; ++k) sum[k] += shape * c[k];
  });
  out.indirect.resize(count);
  for (std::size_t k = 0; k < count; ++k) out.indirect[k] = static_cast<float>(sum[k] / rays);
  return out;
}

HourSky hour_sky(const SkyModel& sky, const Vec3d& sun, double direct_normal, const SkyPatches& fine,
                 const SkyPatches& indirect, const SunNodes& nodes) {
  HourSky h;
  h.fine = sky_vector(fine, sky, 2);
  if (fine.subdivision() % indirect.subdivision() == 0) {
    // The fine patches tile the coarse ones: their means, weighted by solid angle.
    h.indirect.assign(indirect.size() + 1, 0.0);
    std::vector<double> solid(indirect.size(), 0.0);
    for (std::size_t i = 0; i < fine.size(); ++i) {
      const std::size_t k = indirect.index(fine.centre(i));
      h.indirect[k] += h.fine[i] * fine.solid_angle(i);
      solid[k] += fine.solid_angle(i);
    }
    for (std::size_t k = 0; k < indirect.size(); ++k) h.indirect[k] /= solid[k];
    h.indirect.back() = h.fine.back();
  } else {
    h.indirect = sky_vector(indirect, sky, 8);
  }
  h.sun = sun;
  h.direct_normal = direct_normal;
  h.nodes = nodes;
  if (direct_normal > 0 && nodes.position[0] < 0) {
    const std::size_t k = indirect.index(sun);
    if (k != indirect.ground()) h.indirect[k] += direct_normal / indirect.solid_angle(k);
  }
  return h;
}

HourIlluminance hour_illuminance(const PointCoefficients& c, const HourSky& hour, double sun_direct) {
  HourIlluminance e;
  e.sun = sun_direct;
  e.sky_direct = c.direct.illuminance(hour.fine);
  for (std::size_t k = 0; k < hour.indirect.size(); ++k) e.indirect += c.indirect[k] * hour.indirect[k];
  if (hour.direct_normal > 0)
    for (std::size_t k = 0; k < 4; ++k)
      if (hour.nodes.position[k] >= 0)
        e.indirect += c.indirect[hour.indirect.size() + static_cast<std::size_t>(hour.nodes.position[k])] *
                      hour.nodes.weight[k] * hour.direct_normal;
  e.total = e.sun + e.sky_direct + e.indirect;
  return e;
}

}  // namespace dynrad::rad
