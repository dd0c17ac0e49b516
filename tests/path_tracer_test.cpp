// The box path tracer (tests/reference), the independent reference for the physics
// tests, against closed forms: the furnace, point-to-rectangle form factors and the
// unit-square facts (Cohen & Wallace 1993), energy balance, shadows of solid boxes;
// reproducibility; and the committed globillum room reference files.
#include "reference/box_tracer.h"
#include "reference/globillum_room.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <tuple>

namespace dynrad_test::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;

TraceOptions to_relative_error(double target, std::uint64_t seed = 1) {
  TraceOptions options;
  options.target_relative_error = target;
  options.seed = seed;
  return options;
}

// |a - b| in combined standard errors.
double sigmas_apart(const Estimate& a, const Estimate& b) {
  return std::abs(a.value - b.value) / std::hypot(a.std_error, b.std_error);
}

// Form factor from a differential area to a parallel rectangle a x b at distance c
// whose corner lies on the area's normal (Cohen & Wallace 1993, §4.6).
double corner_rectangle(double a, double b, double c) {
  const double x = a / c, y = b / c;
  return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
         (2 * kPi);
}

// Form factor from (px, py) to the parallel rectangle [x0, x1] x [y0, y1] at distance
// c: four corner rectangles, signed.
double parallel_rectangle(double px, double py, double c, double x0, double x1, double y0, double y1) {
  auto corner = [c](double dx, double dy) {
    return std::copysign(1.0, dx) * std::copysign(1.0, dy) * corner_rectangle(std::abs(dx), std::abs(dy), c);
  };
  return corner(x1 - px, y1 - py) - corner(x0 - px, y1 - py) - corner(x1 - px, y0 - py) + corner(x0 - px, y0 - py);
}

// Every face of every box emits `exitance` and reflects `rho`.
void make_all_faces_emit(BoxScene& scene, double exitance, double rho) {
  for (int box = 0; box < static_cast<int>(scene.boxes().size()); ++box)
    for (int f = 0; f < 6; ++f) scene.add_emitter(box, static_cast<Face>(f), exitance, rho);
}

// A room with a box floating in it and a table block on the floor.
BoxScene furnished_room(double rho) {
  BoxScene scene;
  scene.add_room({0, 0, 0}, {3, 2, 2.5}, Reflectances::uniform(rho));
  scene.add_solid({1, 0.5, 0.8}, {1.6, 1.2, 1.3}, Reflectances::uniform(rho));
  scene.add_solid({2, 1.2, 0}, {2.8, 1.9, 0.7}, Reflectances::uniform(rho));
  return scene;
}

TEST(BoxTracer, FurnaceRadiosityIsEmissionOverOneMinusReflectance) {
  const double e = 1.0, rho = 0.5, expected = e / (1 - rho);
  BoxScene scene = furnished_room(rho);
  make_all_faces_emit(scene, e, rho);
  const SurfacePoint points[] = {
      {{1.5, 1, 0}, {0, 0, 1}},       // floor, under the floating box
      {{0, 0.02, 2.45}, {1, 0, 0}},   // wall, next to two edges
      {{2.9, 1.9, 2.5}, {0, 0, -1}},  // ceiling corner
      {{1.3, 0.5, 1}, {0, -1, 0}},    // floating box's side
      {{2.4, 1.5, 0.7}, {0, 0, 1}},   // table top
      {{1.3, 0.9, 0.8}, {0, 0, -1}},  // floating box's bottom
  };
  for (const SurfacePoint& p : points) {
    const Estimate b = radiosity(scene, p.point, p.normal, to_relative_error(5e-4));
    EXPECT_LE(std::abs(b.value - expected), 3 * b.std_error) << b.value << " +- " << b.std_error;
    EXPECT_LE(std::abs(b.value - expected), 2e-3 * expected) << b.value << " +- " << b.std_error;
    EXPECT_GT(b.samples, 0);
  }
}

