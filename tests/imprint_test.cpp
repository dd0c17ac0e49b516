// Imprinting, hidden parts and flattening in cleanup: geometric facts on scenes built as
// architects' models are (solids standing on and passing through each other).
#include "mesh/repair/cleanup.h"
#include "mesh/io/import.h"
#include "mesh/core/scene_mesh.h"
#include "scene_builder.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace dynrad {
namespace {

using test::SceneBuilder;

struct Cleaned {
  TriangleSoup soup;
  CleanupReport report;
};

Cleaned clean(const PolygonSoup& input, CleanupOptions options = {}) {
  Cleaned c;
  c.report = cleanup(input, c.soup, options);
  return c;
}

double triangle_area(const TriangleSoup& s, std::size_t t) {
  const auto& c = s.triangles[t];
  return 0.5 * OpenMesh::cross(s.points[c[1]] - s.points[c[0]], s.points[c[2]] - s.points[c[0]]).norm();
}

double area(const TriangleSoup& s, const std::string& material = "") {
  double sum = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    if (material.empty() || s.materials[s.material[t]].name == material) sum += triangle_area(s, t);
  return sum;
}

Vec3d centroid(const TriangleSoup& s, std::size_t t) {
  const auto& c = s.triangles[t];
  return (s.points[c[0]] + s.points[c[1]] + s.points[c[2]]) / 3.0;
}

// Area of `material`'s triangles whose centroids lie in the box [lo, hi].
double area_inside(const TriangleSoup& s, const std::string& material, const Vec3d& lo, const Vec3d& hi) {
  double sum = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    if (s.materials[s.material[t]].name != material) continue;
    const Vec3d c = centroid(s, t);
    bool in = true;
    for (int k = 0; k < 3; ++k) in = in && c[k] >= lo[k] && c[k] <= hi[k];
    if (in) sum += triangle_area(s, t);
  }
  return sum;
}

// A floor slab 4 x 4 x 0.3 (top at z = 0) and a wall 0.2 x 2 standing on it or passing
// through it.
SceneBuilder slab_and_wall(double wall_bottom) {
  SceneBuilder b;
  const auto floor = b.material("floor", 0.3), plaster = b.material("plaster", 0.6);
  b.group("slab");
  b.box({0, 0, -0.3}, {4, 4, 0}, floor);
  b.group("wall");
  b.box({1, 1, wall_bottom}, {1.2, 3, 2}, plaster);
  return b;
}

TEST(Imprint, WallStandingOnASlabHidesTheFloorUnderItAndItsBottom) {
  const Cleaned c = clean(slab_and_wall(0).soup());
  // The slab top under the wall (0.2 x 2) and the wall's bottom face against it.
  EXPECT_NEAR(c.report.hidden_area, 0.8, 1e-9);
  EXPECT_EQ(c.report.hidden_pieces, 2u);
  EXPECT_GE(c.report.imprinted_edges, 4u);
  EXPECT_NEAR(area_inside(c.soup, "floor", {1, 1, -1e-9}, {1.2, 3, 1e-9}), 0.0, 1e-12);
  EXPECT_NEAR(area(c.soup, "floor"), 16 - 0.4 + 16 + 4 * 4 * 0.3, 1e-9);
  EXPECT_NEAR(area(c.soup, "plaster"), 2 * (0.2 + 2) * 2 + 0.4, 1e-9);
  SceneMesh mesh(c.soup);
  EXPECT_EQ(test::count_t_vertices(mesh), 0u);
}

TEST(Imprint, WallThroughASlabLosesWhatIsInsideIt) {
  const Cleaned c = clean(slab_and_wall(-0.3).soup());
  // Inside: the slab top under the wall (0.4) and the wall's sides within the slab
  // (perimeter 4.4 x 0.3). The wall's bottom lies on the slab's bottom, both facing
  // down: the smaller (the wall's) stays, the slab's piece under it goes (0.4).
  EXPECT_NEAR(c.report.hidden_area, 0.4 + 4.4 * 0.3 + 0.4, 1e-9);
  EXPECT_NEAR(area(c.soup, "floor"), 15.6 + 15.6 + 4.8, 1e-9);
  EXPECT_NEAR(area(c.soup, "plaster"), 4.4 * 2 + 0.4 + 0.4, 1e-9);
  EXPECT_NEAR(area_inside(c.soup, "plaster", {0, 0, -0.3 + 1e-6}, {4, 4, -1e-9}), 0.0, 1e-12);
  SceneMesh mesh(c.soup);
  EXPECT_EQ(test::count_t_vertices(mesh), 0u);
}

