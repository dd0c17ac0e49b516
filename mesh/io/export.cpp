#include "mesh/io/export.h"

#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "mesh/io/export_gltf.h"
#include "mesh/io/io_util.h"

#include <OpenMesh/Core/IO/MeshIO.hh>

#include <stdexcept>

namespace dynrad {
namespace {

using OutMesh = OpenMesh::TriMesh_ArrayKernelT<>;

}  // namespace

void write_mesh_with_values(const std::string& path, const SceneMesh& scene, const VertexSplit& split,
                            const VertexValues& values, const WriteOptions& options) {
  if (detail::extension_of(path) == ".glb") {
    write_glb(path, scene, split, values, options);
    return;
  }
  std::vector<Vec3d> positions(split.size());
  for (std::size_t i = 0; i < split.size(); ++i) positions[i] = scene.mesh().point(split.source[i]);
  std::vector<std::array<std::uint32_t, 3>> triangles;
  triangles.reserve(scene.face_count());
  for (auto f : scene.mesh().faces()) {
    const auto* c = &split.corner[3 * f.idx()];
    triangles.push_back({c[0], c[1], c[2]});
  }
  write_triangles_with_values(path, positions, triangles, values, options);
}

void write_triangles_with_values(const std::string& path, const std::vector<Vec3d>& positions,
                                 const std::vector<std::array<std::uint32_t, 3>>& triangles, const VertexValues& values,
                                 const WriteOptions& options) {
  const std::string ext = detail::extension_of(path);
  if (ext != ".ply" && ext != ".off")
    throw OutputError(path, "unsupported output type '" + ext + "'; use .ply, .off or (a lit model) .glb.");
  const std::size_t n = positions.size();
  if (values.linear.size() != n || values.display.size() != n || values.quality.size() != n)
    throw std::logic_error("write_triangles_with_values: value arrays do not match the vertices");
  for (const auto& [name, scalar] : values.scalars)
    if (scalar.size() != n) throw std::logic_error("write_triangles_with_values: " + name + " does not match the vertices");

  OutMesh out;
  out.request_vertex_colors();
  out.reserve(n, 0, triangles.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d& p = positions[i];
    auto v = out.add_vertex(OutMesh::Point(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])));
    out.set_color(v, OutMesh::Color(values.display[i][0], values.display[i][1], values.display[i][2]));
  }
  for (const auto& t : triangles) {
    auto added = out.add_face(OpenMesh::VertexHandle(static_cast<int>(t[0])), OpenMesh::VertexHandle(static_cast<int>(t[1])),
                              OpenMesh::VertexHandle(static_cast<int>(t[2])));
    if (!added.is_valid()) throw std::logic_error("write_triangles_with_values: output face rejected by OpenMesh");
  }
  OpenMesh::IO::Options io = OpenMesh::IO::Options::VertexColor;
  OpenMesh::VPropHandleT<float> channel[3];
  OpenMesh::VPropHandleT<float> quality;
  if (ext == ".ply") {
    const char* suffix[3] = {"_r", "_g", "_b"};
    for (int c = 0; c < 3; ++c) {
      out.add_property(channel[c], values.name + suffix[c]);
      out.property(channel[c]).set_persistent(true);
    }
    out.add_property(quality, "quality");
    out.property(quality).set_persistent(true);
    std::vector<OpenMesh::VPropHandleT<float>> scalars(values.scalars.size());
    for (std::size_t k = 0; k < scalars.size(); ++k) {
      out.add_property(scalars[k], values.scalars[k].first);
      out.property(scalars[k]).set_persistent(true);
      for (std::size_t i = 0; i < n; ++i)
        out.property(scalars[k], OpenMesh::VertexHandle(static_cast<int>(i))) = values.scalars[k].second[i];
    }
    for (std::size_t i = 0; i < n; ++i) {
      OpenMesh::VertexHandle v(static_cast<int>(i));
      for (int c = 0; c < 3; ++c) out.property(channel[c], v) = static_cast<float>(values.linear[i][c]);
      out.property(quality, v) = values.quality[i];
    }
    io += OpenMesh::IO::Options::Custom;
    if (!options.ascii) io += OpenMesh::IO::Options::Binary;
  }

  AtomicFile file(path);
  if (!OpenMesh::IO::write_mesh(out, file.stream(), ext, io, 9))
    throw OutputError(path, "OpenMesh could not write the mesh.");
  file.commit();
}

}  // namespace dynrad
