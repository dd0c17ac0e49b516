// Form factors against closed forms (Cohen & Wallace 1993), numerical integration,
// reciprocity; and visibility with occluders through Embree.
#include "mesh/load.h"
#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/visibility.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace dynrad::rad {
namespace {

// Area-to-area form factor F(receiver -> sender) as the receiver-average of point form
// factors, midpoint rule on an n x n grid over the receiver rectangle
// origin + s*u + t*v, s,t in [0,1].
double rectangle_to_polygon(const Vec3d& origin, const Vec3d& u, const Vec3d& v, const Vec3d* sender, int count,
                            const Vec3d& sender_front, int n) {
  const Vec3d normal = OpenMesh::cross(u, v).normalized();
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3d x = origin + u * ((i + 0.5) / n) + v * ((j + 0.5) / n);
      sum += point_to_polygon(x, normal, sender, count, sender_front);
    }
  return sum / (n * n);
}

TEST(FormFactor, ParallelUnitSquaresAtDistanceOne) {
  // Receiver z = 0 facing +z; sender z = 1 facing -z (counter-clockwise seen from below).
  const Vec3d sender[4] = {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};
  const double f = rectangle_to_polygon({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, sender, 4, {0, 0, -1}, 64);
  EXPECT_NEAR(f, 0.1998, 2e-4);
}

TEST(FormFactor, PerpendicularUnitSquaresSharingAnEdge) {
  // Receiver floor z = 0 (facing +z); sender wall x = 0 facing +x.
  const Vec3d sender[4] = {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}};
  const double f = rectangle_to_polygon({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, sender, 4, {1, 0, 0}, 256);
  EXPECT_NEAR(f, 0.20004, 1e-3);
}

TEST(FormFactor, BackFacingAndBelowTheHorizonGiveZero) {
  const Vec3d tri[3] = {{0, 0, 1}, {0, 1, 1}, {1, 0, 1}};
  EXPECT_EQ(point_to_polygon({0.2, 0.2, 0}, {0, 0, 1}, tri, 3, {0, 0, 1}), 0.0);   // sender faces away
  EXPECT_EQ(point_to_polygon({0.2, 0.2, 0}, {0, 0, -1}, tri, 3, {0, 0, -1}), 0.0); // sender behind receiver
  // A sender of one infinite-looking half plane seen from its edge: F -> 1/2 of a hemisphere.
  const Vec3d big[4] = {{-1e4, -1e4, 1e-3}, {-1e4, 1e4, 1e-3}, {1e4, 1e4, 1e-3}, {1e4, -1e4, 1e-3}};
  EXPECT_NEAR(point_to_polygon({0, 0, 0}, {0, 0, 1}, big, 4, {0, 0, -1}), 1.0, 1e-3);
}

// Lambert's closed form against brute-force integration of cos cos / (pi r^2) over the
// sender, for random triangles, including ones cut by the receiver's horizon.
TEST(FormFactor, LambertMatchesNumericalIntegration) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  int clipped = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Vec3d a(coord(rng), coord(rng), 0.6 + coord(rng)), b(coord(rng), coord(rng), 0.6 + coord(rng)),
        c(coord(rng), coord(rng), 0.6 + coord(rng));
    Vec3d front = OpenMesh::cross(b - a, c - a);
    if (front.norm() < 0.2) continue;
    front.normalize();
    const Vec3d x(0, 0, 0), n(0, 0, 1);
    if (OpenMesh::dot(front, x - a) <= 0) {  // make it face the receiver
      std::swap(b, c);
      front = -front;
    }
    clipped += (a[2] < 0 || b[2] < 0 || c[2] < 0);
    const double closed = point_to_triangle(x, n, a, b, c, front);
    // Numerical: 400 x 400 midpoint samples in barycentric squares.
    const int m = 400;
    double sum = 0;
    const double area = 0.5 * OpenMesh::cross(b - a, c - a).norm();
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m - i; ++j)
        for (int up = 0; up < 2; ++up) {
          if (up && j == m - i - 1) continue;
          const double s = up ? (i + 2.0 / 3) / m : (i + 1.0 / 3) / m;
          const double t = up ? (j + 2.0 / 3) / m : (j + 1.0 / 3) / m;
          const Vec3d p = a + (b - a) * s + (c - a) * t;
          const Vec3d r = p - x;
          const double d2 = r.sqrnorm();
          const double cos_x = OpenMesh::dot(n, r) / std::sqrt(d2);
          const double cos_p = -OpenMesh::dot(front, r) / std::sqrt(d2);
          if (cos_x > 0 && cos_p > 0) sum += cos_x * cos_p / (M_PI * d2);
        }
    const double numeric = sum * area / (m * m);
    EXPECT_NEAR(closed, numeric, 2e-3 * std::max(numeric, 0.05)) << "trial " << trial;
  }
  EXPECT_GT(clipped, 3);  // the horizon clipping was exercised
}