TEST(Imprint, TurnedAndMovedFarAwayGivesTheSameResult) {
  // Turned about a skew axis and moved 2 km: faces meet only to within rounding.
  const SceneBuilder b = slab_and_wall(-0.3);
  const Cleaned straight = clean(b.soup());
  const Cleaned turned = clean(b.transformed(37, {1000, -2000, 500}));
  EXPECT_NEAR(turned.report.hidden_area, straight.report.hidden_area, 1e-6);
  EXPECT_EQ(turned.report.hidden_pieces, straight.report.hidden_pieces);
  EXPECT_NEAR(area(turned.soup), area(straight.soup), 1e-6);
  SceneMesh mesh(turned.soup);
  EXPECT_EQ(test::count_t_vertices(mesh), 0u);
}

TEST(Imprint, AWallAHairAboveTheSlabStandsOnIt) {
  // 1e-9 m up: within the merge distance (1e-6 of the 6 m diagonal).
  const Cleaned c = clean(slab_and_wall(1e-9).soup());
  EXPECT_NEAR(c.report.hidden_area, 0.8, 1e-6);
  // Out of reach when imprinting is off: the floor under the wall stays.
  CleanupOptions off;
  off.imprint = false;
  const Cleaned raw = clean(slab_and_wall(1e-9).soup(), off);
  EXPECT_EQ(raw.report.hidden_area, 0.0);
  EXPECT_EQ(raw.report.imprinted_edges, 0u);
  EXPECT_NEAR(area(raw.soup, "floor"), 16 + 16 + 4.8, 1e-9);
}

SceneBuilder box_on_floor(std::array<bool, 6> skip) {
  SceneBuilder b;
  const auto floor = b.material("floor", 0.3), wood = b.material("wood", 0.4);
  b.group("floor");
  b.rectangle(0, 0, 4, 4, 0, +1, floor);
  b.group("box");
  b.box({1, 1, 0}, {2, 2, 1}, wood, SceneBuilder::outward, skip);
  return b;
}

TEST(Imprint, ClosedBoxOnASheetFloor) {
  const Cleaned c = clean(box_on_floor({}).soup());
  // The floor under the box is enclosed; the box's bottom lies face to face on it.
  EXPECT_NEAR(c.report.hidden_area, 2.0, 1e-9);
  EXPECT_NEAR(area(c.soup, "floor"), 15.0, 1e-9);
  EXPECT_NEAR(area(c.soup, "wood"), 5.0, 1e-9);
  EXPECT_NEAR(area_inside(c.soup, "floor", {1, 1, -1}, {2, 2, 1}), 0.0, 1e-12);
}

TEST(Imprint, BoxWithoutABottomEnclosesTheFloorUnderIt) {
  const Cleaned c = clean(box_on_floor({false, false, false, false, true, false}).soup());
  EXPECT_NEAR(c.report.hidden_area, 1.0, 1e-9);
  EXPECT_NEAR(area(c.soup, "floor"), 15.0, 1e-9);
}

TEST(Imprint, OpenBoxKeepsTheFloorInsideIt) {
  // No top: the floor inside sees out. It stays, cut along the box's foot.
  const Cleaned c = clean(box_on_floor({false, false, false, false, true, true}).soup());
  EXPECT_EQ(c.report.hidden_area, 0.0);
  EXPECT_GE(c.report.imprinted_edges, 4u);
  EXPECT_NEAR(area(c.soup, "floor"), 16.0, 1e-9);
  EXPECT_NEAR(area_inside(c.soup, "floor", {1, 1, -1}, {2, 2, 1}), 1.0, 1e-9);
  // Every floor triangle lies on one side of the foot: none crosses it.
  for (std::size_t t = 0; t < c.soup.triangles.size(); ++t) {
    if (c.soup.materials[c.soup.material[t]].name != "floor") continue;
    int inside = 0;
    for (auto v : c.soup.triangles[t]) {
      const Vec3d& p = c.soup.points[v];
      inside += p[0] >= 1 - 1e-12 && p[0] <= 2 + 1e-12 && p[1] >= 1 - 1e-12 && p[1] <= 2 + 1e-12;
    }
    EXPECT_TRUE(inside == 0 || inside == 3 || triangle_area(c.soup, t) < 1e-12 ||
                !(centroid(c.soup, t)[0] > 1 && centroid(c.soup, t)[0] < 2 && centroid(c.soup, t)[1] > 1 &&
                  centroid(c.soup, t)[1] < 2))
        << "a floor triangle crosses the box's foot";
  }
}

