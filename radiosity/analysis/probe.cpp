#include "radiosity/analysis/probe.h"

#include <cmath>

namespace dynrad::rad {

std::optional<Rgb> probe(const SceneMesh& scene, const VertexSplit& split, const std::vector<Rgb>& values,
                         const Vec3d& point, const Vec3d& normal) {
  const TriMesh& mesh = scene.mesh();
  const double tolerance = 1e-6 * scene.bounds().diagonal();
  const Vec3d n = normal.normalized();
  for (auto f : mesh.faces()) {
    if (OpenMesh::dot(scene.normal(f), n) < std::cos(25.0 * M_PI / 180.0)) continue;
    Vec3d c[3];
    int k = 0;
    for (auto v : mesh.fv_range(f)) c[k++] = mesh.point(v);
    const Vec3d fn = scene.normal(f);
    if (std::abs(OpenMesh::dot(point - c[0], fn)) > tolerance) continue;
    // Barycentric coordinates from sub-triangle areas (signed along the face normal).
    const double area = OpenMesh::dot(OpenMesh::cross(c[1] - c[0], c[2] - c[0]), fn);
    double w[3];
    for (int i = 0; i < 3; ++i)
      w[i] = OpenMesh::dot(OpenMesh::cross(c[(i + 1) % 3] - point, c[(i + 2) % 3] - point), fn) / area;
    const double slack = tolerance / std::sqrt(std::abs(area));
    if (w[0] < -slack || w[1] < -slack || w[2] < -slack) continue;
    Rgb value;
    for (int i = 0; i < 3; ++i) value += values[split.corner[3 * f.idx() + i]] * w[i];
    return value;
  }
  return std::nullopt;
}

}  // namespace dynrad::rad
