#include "mesh/core/openings.h"

#include "mesh/core/polygon_triangulation.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace dynrad {

namespace {

using Halfedge = OpenMesh::HalfedgeHandle;

// The mesh seen as flat regions: faces that share an edge and face the same way. Where
// a surface meets a face along a line, cleanup leaves a slit (the line's two sides as
// separate boundary edges, corners repeated): a slit is glued here, its two sides
// across each other, so a window hole that an overhang's edge reaches stays one hole.
class Regions {
 public:
  // What lies across a face's half-edge: the same region, nothing, or a face of
  // another plane behind the region or in front of it.
  enum class Across { region, nothing, behind, in_front };

  explicit Regions(const TriMesh& mesh) : mesh_(mesh) {
    for (auto h : mesh.halfedges())
      if (!mesh.is_boundary(h) && !same_facing(h, mesh.opposite_halfedge_handle(h))) seams_.emplace(key(h), h);
  }

  // The face half-edge across h in h's region (through a seam: the other side of a slit,
  // which a face of another plane may also meet), else the face across h, else an
  // invalid handle.
  Halfedge beyond(Halfedge h) const {
    const Halfedge opposite = mesh_.opposite_halfedge_handle(h);
    if (same_facing(h, opposite)) return opposite;
    const Vec3d from = mesh_.point(mesh_.from_vertex_handle(h)), to = mesh_.point(mesh_.to_vertex_handle(h));
    const auto [first, last] = seams_.equal_range({to[0], to[1], to[2], from[0], from[1], from[2]});
    for (auto it = first; it != last; ++it)
      if (same_facing(h, it->second)) return it->second;
    return mesh_.is_boundary(opposite) ? Halfedge() : opposite;
  }

  Across across(Halfedge h) const {
    const Halfedge b = beyond(h);
    if (!b.is_valid()) return Across::nothing;
    const Vec3d& n = mesh_.normal(mesh_.face_handle(h));
    if (OpenMesh::dot(n, mesh_.normal(mesh_.face_handle(b))) > 1 - 1e-9) return Across::region;
    // The corner of the face beyond, off the shared edge, against h's plane.
    const Vec3d off = mesh_.point(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(b)));
    return OpenMesh::dot(off - mesh_.point(mesh_.to_vertex_handle(h)), n) < 0 ? Across::behind : Across::in_front;
  }

  // The half-edge after h along the outline of h's region: turn about h's end through
  // the region's faces.
  Halfedge next_on_outline(Halfedge h) const {
    Halfedge next = mesh_.next_halfedge_handle(h);
    for (std::size_t turns = 0; across(next) == Across::region && turns < 64; ++turns)
      next = mesh_.next_halfedge_handle(beyond(next));
    return next;
  }

 private:
  std::array<double, 6> key(Halfedge h) const {
    const Vec3d from = mesh_.point(mesh_.from_vertex_handle(h)), to = mesh_.point(mesh_.to_vertex_handle(h));
    return {from[0], from[1], from[2], to[0], to[1], to[2]};
  }
  bool same_facing(Halfedge a, Halfedge b) const {
    return !mesh_.is_boundary(a) && !mesh_.is_boundary(b) &&
           OpenMesh::dot(mesh_.normal(mesh_.face_handle(a)), mesh_.normal(mesh_.face_handle(b))) > 1 - 1e-9;
  }
  const TriMesh& mesh_;
  // Face half-edges whose region ends across them, by their ends.
  std::multimap<std::array<double, 6>, Halfedge> seams_;
};

void add_loop(const std::vector<Vec3d>& points, const Vec3d& facing, std::vector<std::array<Vec3d, 3>>& out) {
  std::vector<std::uint32_t> loop(points.size());
  for (std::uint32_t k = 0; k < loop.size(); ++k) loop[k] = k;
  std::vector<Triangle> triangles;
  if (!triangulate_polygon(points, loop, facing, triangles)) return;
  for (const Triangle& t : triangles) out.push_back({points[t[0]], points[t[1]], points[t[2]]});
}

