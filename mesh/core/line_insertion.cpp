#include "mesh/core/line_insertion.h"

#include "mesh/core/refinement.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_set>

namespace dynrad {

namespace {

// Faces whose unit normals agree this closely are in one plane (they share an edge).
constexpr double kSameNormal = 1 - 1e-9;

class LineWalk {
 public:
  LineWalk(SceneMesh& scene, const Vec3d& normal, const LineOptions& options)
      : scene_(scene), mesh_(scene.mesh()), n_(normal), options_(options) {}

  // The face of the flat region around `start` that holds p, or an invalid handle.
  FaceHandle locate(FaceHandle start, const Vec3d& p) const {
    std::deque<FaceHandle> queue{start};
    std::unordered_set<int> seen{start.idx()};
    const double slack = std::max(options_.snap, 1e-12);
    while (!queue.empty() && seen.size() <= options_.search_limit) {
      const FaceHandle f = queue.front();
      queue.pop_front();
      if (inside(f, p, slack)) return f;
      for (auto g : mesh_.ff_range(f))
        if (coplanar(g) && seen.insert(g.idx()).second) queue.push_back(g);
    }
    return FaceHandle();
  }

  // p, in face f, as a vertex: a corner within snap, a point on an edge within snap of
  // it, or a new vertex splitting f.
  VertexHandle insert_point(FaceHandle f, const Vec3d& p) {
    for (VertexHandle v : mesh_.fv_range(f))
      if ((mesh_.point(v) - p).norm() <= options_.snap) return v;
    for (auto h : mesh_.fh_range(f)) {
      const Vec3d& a = mesh_.point(mesh_.from_vertex_handle(h));
      const Vec3d& b = mesh_.point(mesh_.to_vertex_handle(h));
      if (inward_distance(a, b, p) <= options_.snap) return split_edge(mesh_.edge_handle(h), on_segment(a, b, p));
    }
    return split_face(f, p);
  }

  // Walks from vertex v to q (see the header), making the line's pieces edges.
  InsertedLine walk(VertexHandle v, const Vec3d& q) {
    InsertedLine& r = result_;
    r.started = true;
    double last_length = std::numeric_limits<double>::infinity();
    for (std::size_t step = 0; step < 1000000; ++step) {
      const Vec3d to_q = q - mesh_.point(v);
      const double length = to_q.norm();
      if (length <= std::max(options_.snap, 1e-12)) {
        r.reached_end = true;
        break;
      }
      // Every step gets nearer q; one that did not (a sliver the line cannot cross
      // without a vertex in the same place) ends the line there.
      if (!(length < last_length)) break;
      last_length = length;
      const Vec3d d = to_q / length;
      // Along an edge of the region that points at q.
      bool followed = false;
      for (auto h : mesh_.voh_range(v)) {
        if (!coplanar(mesh_.face_handle(h)) && !coplanar(mesh_.opposite_face_handle(h))) continue;
        const VertexHandle a = mesh_.to_vertex_handle(h);
        const Vec3d u = mesh_.point(a) - mesh_.point(v);
        const double along = OpenMesh::dot(u, d);
        if (!(along > 0) || (u - d * along).norm() > options_.snap) continue;
        followed = true;
        if (along < length - options_.snap) {
          mark(v, a);
          v = a;
        } else if ((mesh_.point(a) - q).norm() <= options_.snap) {
          mark(v, a);
          v = a;
          r.reached_end = true;
        } else {  // q lies on this edge
          const VertexHandle m = split_edge(mesh_.edge_handle(h), on_segment(mesh_.point(v), mesh_.point(a), q));
          mark(v, m);
          v = m;
          r.reached_end = true;
        }
        break;
      }
      if (r.reached_end) break;
      if (followed) continue;
      // Into the face whose corner at v holds the direction to q.
      OpenMesh::HalfedgeHandle across;  // the edge opposite v in that face, run a -> b
      for (auto h : mesh_.voh_range(v)) {
        if (!coplanar(mesh_.face_handle(h))) continue;
        const OpenMesh::HalfedgeHandle ab = mesh_.next_halfedge_handle(h);
        const Vec3d va = mesh_.point(mesh_.from_vertex_handle(ab)) - mesh_.point(v);
        const Vec3d vb = mesh_.point(mesh_.to_vertex_handle(ab)) - mesh_.point(v);
        if (cross_n(va, d) >= 0 && cross_n(d, vb) >= 0) {
          across = ab;
          break;
        }
      }
      if (!across.is_valid()) break;  // the flat region ends here
      const VertexHandle a = mesh_.from_vertex_handle(across), b = mesh_.to_vertex_handle(across);
      const Vec3d pa = mesh_.point(a), pb = mesh_.point(b), pv = mesh_.point(v);
      if (inward_distance(pa, pb, q) >= 0) {  // q is in this face: the line ends in it
        VertexHandle end;
        if ((pa - q).norm() <= options_.snap)
          end = a;
        else if ((pb - q).norm() <= options_.snap)
          end = b;
        else if (inward_distance(pa, pb, q) <= options_.snap)
          end = split_edge(mesh_.edge_handle(across), on_segment(pa, pb, q));
        else if ((on_segment(pv, pa, q) - q).norm() <= options_.snap)  // (a sliver otherwise)
          end = split_edge(mesh_.edge_handle(mesh_.find_halfedge(v, a)), on_segment(pv, pa, q));
        else if ((on_segment(pv, pb, q) - q).norm() <= options_.snap)
          end = split_edge(mesh_.edge_handle(mesh_.find_halfedge(v, b)), on_segment(pv, pb, q));
        else
          end = split_face(mesh_.face_handle(across), q);
        if (!end.is_valid()) break;
        mark(v, end);
        v = end;
        r.reached_end = true;
        break;
      }
      const Vec3d e = pb - pa;
      const double denominator = cross_n(d, e);
      if (!(std::abs(denominator) > 0)) break;
      const double t = std::clamp(cross_n(pa - pv, d) / denominator, 0.0, 1.0);
      const Vec3d x = pa + e * t;
      VertexHandle next;
      if ((x - pa).norm() <= options_.snap)
        next = a;
      else if ((x - pb).norm() <= options_.snap)
        next = b;
      else
        next = split_edge(mesh_.edge_handle(across), x, v);
      mark(v, next);
      v = next;
    }
    return r;
  }

