#include "mesh/repair/cleanup.h"
#include "mesh/core/scene_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace dynrad {
namespace {

// A soup built in code: points, polygons, one default material.
PolygonSoup make_soup(std::vector<Vec3d> points, std::vector<std::vector<std::uint32_t>> polygons) {
  PolygonSoup soup;
  soup.points = std::move(points);
  soup.polygons = std::move(polygons);
  soup.materials.push_back(Material{"grey", Rgb(0.5), Rgb(0.0), "test", true});
  soup.group_names.push_back("all");
  soup.files.push_back("test");
  for (std::size_t i = 0; i < soup.polygons.size(); ++i) {
    soup.material.push_back(0);
    soup.group.push_back(0);
    soup.origin.push_back(SourceRef{0, 0, static_cast<std::uint32_t>(i)});
  }
  return soup;
}

Vec3d triangle_normal(const TriangleSoup& s, std::size_t t) {
  const auto& tri = s.triangles[t];
  return OpenMesh::cross(s.points[tri[1]] - s.points[tri[0]], s.points[tri[2]] - s.points[tri[0]]);
}

double total_area(const TriangleSoup& s) {
  double a = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) a += 0.5 * triangle_normal(s, t).norm();
  return a;
}

TEST(Cleanup, MergesPointsWithinTheTolerance) {
  // Two triangles whose shared edge's points differ by 1e-9 (scene size ~1.4).
  auto soup = make_soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1 + 1e-9, 0, 0}, {1, 1, 0}, {0, 1 + 1e-9, 0}},
                        {{0, 1, 2}, {3, 4, 5}});
  TriangleSoup out;
  const CleanupReport r = cleanup(soup, out);
  EXPECT_EQ(r.merged_points, 2u);
  EXPECT_EQ(out.points.size(), 4u);
  SceneMesh mesh(out);
  EXPECT_EQ(mesh.mesh().n_edges(), 5u);  // the diagonal is shared
}

TEST(Cleanup, PointsFartherThanTheToleranceStayApart) {
  auto soup = make_soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1 + 1e-3, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {3, 4, 5}});
  TriangleSoup out;
  const CleanupReport r = cleanup(soup, out);
  EXPECT_EQ(r.merged_points, 1u);  // only the exact duplicate (0,1,0)
  std::set<std::array<double, 3>> positions;
  for (const auto& p : out.points) positions.insert({p[0], p[1], p[2]});
  EXPECT_EQ(positions.size(), 5u);
  EXPECT_EQ(r.split_vertices, 1u);  // the triangles now touch at one point only: a bow tie
}

TEST(Cleanup, RemovesDegenerateAndDuplicateFacesButKeepsOppositeFacing) {
  auto soup = make_soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}},
                        {{0, 1, 2},      // kept
                         {1, 2, 0},      // same face, same facing (rotated): duplicate
                         {0, 2, 1},      // same corners, opposite facing: a second surface, kept
                         {0, 1, 3},      // collinear: no area
                         {0, 0, 1}});    // repeated corner
  TriangleSoup out;
  const CleanupReport r = cleanup(soup, out);
  EXPECT_EQ(r.duplicate_triangles, 1u);
  EXPECT_EQ(r.degenerate_polygons, 2u);
  EXPECT_EQ(out.triangles.size(), 2u);
  EXPECT_LT(triangle_normal(out, 0)[2] * triangle_normal(out, 1)[2], 0.0);  // they face opposite ways
  SceneMesh mesh(out);  // a closed two-triangle "pillow": valid half-edge mesh
  EXPECT_EQ(mesh.face_count(), 2u);
}

TEST(Cleanup, SnapsTJunctionsSoThatNeighboursShareEdges) {
  // A 2x1 quad above two 1x1 quads: (1,0) lies inside the big quad's lower edge.
  auto soup = make_soup({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {0, -1, 0}, {1, -1, 0}, {1, 0, 0}, {2, -1, 0}},
                        {{0, 1, 2, 3}, {4, 5, 6, 0}, {5, 7, 1, 6}});
  TriangleSoup out;
  const CleanupReport r = cleanup(soup, out);
  EXPECT_EQ(r.t_junctions, 1u);
  SceneMesh mesh(out);
  EXPECT_EQ(test::count_t_vertices(mesh), 0u);
  EXPECT_NEAR(total_area(out), 4.0, 1e-12);
  // Without snapping (and without imprinting, which would find the corner on the edge
  // too) the same input keeps its T-vertex.
  CleanupOptions no_snap;
  no_snap.snap_t_junctions = false;
  no_snap.imprint = false;
  TriangleSoup raw;
  cleanup(soup, raw, no_snap);
  SceneMesh raw_mesh(raw);
  EXPECT_EQ(test::count_t_vertices(raw_mesh), 1u);
}

