// Decimation of a lit mesh with a bounded colour error (see lit_decimate.h), with
// OpenMesh's Decimater and three modules:
//
// - ModKeepSurfaceT (binary): the surface stays what it was. A half-edge collapse never
//   moves a vertex and never creates a face: it rewires the faces around the removed
//   vertex v0 to the kept vertex v1. Each face remembers the plane it was in; a collapse
//   is legal only if v1 lies in the original plane of every face it rewires and each
//   rewired face keeps its facing with a real area (as mesh/repair/simplify.cpp does). Inside
//   a plane the faces then cover what they covered; on a crease v1 must lie in both
//   planes, so v0 slides along the crease only. A vertex on a border (a boundary edge,
//   or an edge between triangles of different labels) goes only along it, and only
//   where the border runs straight through it.
// - ModNormalFlippingT (binary, OpenMesh's): no face turns by more than a degree.
// - ModColourBoundT (the priority): every input vertex that is gone is remembered by the
//   face that covers it. For a candidate collapse, the vertex v0 and the vertices the
//   faces around it remember are located in the rewired faces (the ones in their
//   plane, the one they lie most inside of) and the colour and quality interpolated
//   there are compared with their own. The priority is the largest error as a fraction
//   of the bound at that vertex; above 1 the collapse is illegal. When a collapse is
//   done, those vertices move to the faces they were located in.
//
// The Decimater takes the smallest priority first and re-evaluates the one-ring of v0
// after each collapse, which is exactly the set of vertices whose candidate collapses
// touch a changed face. Everything is sequential: same input, same output.
#include "mesh/io/lit_decimate.h"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace dynrad {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

struct Plane {
  Vec3d normal{0.0};  // unit
  double offset = 0;  // normal . x for the points x of the plane
};

// What the modules share: per-face properties of the mesh and the tolerances. Mesh
// vertex i is input vertex i; points are relative to the middle of the model.
struct Shared {
  OpenMesh::FPropHandleT<Plane> plane;
  OpenMesh::FPropHandleT<std::uint32_t> label;
  // The input vertices, gone from the mesh, that this face covers.
  OpenMesh::FPropHandleT<std::vector<std::uint32_t>> remembered;
  double distance = 0;  // how far from its plane a point may be and lie in it
  const VertexValues* values = nullptr;
  double colour_units = 0, colour_fraction = 0, quality_fraction = 0, quality_floor = 0;
};

// Whether p lies within `distance` of the segment ab, strictly between its ends.
bool on_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b, double distance) {
  const Vec3d d = b - a;
  const double length2 = d.sqrnorm();
  if (!(length2 > 0)) return false;
  const double t = OpenMesh::dot(p - a, d) / length2;
  return t > 0 && t < 1 && (p - (a + d * t)).norm() <= distance;
}

// Whether a triangle is wider than `distance` (twice its area over its longest edge): a
// narrower one has no plane or facing to speak of at that tolerance, and the points it
// covers could not be told from those of its neighbours.
bool wider_than(const Vec3d& a, const Vec3d& b, const Vec3d& c, double double_area, double distance) {
  const double longest2 = std::max({(b - a).sqrnorm(), (c - b).sqrnorm(), (a - c).sqrnorm()});
  return double_area > 0 && double_area * double_area > distance * distance * longest2;
}

bool is_border(const TriMesh& mesh, const Shared& shared, OpenMesh::EdgeHandle e) {
  const FaceHandle a = mesh.face_handle(mesh.halfedge_handle(e, 0)), b = mesh.face_handle(mesh.halfedge_handle(e, 1));
  return !a.is_valid() || !b.is_valid() || mesh.property(shared.label, a) != mesh.property(shared.label, b);
}