// In a closed room whose every face emits E, light arrives from every direction with
// radiance E / pi: direct irradiance is exactly E at any point and for any normal,
// however solids hide parts of the faces, which tests the horizon and the shadows.
TEST(BoxTracer, DirectLightInAGlowingFurnishedRoomIsExactlyTheExitance) {
  BoxScene scene = furnished_room(0);
  make_all_faces_emit(scene, 2.0, 0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  int tested = 0;
  while (tested < 300) {
    const Vec3 p{3 * unit(rng), 2 * unit(rng), 2.5 * unit(rng)};
    const bool in_a_solid = (p.x > 1 && p.x < 1.6 && p.y > 0.5 && p.y < 1.2 && p.z > 0.8 && p.z < 1.3) ||
                            (p.x > 2 && p.x < 2.8 && p.y > 1.2 && p.y < 1.9 && p.z < 0.7);
    if (in_a_solid) continue;
    const Vec3 n{unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5};
    EXPECT_NEAR(direct_irradiance(scene, p, n), 2.0, 1e-9) << p.x << " " << p.y << " " << p.z;
    ++tested;
  }
  // On the surfaces too, next to the solids.
  EXPECT_NEAR(direct_irradiance(scene, {1.7, 0.8, 0}, {0, 0, 1}), 2.0, 1e-9);
  EXPECT_NEAR(direct_irradiance(scene, {2.9, 1.5, 0.3}, {-1, 0, 0}), 2.0, 1e-9);
  EXPECT_NEAR(direct_irradiance(scene, {2.4, 1.9, 0.3}, {0, 1, 0}), 2.0, 1e-9);
}

TEST(BoxTracer, DirectLightUnderARectangleIsTheClosedForm) {
  // All reflectances 0: irradiance is direct light only, exact.
  BoxScene scene;
  const int room = scene.add_room({-3, -2, 0}, {4, 5, 1.7}, Reflectances::uniform(0));
  scene.add_emitter(room, Face::plus_z, {0.2, 0.5, 1.7}, {1.4, 2.5, 1.7}, 5.0);
  for (const Vec3 p : {Vec3{0.8, 1.5, 0}, Vec3{0.3, 0.6, 0}, Vec3{-1, 3, 0}, Vec3{3.5, -1.5, 0.9}}) {
    const double f = parallel_rectangle(p.x, p.y, 1.7 - p.z, 0.2, 1.4, 0.5, 2.5);
    EXPECT_NEAR(direct_irradiance(scene, p, {0, 0, 1}), 5.0 * f, 1e-12) << p.x << " " << p.y;
    const Estimate h = irradiance(scene, p, {0, 0, 1});
    EXPECT_NEAR(h.value, 5.0 * f, 1e-12);
    EXPECT_EQ(h.std_error, 0.0);
  }
}

// The area mean of point irradiance over a receiving unit square, divided by the
// exitance, is the square-to-square form factor.
double mean_over_unit_floor_square(const BoxScene& scene, int n) {
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sum += direct_irradiance(scene, {(i + 0.5) / n, (j + 0.5) / n, 0}, {0, 0, 1});
  return sum / (n * n);
}

TEST(BoxTracer, UnitSquaresExchangeTheirTabulatedFormFactors) {
  BoxScene parallel;
  const int room = parallel.add_room({-1, -1, 0}, {2, 2, 1}, Reflectances::uniform(0));
  parallel.add_emitter(room, Face::plus_z, {0, 0, 1}, {1, 1, 1}, 1.0);
  EXPECT_NEAR(mean_over_unit_floor_square(parallel, 64), 0.1998, 1e-4);

  BoxScene perpendicular;  // a unit square on the wall x = 0, above the floor's
  const int box = perpendicular.add_room({0, -1, 0}, {2, 2, 2}, Reflectances::uniform(0));
  perpendicular.add_emitter(box, Face::minus_x, {0, 0, 0}, {0, 1, 1}, 1.0);
  EXPECT_NEAR(mean_over_unit_floor_square(perpendicular, 256), 0.20004, 2e-4);
}

TEST(BoxTracer, EnergyBalanceOfAClosedRoom) {
  // One emitter, every surface (the emitter too) reflecting rho: the power leaving
  // all surfaces, sum of B A, is E A_emitter / (1 - rho); the direct light they
  // receive, sum of H_direct A, is E A_emitter.
  const double rho = 0.5, e = 3.0;
  const Vec3 lamp_lo{0.5, 0.6, 2.5}, lamp_hi{1.5, 1.4, 2.5};
  BoxScene scene = furnished_room(rho);
  scene.add_emitter(0, Face::plus_z, lamp_lo, lamp_hi, e, rho);
  const double lamp_power = e * (lamp_hi.x - lamp_lo.x) * (lamp_hi.y - lamp_lo.y);

  // A jittered k x k grid of points on every face of every box (hidden ones too, where
  // B = 0), a few paths at each.
  const int k = 24;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<SurfacePoint> points;
  std::vector<double> areas;  // of each face
  for (const BoxScene::Box& box : scene.boxes())
    for (int f = 0; f < 6; ++f) {
      const int axis = f / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
      const bool plus = f % 2 == 1;
      Vec3 normal;
      normal[axis] = (plus != box.room) ? 1 : -1;
      areas.push_back((box.hi[u] - box.lo[u]) * (box.hi[v] - box.lo[v]));
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
          Vec3 p;
          p[axis] = plus ? box.hi[axis] : box.lo[axis];
          p[u] = box.lo[u] + (box.hi[u] - box.lo[u]) * (i + unit(rng)) / k;
          p[v] = box.lo[v] + (box.hi[v] - box.lo[v]) * (j + unit(rng)) / k;
          points.push_back({p, normal});
        }
    }
  TraceOptions options;
  options.paths_per_replicate = 32;
  options.samples = 64;
  const std::vector<Estimate> b = radiosity(scene, points, options);

  // Per face, area times the mean over its points of the reflected part of B (the
  // emitted part, a step at the lamp's edge, is known: lamp_power), and of H_direct.
  // The variance as if the points were independent (stratification makes it larger).
  double reflected = 0, variance = 0, direct = 0;
  for (std::size_t face = 0; face < areas.size(); ++face) {
    std::vector<double> values;
    for (int i = 0; i < k * k; ++i) {
      const SurfacePoint& p = points[face * k * k + i];
      const bool on_lamp = p.normal.z == -1 && p.point.z == lamp_hi.z && p.point.x > lamp_lo.x &&
                           p.point.x < lamp_hi.x && p.point.y > lamp_lo.y && p.point.y < lamp_hi.y;
      values.push_back(b[face * k * k + i].value - (on_lamp ? e : 0));
      direct += areas[face] * direct_irradiance(scene, p.point, p.normal) / (k * k);
    }
    double mean = 0, spread = 0;
    for (double value : values) mean += value / (k * k);
    for (double value : values) spread += (value - mean) * (value - mean) / (k * k - 1);
    reflected += areas[face] * mean;
    variance += areas[face] * areas[face] * spread / (k * k);
  }
  const double total = lamp_power + reflected, expected = lamp_power / (1 - rho);
  EXPECT_LE(std::abs(total - expected), 3 * std::sqrt(variance)) << total << " +- " << std::sqrt(variance);
  EXPECT_NEAR(total, expected, 5e-3 * expected);
  EXPECT_NEAR(direct, lamp_power, 2e-3 * lamp_power);
}