 private:
  bool coplanar(FaceHandle f) const { return f.is_valid() && OpenMesh::dot(mesh_.normal(f), n_) > kSameNormal; }
  double cross_n(const Vec3d& a, const Vec3d& b) const { return OpenMesh::dot(OpenMesh::cross(a, b), n_); }

  // Distance of p from the line a -> b, positive on its left seen from the front (the
  // inside of a face whose edge runs a -> b).
  double inward_distance(const Vec3d& a, const Vec3d& b, const Vec3d& p) const {
    const double length = (b - a).norm();
    return length > 0 ? cross_n(b - a, p - a) / length : 0;
  }

  static Vec3d on_segment(const Vec3d& a, const Vec3d& b, const Vec3d& p) {
    const Vec3d e = b - a;
    const double t = std::clamp(OpenMesh::dot(p - a, e) / e.sqrnorm(), 0.0, 1.0);
    return a + e * t;
  }

  bool inside(FaceHandle f, const Vec3d& p, double slack) const {
    for (auto h : mesh_.fh_range(f))
      if (inward_distance(mesh_.point(mesh_.from_vertex_handle(h)), mesh_.point(mesh_.to_vertex_handle(h)), p) < -slack)
        return false;
    return true;
  }

  // Splits edge e at x (refinement.h's split_edge), unless a corner of the faces beside
  // e is within snap of x already (a line crossing another at one of its vertices, or
  // a flat corner): then that corner, not a second vertex in its place. (Not the vertex
  // the walk crosses e from: in a sliver it may lie within snap of e, and the line must
  // get past it.)
  VertexHandle split_edge(OpenMesh::EdgeHandle e, const Vec3d& x, VertexHandle walking_from = VertexHandle()) {
    VertexHandle near[4];  // e's ends, then the opposite corners
    for (int s = 0; s < 2; ++s) {
      const OpenMesh::HalfedgeHandle h = mesh_.halfedge_handle(e, s);
      near[s] = mesh_.from_vertex_handle(h);
      if (mesh_.face_handle(h).is_valid()) near[2 + s] = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    }
    for (VertexHandle c : near)
      if (c.is_valid() && c != walking_from && (mesh_.point(c) - x).norm() <= options_.snap) return c;
    ++result_.vertices_added;
    return cut(e, x);
  }

  VertexHandle cut(OpenMesh::EdgeHandle e, const Vec3d& x) {
    return options_.split ? options_.split(e, x).vertex : dynrad::split_edge(mesh_, e, x, scene_.line_width_property()).vertex;
  }