// The push-down oracle's far-field estimate (Solver::estimate_pushdown_error): from
// kFarField = 5 sender radii on, the second difference of the point-to-area form along a
// receiver's edge must match the closed form's within a small fraction of itself, and
// the form itself within (R / r)^2 or so.
TEST(FormFactor, PointToAreaSecondDifferenceFarFromTheSender) {
  // Sender: a triangle in the plane z = 4 facing down, radius 0.5 around (0, 0, 4).
  const Vec3d a(0.5, 0, 4), b(-0.25, 0.433, 4), c(-0.25, -0.433, 4), front(0, 0, -1);
  const Vec3d centre = (a + b + c) / 3.0;
  const double area = 0.5 * OpenMesh::cross(b - a, c - a).norm(), radius = 0.5;
  for (double tilt : {0.0, 0.3}) {
    const Vec3d n = Vec3d(std::sin(tilt), 0, std::cos(tilt));  // the receiver's normal
    for (double h : {0.5, 1.0, 2.0}) {  // receiver edge length
      for (double x0 : {0.0, 1.0, 2.5}) {
        // An edge of the receiver plane through (x0, 0, 0), at least 5 radii away.
        const Vec3d p0(x0 - h / 2, 0.3, 0), p1(x0 + h / 2, 0.3, 0), mid = (p0 + p1) * 0.5;
        ASSERT_GE((centre - mid).norm() - h / 2, 5 * radius);
        auto exact = [&](const Vec3d& x) { return point_to_triangle(x, n, a, b, c, front); };
        auto far = [&](const Vec3d& x) { return point_to_area(x, n, centre, front, area); };
        const double f = exact(mid), g = far(mid);
        const double r = (centre - mid).norm();
        EXPECT_NEAR(g, f, 2 * (radius / r) * (radius / r) * f) << "h " << h << " x0 " << x0 << " tilt " << tilt;
        const double d_exact = exact(mid) - 0.5 * (exact(p0) + exact(p1));
        const double d_far = far(mid) - 0.5 * (far(p0) + far(p1));
        EXPECT_NEAR(d_far, d_exact, 0.05 * std::abs(d_exact) + 1e-6 * f)
            << "h " << h << " x0 " << x0 << " tilt " << tilt;
      }
    }
  }
}

TEST(FormFactor, Reciprocity) {
  // Two unit squares at a skew: A_i F_ij = A_j F_ji, each side integrated numerically.
  const Vec3d floor[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};                 // faces +z, area 1
  const Vec3d slope[4] = {{0.5, 0, 1.5}, {0.5, 2, 1.5}, {2, 2, 0.8}, {2, 0, 0.8}};      // faces down-ish
  const Vec3d slope_front = OpenMesh::cross(slope[1] - slope[0], slope[2] - slope[0]).normalized();
  const double slope_area = OpenMesh::cross(slope[1] - slope[0], slope[3] - slope[0]).norm();
  const double f_floor_to_slope = rectangle_to_polygon(floor[0], {1, 0, 0}, {0, 1, 0}, slope, 4, slope_front, 96);
  const double f_slope_to_floor =
      rectangle_to_polygon(slope[0], slope[1] - slope[0], slope[3] - slope[0], floor, 4, {0, 0, 1}, 96);
  ASSERT_GT(f_floor_to_slope, 0.01);
  EXPECT_NEAR(1.0 * f_floor_to_slope, slope_area * f_slope_to_floor, 2e-3 * f_floor_to_slope);
}