TEST(Imprint, AWallDrawnAsTwoSheetsBackToBackKeepsBothSides) {
  SceneBuilder b;
  const auto floor = b.material("floor", 0.3), plaster = b.material("plaster", 0.6);
  b.group("floor");
  b.rectangle(0, 0, 4, 4, 0, +1, floor);
  b.group("partition");
  b.quad({2, 1, 0}, {2, 3, 0}, {2, 3, 2}, {2, 1, 2}, plaster);  // faces +x
  b.quad({2, 1, 0}, {2, 1, 2}, {2, 3, 2}, {2, 3, 0}, plaster);  // faces -x
  const Cleaned c = clean(b.soup());
  EXPECT_EQ(c.report.hidden_area, 0.0);
  EXPECT_GE(c.report.imprinted_edges, 1u);  // the foot line, on the floor
  EXPECT_NEAR(area(c.soup, "plaster"), 8.0, 1e-9);
  EXPECT_NEAR(area(c.soup, "floor"), 16.0, 1e-9);
}

TEST(Imprint, ALampDrawnOnTheCeilingCoversIt) {
  SceneBuilder b;
  const auto ceiling = b.material("ceiling", 0.8), lamp = b.material("lamp", 0.0, 100);
  b.group("ceiling");
  b.rectangle(0, 0, 4, 4, 3, -1, ceiling);
  b.group("lamp");
  b.rectangle(1.5, 1.5, 2.5, 2.5, 3, -1, lamp);
  const Cleaned c = clean(b.soup());
  EXPECT_NEAR(c.report.hidden_area, 1.0, 1e-9);
  EXPECT_NEAR(area(c.soup, "lamp"), 1.0, 1e-9);
  EXPECT_NEAR(area(c.soup, "ceiling"), 15.0, 1e-9);
}

// Found by fuzzing: a damaged room whose faces piled up in one plane (22,000 pieces) took
// 31 s in the hidden-part rules (every triangle pair of two overlapping facets, every
// piece tested again after each hiding); now 0.9 s. The same shape here: 40 nested
// squares on a floor, all facing up. Wherever several overlap, the smallest stays, so
// what is left covers the largest square once.
TEST(Imprint, NestedCopiesInOnePlaneLeaveOneSurface) {
  SceneBuilder b;
  const auto grey = b.material("grey", 0.5);
  double total = 0;
  for (int k = 1; k <= 40; ++k) {
    b.group("square" + std::to_string(k));
    const double h = 0.025 * k;
    b.rectangle(-h, -h, h, h, 0, +1, grey);
    total += 4 * h * h;
  }
  const Cleaned c = clean(b.soup());
  EXPECT_NEAR(area(c.soup), 4.0, 1e-9);
  EXPECT_NEAR(c.report.hidden_area, total - 4.0, 1e-9);
  SceneMesh mesh(c.soup);
  EXPECT_EQ(test::count_t_vertices(mesh), 0u);
}

TEST(Imprint, CleaningACleanedMeshChangesNothing) {
  for (const std::string& name : {std::string("storey.obj"), std::string("cornell_box.obj")}) {
    const PolygonSoup input = read_input(test::sample(name));
    const Cleaned first = clean(input);
    SceneMesh mesh(first.soup);
    EXPECT_EQ(test::count_t_vertices(mesh), 0u) << name;
    // The cleaned triangles as a soup of their own.
    PolygonSoup again;
    again.points = first.soup.points;
    again.materials = first.soup.materials;
    again.group_names = first.soup.group_names;
    again.files = first.soup.files;
    for (std::size_t t = 0; t < first.soup.triangles.size(); ++t) {
      const auto& tri = first.soup.triangles[t];
      again.polygons.push_back({tri[0], tri[1], tri[2]});
      again.material.push_back(first.soup.material[t]);
      again.group.push_back(first.soup.group[t]);
      again.origin.push_back(first.soup.origin[t]);
    }
    const Cleaned second = clean(again);
    EXPECT_EQ(second.report.imprinted_edges, 0u) << name;
    EXPECT_EQ(second.report.hidden_area, 0.0) << name;
    EXPECT_EQ(second.report.flattened_polygons, 0u) << name;
    ASSERT_EQ(second.soup.triangles.size(), first.soup.triangles.size()) << name;
    // The same triangles (corners by position, starting at the smallest), in any order.
    auto shapes = [](const TriangleSoup& s) {
      std::multiset<std::array<double, 9>> set;
      for (const auto& t : s.triangles) {
        std::array<std::array<double, 3>, 3> c;
        for (int k = 0; k < 3; ++k) c[k] = {s.points[t[k]][0], s.points[t[k]][1], s.points[t[k]][2]};
        std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
        set.insert({c[0][0], c[0][1], c[0][2], c[1][0], c[1][1], c[1][2], c[2][0], c[2][1], c[2][2]});
      }
      return set;
    };
    EXPECT_TRUE(shapes(first.soup) == shapes(second.soup)) << name;
  }
}

