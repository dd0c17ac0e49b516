// SphereIndex (mesh/core/sphere_index.h) against a loop over every ball.
#include "mesh/core/sphere_index.h"

#include <gtest/gtest.h>

#include <random>

namespace dynrad {
namespace {

TEST(SphereIndex, FindsExactlyTheBallsALoopFinds) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coordinate(-10, 10), size(0.01, 2);
  std::vector<SphereIndex::Ball> balls(2000);
  for (auto& b : balls) b = {Vec3d(coordinate(rng), coordinate(rng), coordinate(rng)), size(rng)};
  SphereIndex index;  // inserted in reverse order: the answers come sorted anyway
  for (std::size_t i = balls.size(); i-- > 0;) index.insert(static_cast<std::uint32_t>(i), balls[i]);
  ASSERT_EQ(index.size(), balls.size());
  std::size_t found = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    const double distance = size(rng);
    std::vector<std::uint32_t> expected, got{99999};  // what was in `out` stays
    for (std::uint32_t i = 0; i < balls.size(); ++i)
      if ((balls[i].centre - x).norm() < balls[i].radius + distance) expected.push_back(i);
    index.near(x, distance, got);
    ASSERT_EQ(got.front(), 99999u);
    got.erase(got.begin());
    EXPECT_EQ(got, expected) << "query " << q;
    found += got.size();
  }
  EXPECT_GT(found, 100u);  // the queries did find balls
}

TEST(SphereIndex, EmptyIndexFindsNothing) {
  const SphereIndex index;
  std::vector<std::uint32_t> out;
  index.near(Vec3d(0, 0, 0), 1e9, out);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace dynrad