// A thin solid plate between a ceiling lamp and the floor: nothing of the lamp is
// seen in its umbra, and in its penumbra exactly the strip beyond the shadow of the
// plate's edge (a rectangle: closed form).
TEST(BoxTracer, SolidPlateCastsAnExactShadow) {
  const double ceiling = 3, plate_bottom = 2, plate_top = 2.05, edge = 2.0;  // plate spans x < edge
  BoxScene scene;
  const int room = scene.add_room({0, 0, 0}, {4, 4, ceiling}, Reflectances::walls_floor_ceiling(0.5, 0.3, 0.7));
  scene.add_emitter(room, Face::plus_z, {1.5, 1.5, ceiling}, {2.5, 2.5, ceiling}, 10.0);
  scene.add_solid({0.2, 0, plate_bottom}, {edge, 4, plate_top}, Reflectances::uniform(0.5));

  const Vec3 up{0, 0, 1};
  EXPECT_EQ(direct_irradiance(scene, {1.0, 2.0, 0}, up), 0.0);    // umbra
  EXPECT_EQ(direct_irradiance(scene, {1.5, 2.0, 1.9}, up), 0.0);  // right under the plate
  const Estimate umbra = radiosity(scene, {1.0, 2.0, 0}, up, to_relative_error(5e-3));
  EXPECT_GT(umbra.value, 0.0);  // lit by the walls and ceiling
  for (const double px : {1.2, 1.6, 1.9, 2.1, 2.4}) {
    // A ray from (px, 0) to (X, ceiling) clears the plate iff it passes the plate's
    // edge at the bottom (rays going towards +x) or at the top (towards -x).
    const double shadow_end = px + (edge - px) * ceiling / (px < edge ? plate_bottom : plate_top);
    const double visible =
        shadow_end < 2.5 ? parallel_rectangle(px, 2.0, ceiling, std::max(1.5, shadow_end), 2.5, 1.5, 2.5) : 0.0;
    EXPECT_NEAR(direct_irradiance(scene, {px, 2.0, 0}, up), 10.0 * visible, 1e-12) << px;
  }
  // Beyond the plate: the whole lamp.
  EXPECT_NEAR(direct_irradiance(scene, {3.5, 2.0, 0}, up),
              10.0 * parallel_rectangle(3.5, 2.0, ceiling, 1.5, 2.5, 1.5, 2.5), 1e-12);
}

