#include "mesh/core/refinement.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace dynrad {

namespace {

double triangle_area(const TriMesh& mesh, FaceHandle f) {
  auto it = mesh.cfv_iter(f);
  const Vec3d& a = mesh.point(*it);
  const Vec3d& b = mesh.point(*++it);
  const Vec3d& c = mesh.point(*++it);
  return 0.5 * OpenMesh::cross(b - a, c - a).norm();
}

std::array<VertexHandle, 3> corners_of(const TriMesh& mesh, FaceHandle f) {
  std::array<VertexHandle, 3> c;
  int k = 0;
  for (auto v : mesh.fv_range(f)) c[k++] = v;
  return c;
}

// See Element::in_strip. `width` is the line widths' property (or invalid: no lines).
bool in_strip(const TriMesh& mesh, FaceHandle f, OpenMesh::EPropHandleT<float> width) {
  if (!width.is_valid()) return false;
  float strip = 0;
  for (auto v : mesh.fv_range(f)) {
    float widest = 0;
    for (auto e : mesh.ve_range(v)) widest = std::max(widest, mesh.property(width, e));
    if (!(widest > 0)) return false;
    strip = std::max(strip, widest);
  }
  double longest = 0;
  for (auto e : mesh.fe_range(f)) longest = std::max(longest, mesh.calc_edge_length(e));
  const double thickness = 2 * triangle_area(mesh, f) / longest;  // the smallest altitude
  return thickness <= 1.01 * strip;
}

}  // namespace

EdgeSplit split_edge(TriMesh& mesh, OpenMesh::EdgeHandle e, const Vec3d& x, OpenMesh::EPropHandleT<float> line_width) {
  EdgeSplit cut;
  std::array<VertexHandle, 2> opposite;
  std::array<Vec3d, 2> normal;
  for (int s = 0; s < 2; ++s) {
    const OpenMesh::HalfedgeHandle h = mesh.halfedge_handle(e, s);
    cut.kept[s] = mesh.face_handle(h);
    if (cut.kept[s].is_valid()) {
      opposite[s] = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
      normal[s] = mesh.normal(cut.kept[s]);
    }
  }
  const VertexHandle end_a = mesh.from_vertex_handle(mesh.halfedge_handle(e, 0));
  const VertexHandle end_b = mesh.to_vertex_handle(mesh.halfedge_handle(e, 0));
  const float width = line_width.is_valid() ? mesh.property(line_width, e) : 0.0f;
  const VertexHandle m = mesh.add_vertex(x);
  mesh.split_copy(e, m);  // face properties (material, patch, ...) go to the new halves
  cut.vertex = m;
  // A line goes on along both halves of its edge, not across to the opposite corners
  // (split_copy gave every new edge the old edge's properties).
  if (line_width.is_valid())
    for (auto h : mesh.voh_range(m)) {
      const VertexHandle to = mesh.to_vertex_handle(h);
      mesh.property(line_width, mesh.edge_handle(h)) = (to == end_a || to == end_b) ? width : 0.0f;
    }
  for (int s = 0; s < 2; ++s) {
    if (!cut.kept[s].is_valid()) continue;
    // The old handle now holds one half; the other lies across the new edge from x to
    // the opposite corner.
    for (auto h : mesh.fh_range(cut.kept[s])) {
      const VertexHandle a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
      if ((a == m && b == opposite[s]) || (a == opposite[s] && b == m)) cut.added[s] = mesh.opposite_face_handle(h);
    }
    mesh.set_normal(cut.kept[s], normal[s]);
    mesh.set_normal(cut.added[s], normal[s]);
  }
  return cut;
}

// Longest-edge bisection with LEPP closure on a triangle mesh. `on_bisect(kept, added)`
// is told about every face cut in two: `kept` is the old handle (now one half),
// `added` the new face holding the other half.
class Bisector {
 public:
  using OnBisect = std::function<void(FaceHandle kept, FaceHandle added)>;

  Bisector(TriMesh& mesh, double min_area, OnBisect on_bisect)
      : mesh_(mesh), min_area_(min_area), on_bisect_(std::move(on_bisect)) {
    mesh_.get_property_handle(line_width_, SceneMesh::kLineWidthProperty);
  }

