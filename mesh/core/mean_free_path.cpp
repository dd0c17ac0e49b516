#include "mesh/core/mean_free_path.h"

#include "mesh/core/ray_cast.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace dynrad {
namespace {

// SplitMix64: a small generator whose stream is the same on every platform.
struct SplitMix {
  std::uint64_t state;
  double next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;  // [0, 1)
  }
};

}  // namespace

MeanFreePath mean_free_path(const SceneMesh& scene, const MeanFreePathOptions& options) {
  MeanFreePath out;
  const TriMesh& mesh = scene.mesh();
  std::vector<Vec3d> points;
  points.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<FaceHandle> faces;
  std::vector<double> cumulative;  // area, for picking faces in proportion to it
  double total = 0;
  for (auto f : mesh.faces()) {
    std::array<std::uint32_t, 3> t{};
    int k = 0;
    for (auto v : mesh.fv_range(f)) t[k++] = static_cast<std::uint32_t>(v.idx());
    triangles.push_back(t);
    faces.push_back(f);
    total += scene.area(f);
    cumulative.push_back(total);
  }
  if (!(total > 0) || options.rays <= 0) return out;
  const RayCaster caster(points, triangles);
  const double offset = 1e-6 * scene.bounds().diagonal();  // off the surface, so it cannot hit itself
  SplitMix random{options.seed};
  const std::vector<Vec3d> directions = cosine_directions(options.rays);
  double sum = 0;
  int hits = 0;
  for (int r = 0; r < options.rays; ++r) {
    const double pick = random.next() * total;
    const std::size_t i =
        std::min<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(),
                              faces.size() - 1);
    const auto& t = triangles[i];
    double a = random.next(), b = random.next();
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Vec3d origin = points[t[0]] + (points[t[1]] - points[t[0]]) * a + (points[t[2]] - points[t[0]]) * b;
    // Cosine-distributed about the face's normal: the r-th of an even spread.
    const Vec3d n = scene.normal(faces[i]);
    const Vec3d direction = about_normal(n, directions[static_cast<std::size_t>(r)]);
    const long hit = caster.first_hit(origin + n * offset, direction);
    ++out.rays;
    if (hit < 0 || static_cast<std::size_t>(hit) == i) {
      if (hit < 0) out.escaped += 1;
      continue;
    }
    // Distance along the ray to the plane of the triangle hit.
    const auto& h = triangles[static_cast<std::size_t>(hit)];
    const Vec3d hn = scene.normal(faces[static_cast<std::size_t>(hit)]);
    const double along = OpenMesh::dot(hn, direction);
    if (std::abs(along) < 1e-12) continue;
    const double distance = OpenMesh::dot(hn, points[h[0]] - origin) / along;
    if (!(distance > 0)) continue;
    sum += distance;
    ++hits;
  }
  out.escaped /= std::max(1, out.rays);
  out.length = hits > 0 ? sum / hits : 0;
  out.met = static_cast<double>(hits) / std::max(1, out.rays);
  return out;
}

}  // namespace dynrad
