// The tree's winding numbers (mesh/core/winding_number.h) against the closed answer (inside a
// box: 1, outside: 0) and against the sum over every triangle.
#include "mesh/core/winding_number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace dynrad {
namespace {

using Triangles = std::vector<std::array<Vec3d, 3>>;

// The box [lo, hi], each face cut into n x n squares of two triangles, facing out.
void add_box(Triangles& out, const Vec3d& lo, const Vec3d& hi, int n) {
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      auto at = [&](double s, double t) {
        Vec3d p;
        p[axis] = side ? hi[axis] : lo[axis];
        p[u] = lo[u] + s * (hi[u] - lo[u]);
        p[v] = lo[v] + t * (hi[v] - lo[v]);
        return p;
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const Vec3d a = at(double(i) / n, double(j) / n), b = at(double(i + 1) / n, double(j) / n),
                      c = at(double(i + 1) / n, double(j + 1) / n), d = at(double(i) / n, double(j + 1) / n);
          // (u, v, axis) is right-handed, so a-b-c turns about +axis: out on the high side.
          if (side) {
            out.push_back({a, b, c});
            out.push_back({a, c, d});
          } else {
            out.push_back({a, c, b});
            out.push_back({a, d, c});
          }
        }
    }
}

bool inside(const Vec3d& x, const Vec3d& lo, const Vec3d& hi) {
  for (int k = 0; k < 3; ++k)
    if (x[k] <= lo[k] || x[k] >= hi[k]) return false;
  return true;
}

TEST(WindingNumber, OneInsideABoxAndZeroOutside) {
  Triangles box;
  const Vec3d lo(0, 0, 0), hi(4, 2, 3);
  add_box(box, lo, hi, 24);  // 3,456 triangles: most nodes are far from most points
  const WindingNumber tree(box);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-2, 6);
  double worst = 0;
  int in = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vec3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    const double expected = inside(x, lo, hi) ? 1 : 0;
    in += expected > 0;
    const double got = tree.at(x);
    worst = std::max(worst, std::abs(got - expected));
    ASSERT_NEAR(WindingNumber::exact(box, x), expected, 1e-9) << x;
  }
  EXPECT_GT(in, 100);
  EXPECT_LT(worst, 0.02) << "the expansion's error, in turns";
}

// A point a hair in front of or behind a face is decided by that face's own triangles,
// which are near and so summed exactly.
TEST(WindingNumber, DecidedAHairFromTheSurface) {
  Triangles box;
  const Vec3d lo(0, 0, 0), hi(10, 10, 3);
  add_box(box, lo, hi, 40);
  const WindingNumber tree(box);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> along(0.05, 9.95);
  for (int k = 0; k < 500; ++k) {
    const double s = along(rng), t = along(rng) * 0.3;
    for (double off : {1e-6, 1e-3}) {
      EXPECT_NEAR(tree.at(Vec3d(s, t, 3 - off)), 1, 0.02);  // under the top
      EXPECT_NEAR(tree.at(Vec3d(s, t, 3 + off)), 0, 0.02);  // above it
      EXPECT_NEAR(tree.at(Vec3d(off, s, t)), 1, 0.02);      // inside the side x = 0
      EXPECT_NEAR(tree.at(Vec3d(-off, s, t)), 0, 0.02);
    }
  }
}

// Two boxes that share an edge (facades that meet at a corner line) are one closed
// surface to cleanup; the winding numbers add, each box counting 1 inside itself.
TEST(WindingNumber, SolidsJoinedAtAnEdgeAdd) {
  Triangles two;
  add_box(two, Vec3d(0, 0, 0), Vec3d(1, 1, 1), 6);
  add_box(two, Vec3d(1, 1, 0), Vec3d(2, 2, 1), 6);
  const WindingNumber tree(two, {/*far_ratio=*/3, /*leaf_triangles=*/4});
  EXPECT_NEAR(tree.at(Vec3d(0.5, 0.5, 0.5)), 1, 0.02);
  EXPECT_NEAR(tree.at(Vec3d(1.5, 1.5, 0.5)), 1, 0.02);
  EXPECT_NEAR(tree.at(Vec3d(1.5, 0.5, 0.5)), 0, 0.02);
  EXPECT_NEAR(tree.at(Vec3d(0.5, 1.5, 0.5)), 0, 0.02);
}

// With no node ever far, the tree sums every triangle: the same as the direct sum, for a
// surface that is not closed too (a box without its top).
TEST(WindingNumber, NoFarNodesIsTheDirectSum) {
  Triangles box;
  add_box(box, Vec3d(0, 0, 0), Vec3d(1, 2, 3), 5);
  Triangles open;
  for (const auto& t : box)
    if (!(t[0][2] == 3 && t[1][2] == 3 && t[2][2] == 3)) open.push_back(t);
  ASSERT_LT(open.size(), box.size());
  const WindingNumber tree(open, {/*far_ratio=*/1e9, /*leaf_triangles=*/3});
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-1, 4);
  for (int k = 0; k < 200; ++k) {
    const Vec3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    EXPECT_NEAR(tree.at(x), WindingNumber::exact(open, x), 1e-12) << x;
  }
}

TEST(WindingNumber, EmptyIsZero) {
  const WindingNumber tree(Triangles{});
  EXPECT_EQ(tree.at(Vec3d(0, 0, 0)), 0);
}

}  // namespace
}  // namespace dynrad