  // The longest edge, ties broken by vertex indices so that the choice is a strict
  // total order (LEPP terminates, and results do not depend on traversal order).
  OpenMesh::EdgeHandle longest_edge(FaceHandle f) const {
    OpenMesh::EdgeHandle best;
    double best_length = -1;
    std::pair<int, int> best_key{0, 0};
    for (auto h : mesh_.fh_range(f)) {
      const VertexHandle a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
      const double length = (mesh_.point(b) - mesh_.point(a)).sqrnorm();
      const std::pair<int, int> key{std::min(a.idx(), b.idx()), std::max(a.idx(), b.idx())};
      if (length > best_length || (length == best_length && key < best_key)) {
        best = mesh_.edge_handle(h);
        best_length = length;
        best_key = key;
      }
    }
    return best;
  }

  double longest_edge_length(FaceHandle f) const { return mesh_.calc_edge_length(longest_edge(f)); }

  // Bisects `target`, after bisecting whatever its longest-edge propagation path needs.
  SplitCounts bisect(FaceHandle target) {
    SplitCounts counts;
    stack_.clear();
    stack_.push_back(target);
    while (!stack_.empty()) {
      const FaceHandle f = stack_.back();
      const OpenMesh::EdgeHandle e = longest_edge(f);
      const OpenMesh::HalfedgeHandle h = mesh_.halfedge_handle(e, 0);
      FaceHandle g = mesh_.face_handle(h) == f ? mesh_.opposite_face_handle(h) : mesh_.face_handle(h);
      if (g.is_valid() && longest_edge(g) != e) {
        stack_.push_back(g);  // the neighbour has a longer edge: it goes first
        continue;
      }
      // f and g share their longest edge (or e is on the boundary): a terminal pair.
      if (triangle_area(mesh_, f) < 2 * min_area_ || (g.is_valid() && triangle_area(mesh_, g) < 2 * min_area_)) {
        ++counts.refused;
        return counts;
      }
      split(e);
      for (FaceHandle cut : {f, g})
        if (cut.is_valid()) ++(cut == target ? counts.requested : counts.closure);
      stack_.pop_back();
    }
    return counts;
  }

 private:
  void split(OpenMesh::EdgeHandle e) {
    const OpenMesh::HalfedgeHandle h = mesh_.halfedge_handle(e, 0);
    const Vec3d midpoint = (mesh_.point(mesh_.from_vertex_handle(h)) + mesh_.point(mesh_.to_vertex_handle(h))) * 0.5;
    const EdgeSplit cut = split_edge(mesh_, e, midpoint, line_width_);
    if (on_bisect_)
      for (int s = 0; s < 2; ++s)
        if (cut.kept[s].is_valid()) on_bisect_(cut.kept[s], cut.added[s]);
  }

  TriMesh& mesh_;
  double min_area_;
  OnBisect on_bisect_;
  OpenMesh::EPropHandleT<float> line_width_;  // invalid when the mesh has no lines
  std::vector<FaceHandle> stack_;
};

// ---------------------------------------------------------------------------

double min_angle_degrees(const TriMesh& mesh, FaceHandle f) {
  const auto c = corners_of(mesh, f);
  double smallest = 180;
  for (int k = 0; k < 3; ++k) {
    const Vec3d u = mesh.point(c[(k + 1) % 3]) - mesh.point(c[k]);
    const Vec3d v = mesh.point(c[(k + 2) % 3]) - mesh.point(c[k]);
    const double angle = std::atan2(OpenMesh::cross(u, v).norm(), OpenMesh::dot(u, v)) * 180.0 / M_PI;
    smallest = std::min(smallest, angle);
  }
  return smallest;
}

double min_angle_degrees(const TriMesh& mesh) {
  double smallest = 180;
  for (auto f : mesh.faces()) smallest = std::min(smallest, min_angle_degrees(mesh, f));
  return smallest;
}

double default_patch_size(const SceneMesh& scene) { return 0.1 * scene.bounds().diagonal(); }

PatchingReport make_patches(SceneMesh& scene, double patch_size) {
  TriMesh& mesh = scene.mesh();
  PatchingReport report;
  report.faces_before = mesh.n_faces();
  report.min_angle_before = min_angle_degrees(mesh);
  Bisector bisector(mesh, 0.0, nullptr);
  // New halves are appended, so one pass over the growing face list sees them all.
  // A face once found small enough is never cut again: closure only cuts faces with
  // an edge longer than the one being refined, which is longer than patch_size.
  for (std::size_t i = 0; i < mesh.n_faces(); ++i) {
    const FaceHandle f(static_cast<int>(i));
    while (bisector.longest_edge_length(f) > patch_size) report.splits += bisector.bisect(f);
  }
  for (auto f : mesh.faces()) scene.set_patch(f, static_cast<std::uint32_t>(f.idx()));
  report.patches = mesh.n_faces();
  report.min_angle_after = min_angle_degrees(mesh);
  return report;
}

