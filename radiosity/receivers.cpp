#include "radiosity/receivers.h"

namespace dynrad::rad {

Receivers make_receivers(const SceneMesh& scene, double crease_angle_degrees) {
  Receivers r;
  r.split = split_vertices(scene, crease_angle_degrees);
  const std::size_t n = r.split.size();
  r.position.resize(n);
  r.normal.assign(n, Vec3d(0.0));
  r.material.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.position[i] = scene.mesh().point(r.split.source[i]);
  for (auto f : scene.mesh().faces()) {
    const Vec3d weighted = scene.normal(f) * scene.area(f);
    for (int k = 0; k < 3; ++k) {
      const auto node = r.split.corner[3 * f.idx() + k];
      r.normal[node] += weighted;
      r.material[node] = scene.material_id(f);
    }
  }
  for (auto& nrm : r.normal) nrm.normalize();
  // A hundredth of the way toward the centroid of the node's faces: far below the
  // resolution of the solution, far above float rounding in the ray tracer.
  std::vector<Vec3d> pull(n, Vec3d(0.0));
  std::vector<double> weight(n, 0.0);
  for (auto f : scene.mesh().faces()) {
    const Vec3d c = scene.centroid(f);
    for (int k = 0; k < 3; ++k) {
      const auto node = r.split.corner[3 * f.idx() + k];
      pull[node] += c - r.position[node];
      weight[node] += 1;
    }
  }
  r.sample_point.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d towards = weight[i] > 0 ? pull[i] / weight[i] : Vec3d(0.0);
    r.sample_point[i] = r.position[i] + towards * 1e-2;
  }
  return r;
}

}  // namespace dynrad::rad