TEST(Visibility, OccludersBlockAndOpenSpaceDoesNot) {
  // The obstructed comparison room: partition A spans x 2.95..3.05, y 3..6.
  LoadedScene loaded = load_scene(test::sample("globillum_room_obstructed.obj"));
  Visibility vis(*loaded.mesh);
  const Vec3d up(0, 0, 1);
  // Across the partition: blocked. Along the open side: clear.
  const Vec3d down(0, 0, -1);
  EXPECT_TRUE(vis.occluded({1.0, 4.5, 0.0}, up, {5.0, 4.5, 3.0}, down));
  EXPECT_FALSE(vis.occluded({1.0, 1.5, 0.0}, up, {5.0, 1.5, 3.0}, down));
  // A ray starting on the floor toward the ceiling light is not blocked by the floor
  // itself or by the light it ends on.
  EXPECT_FALSE(vis.occluded({5.0, 3.0, 0.0}, up, {5.0, 3.0, 3.0}, down));
  // Grazing: from a floor point next to the wall x = 0 to a point on that wall.
  EXPECT_FALSE(vis.occluded({0.01, 0.5, 0.0}, up, {0.0, 2.5, 0.2}, {1, 0, 0}));
  EXPECT_EQ(vis.rays(), 4u);
  // Straight up from the floor meets the ceiling's front; from outside the room, nothing.
  EXPECT_EQ(vis.trace({1, 1, 0}, up, up), Visibility::Hit::front);
  EXPECT_EQ(vis.trace({1, 1, 3.5}, up, up), Visibility::Hit::nothing);
  EXPECT_EQ(vis.trace({1, 1, -0.5}, up, up), Visibility::Hit::back);  // the floor's underside
}

// The same queries on plain triangles (dynrad probe's lit mesh): two squares, one above
// the other, in metres far from the origin (floats near 1e6 would round to 0.06 m).
TEST(Visibility, PlainTrianglesFindTheFirstFace) {
  const Vec3d o(1e6, 2e6, 0);
  const std::vector<Vec3d> points = {o + Vec3d(0, 0, 0), o + Vec3d(1, 0, 0), o + Vec3d(1, 1, 0), o + Vec3d(0, 1, 0),
                                     o + Vec3d(0, 0, 2), o + Vec3d(1, 0, 2), o + Vec3d(1, 1, 2), o + Vec3d(0, 1, 2)};
  // The floor faces up (counter-clockwise from above); the ceiling faces down.
  const std::vector<std::array<std::uint32_t, 3>> triangles = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}};
  const Visibility vis(points, triangles);
  const Vec3d down(0, 0, -1), up(0, 0, 1);
  auto hit = vis.intersect(o + Vec3d(0.7, 0.2, 1), down);
  ASSERT_TRUE(hit.hit);
  EXPECT_EQ(hit.face, 0);
  EXPECT_TRUE(hit.front);
  EXPECT_NEAR(hit.distance, 1.0, 1e-6);
  EXPECT_NEAR(hit.u, 0.5, 1e-6);  // (0.7, 0.2) = 0.5 (1,0) + 0.2 (1,1) + 0.3 (0,0)
  EXPECT_NEAR(hit.v, 0.2, 1e-6);
  hit = vis.intersect(o + Vec3d(0.2, 0.7, 1), up);
  ASSERT_TRUE(hit.hit);
  EXPECT_EQ(hit.face, 3);
  EXPECT_TRUE(hit.front);
  hit = vis.intersect(o + Vec3d(0.5, 0.5, -1), down);  // below the floor, looking away
  EXPECT_FALSE(hit.hit);
  hit = vis.intersect(o + Vec3d(0.5, 0.5, 3), down);  // above the ceiling: its back
  ASSERT_TRUE(hit.hit);
  EXPECT_FALSE(hit.front);
  EXPECT_NEAR(hit.distance, 1.0, 1e-6);
  const std::vector<std::array<std::uint32_t, 3>> broken = {{0, 1, 8}};
  EXPECT_THROW(Visibility(points, broken), std::invalid_argument);
}