TEST(Imprint, TheStoreySampleLosesWhatIsInsideItsSolids) {
  const PolygonSoup input = read_input(test::sample("storey.obj"));
  const Cleaned c = clean(input);
  EXPECT_GT(c.report.hidden_area, 100.0);
  // No floor remains under the inner walls (x in [6.44, 6.56] south of y = 4.94, but in
  // the door from y = 2.05 to 2.95), under
  // the cupboard or the bed, and no wall below the floor slab's top.
  EXPECT_NEAR(area_inside(c.soup, "floor", {6.45, 0.2, -1e-9}, {6.55, 2.0, 1e-9}), 0.0, 1e-12);
  EXPECT_NEAR(area_inside(c.soup, "floor", {6.45, 3.0, -1e-9}, {6.55, 4.9, 1e-9}), 0.0, 1e-12);
  EXPECT_NEAR(area_inside(c.soup, "floor", {11.25, 3.4, -1e-9}, {11.85, 4.6, 1e-9}), 0.0, 1e-12);
  EXPECT_NEAR(area_inside(c.soup, "floor", {3.5, 6.77, -1e-9}, {5.1, 8.85, 1e-9}), 0.0, 1e-12);
  EXPECT_NEAR(area_inside(c.soup, "plaster", {0.1, 0.1, -0.25 + 1e-6}, {11.9, 8.9, -1e-6}), 0.0, 1e-12);
  // The rooms' floors are there: 4 rooms of the layout, less the furniture's footprints.
  const double rooms = (6.44 - 0.15) * (4.94 - 0.15) + (11.85 - 6.56) * (4.94 - 0.15) + (5.94 - 0.15) * (8.85 - 5.06) +
                       (11.85 - 6.06) * (8.85 - 5.06);
  // Floor in the four inner doors' openings. In the entrance the wall's own threshold
  // (its top below the door, in the floor's plane) covers the slab.
  const double doors = 4 * 0.9 * 0.12;
  const double footprints = 1.6 * 2.1 + 2.2 * 0.8 + 0.6 * 1.2 + 1.6 * 0.65 + 4 * 0.06 * 0.06;
  EXPECT_NEAR(area_inside(c.soup, "floor", {-1, -1, -1e-9}, {13, 10, 1e-9}), rooms + doors - footprints, 1e-6);
}

TEST(Flatten, TheCornellRedWallIsMadePlanarAndStaysConnected) {
  const PolygonSoup input = read_input(test::sample("cornell_box.obj"));
  const Cleaned c = clean(input);
  EXPECT_EQ(c.report.flattened_polygons, 1u);
  EXPECT_EQ(c.report.warped_polygons, 0u);
  EXPECT_GT(c.report.largest_flattening_move, 0.0);
  EXPECT_LT(c.report.largest_flattening_move, 1.0);  // mm
  Vec3d first(0.0);
  std::size_t red = 0;
  for (std::size_t t = 0; t < c.soup.triangles.size(); ++t) {
    if (c.soup.materials[c.soup.material[t]].name != "red") continue;
    const auto& tri = c.soup.triangles[t];
    const Vec3d n =
        OpenMesh::cross(c.soup.points[tri[1]] - c.soup.points[tri[0]], c.soup.points[tri[2]] - c.soup.points[tri[0]])
            .normalized();
    if (red++ == 0) first = n;
    EXPECT_GT(OpenMesh::dot(n, first), 1 - 1e-12);
  }
  EXPECT_GE(red, 2u);
  // Without flattening its triangles disagree (the blotches the issue shows).
  CleanupOptions off;
  off.flatten = false;
  const Cleaned raw = clean(input, off);
  double worst = 1;
  for (std::size_t t = 0; t < raw.soup.triangles.size(); ++t) {
    if (raw.soup.materials[raw.soup.material[t]].name != "red") continue;
    const auto& tri = raw.soup.triangles[t];
    const Vec3d n = OpenMesh::cross(raw.soup.points[tri[1]] - raw.soup.points[tri[0]],
                                    raw.soup.points[tri[2]] - raw.soup.points[tri[0]])
                        .normalized();
    worst = std::min(worst, OpenMesh::dot(n, first));
  }
  EXPECT_LT(worst, 1 - 1e-6);
  SceneMesh mesh(c.soup);
  EXPECT_EQ(test::count_t_vertices(mesh), 0u);
}