// ---------------------------------------------------------------------------

ElementHierarchy::ElementHierarchy(SceneMesh& scene, RefinementOptions options)
    : scene_(scene), options_(options) {
  TriMesh& mesh = scene_.mesh();
  mesh.add_property(element_of_face_, "dynrad:element");
  if (scene_.has_lines()) mesh.get_property_handle(line_width_, SceneMesh::kLineWidthProperty);
  elements_.reserve(mesh.n_faces() * 2);
  roots_.reserve(mesh.n_faces());
  normals_.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    Element e;
    e.patch = static_cast<std::uint32_t>(roots_.size());
    e.face = f;
    e.corners = corners_of(mesh, f);
    e.area = scene_.area(f);
    e.in_strip = in_strip(mesh, f, line_width_);
    const auto id = static_cast<ElementId>(elements_.size());
    elements_.push_back(e);
    roots_.push_back(id);
    normals_.push_back(mesh.normal(f));
    mesh.property(element_of_face_, f) = id;
    scene_.set_patch(f, e.patch);
  }
}

void ElementHierarchy::on_bisect(FaceHandle kept, FaceHandle added, const std::array<VertexHandle, 3>& corners_kept,
                                 const std::array<VertexHandle, 3>& corners_added) {
  TriMesh& mesh = scene_.mesh();
  const ElementId parent = mesh.property(element_of_face_, kept);
  const auto first = static_cast<ElementId>(elements_.size());
  for (int k = 0; k < 2; ++k) {
    Element child;
    child.parent = parent;
    child.patch = elements_[parent].patch;
    child.generation = static_cast<std::uint16_t>(elements_[parent].generation + 1);
    child.face = k == 0 ? kept : added;
    child.corners = k == 0 ? corners_kept : corners_added;
    child.area = scene_.area(child.face);
    child.in_strip = in_strip(mesh, child.face, line_width_);
    elements_.push_back(child);
    mesh.property(element_of_face_, child.face) = first + k;
  }
  Element& p = elements_[parent];
  p.children = {first, first + 1};
  p.face = FaceHandle();
}

SplitCounts ElementHierarchy::refine(ElementId e) {
  if (!elements_[e].is_leaf()) return {};
  TriMesh& mesh = scene_.mesh();
  Bisector bisector(mesh, options_.min_area, [this, &mesh](FaceHandle kept, FaceHandle added) {
    on_bisect(kept, added, corners_of(mesh, kept), corners_of(mesh, added));
  });
  return bisector.bisect(elements_[e].face);
}

EdgeSplit ElementHierarchy::split_at(OpenMesh::EdgeHandle e, const Vec3d& x) {
  TriMesh& mesh = scene_.mesh();
  // (lines may have been added since the hierarchy was made)
  if (!line_width_.is_valid()) mesh.get_property_handle(line_width_, SceneMesh::kLineWidthProperty);
  const EdgeSplit cut = split_edge(mesh, e, x, line_width_);
  for (int s = 0; s < 2; ++s)
    if (cut.kept[s].is_valid())
      on_bisect(cut.kept[s], cut.added[s], corners_of(mesh, cut.kept[s]), corners_of(mesh, cut.added[s]));
  return cut;
}

void ElementHierarchy::leaves(ElementId e, std::vector<ElementId>& out) const {
  std::vector<ElementId> stack{e};
  while (!stack.empty()) {
    const ElementId top = stack.back();
    stack.pop_back();
    const Element& el = elements_[top];
    if (el.is_leaf()) {
      out.push_back(top);
    } else {
      stack.push_back(el.children[1]);
      stack.push_back(el.children[0]);
    }
  }
}

std::vector<ElementId> ElementHierarchy::elements_at_generation(int generation) const {
  std::vector<ElementId> out;
  for (std::size_t i = 0; i < elements_.size(); ++i)
    if (elements_[i].generation == generation) out.push_back(static_cast<ElementId>(i));
  return out;
}

Vec3d ElementHierarchy::centroid(ElementId e) const {
  const Element& el = elements_[e];
  return (position(el.corners[0]) + position(el.corners[1]) + position(el.corners[2])) / 3.0;
}


}  // namespace dynrad
