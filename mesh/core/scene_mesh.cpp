#include "mesh/core/scene_mesh.h"

#include <stdexcept>

namespace dynrad {

SceneMesh::SceneMesh(const TriangleSoup& soup)
    : materials_(soup.materials), group_names_(soup.group_names), files_(soup.files) {
  mesh_.add_property(material_, "dynrad:material");
  mesh_.add_property(patch_, "dynrad:patch");
  mesh_.add_property(group_, "dynrad:group");
  mesh_.add_property(origin_, "dynrad:origin");
  mesh_.add_property(line_width_, kLineWidthProperty);
  mesh_.reserve(soup.points.size(), soup.triangles.size() * 3 / 2, soup.triangles.size());
  std::vector<VertexHandle> vertices;
  vertices.reserve(soup.points.size());
  for (const auto& p : soup.points) vertices.push_back(mesh_.add_vertex(p));
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const auto& tri = soup.triangles[t];
    FaceHandle f = mesh_.add_face(vertices[tri[0]], vertices[tri[1]], vertices[tri[2]]);
    if (!f.is_valid())
      throw std::logic_error("internal error: cleaned triangle " + std::to_string(t) +
                             " could not be added to the half-edge mesh (not manifold)");
    mesh_.property(material_, f) = soup.material[t];
    mesh_.property(group_, f) = soup.group[t];
    mesh_.property(origin_, f) = soup.origin[t];
    mesh_.property(patch_, f) = static_cast<std::uint32_t>(f.idx());
  }
  mesh_.update_face_normals();
  for (auto e : mesh_.edges()) mesh_.property(line_width_, e) = 0;
}

std::string SceneMesh::where(FaceHandle f) const {
  const SourceRef& ref = origin(f);
  std::string file = ref.file < files_.size() ? files_[ref.file] : std::string("<input>");
  if (ref.line > 0) return file + ":" + std::to_string(ref.line);
  return file + " face " + std::to_string(ref.face);
}

double SceneMesh::area(FaceHandle f) const {
  auto it = mesh_.cfv_iter(f);
  const Vec3d& a = mesh_.point(*it);
  const Vec3d& b = mesh_.point(*++it);
  const Vec3d& c = mesh_.point(*++it);
  return 0.5 * OpenMesh::cross(b - a, c - a).norm();
}

Vec3d SceneMesh::centroid(FaceHandle f) const {
  Vec3d sum(0.0);
  for (auto v : mesh_.fv_range(f)) sum += mesh_.point(v);
  return sum / 3.0;
}

Bounds SceneMesh::bounds() const {
  Bounds b;
  for (auto v : mesh_.vertices()) b.extend(mesh_.point(v));
  return b;
}

double SceneMesh::total_area() const {
  double sum = 0;
  for (auto f : mesh_.faces()) sum += area(f);
  return sum;
}

double SceneMesh::emitting_area() const {
  double sum = 0;
  for (auto f : mesh_.faces())
    if (material(f).emits()) sum += area(f);
  return sum;
}

Rgb SceneMesh::emitted_power() const {
  Rgb sum;
  for (auto f : mesh_.faces()) sum += material(f).emission * area(f);
  return sum;
}

}  // namespace dynrad
