#include "mesh/openings.h"

#include "mesh/polygon_triangulation.h"

#include <algorithm>
#include <cmath>

namespace dynrad {

std::vector<std::array<Vec3d, 3>> find_openings(const TriMesh& mesh) {
  std::vector<std::array<Vec3d, 3>> out;
  std::vector<char> seen(mesh.n_halfedges(), 0);
  std::vector<Vec3d> points;
  std::vector<std::uint32_t> loop;
  std::vector<OpenMesh::HalfedgeHandle> edges;
  for (auto start : mesh.halfedges()) {
    if (!mesh.is_boundary(start) || seen[start.idx()]) continue;
    points.clear();
    edges.clear();
    auto h = start;
    do {
      seen[h.idx()] = 1;
      edges.push_back(h);
      points.push_back(mesh.point(mesh.from_vertex_handle(h)));
      h = mesh.next_halfedge_handle(h);
    } while (h != start && edges.size() <= mesh.n_halfedges());
    if (points.size() < 3) continue;
    loop.resize(points.size());
    for (std::uint32_t k = 0; k < loop.size(); ++k) loop[k] = k;
    const Vec3d area = newell_normal(points, loop);  // twice the area, along the loop's facing
    if (!(area.norm() > 0)) continue;
    const Vec3d m = area.normalized();
    Vec3d centre(0, 0, 0);
    for (const Vec3d& p : points) centre += p / static_cast<double>(points.size());
    double size = 0, off = 0;
    for (const Vec3d& p : points) {
      size = std::max(size, (p - centre).norm());
      off = std::max(off, std::abs(OpenMesh::dot(p - centre, m)));
    }
    if (off > 1e-4 * size) continue;  // not flat: no plane to sample through
    // A border of faces lying in the loop's plane runs clockwise about their facing
    // (the faces' own edges run counter-clockwise); a hole in them runs the other way.
    bool border = false, any_coplanar = false, all_coplanar = true;
    for (auto e : edges) {
      const Vec3d& n = mesh.normal(mesh.face_handle(mesh.opposite_halfedge_handle(e)));
      if (std::abs(OpenMesh::dot(n, m)) > 1 - 1e-6) {
        any_coplanar = true;
        if (OpenMesh::dot(n, m) < 0) border = true;
      } else {
        all_coplanar = false;
      }
    }
    if (border || (all_coplanar && !any_coplanar)) continue;
    std::vector<Triangle> triangles;
    if (!triangulate_polygon(points, loop, m, triangles)) continue;
    for (const Triangle& t : triangles) out.push_back({points[t[0]], points[t[1]], points[t[2]]});
  }
  return out;
}

}  // namespace dynrad
