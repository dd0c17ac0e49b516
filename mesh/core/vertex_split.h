// Output vertices for shading: a mesh vertex is split where the surfaces around it
// should not share a value, so that a wall/floor junction carries one value on the
// wall side and another on the floor side. Corners around a vertex share an output
// vertex when they are connected through edges whose two faces have the same
// material and meet at less than the crease angle.
#pragma once

#include "mesh/core/scene_mesh.h"

#include <vector>

namespace dynrad {

struct VertexSplit {
  // Output vertex of corner k (0..2, in fv order) of face f: corner[3 * f.idx() + k].
  std::vector<std::uint32_t> corner;
  // Mesh vertex each output vertex copies.
  std::vector<VertexHandle> source;

  std::size_t size() const { return source.size(); }
};

VertexSplit split_vertices(const SceneMesh& scene, double crease_angle_degrees = 30.0);

// A third of the area of each face around each output vertex.
std::vector<double> split_vertex_areas(const SceneMesh& scene, const VertexSplit& split);

// Area-weighted average of a per-face value over the faces that share each output
// vertex (the faces of one smooth, single-material fan).
template <typename T, typename FaceValue>
std::vector<T> average_over_faces(const SceneMesh& scene, const VertexSplit& split, FaceValue face_value) {
  std::vector<T> sum(split.size(), T{});
  std::vector<double> weight(split.size(), 0.0);
  for (auto f : scene.mesh().faces()) {
    const double a = scene.area(f);
    const T value = face_value(f);
    for (int k = 0; k < 3; ++k) {
      const auto out = split.corner[3 * f.idx() + k];
      sum[out] += value * a;
      weight[out] += a;
    }
  }
  for (std::size_t i = 0; i < sum.size(); ++i)
    if (weight[i] > 0) sum[i] = sum[i] * (1.0 / weight[i]);
  return sum;
}

}  // namespace dynrad