template <typename MeshT>
class ModKeepSurfaceT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModKeepSurfaceT, MeshT, KeepSurface);

  explicit ModKeepSurfaceT(MeshT& mesh) : Base(mesh, true) {}
  void set_shared(const Shared* shared) { shared_ = shared; }

  float collapse_priority(const CollapseInfo& ci) override {
    const MeshT& mesh = Base::mesh();
    // A border vertex: exactly two border edges, the collapse along one of them, and
    // the vertex on the segment between their other ends.
    int borders = 0;
    bool along = false;
    VertexHandle other;
    for (auto h : mesh.voh_range(ci.v0)) {
      if (!is_border(mesh, *shared_, mesh.edge_handle(h))) continue;
      ++borders;
      if (mesh.to_vertex_handle(h) == ci.v1)
        along = true;
      else
        other = mesh.to_vertex_handle(h);
    }
    if (borders != 0 && (borders != 2 || !along || !other.is_valid() ||
                         !on_segment(ci.p0, ci.p1, mesh.point(other), shared_->distance)))
      return Base::ILLEGAL_COLLAPSE;
    // Every rewired face: v1 in its original plane, same facing, wider than the tolerance.
    for (auto h : mesh.voh_range(ci.v0)) {
      const FaceHandle f = mesh.face_handle(h);
      if (!f.is_valid() || f == ci.fl || f == ci.fr) continue;
      // The face is (v0, a, b) counter-clockwise; after the collapse it is (v1, a, b).
      const Vec3d& a = mesh.point(mesh.to_vertex_handle(h));
      const Vec3d& b = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
      const Plane& plane = mesh.property(shared_->plane, f);
      if (std::abs(OpenMesh::dot(plane.normal, ci.p1) - plane.offset) > shared_->distance)
        return Base::ILLEGAL_COLLAPSE;
      if (!wider_than(ci.p1, a, b, OpenMesh::dot(OpenMesh::cross(a - ci.p1, b - ci.p1), plane.normal),
                      shared_->distance))
        return Base::ILLEGAL_COLLAPSE;
    }
    return Base::LEGAL_COLLAPSE;
  }

 private:
  const Shared* shared_ = nullptr;
};

// A triangle ready to locate points in: barycentric coordinates and the distance from
// its plane.
struct Frame {
  Vec3d a, e1, e2, scaled_normal;  // scaled_normal = n / |n|^2, n = e1 x e2
  Vec3d unit_normal;

  Frame(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2) : a(p0), e1(p1 - p0), e2(p2 - p0) {
    const Vec3d n = OpenMesh::cross(e1, e2);
    const double n2 = n.sqrnorm();
    scaled_normal = n2 > 0 ? n / n2 : Vec3d(0.0);
    unit_normal = n2 > 0 ? n / std::sqrt(n2) : Vec3d(0.0);
  }
  std::array<double, 3> barycentric(const Vec3d& p) const {
    const Vec3d w = p - a;
    const double l1 = OpenMesh::dot(OpenMesh::cross(w, e2), scaled_normal);
    const double l2 = OpenMesh::dot(OpenMesh::cross(e1, w), scaled_normal);
    return {1 - l1 - l2, l1, l2};
  }
  double distance(const Vec3d& p) const { return std::abs(OpenMesh::dot(p - a, unit_normal)); }
};

