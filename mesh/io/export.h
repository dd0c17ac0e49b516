// Writing a mesh with per-vertex values: PLY (binary by default) or OFF (COFF); a
// scene mesh also as binary glTF (.glb, mesh/io/export_gltf.h).
//
// PLY vertex properties, in order: float x y z; uchar red green blue (display colour,
// the only colour MeshLab reads); float <name>_r <name>_g <name>_b (linear values);
// float quality (MeshLab's per-vertex scalar). OFF carries positions and the uchar
// colours only. The format follows the extension.
#pragma once

#include "mesh/core/vertex_split.h"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dynrad {

struct VertexValues {
  std::string name = "value";  // prefix of the three linear float properties (value_r, value_g, value_b)
  std::vector<Rgb> linear;
  std::vector<std::array<std::uint8_t, 3>> display;
  std::vector<float> quality;
  // More float properties, one value per vertex each, written after `quality` (PLY
  // only), by name.
  std::vector<std::pair<std::string, std::vector<float>>> scalars;
};

// A perspective camera to carry along with the mesh (glTF only): where a viewer opens
// the model, and the named viewpoints it offers. Positions in the mesh's coordinates.
struct Viewpoint {
  std::string name;
  Vec3d eye, target, up{0, 0, 1};
  double fov_degrees = 60;  // vertical
  double aspect = 4.0 / 3.0;
};

struct WriteOptions {
  bool ascii = false;  // PLY only; OFF is always ASCII
  std::vector<Viewpoint> viewpoints;  // glTF only: camera nodes, in this order
  std::vector<GlazingTriangle> glass;  // glTF only: the windows, a "glazing" node, see-through
  // glTF only: what a viewer shows where the model is not (the sky, in daylight), as a
  // linear colour like COLOR_0's, in the scene's extras as "background". Negative: none.
  Rgb background{-1, -1, -1};
};

// Any triangle mesh given by positions and corner indices, with one value per vertex.
void write_triangles_with_values(const std::string& path, const std::vector<Vec3d>& positions,
                                 const std::vector<std::array<std::uint32_t, 3>>& triangles, const VertexValues& values,
                                 const WriteOptions& options = {});

// Writes atomically (see AtomicFile). Throws OutputError on failure or an unknown
// extension.
void write_mesh_with_values(const std::string& path, const SceneMesh& scene, const VertexSplit& split,
                            const VertexValues& values, const WriteOptions& options = {});

}  // namespace dynrad
