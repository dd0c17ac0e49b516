// Openings (mesh/core/openings.h): the holes light comes in through, and nothing else.
#include "mesh/load.h"
#include "scene_builder.h"

#include <gtest/gtest.h>

namespace dynrad {
namespace {

using test::SceneBuilder;

double area(const std::vector<std::array<Vec3d, 3>>& triangles) {
  double sum = 0;
  for (const auto& t : triangles) sum += 0.5 * OpenMesh::cross(t[1] - t[0], t[2] - t[0]).norm();
  return sum;
}

// A 4 x 3 wall in the plane y = 0, facing +y, with a 2 x 1 hole over x in [1, 3],
// z in [1, 2].
void wall_with_hole(SceneBuilder& b, std::uint32_t material) {
  auto facade = [&](double x0, double z0, double x1, double z1) {
    b.quad(Vec3d(x0, 0, z0), Vec3d(x0, 0, z1), Vec3d(x1, 0, z1), Vec3d(x1, 0, z0), material);
  };
  facade(0, 0, 1, 3);
  facade(3, 0, 4, 3);
  facade(1, 0, 3, 1);
  facade(1, 2, 3, 3);
}

TEST(Openings, AFlatSurfaceStandingAloneHasNone) {
  SceneBuilder b;
  const std::uint32_t m = b.material("grey", 0.5);
  b.quad(Vec3d(0, 0, 0), Vec3d(4, 0, 0), Vec3d(4, 3, 0), Vec3d(0, 3, 0), m);  // its outline is not a hole
  EXPECT_TRUE(load_soup(b.soup(), "plate").openings.empty());
  SceneBuilder closed;
  closed.box(Vec3d(0, 0, 0), Vec3d(4, 3, 2), closed.material("grey", 0.5), SceneBuilder::inward);
  EXPECT_TRUE(load_soup(closed.soup(), "closed room").openings.empty());
  // An L of two walls: its boundary is not flat.
  SceneBuilder l;
  const std::uint32_t g = l.material("grey", 0.5);
  l.quad(Vec3d(0, 0, 0), Vec3d(4, 0, 0), Vec3d(4, 0, 3), Vec3d(0, 0, 3), g);
  l.quad(Vec3d(0, 0, 0), Vec3d(0, 0, 3), Vec3d(0, 4, 3), Vec3d(0, 4, 0), g);
  EXPECT_TRUE(load_soup(l.soup(), "corner").openings.empty());
}

TEST(Openings, AHoleInAWallAnOpenTopAndADoorAreFound) {
  SceneBuilder wall;
  wall_with_hole(wall, wall.material("grey", 0.5));
  const auto hole = load_soup(wall.soup(), "wall").openings;
  EXPECT_NEAR(area(hole), 2.0, 1e-9);
  for (const auto& t : hole)
    for (const Vec3d& c : t) {
      EXPECT_NEAR(c[1], 0, 1e-12);
      EXPECT_TRUE(c[0] >= 1 - 1e-12 && c[0] <= 3 + 1e-12 && c[2] >= 1 - 1e-12 && c[2] <= 2 + 1e-12) << c;
    }

  // A room without its ceiling: the missing ceiling.
  SceneBuilder cup;
  cup.box(Vec3d(0, 0, 0), Vec3d(4, 3, 2), cup.material("grey", 0.5), SceneBuilder::inward,
          {false, false, false, false, false, true});
  const auto top = load_soup(cup.soup(), "cup").openings;
  EXPECT_NEAR(area(top), 12.0, 1e-9);
  for (const auto& t : top)
    for (const Vec3d& c : t) EXPECT_NEAR(c[2], 2, 1e-12);

  // A floor and a wall with a 1 x 2 door down to the floor: the door (the floor's edge
  // under it closes the loop).
  SceneBuilder room;
  const std::uint32_t g = room.material("grey", 0.5);
  room.quad(Vec3d(0, 0, 0), Vec3d(4, 0, 0), Vec3d(4, 4, 0), Vec3d(0, 4, 0), g);  // floor, up
  auto door_wall = [&](double x0, double z0, double x1, double z1) {
    room.quad(Vec3d(x0, 0, z0), Vec3d(x0, 0, z1), Vec3d(x1, 0, z1), Vec3d(x1, 0, z0), g);
  };
  door_wall(0, 0, 1, 3);
  door_wall(2, 0, 4, 3);
  door_wall(1, 2, 2, 3);
  const auto door = load_soup(room.soup(), "door").openings;
  EXPECT_NEAR(area(door), 2.0, 1e-9);
}

TEST(Openings, HolesThatSurfacesBehindMeetAreFoundAndOnesClosedInFrontAreNot) {
  // The wall with its 2 x 1 hole, and an overhang outside along the hole's head, wider
  // than the hole: where it meets the wall beside the hole, cleanup leaves slits.
  SceneBuilder wall;
  const std::uint32_t m = wall.material("grey", 0.5);
  wall_with_hole(wall, m);
  wall.quad(Vec3d(0, -1, 2), Vec3d(0, 0, 2), Vec3d(4, 0, 2), Vec3d(4, -1, 2), m);  // facing down
  EXPECT_NEAR(area(load_soup(wall.soup(), "overhang").openings), 2.0, 1e-9);

  // A wall 0.3 m thick with a 1 x 1 window hole lined by its reveals: the hole's inner
  // outline, in the inner face's plane.
  SceneBuilder thick;
  const std::uint32_t g = thick.material("grey", 0.5);
  auto inner = [&](double x0, double z0, double x1, double z1) {  // y = 0, facing +y
    thick.quad(Vec3d(x0, 0, z0), Vec3d(x0, 0, z1), Vec3d(x1, 0, z1), Vec3d(x1, 0, z0), g);
  };
  auto outer = [&](double x0, double z0, double x1, double z1) {  // y = -0.3, facing -y
    thick.quad(Vec3d(x0, -0.3, z0), Vec3d(x1, -0.3, z0), Vec3d(x1, -0.3, z1), Vec3d(x0, -0.3, z1), g);
  };
  inner(0, 0, 1, 3);
  inner(2, 0, 3, 3);
  inner(1, 0, 2, 1);
  inner(1, 2, 2, 3);
  outer(0, 0, 1, 3);
  outer(2, 0, 3, 3);
  outer(1, 0, 2, 1);
  outer(1, 2, 2, 3);
  // The reveals, facing into the hole.
  thick.quad(Vec3d(1, -0.3, 1), Vec3d(1, 0, 1), Vec3d(1, 0, 2), Vec3d(1, -0.3, 2), g);  // +x
  thick.quad(Vec3d(2, -0.3, 1), Vec3d(2, -0.3, 2), Vec3d(2, 0, 2), Vec3d(2, 0, 1), g);  // -x
  thick.quad(Vec3d(1, -0.3, 1), Vec3d(2, -0.3, 1), Vec3d(2, 0, 1), Vec3d(1, 0, 1), g);  // +z
  thick.quad(Vec3d(1, -0.3, 2), Vec3d(1, 0, 2), Vec3d(2, 0, 2), Vec3d(2, -0.3, 2), g);  // -z
  const auto reveal = load_soup(thick.soup(), "thick wall").openings;
  EXPECT_NEAR(area(reveal), 2.0, 1e-9);  // the inner outline and the outer one
  for (const auto& t : reveal)
    for (const Vec3d& c : t) EXPECT_TRUE(c[0] >= 1 - 1e-12 && c[0] <= 2 + 1e-12 && c[2] >= 1 - 1e-12 && c[2] <= 2 + 1e-12) << c;

  // A 0.4 m square column standing through a floor: a hole in the floor, closed by the
  // column in front of it. No opening.
  SceneBuilder column;
  const std::uint32_t c = column.material("grey", 0.5);
  column.quad(Vec3d(0, 0, 0), Vec3d(4, 0, 0), Vec3d(4, 4, 0), Vec3d(0, 4, 0), c);
  column.box(Vec3d(1.8, 1.8, 0), Vec3d(2.2, 2.2, 3), c, SceneBuilder::outward, {false, false, false, false, true, false});
  EXPECT_TRUE(load_soup(column.soup(), "column").openings.empty());
}

}  // namespace
}  // namespace dynrad