// The closed form's angle: std::atan2 to 1e-14 over every direction pair, including
// the reduction boundaries, right angles and near-opposite directions.
TEST(AngleBetween, MatchesAtan2) {
  double worst = 0;
  for (int i = 0; i <= 20000; ++i) {
    const double phi = M_PI * i / 20000;
    for (double scale : {1e-6, 1.0, 3e5}) {
      const double y = scale * std::sin(phi), x = scale * std::cos(phi);
      worst = std::max(worst, std::abs(angle_between(y, x) - std::atan2(y, x)));
    }
  }
  for (double t : {0.19891236737965800691, 0.66817863791929891999, 1.0, 0.0}) {
    worst = std::max(worst, std::abs(angle_between(t, 1.0) - std::atan2(t, 1.0)));
    worst = std::max(worst, std::abs(angle_between(t, -1.0) - std::atan2(t, -1.0)));
    worst = std::max(worst, std::abs(angle_between(1.0, t) - std::atan2(1.0, t)));
  }
  EXPECT_LT(worst, 1e-14);
}


// Points all around a triangle in the plane z = 0 (spanning about [0, 2] x [0, 1.7]),
// with tilted normals: in front of it, beside it (parts of it below the point's
// horizon), close to it and far; `clipped` counts those that see part of it behind.
struct ProbePoint {
  Vec3d x, n;
};
std::vector<ProbePoint> points_around_triangle(const Vec3d* c, int& clipped) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<ProbePoint> out;
  clipped = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3d x(u(rng) * 3, u(rng) * 3, 0.05 + (u(rng) + 1) * (trial % 2 ? 0.3 : 3));
    const Vec3d n = Vec3d(u(rng), u(rng), u(rng) - 0.2).normalized();
    bool clips = false;
    for (int k = 0; k < 3; ++k) clips = clips || OpenMesh::dot(c[k] - x, n) < 0;
    clipped += clips;
    out.push_back({x, n});
  }
  return out;
}

// The quartered triangle's shared-edge sum against the four parts' own closed forms,
// for points all around a triangle: in front, beside it (its parts clipped at the
// point's horizon), tilted, close to it and far, with weights above and below 1.
TEST(FormFactor, QuarteredTriangleIsTheWeightedSumOfItsParts) {
  const Vec3d c[3] = {Vec3d(0, 0, 0), Vec3d(2, 0.3, 0), Vec3d(0.4, 1.7, 0)};
  const Vec3d front(0, 0, 1);
  const Vec3d m01 = (c[0] + c[1]) * 0.5, m12 = (c[1] + c[2]) * 0.5, m20 = (c[2] + c[0]) * 0.5;
  const Vec3d parts[4][3] = {{c[0], m01, m20}, {m01, c[1], m12}, {m20, m12, c[2]}, {m01, m12, m20}};
  const double weights[3][4] = {{1, 1, 1, 1}, {1.6, 0.7, 0.9, 0.8}, {-0.2, 2.5, 0.4, 1.3}};
  int clipped = 0;
  const std::vector<ProbePoint> points = points_around_triangle(c, clipped);
  for (const auto& [x, n] : points) {
    for (const auto& w : weights) {
      double expected = 0;
      for (int s = 0; s < 4; ++s) expected += w[s] * point_to_polygon(x, n, parts[s], 3, front);
      EXPECT_NEAR(point_to_quartered_triangle(x, n, c, w, front), expected, 1e-12 * (1 + std::abs(expected)))
          << "x " << x << " n " << n;
    }
  }
  EXPECT_GT(static_cast<int>(points.size()) - clipped, 300);  // both paths were taken
  EXPECT_GT(clipped, 300);
  // Behind the triangle: nothing.
  EXPECT_EQ(point_to_quartered_triangle(Vec3d(0.5, 0.5, -1), Vec3d(0, 0, 1), c, weights[1], front), 0.0);
}

