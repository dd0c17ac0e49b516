// The mean free path (mesh/core/mean_free_path.h) and the share of its rays that meet a
// surface: in a closed room every ray meets one, and the mean is the mean chord 4V/S;
// turned inside out, almost none do, and what is left is a lamp's gap to the ceiling.
#include "mesh/core/mean_free_path.h"
#include "mesh/core/scene_mesh.h"
#include "mesh/repair/cleanup.h"
#include "scene_builder.h"

#include <gtest/gtest.h>

namespace dynrad {
namespace {

SceneMesh room(test::SceneBuilder::Facing facing) {
  test::SceneBuilder b;
  const std::uint32_t wall = b.material("wall", 0.6);
  const std::uint32_t lamp = b.material("lamp", 0.2, 1);
  b.box({0, 0, 0}, {2, 2, 2}, wall, facing);
  // A lamp 1 cm under the ceiling, facing down into the room, or, in the room turned
  // inside out, up at the ceiling.
  b.rectangle(0.8, 0.8, 1.2, 1.2, 1.99, facing == test::SceneBuilder::inward ? -1 : 1, lamp);
  TriangleSoup clean;
  cleanup(b.soup(), clean);
  return SceneMesh(clean);
}

TEST(MeanFreePath, ClosedRoomIsItsMeanChordAndInsideOutMeetsAlmostNothing) {
  const MeanFreePath in = mean_free_path(room(test::SceneBuilder::inward));
  EXPECT_GT(in.met, 0.99);
  EXPECT_LT(in.escaped, 0.01);
  // 4V/S of the 2 m cube, 4 * 8 / 24; the lamp's small area moves it little.
  EXPECT_NEAR(in.length, 4.0 * 8 / 24, 0.05 * 4.0 * 8 / 24);
  const MeanFreePath out = mean_free_path(room(test::SceneBuilder::outward));
  EXPECT_LT(out.met, 0.05);  // the pipeline's warning threshold (kFewRaysMet)
  EXPECT_GT(out.escaped, 0.95);
  EXPECT_LT(out.length, 0.05);  // the lamp's 1 cm gap, not the room
}

}  // namespace
}  // namespace dynrad