// Interpolation weights for a point located in a face: negative ones (a point a rounding
// outside) set to zero, the rest rescaled to sum to one.
std::array<double, 3> weights(std::array<double, 3> l) {
  double sum = 0;
  for (double& x : l) sum += (x = std::max(x, 0.0));
  if (!(sum > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  for (double& x : l) x /= sum;
  return l;
}

// The errors at one input vertex shown through a face with these corners and weights.
struct VertexError {
  double colour = 0;    // 8-bit units, largest channel
  double quality = 0;   // quality units
  double fraction = 0;  // of the bound, largest of colour and quality
};

double over(double error, double bound) {
  if (bound > 0) return error / bound;
  return error > 0 ? std::numeric_limits<double>::infinity() : 0.0;
}

VertexError error_at(const Shared& s, std::uint32_t p, const std::array<std::uint32_t, 3>& corner,
                     const std::array<double, 3>& w) {
  const VertexValues& v = *s.values;
  VertexError e;
  for (int c = 0; c < 3; ++c) {
    const double shown =
        w[0] * v.display[corner[0]][c] + w[1] * v.display[corner[1]][c] + w[2] * v.display[corner[2]][c];
    const double own = v.display[p][c];
    const double error = std::abs(shown - own);
    e.colour = std::max(e.colour, error);
    e.fraction = std::max(e.fraction, over(error, std::max(s.colour_units, s.colour_fraction * own)));
  }
  if (!v.quality.empty()) {
    const double shown = w[0] * v.quality[corner[0]] + w[1] * v.quality[corner[1]] + w[2] * v.quality[corner[2]];
    const double own = v.quality[p];
    e.quality = std::abs(shown - own);
    e.fraction = std::max(e.fraction, over(e.quality, std::max(s.quality_fraction * std::abs(own), s.quality_floor)));
  }
  return e;
}

template <typename MeshT>
class ModColourBoundT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModColourBoundT, MeshT, ColourBound);

  explicit ModColourBoundT(MeshT& mesh) : Base(mesh, false) {}
  void set_shared(const Shared* shared) { shared_ = shared; }

  float collapse_priority(const CollapseInfo& ci) override {
    gather(ci);
    double worst = 0;
    for (std::uint32_t p : points_) {
      const auto [k, w] = locate(p);
      const double fraction = error_at(*shared_, p, faces_[k].corner, w).fraction;
      if (!(fraction <= 1)) return Base::ILLEGAL_COLLAPSE;
      worst = std::max(worst, fraction);
    }
    return static_cast<float>(worst);
  }

  void preprocess_collapse(const CollapseInfo& ci) override {
    MeshT& mesh = Base::mesh();
    gather(ci);
    std::vector<std::vector<std::uint32_t>> moved(faces_.size());
    for (std::uint32_t p : points_) moved[locate(p).first].push_back(p);
    for (auto f : mesh.vf_range(ci.v0)) mesh.property(shared_->remembered, f).clear();
    for (std::size_t k = 0; k < faces_.size(); ++k)
      mesh.property(shared_->remembered, faces_[k].face) = std::move(moved[k]);
  }

 private:
  struct NewFace {
    FaceHandle face;
    std::array<std::uint32_t, 3> corner;  // v1 first
    Frame frame;
  };

  // The faces around v0 as the collapse would leave them, and the input vertices to
  // place in them: v0 and those the faces around it remember.
  void gather(const CollapseInfo& ci) {
    const MeshT& mesh = Base::mesh();
    faces_.clear();
    points_.clear();
    points_.push_back(static_cast<std::uint32_t>(ci.v0.idx()));
    for (auto h : mesh.voh_range(ci.v0)) {
      const FaceHandle f = mesh.face_handle(h);
      if (!f.is_valid()) continue;
      const auto& list = mesh.property(shared_->remembered, f);
      points_.insert(points_.end(), list.begin(), list.end());
      if (f == ci.fl || f == ci.fr) continue;
      const VertexHandle a = mesh.to_vertex_handle(h), b = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
      faces_.push_back(NewFace{f,
                               {static_cast<std::uint32_t>(ci.v1.idx()), static_cast<std::uint32_t>(a.idx()),
                                static_cast<std::uint32_t>(b.idx())},
                               Frame(ci.p1, mesh.point(a), mesh.point(b))});
    }
  }

  // The new face input vertex p lies in: among those whose plane it lies in (all, if
  // none), the one it is most inside of; with its interpolation weights.
  std::pair<std::size_t, std::array<double, 3>> locate(std::uint32_t p) {
    const Vec3d& x = Base::mesh().point(VertexHandle(static_cast<int>(p)));
    std::size_t best = 0;
    bool best_in_plane = false;
    double best_inside = -std::numeric_limits<double>::infinity();
    std::array<double, 3> best_l{1, 0, 0};
    for (std::size_t k = 0; k < faces_.size(); ++k) {
      const bool in_plane = faces_[k].frame.distance(x) <= 2 * shared_->distance;
      if (best_in_plane && !in_plane) continue;
      const auto l = faces_[k].frame.barycentric(x);
      const double inside = std::min({l[0], l[1], l[2]});
      if ((in_plane && !best_in_plane) || inside > best_inside) {
        best = k;
        best_in_plane = in_plane;
        best_inside = inside;
        best_l = l;
      }
    }
    return {best, weights(best_l)};
  }

  const Shared* shared_ = nullptr;
  std::vector<NewFace> faces_;
  std::vector<std::uint32_t> points_;
};

