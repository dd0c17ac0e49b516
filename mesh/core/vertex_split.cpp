#include "mesh/core/vertex_split.h"

#include <cmath>
#include <numeric>

namespace dynrad {

VertexSplit split_vertices(const SceneMesh& scene, double crease_angle_degrees) {
  const TriMesh& mesh = scene.mesh();
  const double cos_crease = std::cos(crease_angle_degrees * M_PI / 180.0);
  VertexSplit split;
  split.corner.assign(3 * mesh.n_faces(), UINT32_MAX);

  // Corner index of (face, vertex): position of the vertex in the face's fv order.
  auto corner_of = [&](FaceHandle f, VertexHandle v) {
    int k = 0;
    for (auto w : mesh.fv_range(f)) {
      if (w == v) return 3 * f.idx() + k;
      ++k;
    }
    return -1;
  };
  auto smooth = [&](FaceHandle a, FaceHandle b) {
    return scene.material_id(a) == scene.material_id(b) &&
           OpenMesh::dot(scene.normal(a), scene.normal(b)) >= cos_crease;
  };

  for (auto v : mesh.vertices()) {
    // Walk the faces around v; start a new output vertex after every sharp edge.
    // On a boundary vertex, start at the boundary so the fan is walked in one piece.
    OpenMesh::HalfedgeHandle start = mesh.halfedge_handle(v);
    if (!start.is_valid()) continue;
    // Clockwise around v, the face across outgoing half-edge h is the next face of
    // the walk, so the sharpness of h's edge separates ring[i] from ring[i + 1].
    std::vector<FaceHandle> ring;
    std::vector<char> sharp_after;
    auto h = start;
    do {
      FaceHandle f = mesh.face_handle(h);
      if (f.is_valid()) {
        FaceHandle across = mesh.opposite_face_handle(h);
        ring.push_back(f);
        sharp_after.push_back(!across.is_valid() || !smooth(f, across));
      }
      h = mesh.cw_rotated_halfedge_handle(h);
    } while (h != start);
    if (ring.empty()) continue;
    const std::size_t n_ring = ring.size();
    auto break_before = [&](std::size_t i) { return sharp_after[(i + n_ring - 1) % n_ring] != 0; };
    // Start the walk just after a sharp edge, if any, so that no fan is cut in two.
    std::size_t first = 0;
    for (std::size_t i = 0; i < n_ring; ++i)
      if (break_before(i)) {
        first = i;
        break;
      }
    std::uint32_t current = UINT32_MAX;
    for (std::size_t n = 0; n < n_ring; ++n) {
      const std::size_t i = (first + n) % n_ring;
      if (current == UINT32_MAX || break_before(i)) {
        current = static_cast<std::uint32_t>(split.source.size());
        split.source.push_back(v);
      }
      split.corner[corner_of(ring[i], v)] = current;
    }
  }
  return split;
}

std::vector<double> split_vertex_areas(const SceneMesh& scene, const VertexSplit& split) {
  std::vector<double> area(split.size(), 0.0);
  for (auto f : scene.mesh().faces())
    for (int k = 0; k < 3; ++k) area[split.corner[3 * f.idx() + k]] += scene.area(f) / 3;
  return area;
}

}  // namespace dynrad
