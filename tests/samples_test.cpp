// Every bundled sample loads, needs no repair (but the Cornell red wall's flattening), is
// conforming and manifold, and has the sizes its published description gives.
#include "mesh/io/import.h"
#include "mesh/load.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace dynrad {
namespace {

struct SampleFacts {
  const char* file;
  double total_area;     // model units squared
  double emitting_area;
  bool closed;           // no boundary edges
  std::size_t repairs = 0;
  double hidden_area = 0;  // removed by imprinting: no light reaches it
};

std::ostream& operator<<(std::ostream& out, const SampleFacts& s) { return out << s.file; }

class Samples : public ::testing::TestWithParam<SampleFacts> {};

TEST_P(Samples, LoadCleanAndConforming) {
  const SampleFacts& facts = GetParam();
  const std::string path = test::sample(facts.file);
  const PolygonSoup soup = read_input(path);
  LoadedScene scene = load_scene(path);
  const SceneMesh& mesh = *scene.mesh;
  EXPECT_EQ(scene.cleanup.repairs(), facts.repairs);
  EXPECT_EQ(test::count_t_vertices(mesh), 0u);
  EXPECT_NEAR(scene.cleanup.hidden_area, facts.hidden_area, 1e-9 * test::polygon_area(soup));
  // Newell's area is the projected one; the measured Cornell red wall is 0.8 mm out of
  // plane before flattening (1e-6 relative).
  EXPECT_NEAR(mesh.total_area() + scene.cleanup.hidden_area, test::polygon_area(soup),
              1e-5 * test::polygon_area(soup));
  if (facts.total_area > 0) {
    EXPECT_NEAR(mesh.total_area(), facts.total_area, 1e-6 * facts.total_area);
  }
  EXPECT_NEAR(mesh.emitting_area(), facts.emitting_area, 1e-6 * facts.emitting_area);
  std::size_t boundary = 0;
  for (auto e : mesh.mesh().edges()) boundary += mesh.mesh().is_boundary(e);
  if (facts.closed) {
    EXPECT_EQ(boundary, 0u);
  } else {
    EXPECT_GT(boundary, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(
    All, Samples,
    ::testing::Values(
        // Cornell box: open at the front; the light is 130 x 105 mm. The red wall is
        // flattened; the blocks have no bottom, so the floor under them, 27,633 and
        // 27,626.5 mm2 (their footprints), is enclosed and removed.
        SampleFacts{"cornell_box.obj", 0, 130.0 * 105.0, false, 1, 27633.0 + 27626.5},
        // 10 x 6 x 3 room: 2 (60 + 30 + 18) m2; 0.5 x 0.5 source.
        SampleFacts{"globillum_room.obj", 216.0, 0.25, true},
        // Partitions add 2 x (2 x 3 x 3 + 0.1 x 3) and cover 2 x 0.3 of floor and ceiling and 2 x 0.3 of wall.
        SampleFacts{"globillum_room_obstructed.obj", 216.0 + 2 * (18.0 + 0.3) - 2 * 0.3 - 2 * 0.3 - 2 * 0.3, 0.25, true},
        // 6 x 6 x 3 room: 2 (36 + 18 + 18) = 144 m2; one 0.75 x 0.375 cell emits.
        SampleFacts{"paper_empty_room_small_source.obj", 144.0, 0.75 * 0.375, true},
        SampleFacts{"paper_empty_room_front_wall.obj", 144.0, 18.0, true},
        SampleFacts{"paper_sphere_room.obj", 0, 2 * 0.75 * 0.375, true},
        // Scene file: a 4 x 4 x 3 room from OFF (2 (16 + 12 + 12) = 80 m2) and a 0.6 x 0.6 lamp.
        SampleFacts{"scene_room.json", 80.0 + 0.36, 0.36, false}));

TEST(SampleFacing, RoomSurfacesFaceIntoTheRoom) {
  for (const char* file : {"globillum_room.obj", "paper_empty_room_small_source.obj", "paper_sphere_room.obj"}) {
    LoadedScene scene = load_scene(test::sample(file));
    const SceneMesh& mesh = *scene.mesh;
    const Bounds b = mesh.bounds();
    const Vec3d centre = (b.lo + b.hi) * 0.5;
    for (auto f : mesh.mesh().faces()) {
      if (mesh.material(f).name == "sphere") continue;
      EXPECT_GT(OpenMesh::dot(mesh.normal(f), centre - mesh.centroid(f)), 0.0) << file << " " << mesh.where(f);
    }
  }
}

TEST(SampleFacing, CornellBoxMatchesTheMeasuredOrientation) {
  LoadedScene scene = load_scene(test::sample("cornell_box.obj"));
  const SceneMesh& mesh = *scene.mesh;
  for (auto f : mesh.mesh().faces()) {
    const std::string& group = mesh.group_names()[mesh.group(f)];
    const Vec3d n = mesh.normal(f);
    if (group == "floor") {
      EXPECT_GT(n[1], 0.99);
    }
    if (group == "ceiling" || group == "light") {
      EXPECT_LT(n[1], -0.99);
    }
    if (group == "back_wall") {
      EXPECT_LT(n[2], -0.99);
    }
    if (group == "green_wall") {
      EXPECT_GT(n[0], 0.99);
    }
    if (group == "red_wall") {
      EXPECT_LT(n[0], -0.99);
    }
  }
}

}  // namespace
}  // namespace dynrad