void check_sizes(const std::vector<Vec3d>& positions, const std::vector<Triangle>& triangles,
                 const std::vector<std::uint32_t>* labels, const VertexValues& values,
                 const LitDecimateOptions& options) {
  const std::size_t n = positions.size();
  auto one_per_vertex_or_none = [n](std::size_t size, const std::string& what) {
    if (size != 0 && size != n)
      throw std::invalid_argument("decimate_lit_mesh: " + what + " has " + std::to_string(size) + " values for " +
                                  std::to_string(n) + " vertices");
  };
  if (values.display.size() != n)
    throw std::invalid_argument("decimate_lit_mesh: " + std::to_string(values.display.size()) +
                                " display colours for " + std::to_string(n) + " vertices");
  one_per_vertex_or_none(values.linear.size(), "linear");
  one_per_vertex_or_none(values.quality.size(), "quality");
  for (const auto& [name, scalar] : values.scalars) one_per_vertex_or_none(scalar.size(), "scalar '" + name + "'");
  if (labels && labels->size() != triangles.size())
    throw std::invalid_argument("decimate_lit_mesh: " + std::to_string(labels->size()) + " labels for " +
                                std::to_string(triangles.size()) + " triangles");
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (std::uint32_t v : triangles[t])
      if (v >= n)
        throw std::invalid_argument("decimate_lit_mesh: triangle " + std::to_string(t) + " names vertex " +
                                    std::to_string(v) + " of " + std::to_string(n));
  for (double x : {options.colour_units, options.colour_fraction, options.quality_fraction, options.flatness})
    if (!(x >= 0) || !std::isfinite(x))
      throw std::invalid_argument("decimate_lit_mesh: a bound is negative or not finite");
}

template <typename T>
void keep_only(std::vector<T>& values, const std::vector<std::uint32_t>& kept) {
  if (values.empty()) return;
  std::vector<T> out;
  out.reserve(kept.size());
  for (std::uint32_t v : kept) out.push_back(values[v]);
  values = std::move(out);
}