// The grid's node tables: the halfway nodes lie halfway between their ends, and the
// midpoint parts are point_to_quartered_triangle's (corner 0, the midpoints of edges
// 01 and 20, and so on).
TEST(FormFactor, GridTablesNameTheNodesTheySay) {
  const Vec3d c[3] = {Vec3d(0, 0, 0), Vec3d(2, 0.3, 0), Vec3d(0.4, 1.7, 0.2)};
  Vec3d node[kTriangleNodes];
  triangle_nodes(c, node);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(node[kGridCorners[k]], c[k]);
  // the parts are made of the nodes
  Vec3d parts[kTriangleParts][3];
  triangle_parts(c, parts);
  for (int s = 0; s < kTriangleParts; ++s)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(parts[s][k], node[triangle_part_nodes()[s][k]]);
  for (const auto& h : kGridHalfway) EXPECT_LT((node[h[0]] - (node[h[1]] + node[h[2]]) * 0.5).norm(), 1e-12);
  const Vec3d m01 = (c[0] + c[1]) * 0.5, m12 = (c[1] + c[2]) * 0.5, m20 = (c[2] + c[0]) * 0.5;
  const Vec3d quarter[4][3] = {{c[0], m01, m20}, {m01, c[1], m12}, {m20, m12, c[2]}, {m01, m12, m20}};
  for (int q = 0; q < 4; ++q) {
    // the same three points, in any order
    for (int k = 0; k < 3; ++k) {
      double nearest = 1e9;
      for (int j = 0; j < 3; ++j) nearest = std::min(nearest, (node[kMidpointParts[q][j]] - quarter[q][k]).norm());
      EXPECT_LT(nearest, 1e-12) << "part " << q;
    }
  }
}

// The 16-part triangle's grid-edge sum against the parts' own closed forms, for points
// all around a triangle: in front, beside it (its parts clipped at the point's
// horizon), tilted, close to it and far, with weights above and below 1.
TEST(FormFactor, PartedTriangleIsTheWeightedSumOfItsParts) {
  const Vec3d c[3] = {Vec3d(0, 0, 0), Vec3d(2, 0.3, 0), Vec3d(0.4, 1.7, 0)};
  const Vec3d front(0, 0, 1);
  Vec3d parts[kTriangleParts][3];
  triangle_parts(c, parts);
  // The parts tile the triangle: equal areas that sum to the whole, each facing front.
  const double area = 0.5 * OpenMesh::cross(c[1] - c[0], c[2] - c[0]).norm();
  for (const auto& p : parts) {
    const Vec3d twice = OpenMesh::cross(p[1] - p[0], p[2] - p[0]);
    EXPECT_NEAR(0.5 * twice.norm(), area / kTriangleParts, 1e-12);
    EXPECT_GT(OpenMesh::dot(twice, front), 0);
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::array<std::array<double, kTriangleParts>, 3> weights;
  for (int s = 0; s < kTriangleParts; ++s) {
    weights[0][s] = 1;
    weights[1][s] = 1 + 0.5 * u(rng);
    weights[2][s] = 1 + 1.5 * u(rng);  // some below 0
  }
  int clipped = 0;
  const std::vector<ProbePoint> points = points_around_triangle(c, clipped);
  for (const auto& [x, n] : points) {
    for (const auto& w : weights) {
      double expected = 0;
      for (int s = 0; s < kTriangleParts; ++s) expected += w[s] * point_to_polygon(x, n, parts[s], 3, front);
      EXPECT_NEAR(point_to_parted_triangle(x, n, c, w.data(), front), expected, 1e-12 * (1 + std::abs(expected)))
          << "x " << x << " n " << n;
    }
    // Equal weights: the whole triangle.
    EXPECT_NEAR(point_to_parted_triangle(x, n, c, weights[0].data(), front), point_to_polygon(x, n, c, 3, front),
                1e-12);
  }
  EXPECT_GT(static_cast<int>(points.size()) - clipped, 300);  // both paths were taken
  EXPECT_GT(clipped, 300);
  // Behind the triangle: nothing.
  EXPECT_EQ(point_to_parted_triangle(Vec3d(0.5, 0.5, -1), Vec3d(0, 0, 1), c, weights[1].data(), front), 0.0);
}

}  // namespace
}  // namespace dynrad::rad
