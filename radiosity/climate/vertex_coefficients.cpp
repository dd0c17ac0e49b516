// Daylight coefficients at vertices (see vertex_coefficients.h).
#include "radiosity/climate/vertex_coefficients.h"

#include "mesh/core/scene_mesh.h"
#include "radiosity/climate/daylight_coefficients.h"

#include <tbb/parallel_for.h>

namespace dynrad::rad {

VertexCoefficients vertex_coefficients(const SceneMesh& mesh, const Solver& solver, const Solver::Output& steering,
                                       std::size_t sky_count, double ground) {
  VertexCoefficients out;
  const std::size_t n = solver.coefficient_count(), absolute = solver.absolute_from(), vertices = steering.split.size();
  out.count = n;
  out.sky_count = sky_count;
  out.values.assign(vertices * n, 0.0f);
  out.point.assign(vertices, Vec3d(0.0));
  std::vector<char> placed(vertices, 0);
  out.normal.assign(vertices, Vec3d(0.0));
  out.reflectance.assign(vertices, 0.0f);
  std::vector<double> light(vertices, 0.0), area(vertices, 0.0);
  std::vector<float> patch(n);
  for (auto f : mesh.mesh().faces()) {
    const double a = mesh.area(f);
    const std::uint32_t p = mesh.patch(f);
    const float* total = solver.patch_coefficients(p);
    const float* direct = solver.patch_direct_coefficients(p);
    for (std::size_t j = 0; j < n; ++j) patch[j] = total[j] - (j >= absolute ? direct[j - absolute] : 0.0f);
    const double l = steering_light(total, sky_count, ground);
    const double rho = mesh.material(f).reflectance.luminance();
    const Vec3d normal = mesh.normal(f) * a;
    Vec3d corner[3], centroid(0.0);
    int i = 0;
    for (auto u : mesh.mesh().fv_range(f)) centroid += (corner[i++] = mesh.mesh().point(u)) / 3.0;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = steering.split.corner[3 * f.idx() + k];
      if (!placed[v]) {
        placed[v] = 1;
        out.point[v] = corner[k] + (centroid - corner[k]) * 1e-2;
      }
      float* to = out.values.data() + v * n;
      for (std::size_t j = 0; j < n; ++j) to[j] += static_cast<float>(a) * patch[j];
      light[v] += a * l;
      area[v] += a;
      out.normal[v] += normal;
      out.reflectance[v] += static_cast<float>(a * rho);
    }
  }
  for (std::size_t v = 0; v < vertices; ++v) {
    if (area[v] > 0) out.reflectance[v] = static_cast<float>(out.reflectance[v] / area[v]);
    const double norm = out.normal[v].norm();
    if (norm > 0) out.normal[v] /= norm;
    // Scaled to the vertex's steering radiosity (the patches' area sum cancels).
    const double scale = light[v] > 0 ? steering.radiosity[v].luminance() / light[v] : 0.0;
    float* c = out.values.data() + v * n;
    for (std::size_t j = 0; j < n; ++j) c[j] = static_cast<float>(c[j] * scale);
  }
  return out;
}

std::vector<double> vertex_hour(const VertexCoefficients& c, const HourSky& hour, const Visibility& visibility,
                                const Glazing* glazing) {
  std::vector<double> out(c.size(), 0.0);
  tbb::parallel_for(std::size_t(0), c.size(), [&](std::size_t v) {
    const float* k = c.at(v);
    double b = 0;
    for (std::size_t j = 0; j < c.sky_count; ++j) b += k[j] * hour.indirect[j];
    if (hour.direct_normal > 0) {
      for (std::size_t i = 0; i < 4; ++i)
        if (hour.nodes.position[i] >= 0)
          b += k[c.sky_count + static_cast<std::size_t>(hour.nodes.position[i])] * hour.nodes.weight[i] *
               hour.direct_normal;
      b += c.reflectance[v] * sun_illuminance(visibility, glazing, c.point[v], c.normal[v], hour.sun,
                                              hour.direct_normal);
    }
    out[v] = b;
  });
  return out;
}

}  // namespace dynrad::rad
