// Conforming refinement on the half-edge mesh, and the element hierarchy above it.
//
// Every mesh face is a leaf element; each leaf belongs to a tree rooted at its patch.
// An element is split by longest-edge bisection: the midpoint of its longest edge is
// inserted and the edge's two faces are each cut in two. If the neighbour across that
// edge has a longer edge of its own, the neighbour is bisected first (Rivara's
// longest-edge propagation path, LEPP), recursively, across patch borders and creases
// alike. So the mesh is conforming after every single edge split: there is never a
// T-vertex, not even in the middle of a refinement.
//
// Why longest-edge bisection rather than newest-vertex bisection: it needs no initial
// marking of a refinement edge (our input is whatever CAD produced), its propagation
// path always ends (edge lengths strictly grow along it), and its smallest angle is at
// least half the smallest angle of the triangles it started from (Rosenberg & Stenger
// 1975). Bisecting a right isosceles triangle, what a quad becomes, gives two right
// isosceles triangles, so rooms made of rectangles keep their quality exactly.
//
// Paper levels. The paper splits a quad patch 1 -> 4 per level. Two bisection
// generations split a triangle 1 -> 4 with the same area ratio, so paper level L is
// bisection generation 2L (paper_level() rounds down: closure can leave odd
// generations). `--max-level 3` therefore allows generation 6.
#pragma once

#include "mesh/core/scene_mesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace dynrad {

using ElementId = std::uint32_t;
constexpr ElementId kNoElement = UINT32_MAX;

struct Element {
  ElementId parent = kNoElement;
  std::array<ElementId, 2> children{kNoElement, kNoElement};
  std::uint32_t patch = 0;       // the patch (root) this element descends from
  std::uint16_t generation = 0;  // bisections below the patch; 0 for a patch
  // Inside the strip between two inserted lines (line_insertion.h: a jump in shading
  // made into edges): every corner is on a line and the element is no thicker than the
  // strip. Refining it would not resolve anything the lines do not already.
  bool in_strip = false;
  FaceHandle face;               // the mesh face while this element is a leaf
  std::array<VertexHandle, 3> corners;
  double area = 0;

  bool is_leaf() const { return children[0] == kNoElement; }
};

inline int paper_level(int generation) { return generation / 2; }

// What a refinement did, worth logging. `requested` counts bisections of elements
// asked for; `closure` the bisections of neighbours that kept the mesh conforming.
struct SplitCounts {
  std::size_t requested = 0;
  std::size_t closure = 0;
  std::size_t refused = 0;  // requests not carried out: an element would be below min_area

  SplitCounts& operator+=(const SplitCounts& o) {
    requested += o.requested;
    closure += o.closure;
    refused += o.refused;
    return *this;
  }
  std::size_t total() const { return requested + closure; }
};

struct RefinementOptions {
  // No bisection creates an element smaller than this (model units squared). A
  // request that would is refused; closure bisections it needed and already did stay
  // (each left the mesh conforming).
  double min_area = 0;
};

// What `dynrad solve` refines with: no element below a millionth of the patch area, far
// below any visible detail.
inline RefinementOptions refinement_for_patch_size(double patch_size) {
  RefinementOptions options;
  options.min_area = 1e-6 * patch_size * patch_size;
  return options;
}

// The one edge split every change of the mesh makes (bisection here, inserted lines in
// line_insertion.h): edge e is cut at x (2 -> 4, or 1 -> 2 on a border) by joining x to
// the opposite corner of each face beside it. Each old face handle `kept[s]` holds one
// half and `added[s]` the other (both invalid on a side with no face); both keep the
// old face's normal and properties. A line on e (the SceneMesh::line_width property,
// passed as `line_width`; an invalid handle when the mesh has none) goes on along both
// halves, not across.
struct EdgeSplit {
  VertexHandle vertex;
  std::array<FaceHandle, 2> kept, added;
};
EdgeSplit split_edge(TriMesh& mesh, OpenMesh::EdgeHandle e, const Vec3d& x, OpenMesh::EPropHandleT<float> line_width);

// ---------------------------------------------------------------------------
// Patches: the initial meshing, done once before lighting.

// A default patch size from the scene's size: a tenth of the bounding-box diagonal.
double default_patch_size(const SceneMesh& scene);

struct PatchingReport {
  std::size_t faces_before = 0;
  std::size_t patches = 0;
  SplitCounts splits;
  double min_angle_before = 0;  // degrees, smallest angle of any triangle
  double min_angle_after = 0;
};

// Bisects (with conforming closure) until no triangle has an edge longer than
// `patch_size`, then numbers every face as its own patch.
PatchingReport make_patches(SceneMesh& scene, double patch_size);

// Smallest interior angle of a triangle, and of the whole mesh, in degrees.
double min_angle_degrees(const TriMesh& mesh, FaceHandle f);
double min_angle_degrees(const TriMesh& mesh);

// ---------------------------------------------------------------------------

class ElementHierarchy {
 public:
  // Makes every current face of `scene` a patch: the root of its own tree. The
  // hierarchy keeps a reference to `scene`, whose mesh it refines.
  explicit ElementHierarchy(SceneMesh& scene, RefinementOptions options = {});
  ElementHierarchy(const ElementHierarchy&) = delete;
  ElementHierarchy& operator=(const ElementHierarchy&) = delete;

  // Bisects leaf `e` (and, first, whatever the closure needs). A no-op on interior
  // elements.
  SplitCounts refine(ElementId e);
  // Splits edge e at x, a point on it (split_edge: 2 -> 4, or 1 -> 2 on a border), each
  // face beside it an element split in two as a bisection is, whatever the edge's length
  // and x's place on it (a line inserted into the refined mesh: line_insertion.h). No
  // minimum area is asked for.
  EdgeSplit split_at(OpenMesh::EdgeHandle e, const Vec3d& x);

  const Element& element(ElementId e) const { return elements_[e]; }
  std::size_t element_count() const { return elements_.size(); }
  std::size_t patch_count() const { return roots_.size(); }
  std::size_t leaf_count() const { return scene_.face_count(); }
  ElementId patch_root(std::uint32_t patch) const { return roots_[patch]; }
  ElementId element_of(FaceHandle f) const { return scene_.mesh().property(element_of_face_, f); }

  // Appends the leaves below `e` (or `e` itself if it is a leaf) to `out`.
  void leaves(ElementId e, std::vector<ElementId>& out) const;
  std::vector<ElementId> elements_at_generation(int generation) const;

  const Vec3d& position(VertexHandle v) const { return scene_.mesh().point(v); }
  // Elements are flat pieces of their patch, so an element's normal is its patch's.
  const Vec3d& normal(ElementId e) const { return normals_[elements_[e].patch]; }
  Vec3d centroid(ElementId e) const;

  const SceneMesh& scene() const { return scene_; }
  const RefinementOptions& options() const { return options_; }

 private:
  void on_bisect(FaceHandle half_a0, FaceHandle half_a1, const std::array<VertexHandle, 3>& corners_a0,
                 const std::array<VertexHandle, 3>& corners_a1);

  SceneMesh& scene_;
  RefinementOptions options_;
  std::vector<Element> elements_;
  std::vector<ElementId> roots_;
  std::vector<Vec3d> normals_;  // per patch
  OpenMesh::FPropHandleT<ElementId> element_of_face_;
  OpenMesh::EPropHandleT<float> line_width_;  // valid when the scene has inserted lines
};

}  // namespace dynrad
