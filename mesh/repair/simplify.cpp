// Flat-region simplification with OpenMesh's Decimater (see simplify.h).
//
// Why not ModQuadricT with a tiny maximum error: its quadrics are weighted by face
// area, so "zero up to rounding" has no fixed threshold (it depends on how finely the
// region was cut), and evaluating a sum of thousands of accumulated planes cancels
// away far more precision than the rounding of the coordinates themselves. Instead,
// ModKeepPlanes below remembers each face's original plane. A half-edge collapse never
// moves a vertex and never creates a face: it rewires the faces around the removed
// vertex v0 to the kept vertex v1. So it is enough to ask, for each rewired face, that
// v1 lie in that face's original plane and that the rewired triangle face the same way
// with a real area. Every face then stays in its original plane forever (no drift over
// many collapses), the faces around v0 cover exactly what they covered before, and a
// vertex in the middle of a straight crease can slide only along the crease (it must
// stay in both planes), while a corner cannot move at all.
#include "mesh/repair/simplify.h"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace dynrad {
namespace {

// Whether p lies within `distance` of the segment ab, strictly between its ends.
bool on_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b, double distance) {
  const Vec3d d = b - a;
  const double t = OpenMesh::dot(p - a, d) / d.sqrnorm();
  return t > 0 && t < 1 && (p - (a + d * t)).norm() <= distance;
}

// Binary module: a collapse is legal only if every face it rewires keeps its original
// plane (within `distance`) and its facing, with twice its area above `min_double_area`.
template <typename MeshT>
class ModKeepPlanesT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModKeepPlanesT, MeshT, KeepPlanes);

  explicit ModKeepPlanesT(MeshT& mesh) : Base(mesh, true) { mesh.add_property(plane_); }
  ~ModKeepPlanesT() override { Base::mesh().remove_property(plane_); }

  // Positions are taken relative to `origin` (the middle of the model) so that a model
  // far from the world origin keeps its precision.
  void set_tolerances(const Vec3d& origin, double distance, double min_double_area) {
    origin_ = origin;
    distance_ = distance;
    min_double_area_ = min_double_area;
  }

  void initialize() override {
    MeshT& mesh = Base::mesh();
    for (auto f : mesh.faces()) {
      auto h = mesh.halfedge_handle(f);
      const Vec3d a = mesh.point(mesh.from_vertex_handle(h)) - origin_;
      const Vec3d b = mesh.point(mesh.to_vertex_handle(h)) - origin_;
      const Vec3d c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - origin_;
      Vec3d n = OpenMesh::cross(b - a, c - a);
      const double length = n.norm();
      if (length > 0) n /= length;
      mesh.property(plane_, f) = Plane{n, OpenMesh::dot(n, (a + b + c) / 3.0)};
    }
  }

  float collapse_priority(const CollapseInfo& ci) override {
    const MeshT& mesh = Base::mesh();
    // A vertex on a straight material border (a feature vertex) may go only if the
    // border stays straight without it: it lies on the segment between its two border
    // neighbours (one of them v1; the Decimater allows feature collapses along the
    // border only).
    if (mesh.status(ci.v0).feature()) {
      VertexHandle other;
      for (auto h : mesh.voh_range(ci.v0))
        if (mesh.status(mesh.edge_handle(h)).feature() && mesh.to_vertex_handle(h) != ci.v1)
          other = mesh.to_vertex_handle(h);
      if (!other.is_valid() || !on_segment(ci.p0, ci.p1, mesh.point(other), distance_)) return Base::ILLEGAL_COLLAPSE;
    }
    const Vec3d p1 = ci.p1 - origin_;
    for (auto h : mesh.voh_range(ci.v0)) {
      const FaceHandle f = mesh.face_handle(h);
      if (!f.is_valid() || f == ci.fl || f == ci.fr) continue;
      // The face is (v0, a, b) counter-clockwise; after the collapse it is (v1, a, b).
      const Vec3d a = mesh.point(mesh.to_vertex_handle(h)) - origin_;
      const Vec3d b = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - origin_;
      const Plane& plane = mesh.property(plane_, f);
      if (std::abs(OpenMesh::dot(plane.normal, p1) - plane.offset) > distance_) return Base::ILLEGAL_COLLAPSE;
      if (OpenMesh::dot(OpenMesh::cross(a - p1, b - p1), plane.normal) <= min_double_area_)
        return Base::ILLEGAL_COLLAPSE;
    }
    return Base::LEGAL_COLLAPSE;
  }

 private:
  struct Plane {
    Vec3d normal;
    double offset = 0;  // normal . x for points x of the plane (relative to origin_)
  };
  OpenMesh::FPropHandleT<Plane> plane_;
  Vec3d origin_{0.0};
  double distance_ = 0, min_double_area_ = 0;
};