TEST(Flatten, AWarpedPolygonIsLeftAsItIsAndItsNeighbourStaysFlat) {
  SceneBuilder b;
  const auto grey = b.material("grey", 0.5);
  // A flat unit quad and, sharing its edge x = 1, a quad 0.3% of its width out of plane
  // (flattened) and, beside that, one 20% out (warped).
  b.quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, grey);
  b.quad({1, 0, 0}, {2, 0, 0.003}, {2, 1, 0}, {1, 1, 0}, grey);
  b.quad({2, 0, 0.003}, {3, 0, 0.2}, {3, 1, 0}, {2, 1, 0}, grey);
  const Cleaned c = clean(b.soup());
  EXPECT_EQ(c.report.flattened_polygons, 1u);
  EXPECT_EQ(c.report.warped_polygons, 1u);
  // The flat quad's corners did not move off z = 0; the middle quad is planar.
  for (const Vec3d& p : c.soup.points) {
    if (p[0] <= 1 + 1e-12) {
      EXPECT_NEAR(p[2], 0.0, 1e-12);
    }
  }
  SceneMesh mesh(c.soup);
  Vec3d normal(0.0);
  for (auto f : mesh.mesh().faces()) {
    const Vec3d centre = mesh.centroid(f);
    if (centre[0] < 1 || centre[0] > 2) continue;
    if (normal == Vec3d(0.0)) normal = mesh.normal(f);
    EXPECT_GT(OpenMesh::dot(mesh.normal(f), normal), 1 - 1e-12);
  }
}

TEST(Imprint, AFacetThatCannotBeImprintedIsNamedAndTheRestIsImprinted) {
  // A fan of five 80-degree triangles around a point: the fifth overlaps the first, so
  // the fan, crossed by a wall, cannot be triangulated again as one flat region.
  SceneBuilder b;
  const auto grey = b.material("grey", 0.5);
  b.group("fan");
  PolygonSoup soup = b.soup();
  soup.points.push_back({0, 0, 0});
  for (int k = 0; k <= 5; ++k) {
    const double angle = k * 80.0 * M_PI / 180;
    soup.points.push_back({std::cos(angle), std::sin(angle), 0});
  }
  for (std::uint32_t k = 0; k < 5; ++k) {
    soup.polygons.push_back({0, k + 1, k + 2});
    soup.material.push_back(grey);
    soup.group.push_back(0);
    soup.origin.push_back(SourceRef{0, 0, k});
  }
  // A vertical square through the fan and a floor it stands on, beside it.
  const std::uint32_t base = static_cast<std::uint32_t>(soup.points.size());
  for (const Vec3d& p : {Vec3d(0.3, -2, -1), Vec3d(0.3, 2, -1), Vec3d(0.3, 2, 1), Vec3d(0.3, -2, 1)})
    soup.points.push_back(p);
  soup.polygons.push_back({base, base + 1, base + 2, base + 3});
  soup.material.push_back(grey);
  soup.group.push_back(0);
  soup.origin.push_back(SourceRef{0, 0, 5});
  const Cleaned c = clean(soup);
  EXPECT_EQ(c.report.imprint_failures, 1u);
  EXPECT_NE(c.report.first_imprint_failure.find("generated face"), std::string::npos) << c.report.first_imprint_failure;
  EXPECT_GE(c.report.imprinted_facets, 1u);  // the square got the fan's line
  EXPECT_GT(c.soup.triangles.size(), 0u);
}

}  // namespace
}  // namespace dynrad