TEST(BoxTracer, SameSeedSameAnswerOnAnyNumberOfThreads) {
  const BoxScene scene = globillum_room(true);
  const Vec3 p{2.25, 4.25, 0}, up{0, 0, 1};
  TraceOptions options = to_relative_error(5e-3, 42);
  options.threads = 1;
  const Estimate one = radiosity(scene, p, up, options);
  for (const int threads : {1, 2, 3}) {
    options.threads = threads;
    const Estimate again = radiosity(scene, p, up, options);
    EXPECT_EQ(again.value, one.value) << threads << " threads";
    EXPECT_EQ(again.std_error, one.std_error);
    EXPECT_EQ(again.samples, one.samples);
  }
  const std::vector<Estimate> batch = radiosity(scene, {{p, up}, {{7.75, 1.25, 3}, {0, 0, -1}}}, options);
  EXPECT_EQ(batch[0].value, one.value);

  options.seed = 43;
  const Estimate other = radiosity(scene, p, up, options);
  EXPECT_NE(other.value, one.value);
  EXPECT_LT(sigmas_apart(other, one), 4);
}

TEST(BoxTracer, ReachesTheTargetError) {
  const BoxScene scene = globillum_room(false);
  const Estimate b = radiosity(scene, {0.25, 0.25, 0}, {0, 0, 1}, to_relative_error(2e-3));
  EXPECT_LE(b.std_error, 2e-3 * b.value);
  EXPECT_GT(b.std_error, 0.0);
  // The source itself, and its corner (the ceiling's).
  const Estimate source = radiosity(scene, {5, 3, 3}, {0, 0, -1});
  EXPECT_EQ(source.value, 31.416);
  EXPECT_EQ(source.samples, 0);
  EXPECT_LT(radiosity(scene, {4.75, 2.75, 3}, {0, 0, -1}, to_relative_error(1e-2)).value, 1.0);
}

TEST(BoxTracer, RejectsBadScenesAndPoints) {
  BoxScene scene;
  EXPECT_THROW(scene.add_room({0, 0, 0}, {1, 0, 1}, Reflectances::uniform(0.5)), std::invalid_argument);
  EXPECT_THROW(scene.add_room({0, 0, 0}, {1, 1, 1}, Reflectances::uniform(1.0)), std::invalid_argument);
  const int room = scene.add_room({0, 0, 0}, {1, 1, 1}, Reflectances::uniform(0.5));
  EXPECT_THROW(scene.add_emitter(room, Face::plus_z, {0, 0, 0.9}, {1, 1, 0.9}, 1), std::invalid_argument);
  EXPECT_THROW(scene.add_emitter(room, Face::plus_z, {0, 0, 1}, {2, 1, 1}, 1), std::invalid_argument);
  EXPECT_THROW(scene.add_emitter(room + 1, Face::plus_z, 1), std::invalid_argument);
  scene.add_emitter(room, Face::plus_z, {0, 0, 1}, {0.5, 0.5, 1}, 1);
  EXPECT_THROW(scene.add_emitter(room, Face::plus_z, {0.4, 0.4, 1}, {0.6, 0.6, 1}, 1), std::invalid_argument);
  EXPECT_THROW(radiosity(scene, {0.5, 0.5, 0.5}, {0, 0, 1}), std::invalid_argument);  // mid-air
  EXPECT_THROW(radiosity(scene, {0.5, 0.5, 0}, {0, 0, -1}), std::invalid_argument);   // the floor's back
}