bool is_material_border(const SceneMesh& scene, OpenMesh::EdgeHandle e) {
  const TriMesh& mesh = scene.mesh();
  const FaceHandle a = mesh.face_handle(mesh.halfedge_handle(e, 0)), b = mesh.face_handle(mesh.halfedge_handle(e, 1));
  return a.is_valid() && b.is_valid() && scene.material_id(a) != scene.material_id(b);
}

// Marks what a collapse may not change from the planes alone. Mesh boundaries
// (openings, cuts) are locked. A vertex on a material border may only slide along it
// where the border runs straight through it (two border edges, in line): it becomes a
// feature vertex and its border edges feature edges, and the Decimater collapses a
// feature vertex only along a feature edge. Anything else on a border (a corner of it,
// or three materials meeting) is locked. Returns how many vertices are locked.
std::size_t mark_vertices(SceneMesh& scene, double distance) {
  TriMesh& mesh = scene.mesh();
  for (auto e : mesh.edges()) mesh.status(e).set_feature(is_material_border(scene, e));
  std::size_t locked = 0;
  for (auto v : mesh.vertices()) {
    bool lock = mesh.is_boundary(v), feature = false;
    if (!lock) {
      std::vector<VertexHandle> along;
      for (auto h : mesh.voh_range(v))
        if (mesh.status(mesh.edge_handle(h)).feature()) along.push_back(mesh.to_vertex_handle(h));
      feature = !along.empty();
      lock = feature &&
             (along.size() != 2 || !on_segment(mesh.point(v), mesh.point(along[0]), mesh.point(along[1]), distance));
    }
    mesh.status(v).set_locked(lock);
    mesh.status(v).set_feature(feature && !lock);
    locked += lock;
  }
  return locked;
}

}  // namespace

double aspect_ratio(const TriMesh& mesh, FaceHandle f) {
  auto it = mesh.cfv_iter(f);
  const Vec3d& a = mesh.point(*it);
  const Vec3d& b = mesh.point(*++it);
  const Vec3d& c = mesh.point(*++it);
  const double longest2 = std::max({(b - a).sqrnorm(), (c - b).sqrnorm(), (a - c).sqrnorm()});
  const double double_area = OpenMesh::cross(b - a, c - a).norm();
  // Height over the longest edge l is 2A / l, so l / height = l^2 / 2A.
  return double_area > 0 ? longest2 / double_area : std::numeric_limits<double>::infinity();
}

double worst_aspect_ratio(const TriMesh& mesh) {
  double worst = 0;
  for (auto f : mesh.faces()) worst = std::max(worst, aspect_ratio(mesh, f));
  return worst;
}

SimplifyReport simplify_flat_regions(SceneMesh& scene, const SimplifyOptions& options) {
  using namespace OpenMesh::Decimater;
  TriMesh& mesh = scene.mesh();
  SimplifyReport report;
  report.faces_before = report.faces_after = mesh.n_faces();
  report.vertices_before = report.vertices_after = mesh.n_vertices();
  if (!options.enabled || mesh.n_faces() == 0) return report;
  const auto start = std::chrono::steady_clock::now();
  report.worst_aspect_before = worst_aspect_ratio(mesh);

  const Bounds bounds = scene.bounds();
  const double diagonal = bounds.diagonal();
  report.locked_vertices = mark_vertices(scene, options.flatness * diagonal);
  {
    DecimaterT<TriMesh> decimater(mesh);
    typename ModKeepPlanesT<TriMesh>::Handle keep_planes;
    typename ModNormalFlippingT<TriMesh>::Handle normal_flipping;
    typename ModAspectRatioT<TriMesh>::Handle aspect;
    decimater.add(keep_planes);
    decimater.add(normal_flipping);
    decimater.add(aspect);
    // Same smallest area as cleanup's degenerate-triangle rule (CleanupOptions::min_area).
    decimater.module(keep_planes)
        .set_tolerances((bounds.lo + bounds.hi) * 0.5, options.flatness * diagonal, 2e-14 * diagonal * diagonal);
    // A second guard against flips, relative to the current normals: faces that stay in
    // their plane turn by rounding only.
    decimater.module(normal_flipping).set_max_normal_deviation(1.0);
    // The priority: the collapse that leaves the best-shaped triangles goes first.
    decimater.module(aspect).set_binary(false);
    decimater.module(aspect).set_aspect_ratio(static_cast<float>(options.max_aspect_ratio));
    if (!decimater.initialize()) throw std::logic_error("internal error: the decimater did not initialise");
    report.collapses = decimater.decimate();
  }
  for (auto v : mesh.vertices()) {
    mesh.status(v).set_locked(false);
    mesh.status(v).set_feature(false);
  }
  for (auto e : mesh.edges()) mesh.status(e).set_feature(false);
  mesh.garbage_collection();
  for (auto f : mesh.faces()) scene.set_patch(f, static_cast<std::uint32_t>(f.idx()));
  mesh.update_face_normals();

  report.faces_after = mesh.n_faces();
  report.vertices_after = mesh.n_vertices();
  report.worst_aspect_after = worst_aspect_ratio(mesh);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace dynrad