Vec3d loop_area(const std::vector<Vec3d>& points) {  // twice the area, along the loop's facing
  std::vector<std::uint32_t> loop(points.size());
  for (std::uint32_t k = 0; k < loop.size(); ++k) loop[k] = k;
  return newell_normal(points, loop);
}

// Holes in flat regions with nothing in front across their outline: glued slits
// inside the region, then nothing (a hole in a wall without thickness) or faces
// behind (an overhang, fins, a reveal). A region's faces run counter-clockwise about
// its facing, so along a hole their half-edges run clockwise.
void region_holes(const TriMesh& mesh, const Regions& regions, std::vector<std::array<Vec3d, 3>>& out) {
  std::vector<char> seen(mesh.n_halfedges(), 0);
  std::vector<Vec3d> points;
  for (auto start : mesh.halfedges()) {
    if (mesh.is_boundary(start) || seen[start.idx()] || regions.across(start) == Regions::Across::region) continue;
    const Vec3d n = mesh.normal(mesh.face_handle(start));
    points.clear();
    bool in_front = false, closed = false;
    Halfedge h = start;
    for (std::size_t steps = 0; steps < mesh.n_halfedges(); ++steps) {
      seen[h.idx()] = 1;
      in_front = in_front || regions.across(h) == Regions::Across::in_front;
      points.push_back(mesh.point(mesh.from_vertex_handle(h)));
      h = regions.next_on_outline(h);
      if (h == start) {
        closed = true;
        break;
      }
      if (!h.is_valid() || mesh.is_boundary(h) || seen[h.idx()]) break;
    }
    if (!closed || in_front || points.size() < 3) continue;
    if (!(OpenMesh::dot(loop_area(points), n) < 0)) continue;  // the region's outer outline
    add_loop(points, n, out);
  }
}

// Flat loops of the mesh's boundary that are not a hole in one region (those are
// region_holes'), and not a region's outline: the missing ceiling of a box open at the
// top, a door down to the floor (the floor's edge closes its loop).
void boundary_openings(const TriMesh& mesh, std::vector<std::array<Vec3d, 3>>& out) {
  std::vector<char> seen(mesh.n_halfedges(), 0);
  std::vector<Vec3d> points;
  std::vector<Halfedge> edges;
  for (auto start : mesh.halfedges()) {
    if (!mesh.is_boundary(start) || seen[start.idx()]) continue;
    points.clear();
    edges.clear();
    Halfedge h = start;
    do {
      seen[h.idx()] = 1;
      edges.push_back(h);
      points.push_back(mesh.point(mesh.from_vertex_handle(h)));
      h = mesh.next_halfedge_handle(h);
    } while (h != start && edges.size() <= mesh.n_halfedges());
    if (points.size() < 3) continue;
    const Vec3d area = loop_area(points);
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
    // The faces along the loop: in its plane, a region's outline runs clockwise about
    // their facing (the faces' own edges run counter-clockwise) and a hole the other
    // way; all in the plane, it is region_holes'.
    bool border = false, all_coplanar = true;
    for (Halfedge e : edges) {
      const Vec3d& n = mesh.normal(mesh.face_handle(mesh.opposite_halfedge_handle(e)));
      if (std::abs(OpenMesh::dot(n, m)) > 1 - 1e-6)
        border = border || OpenMesh::dot(n, m) < 0;
      else
        all_coplanar = false;
    }
    if (border || all_coplanar) continue;
    add_loop(points, m, out);
  }
}

}  // namespace

std::vector<std::array<Vec3d, 3>> find_openings(const TriMesh& mesh) {
  std::vector<std::array<Vec3d, 3>> out;
  const Regions regions(mesh);
  region_holes(mesh, regions, out);
  boundary_openings(mesh, out);
  return out;
}

}  // namespace dynrad
