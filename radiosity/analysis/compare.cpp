#include "radiosity/analysis/compare.h"

#include <cmath>

namespace dynrad::rad {

Comparison compare(const SceneMesh& a_scene, const Solver::Output& a, const SceneMesh& b_scene,
                   const Solver::Output& b, const Visibility& b_visibility) {
  // One face per output vertex of A: where the vertex's surface lies.
  std::vector<int> face_of(a.split.size(), -1);
  for (auto f : a_scene.mesh().faces())
    for (int k = 0; k < 3; ++k) face_of[a.split.corner[3 * f.idx() + k]] = f.idx();
  const double lift = 1e-4 * a_scene.bounds().diagonal();
  Comparison c;
  double sum_square = 0, sum_a = 0;
  for (std::size_t x = 0; x < a.split.size(); ++x) {
    if (face_of[x] < 0) continue;
    const FaceHandle f(face_of[x]);
    const Vec3d n = a_scene.normal(f);
    const Vec3d p = a_scene.mesh().point(a.split.source[x]);
    const Vec3d inside = p + (a_scene.centroid(f) - p) * 1e-3;
    const auto hit = b_visibility.intersect(inside + n * lift, -n);
    if (!hit.hit || !hit.front || hit.distance > 3 * lift) {
      ++c.missed;
      continue;
    }
    const FaceHandle g(hit.face);
    const Rgb vb = b.radiosity[b.split.corner[3 * g.idx()]] * (1 - hit.u - hit.v) +
                   b.radiosity[b.split.corner[3 * g.idx() + 1]] * hit.u +
                   b.radiosity[b.split.corner[3 * g.idx() + 2]] * hit.v;
    const double d = (a.radiosity[x] - vb).luminance();
    sum_square += d * d;
    sum_a += a.radiosity[x].luminance() * a.radiosity[x].luminance();
    ++c.compared;
  }
  (void)b_scene;
  if (c.compared > 0) {
    c.rms_difference = std::sqrt(sum_square / c.compared);
    c.rms_a = std::sqrt(sum_a / c.compared);
  }
  return c;
}

}  // namespace dynrad::rad