LitDecimateReport decimate(std::vector<Vec3d>& positions, std::vector<Triangle>& triangles,
                           std::vector<std::uint32_t>* labels, VertexValues& values,
                           const LitDecimateOptions& options) {
  using namespace OpenMesh::Decimater;
  const auto start = std::chrono::steady_clock::now();
  check_sizes(positions, triangles, labels, values, options);
  LitDecimateReport report;
  report.triangles_before = triangles.size();
  report.vertices_before = positions.size();

  Bounds bounds;
  for (const Triangle& t : triangles)
    for (std::uint32_t v : t) bounds.extend(positions[v]);
  const Vec3d origin = bounds.empty() ? Vec3d(0.0) : (bounds.lo + bounds.hi) * 0.5;
  const double diagonal = bounds.diagonal();

  Shared shared;
  shared.distance = options.flatness * diagonal;
  shared.values = &values;
  shared.colour_units = options.colour_units;
  shared.colour_fraction = options.colour_fraction;
  shared.quality_fraction = options.quality_fraction;
  shared.quality_floor = options.quality_floor;
  if (shared.quality_floor < 0) {
    double largest = 0;
    for (float q : values.quality) largest = std::max(largest, static_cast<double>(q));
    shared.quality_floor = 1e-3 * largest;
  }
  report.quality_floor = shared.quality_floor;

  // The half-edge mesh: vertex i is input vertex i. Triangles it cannot take (a corner
  // twice, no wider than the tolerance, not manifold next to those before) stay as they
  // are, and so do their corners.
  TriMesh mesh;
  OpenMesh::FPropHandleT<std::uint32_t> source;  // input triangle of each face
  mesh.add_property(shared.plane);
  mesh.add_property(shared.label);
  mesh.add_property(shared.remembered);
  mesh.add_property(source);
  mesh.reserve(positions.size(), 3 * triangles.size() / 2, triangles.size());
  for (const Vec3d& p : positions) mesh.add_vertex(p - origin);
  std::vector<std::uint32_t> kept_as_they_are;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& c = triangles[t];
    const VertexHandle a(static_cast<int>(c[0])), b(static_cast<int>(c[1])), d(static_cast<int>(c[2]));
    const Vec3d n = OpenMesh::cross(mesh.point(b) - mesh.point(a), mesh.point(d) - mesh.point(a));
    FaceHandle f;
    if (c[0] != c[1] && c[1] != c[2] && c[2] != c[0] &&
        wider_than(mesh.point(a), mesh.point(b), mesh.point(d), n.norm(), shared.distance))
      f = mesh.add_face(a, b, d);
    if (!f.is_valid()) {
      kept_as_they_are.push_back(static_cast<std::uint32_t>(t));
      continue;
    }
    const Vec3d unit = n / n.norm();
    mesh.property(shared.plane, f) =
        Plane{unit, OpenMesh::dot(unit, (mesh.point(a) + mesh.point(b) + mesh.point(d)) / 3.0)};
    mesh.property(shared.label, f) = labels ? (*labels)[t] : 0;
    mesh.property(source, f) = static_cast<std::uint32_t>(t);
  }
  for (std::uint32_t t : kept_as_they_are)
    for (std::uint32_t v : triangles[t]) mesh.status(VertexHandle(static_cast<int>(v))).set_locked(true);
  report.triangles_kept_as_they_are = kept_as_they_are.size();
  mesh.update_face_normals();

  const std::size_t target =
      options.max_triangles > kept_as_they_are.size() ? options.max_triangles - kept_as_they_are.size() : 0;
  if (target < mesh.n_faces()) {
    DecimaterT<TriMesh> decimater(mesh);
    typename ModKeepSurfaceT<TriMesh>::Handle keep_surface;
    typename ModNormalFlippingT<TriMesh>::Handle normal_flipping;
    typename ModColourBoundT<TriMesh>::Handle colour_bound;
    decimater.add(keep_surface);
    decimater.add(normal_flipping);
    decimater.add(colour_bound);
    decimater.module(keep_surface).set_shared(&shared);
    decimater.module(normal_flipping).set_max_normal_deviation(options.max_normal_deviation_degrees);
    decimater.module(colour_bound).set_shared(&shared);
    if (!decimater.initialize()) throw std::logic_error("internal error: the decimater did not initialise");
    report.collapses = decimater.decimate_to_faces(0, target);
  }

  // Output triangles in the order of the input triangles they come from; a face that
  // still has its input corners keeps their order.
  std::vector<std::pair<std::uint32_t, Triangle>> out;
  out.reserve(mesh.n_faces() + kept_as_they_are.size());
  for (auto f : mesh.faces()) {
    const std::uint32_t t = mesh.property(source, f);
    Triangle c;
    int k = 0;
    for (auto v : mesh.fv_range(f)) c[k++] = static_cast<std::uint32_t>(v.idx());
    const auto first = std::find(c.begin(), c.end(), triangles[t][0]);
    if (first != c.end()) std::rotate(c.begin(), first, c.end());
    out.emplace_back(t, c);
  }
  for (std::uint32_t t : kept_as_they_are) out.emplace_back(t, triangles[t]);
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });

  // The errors at every input vertex gone, through the face that remembers it.
  for (auto f : mesh.faces()) {
    std::array<std::uint32_t, 3> corner;
    int k = 0;
    for (auto v : mesh.fv_range(f)) corner[k++] = static_cast<std::uint32_t>(v.idx());
    const Frame frame(mesh.point(VertexHandle(static_cast<int>(corner[0]))),
                      mesh.point(VertexHandle(static_cast<int>(corner[1]))),
                      mesh.point(VertexHandle(static_cast<int>(corner[2]))));
    for (std::uint32_t p : mesh.property(shared.remembered, f)) {
      const VertexError e =
          error_at(shared, p, corner, weights(frame.barycentric(mesh.point(VertexHandle(static_cast<int>(p))))));
      report.worst_colour_error = std::max(report.worst_colour_error, e.colour);
      report.worst_quality_error = std::max(report.worst_quality_error, e.quality);
      report.worst_error_fraction = std::max(report.worst_error_fraction, e.fraction);
    }
  }

  // Kept vertices, in their order, renumbered.
  constexpr std::uint32_t unused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> renumber(positions.size(), unused), kept;
  for (const auto& [t, c] : out)
    for (std::uint32_t v : c) renumber[v] = 0;
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (renumber[v] != unused) {
      renumber[v] = static_cast<std::uint32_t>(kept.size());
      kept.push_back(static_cast<std::uint32_t>(v));
    }
  triangles.clear();
  std::vector<std::uint32_t> out_labels;
  for (const auto& [t, c] : out) {
    triangles.push_back({renumber[c[0]], renumber[c[1]], renumber[c[2]]});
    if (labels) out_labels.push_back((*labels)[t]);
  }
  if (labels) *labels = std::move(out_labels);
  keep_only(positions, kept);
  keep_only(values.linear, kept);
  keep_only(values.display, kept);
  keep_only(values.quality, kept);
  for (auto& [name, scalar] : values.scalars) keep_only(scalar, kept);

  report.triangles_after = triangles.size();
  report.vertices_after = positions.size();
  report.reached_target = report.triangles_after <= options.max_triangles;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace

LitDecimateReport decimate_lit_mesh(std::vector<Vec3d>& positions, std::vector<Triangle>& triangles,
                                    VertexValues& values, const LitDecimateOptions& options) {
  return decimate(positions, triangles, nullptr, values, options);
}

LitDecimateReport decimate_lit_mesh(std::vector<Vec3d>& positions, std::vector<Triangle>& triangles,
                                    std::vector<std::uint32_t>& labels, VertexValues& values,
                                    const LitDecimateOptions& options) {
  return decimate(positions, triangles, &labels, values, options);
}

DecimatedLitMesh decimate_lit_scene(const SceneMesh& scene, const VertexSplit& split, const VertexValues& values,
                                    const LitDecimateOptions& options) {
  // The lit mesh as write_mesh_with_values (mesh/io/export.cpp) writes it, each face
  // labelled with its (group, material).
  const TriMesh& in = scene.mesh();
  std::vector<Vec3d> positions(split.size());
  for (std::size_t i = 0; i < split.size(); ++i) positions[i] = in.point(split.source[i]);
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> labels;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> label_of;
  std::vector<FaceHandle> first_face;  // per label
  triangles.reserve(scene.face_count());
  labels.reserve(scene.face_count());
  for (auto f : in.faces()) {
    const auto* c = &split.corner[3 * static_cast<std::size_t>(f.idx())];
    triangles.push_back({c[0], c[1], c[2]});
    const auto [it, added] = label_of.emplace(std::make_pair(scene.group(f), scene.material_id(f)),
                                              static_cast<std::uint32_t>(label_of.size()));
    if (added) first_face.push_back(f);
    labels.push_back(it->second);
  }

  DecimatedLitMesh result;
  result.values = values;
  result.report = decimate_lit_mesh(positions, triangles, labels, result.values, options);

  TriangleSoup soup;
  soup.points = std::move(positions);
  soup.triangles = std::move(triangles);
  soup.materials = scene.materials();
  soup.group_names = scene.group_names();
  soup.files = scene.files();
  for (std::uint32_t label : labels) {
    const FaceHandle f = first_face[label];
    soup.material.push_back(scene.material_id(f));
    soup.group.push_back(scene.group(f));
    soup.origin.push_back(scene.origin(f));
  }
  result.scene = std::make_unique<SceneMesh>(soup);
  // One output vertex per mesh vertex, in order.
  const TriMesh& out = result.scene->mesh();
  result.split.source.reserve(out.n_vertices());
  for (auto v : out.vertices()) result.split.source.push_back(v);
  result.split.corner.reserve(3 * out.n_faces());
  for (auto f : out.faces())
    for (auto v : out.fv_range(f)) result.split.corner.push_back(static_cast<std::uint32_t>(v.idx()));
  return result;
}

}  // namespace dynrad
