// The scene as an OpenMesh triangle mesh with the per-face data the solver needs:
// material, patch id, source group, unit normal, area. Positions are doubles so that
// models in millimetres a kilometre from the origin keep their precision.
#pragma once

#include "mesh/core/soup.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <cstdint>
#include <string>
#include <vector>

namespace dynrad {

struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  FaceAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Status);
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;
using FaceHandle = OpenMesh::FaceHandle;
using VertexHandle = OpenMesh::VertexHandle;

class SceneMesh {
 public:
  // Builds the half-edge mesh from a cleaned soup. Throws std::logic_error if the soup
  // is not manifold (cleanup guarantees it is).
  explicit SceneMesh(const TriangleSoup& soup);
  SceneMesh(const SceneMesh&) = delete;
  SceneMesh& operator=(const SceneMesh&) = delete;

  TriMesh& mesh() { return mesh_; }
  const TriMesh& mesh() const { return mesh_; }

  std::uint32_t material_id(FaceHandle f) const { return mesh_.property(material_, f); }
  const Material& material(FaceHandle f) const { return materials_[material_id(f)]; }
  std::uint32_t patch(FaceHandle f) const { return mesh_.property(patch_, f); }
  void set_patch(FaceHandle f, std::uint32_t id) { mesh_.property(patch_, f) = id; }
  std::uint32_t group(FaceHandle f) const { return mesh_.property(group_, f); }
  const SourceRef& origin(FaceHandle f) const { return mesh_.property(origin_, f); }

  // Inserted lines (line_insertion.h): an edge on one carries the width of the strip
  // its line bounds (model units); 0 on every other edge. Refinement keeps it on both
  // halves of a split edge. Stored as the mesh property kLineWidthProperty.
  static constexpr const char* kLineWidthProperty = "dynrad:line_width";
  float line_width(OpenMesh::EdgeHandle e) const { return mesh_.property(line_width_, e); }
  void set_line_width(OpenMesh::EdgeHandle e, float width) {
    mesh_.property(line_width_, e) = width;
    if (width > 0) has_lines_ = true;
  }
  bool has_lines() const { return has_lines_; }
  OpenMesh::EPropHandleT<float> line_width_property() const { return line_width_; }

  // "room.obj:17" / "room.ply face 3": where the user finds this face's polygon.
  std::string where(FaceHandle f) const;

  const Vec3d& normal(FaceHandle f) const { return mesh_.normal(f); }
  double area(FaceHandle f) const;
  Vec3d centroid(FaceHandle f) const;

  const std::vector<Material>& materials() const { return materials_; }
  // Replaces material `id`'s properties (its faces keep it); the id must exist.
  void set_material(std::size_t id, const Material& m) { materials_.at(id) = m; }
  const std::vector<std::string>& group_names() const { return group_names_; }
  const std::vector<std::string>& files() const { return files_; }

  std::size_t face_count() const { return mesh_.n_faces(); }
  std::size_t vertex_count() const { return mesh_.n_vertices(); }
  Bounds bounds() const;
  double total_area() const;
  double emitting_area() const;
  // Emitted power per channel, sum of area * exitance (W when lengths are metres).
  Rgb emitted_power() const;

 private:
  TriMesh mesh_;
  OpenMesh::FPropHandleT<std::uint32_t> material_, patch_, group_;
  OpenMesh::FPropHandleT<SourceRef> origin_;
  OpenMesh::EPropHandleT<float> line_width_;
  bool has_lines_ = false;
  std::vector<Material> materials_;
  std::vector<std::string> group_names_;
  std::vector<std::string> files_;
};

}  // namespace dynrad