  // Splits face f at x (1 -> 3; with LineOptions::split, two edge splits).
  VertexHandle split_face(FaceHandle f, const Vec3d& x) {
    for (auto c : mesh_.fv_range(f))
      if ((mesh_.point(c) - x).norm() <= options_.snap) return c;
    if (options_.split) {
      // The longest edge a -> b and the corner c opposite it: the line from c through x
      // meets a -> b at y; split there, then the new edge c - y at x.
      OpenMesh::HalfedgeHandle longest;
      double length = -1;
      for (auto h : mesh_.fh_range(f))
        if (mesh_.calc_edge_sqr_length(h) > length) {
          length = mesh_.calc_edge_sqr_length(h);
          longest = h;
        }
      const VertexHandle a = mesh_.from_vertex_handle(longest), b = mesh_.to_vertex_handle(longest);
      const VertexHandle c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(longest));
      const Vec3d pa = mesh_.point(a), pb = mesh_.point(b), pc = mesh_.point(c);
      const double denominator = cross_n(x - pc, pb - pa);
      if (!(std::abs(denominator) > 0)) return VertexHandle();
      const double t = std::clamp(cross_n(pa - pc, x - pc) / denominator, 0.0, 1.0);
      const VertexHandle y = cut(mesh_.edge_handle(longest), pa + (pb - pa) * t);
      const OpenMesh::HalfedgeHandle cy = mesh_.find_halfedge(c, y);
      if (!cy.is_valid()) return y;
      ++result_.vertices_added;
      return cut(mesh_.edge_handle(cy), x);
    }
    const Vec3d normal = mesh_.normal(f);
    const VertexHandle m = mesh_.add_vertex(x);
    mesh_.split_copy(f, m);
    for (auto g : mesh_.vf_range(m)) mesh_.set_normal(g, normal);
    for (auto e : mesh_.ve_range(m)) scene_.set_line_width(e, 0.0f);
    ++result_.vertices_added;
    return m;
  }

  // The edge v - w is now part of the line.
  void mark(VertexHandle v, VertexHandle w) {
    const OpenMesh::HalfedgeHandle h = mesh_.find_halfedge(v, w);
    if (!h.is_valid()) return;
    const OpenMesh::EdgeHandle e = mesh_.edge_handle(h);
    scene_.set_line_width(e, std::max(scene_.line_width(e), options_.width));
    ++result_.edges;
  }

  SceneMesh& scene_;
  TriMesh& mesh_;
  Vec3d n_;
  LineOptions options_;
  InsertedLine result_;
};

}  // namespace

InsertedLine insert_line(SceneMesh& scene, FaceHandle start, const Vec3d& p, const Vec3d& q,
                         const LineOptions& options) {
  if (!start.is_valid() || !(options.width > 0)) return {};
  LineWalk walk(scene, scene.mesh().normal(start), options);
  const FaceHandle f = walk.locate(start, p);
  if (!f.is_valid()) return {};
  const VertexHandle v = walk.insert_point(f, p);
  if (!v.is_valid()) return {};
  return walk.walk(v, q);
}

std::size_t flip_beside_lines(SceneMesh& scene) {
  TriMesh& mesh = scene.mesh();
  if (!scene.has_lines()) return 0;
  std::vector<OpenMesh::EdgeHandle> queue;
  std::vector<char> queued(mesh.n_edges(), 0);
  auto push = [&](OpenMesh::EdgeHandle e) {
    if (!queued[e.idx()]) {
      queued[e.idx()] = 1;
      queue.push_back(e);
    }
  };
  for (auto e : mesh.edges())
    if (scene.line_width(e) > 0)
      for (int k = 0; k < 2; ++k)
        for (auto around : mesh.ve_range(k == 0 ? mesh.from_vertex_handle(mesh.halfedge_handle(e, 0))
                                                : mesh.to_vertex_handle(mesh.halfedge_handle(e, 0))))
          push(around);
  auto angle_at = [&](VertexHandle c, VertexHandle a, VertexHandle b) {
    const Vec3d u = mesh.point(a) - mesh.point(c), v = mesh.point(b) - mesh.point(c);
    return std::atan2(OpenMesh::cross(u, v).norm(), OpenMesh::dot(u, v));
  };
  std::size_t flips = 0;
  const std::size_t limit = 50 * queue.size() + 1000;
  for (std::size_t step = 0; !queue.empty() && step < limit; ++step) {
    const OpenMesh::EdgeHandle e = queue.back();
    queue.pop_back();
    queued[e.idx()] = 0;
    if (scene.line_width(e) > 0 || mesh.is_boundary(e)) continue;
    const OpenMesh::HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const FaceHandle f0 = mesh.face_handle(h0), f1 = mesh.face_handle(h1);
    if (OpenMesh::dot(mesh.normal(f0), mesh.normal(f1)) <= kSameNormal) continue;
    if (scene.material_id(f0) != scene.material_id(f1) || scene.group(f0) != scene.group(f1)) continue;
    const SourceRef &r0 = scene.origin(f0), &r1 = scene.origin(f1);
    if (r0.file != r1.file || r0.line != r1.line || r0.face != r1.face) continue;
    const VertexHandle a = mesh.from_vertex_handle(h0), b = mesh.to_vertex_handle(h0);
    const VertexHandle c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
    const VertexHandle d = mesh.to_vertex_handle(mesh.next_halfedge_handle(h1));
    if (angle_at(c, a, b) + angle_at(d, a, b) <= M_PI + 1e-9 || !mesh.is_flip_ok(e)) continue;
    const Vec3d normal = mesh.normal(f0);
    mesh.flip(e);
    mesh.set_normal(f0, normal);
    mesh.set_normal(f1, normal);
    ++flips;
    for (FaceHandle f : {f0, f1})
      for (auto around : mesh.fe_range(f))
        if (around != e) push(around);
  }
  return flips;
}

}  // namespace dynrad