// ---------------------------------------------------------------------------------
// The committed reference files (written by box_reference).

struct ReferenceLine {
  std::string surface;
  Vec3 point;
  Estimate b;
};

std::vector<ReferenceLine> read_reference(const std::string& name) {
  std::ifstream in(std::string(DYNRAD_TEST_DATA_DIR) + "/" + name);
  EXPECT_TRUE(in) << name;
  std::vector<ReferenceLine> lines;
  for (std::string text; std::getline(in, text);) {
    if (text.empty() || text[0] == '#') continue;
    std::istringstream fields(text);
    ReferenceLine line;
    fields >> line.surface >> line.point.x >> line.point.y >> line.point.z >> line.b.value >> line.b.std_error;
    EXPECT_TRUE(fields) << name << ": " << text;
    lines.push_back(line);
  }
  return lines;
}

class GlobillumReference : public testing::TestWithParam<bool> {
 protected:
  std::string file() const {
    return GetParam() ? "globillum_room_obstructed_reference.txt" : "globillum_room_reference.txt";
  }
};

// The file has every comparison point once, each to 0.1%.
TEST_P(GlobillumReference, HasEveryPointToATenthOfAPercent) {
  const std::vector<ReferenceLine> lines = read_reference(file());
  const std::vector<ReferencePoint> points = globillum_points();
  ASSERT_EQ(lines.size(), points.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].surface, points[i].surface);
    EXPECT_EQ(lines[i].point.x, points[i].at.point.x);
    EXPECT_EQ(lines[i].point.y, points[i].at.point.y);
    EXPECT_EQ(lines[i].point.z, points[i].at.point.z);
    EXPECT_LE(lines[i].b.std_error, 1.01e-3 * lines[i].b.value) << i;
  }
}

// Points a half turn apart about the room's vertical axis are independent estimates
// of the same radiosity: their differences in combined standard errors must look like
// draws of a unit normal (so the stated errors are honest).
TEST_P(GlobillumReference, HalfTurnSymmetricPointsAgreeWithinTheirErrors) {
  const std::vector<ReferenceLine> lines = read_reference(file());
  std::map<std::tuple<std::string, double, double>, Estimate> by_point;
  for (const ReferenceLine& line : lines) by_point[{line.surface, line.point.x, line.point.y}] = line.b;
  double sum_of_squares = 0, worst = 0;
  int pairs = 0;
  for (const ReferenceLine& line : lines) {
    if (line.point.x > 5) continue;  // each pair once
    const Estimate& twin = by_point.at({line.surface, 10 - line.point.x, 6 - line.point.y});
    const double z = sigmas_apart(line.b, twin);
    sum_of_squares += z * z;
    worst = std::max(worst, z);
    ++pairs;
  }
  ASSERT_EQ(pairs, 240);
  EXPECT_GT(sum_of_squares / pairs, 0.65);  // 1 +- 0.09 for honest errors
  EXPECT_LT(sum_of_squares / pairs, 1.35);
  EXPECT_LT(worst, 4.5);
}

// The file comes from the tracer: a few of its points traced again, with another seed
// and fewer paths, agree within 4 combined standard errors.
TEST_P(GlobillumReference, PointsTracedAgainAgree) {
  const std::vector<ReferenceLine> lines = read_reference(file());
  ASSERT_EQ(lines.size(), 480u);
  const BoxScene scene = globillum_room(GetParam());
  for (const std::size_t i : {0u, 57u, 130u, 251u, 369u, 454u}) {
    const Vec3 normal{0, 0, lines[i].surface == "floor" ? 1.0 : -1.0};
    const Estimate again = radiosity(scene, lines[i].point, normal, to_relative_error(3e-3, 12345));
    EXPECT_LT(sigmas_apart(again, lines[i].b), 4)
        << lines[i].surface << " " << lines[i].point.x << " " << lines[i].point.y << ": " << again.value << " +- "
        << again.std_error << " vs " << lines[i].b.value << " +- " << lines[i].b.std_error;
  }
}

INSTANTIATE_TEST_SUITE_P(BoxTracer, GlobillumReference, testing::Values(false, true),
                         [](const testing::TestParamInfo<bool>& room) { return room.param ? "obstructed" : "plain"; });

}  // namespace
}  // namespace dynrad_test::reference