TEST(Cleanup, TriangulatesConcavePolygonsKeepingAreaAndFacing) {
  // An L of area 3, counter-clockwise seen from +z, and the same L reversed.
  const std::vector<Vec3d> l = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  for (bool reversed : {false, true}) {
    std::vector<std::uint32_t> loop = {0, 1, 2, 3, 4, 5};
    if (reversed) std::reverse(loop.begin(), loop.end());
    TriangleSoup out;
    const CleanupReport r = cleanup(make_soup(l, {loop}), out);
    EXPECT_EQ(r.triangulated_polygons, 1u);
    ASSERT_EQ(out.triangles.size(), 4u);
    EXPECT_NEAR(total_area(out), 3.0, 1e-12);
    for (std::size_t t = 0; t < out.triangles.size(); ++t)
      EXPECT_EQ(triangle_normal(out, t)[2] > 0, !reversed) << "triangle " << t;
  }
}

TEST(Cleanup, TriangulatesPolygonsWithCollinearCorners) {
  // A strip whose long edge carries two extra collinear points (as a ceiling cut
  // around a light does).
  auto soup = make_soup({{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2, 3, 4, 5}});
  TriangleSoup out;
  cleanup(soup, out);
  EXPECT_EQ(out.triangles.size(), 4u);
  EXPECT_NEAR(total_area(out), 4.0, 1e-12);
}

TEST(Cleanup, CutsEdgesSharedByThreeFaces) {
  // Three pages of a book around the edge (0,0,0)-(0,0,1).
  auto soup = make_soup({{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, -1, 0}}, {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}});
  TriangleSoup out;
  const CleanupReport r = cleanup(soup, out);
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_GT(r.split_vertices, 0u);
  SceneMesh mesh(out);  // would throw if not manifold
  EXPECT_EQ(mesh.face_count(), 3u);
}

TEST(Cleanup, NeverFlipsAFaceToAgreeWithItsNeighbour) {
  // Two triangles of one square, the second given with the "wrong" facing.
  auto soup = make_soup({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 3, 2}});
  TriangleSoup out;
  const CleanupReport r = cleanup(soup, out);
  EXPECT_EQ(r.non_manifold_edges, 1u);  // the diagonal is cut instead
  ASSERT_EQ(out.triangles.size(), 2u);
  EXPECT_GT(triangle_normal(out, 0)[2], 0.0);
  EXPECT_LT(triangle_normal(out, 1)[2], 0.0);
  SceneMesh mesh(out);
  EXPECT_EQ(mesh.face_count(), 2u);
}

TEST(Cleanup, SplitsVerticesWhereOnlyACornerIsShared) {
  // Two triangles touching at one point (a bow tie).
  auto soup = make_soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
  TriangleSoup out;
  const CleanupReport r = cleanup(soup, out);
  EXPECT_EQ(r.split_vertices, 1u);
  EXPECT_EQ(out.points.size(), 6u);
  SceneMesh mesh(out);
  EXPECT_EQ(mesh.vertex_count(), 6u);
}

// Random soups with a fixed seed: a grid of quads, some reversed, some duplicated, some
// points perturbed below the tolerance. Cleanup must always give a mesh OpenMesh
// accepts, keep every face's facing and lose no area.
TEST(Cleanup, RandomGridSoupsBecomeValidMeshesWithTheirFacingKept) {
  std::mt19937 rng(1234);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 6;
    std::vector<Vec3d> points;
    std::vector<std::vector<std::uint32_t>> polys;
    std::vector<int> facing;  // +1 / -1 per polygon
    std::uniform_real_distribution<double> jitter(-1e-8, 1e-8);
    std::bernoulli_distribution flip(0.2), dup(0.1);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        // Each quad has its own copies of its corners (a true soup).
        std::vector<std::uint32_t> q;
        for (auto [di, dj] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
          points.emplace_back(i + di + jitter(rng), j + dj + jitter(rng), 0.0);
          q.push_back(static_cast<std::uint32_t>(points.size() - 1));
        }
        const bool reversed = flip(rng);
        if (reversed) std::reverse(q.begin(), q.end());
        polys.push_back(q);
        facing.push_back(reversed ? -1 : 1);
        if (dup(rng)) {
          polys.push_back(q);
          facing.push_back(reversed ? -1 : 1);
        }
      }
    const PolygonSoup soup = make_soup(points, polys);
    TriangleSoup out;
    const CleanupReport r = cleanup(soup, out);
    ASSERT_NO_THROW(SceneMesh mesh(out)) << "trial " << trial;
    EXPECT_NEAR(total_area(out), n * n, 1e-6) << "trial " << trial;
    for (std::size_t t = 0; t < out.triangles.size(); ++t) {
      const int expected = facing[out.origin[t].face];
      EXPECT_EQ(triangle_normal(out, t)[2] > 0 ? 1 : -1, expected) << "trial " << trial << " triangle " << t;
    }
    EXPECT_GT(r.merged_points, 0u);
  }
}

}  // namespace
}  // namespace dynrad
