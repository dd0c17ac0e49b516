// Lines inserted into the mesh as edges (mesh/core/line_insertion.h): the line's edges cover
// exactly the segment, the mesh stays conforming with no empty triangle, and the line
// survives refinement (both halves of a split line edge stay on it).
#include "mesh/core/line_insertion.h"
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "scene_builder.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dynrad {
namespace {

using test::SceneBuilder;

// Length of the line edges lying on the segment a -> b (both ends within 1e-9 of it);
// `off` counts line edges that do not.
double length_on(const SceneMesh& scene, const Vec3d& a, const Vec3d& b, int* off = nullptr) {
  const TriMesh& mesh = scene.mesh();
  const Vec3d u = (b - a).normalized();
  auto distance = [&](const Vec3d& p) {
    const double t = std::clamp(OpenMesh::dot(p - a, u), 0.0, (b - a).norm());
    return (a + u * t - p).norm();
  };
  double sum = 0;
  for (auto e : mesh.edges()) {
    if (!(scene.line_width(e) > 0)) continue;
    const auto h = mesh.halfedge_handle(e, 0);
    const Vec3d p = mesh.point(mesh.from_vertex_handle(h)), q = mesh.point(mesh.to_vertex_handle(h));
    if (distance(p) < 1e-9 && distance(q) < 1e-9)
      sum += (q - p).norm();
    else if (off)
      ++*off;
  }
  return sum;
}

void expect_conforming(const SceneMesh& scene, double area) {
  const TriMesh& mesh = scene.mesh();
  double total = 0;
  for (auto f : mesh.faces()) {
    EXPECT_GT(scene.area(f), 1e-12) << "face " << f.idx();
    total += scene.area(f);
  }
  EXPECT_NEAR(total, area, 1e-9);
  // Conforming: no vertex lies inside another face's edge (a T-vertex).
  for (auto v : mesh.vertices())
    for (auto e : mesh.edges()) {
      const auto h = mesh.halfedge_handle(e, 0);
      const Vec3d p = mesh.point(mesh.from_vertex_handle(h)), q = mesh.point(mesh.to_vertex_handle(h));
      const Vec3d x = mesh.point(v);
      const double t = OpenMesh::dot(x - p, q - p) / (q - p).sqrnorm();
      if (t > 1e-9 && t < 1 - 1e-9) {
        EXPECT_GT((p + (q - p) * t - x).norm(), 1e-9) << "T-vertex " << v.idx();
      }
    }
}

TEST(LineInsertion, TwoCrossingLinesBecomeEdgesThatSurviveRefinement) {
  SceneBuilder b;
  b.rectangle(-1, -1, 1, 1, 0, +1, b.material("grey", 0.5));
  LoadedScene loaded = load_soup(b.soup(), "line test");
  SceneMesh& scene = *loaded.mesh;
  const Vec3d a1(-0.7, -0.3, 0), b1(0.8, 0.6, 0), a2(-0.5, 0.9, 0), b2(0.6, -0.95, 0);
  LineOptions options;
  options.snap = 1e-4;
  options.width = 0.01f;
  const InsertedLine first = insert_line(scene, FaceHandle(0), a1, b1, options);
  EXPECT_TRUE(first.started);
  EXPECT_TRUE(first.reached_end);
  // The second starts from a face that need not hold its first point (found by walking).
  const InsertedLine second = insert_line(scene, FaceHandle(0), a2, b2, options);
  EXPECT_TRUE(second.reached_end);
  int off1 = 0, off2 = 0;
  EXPECT_NEAR(length_on(scene, a1, b1, &off1), (b1 - a1).norm(), 1e-9);
  EXPECT_NEAR(length_on(scene, a2, b2, &off2), (b2 - a2).norm(), 1e-9);
  int line_edges = 0;
  for (auto e : scene.mesh().edges()) line_edges += scene.line_width(e) > 0;
  EXPECT_EQ(off1 + off2, line_edges) << "a line edge on neither line";
  expect_conforming(scene, 4.0);

  // Flips beside the lines never touch them.
  flip_beside_lines(scene);
  EXPECT_NEAR(length_on(scene, a1, b1), (b1 - a1).norm(), 1e-9);
  expect_conforming(scene, 4.0);

  // Patching and refinement split line edges; the halves stay on the line, and the
  // edges from a split point to the opposite corners are not on it.
  make_patches(scene, 0.3);
  ElementHierarchy hierarchy(scene);
  for (int round = 0; round < 3; ++round) {
    const std::size_t n = hierarchy.element_count();
    for (ElementId e = 0; e < n; ++e)
      if (hierarchy.element(e).is_leaf()) hierarchy.refine(e);
  }
  // (every line edge is on one line or the other: none was left on a cross edge)
  off1 = off2 = 0;
  EXPECT_NEAR(length_on(scene, a1, b1, &off1), (b1 - a1).norm(), 1e-9);
  EXPECT_NEAR(length_on(scene, a2, b2, &off2), (b2 - a2).norm(), 1e-9);
  line_edges = 0;
  for (auto e : scene.mesh().edges()) line_edges += scene.line_width(e) > 0;
  EXPECT_EQ(off1 + off2, line_edges);
}

// A line leaving the flat region stops at its border; one starting outside it is not
// inserted at all.
TEST(LineInsertion, StopsWhereTheFlatRegionEnds) {
  SceneBuilder b;
  b.rectangle(-1, -1, 1, 1, 0, +1, b.material("grey", 0.5));
  LoadedScene loaded = load_soup(b.soup(), "line test");
  SceneMesh& scene = *loaded.mesh;
  LineOptions options;
  options.snap = 1e-4;
  const InsertedLine through = insert_line(scene, FaceHandle(0), {0, 0, 0}, {3, 0.5, 0}, options);
  EXPECT_TRUE(through.started);
  EXPECT_FALSE(through.reached_end);
  EXPECT_NEAR(length_on(scene, {0, 0, 0}, {1, 1.0 / 6, 0}), std::hypot(1.0, 1.0 / 6), 1e-9);
  const InsertedLine outside = insert_line(scene, FaceHandle(0), {2, 2, 0}, {3, 3, 0}, options);
  EXPECT_FALSE(outside.started);
  expect_conforming(scene, 4.0);
}

}  // namespace
}  // namespace dynrad
