// Light on models built as architects' models are: a room whose floor slab runs under
// its walls lights as the same room modelled cleanly, a box standing on a floor as the
// floor cut around it, for every method; hidden parts take no light.
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "radiosity/analysis/probe.h"
#include "radiosity/pipeline/pipeline.h"
#include "radiosity/solver/solver.h"
#include "scene_builder.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace dynrad::rad {
namespace {

using test::SceneBuilder;

constexpr double kFloor = 0.3;
constexpr double kX = 4, kY = 3, kH = 2.5;  // the room's inside

struct Materials {
  std::uint32_t floor, plaster, ceiling, lamp, wood;
};

Materials materials(SceneBuilder& b) {
  return {b.material("floor", kFloor), b.material("plaster", 0.6), b.material("ceiling", 0.8),
          b.material("lamp", 0.0, 100), b.material("wood", 0.4)};
}

// A 0.6 m square lamp hanging 5 cm under the ceiling, facing down.
void add_lamp(SceneBuilder& b, const Materials& m) {
  b.group("lamp");
  b.rectangle(kX / 2 - 0.3, kY / 2 - 0.3, kX / 2 + 0.3, kY / 2 + 0.3, kH - 0.05, -1, m.lamp);
}

// The room as six faces facing in: the floor ends at the walls.
SceneBuilder clean_room() {
  SceneBuilder b;
  const Materials m = materials(b);
  b.group("floor");
  b.rectangle(0, 0, kX, kY, 0, +1, m.floor);
  b.group("ceiling");
  b.rectangle(0, 0, kX, kY, kH, -1, m.ceiling);
  b.group("walls");
  b.box({0, 0, 0}, {kX, kY, kH}, m.plaster, SceneBuilder::inward, {false, false, false, false, true, true});
  add_lamp(b, m);
  return b;
}

// The same room as an export gives it: slabs 0.25 thick running 0.3 m under and over
// walls 0.3 thick that stand between them, every element a closed solid.
SceneBuilder slab_room() {
  SceneBuilder b;
  const Materials m = materials(b);
  const double t = 0.3;
  b.group("floor_slab");
  b.box({-t, -t, -0.25}, {kX + t, kY + t, 0}, m.floor);
  b.group("ceiling_slab");
  b.box({-t, -t, kH}, {kX + t, kY + t, kH + 0.25}, m.ceiling);
  b.group("south");
  b.box({-t, -t, 0}, {kX + t, 0, kH}, m.plaster);
  b.group("north");
  b.box({-t, kY, 0}, {kX + t, kY + t, kH}, m.plaster);
  b.group("west");
  b.box({-t, 0, 0}, {0, kY, kH}, m.plaster);
  b.group("east");
  b.box({kX, 0, 0}, {kX + t, kY, kH}, m.plaster);
  add_lamp(b, m);
  return b;
}

struct Lit {
  LoadedScene scene;
  std::unique_ptr<ElementHierarchy> hierarchy;
  std::unique_ptr<Solver> solver;
  Solver::Output output;
  SolveReport report;
};

Lit solve(const PolygonSoup& soup, Method method, bool imprint = true, double patch = 0.5, int level = 2,
          double converge = 0.01) {
  Lit lit;
  CleanupOptions cleanup;
  cleanup.imprint = imprint;
  SimplifyOptions simplify;
  simplify.enabled = true;  // as `dynrad solve` does
  lit.scene = load_soup(soup, "test", cleanup, simplify);
  make_patches(*lit.scene.mesh, patch);
  lit.hierarchy = std::make_unique<ElementHierarchy>(*lit.scene.mesh);
  RefineSettings refine;
  refine.method = method;
  refine.max_level = level;
  SolveOptions options;
  options.converge = converge;
  lit.solver = std::make_unique<Solver>(*lit.scene.mesh, *lit.hierarchy, options, refine);
  lit.report = lit.solver->run();
  lit.output = lit.solver->output();
  return lit;
}

// Irradiance on the floor (radiosity over reflectance) at a point, if the floor is there.
std::optional<double> floor_irradiance(const Lit& lit, double x, double y) {
  const auto b = probe(*lit.scene.mesh, lit.output.split, lit.output.radiosity, {x, y, 0}, {0, 0, 1});
  if (!b) return std::nullopt;
  return b->r / kFloor;
}

// Points 5, 10 and 15 cm from each wall of the room, every 0.25 m along it.
std::vector<std::array<double, 2>> near_the_walls() {
  std::vector<std::array<double, 2>> points;
  for (double d : {0.05, 0.10, 0.15}) {
    for (double x = 0.25; x < kX - 0.2; x += 0.25) {
      points.push_back({x, d});
      points.push_back({x, kY - d});
    }
    for (double y = 0.25; y < kY - 0.2; y += 0.25) {
      points.push_back({d, y});
      points.push_back({kX - d, y});
    }
  }
  return points;
}

// The largest relative difference of floor irradiance between two lit models at the
// points, which must be on both floors.
double largest_difference(const Lit& a, const Lit& b, const std::vector<std::array<double, 2>>& points) {
  double worst = 0;
  for (const auto& p : points) {
    const auto ea = floor_irradiance(a, p[0], p[1]), eb = floor_irradiance(b, p[0], p[1]);
    EXPECT_TRUE(ea && eb) << "no floor at (" << p[0] << ", " << p[1] << ")";
    if (!ea || !eb) continue;
    worst = std::max(worst, std::abs(*ea - *eb) / *eb);
  }
  return worst;
}

class Junctions : public ::testing::TestWithParam<Method> {};
INSTANTIATE_TEST_SUITE_P(Methods, Junctions, ::testing::Values(Method::progressive, Method::adaptive, Method::dynamic),
                         [](const auto& param_info) { return std::string(method_name(param_info.param)); });

TEST_P(Junctions, FloorByTheWallsIsLitAsIfItEndedThere) {
  const Lit clean = solve(clean_room().soup(), GetParam());
  const Lit slab = solve(slab_room().soup(), GetParam());
  const auto points = near_the_walls();
  EXPECT_LT(largest_difference(slab, clean, points), 0.01);
  // The fringe this removes: without imprinting, the floor's corners under the walls
  // are dark and darken the floor beside them.
  if (GetParam() == Method::progressive) {
    const Lit raw = solve(slab_room().soup(), GetParam(), /*imprint=*/false);
    EXPECT_GT(largest_difference(raw, clean, points), 0.05);
  }
}

TEST_P(Junctions, HiddenPartsTakeNoLightAndTheBalanceHolds) {
  // The balance holds after every shot: a partial solve shows it as well.
  const Lit slab = solve(slab_room().soup(), GetParam(), true, 0.5, 2, 0.1);
  const EnergyBalance& e = slab.report.energy;
  const double emitted = e.emitted.r;
  EXPECT_NEAR(e.absorbed.r + e.escaped.r + e.unshot.r, emitted, 1e-9 * emitted);
  EXPECT_EQ(e.escaped.r, 0.0);  // nothing leaks out through the junctions
  // What is left is the room's inside (and the lamp) and the outsides of the solids:
  // the hidden parts are gone.
  const double inside = 2 * kX * kY + 2 * (kX + kY) * kH + 0.36;
  const double wx = kX + 0.6, wy = kY + 0.6;  // the walls' outer outline
  const double outside = 2 * (wx + wy) * (kH + 0.5) + 2 * wx * wy;
  EXPECT_NEAR(slab.scene.mesh->total_area(), inside + outside, 1e-9 * (inside + outside));
  // No light outside the room: every vertex off the room's inside is dark.
  const TriMesh& mesh = slab.scene.mesh->mesh();
  for (std::size_t v = 0; v < slab.output.split.size(); ++v) {
    const Vec3d p = mesh.point(slab.output.split.source[v]);
    const bool outside_room =
        p[0] < -1e-9 || p[0] > kX + 1e-9 || p[1] < -1e-9 || p[1] > kY + 1e-9 || p[2] < -1e-9 || p[2] > kH + 1e-9;
    if (outside_room) {
      EXPECT_EQ(slab.output.radiosity[v].r, 0.0) << p;
    }
  }
}

// A 2 x 2 x 2 m room with a closed box 0.8 x 0.8 x 0.6 standing in its middle, against
// the same room with the floor cut around the box's footprint and the box without a
// bottom.
SceneBuilder room_with_box(bool cut_floor) {
  SceneBuilder b;
  const Materials m = materials(b);
  const double s = 2, lo = 0.6, hi = 1.4;
  b.group("floor");
  if (cut_floor) {
    b.rectangle(0, 0, s, lo, 0, +1, m.floor);
    b.rectangle(0, hi, s, s, 0, +1, m.floor);
    b.rectangle(0, lo, lo, hi, 0, +1, m.floor);
    b.rectangle(hi, lo, s, hi, 0, +1, m.floor);
  } else {
    b.rectangle(0, 0, s, s, 0, +1, m.floor);
  }
  b.group("ceiling");
  b.rectangle(0, 0, s, s, s, -1, m.ceiling);
  b.group("walls");
  b.box({0, 0, 0}, {s, s, s}, m.plaster, SceneBuilder::inward, {false, false, false, false, true, true});
  b.group("lamp");
  b.rectangle(0.8, 0.8, 1.2, 1.2, s - 0.05, -1, m.lamp);
  b.group("box");
  b.box({lo, lo, 0}, {hi, hi, 0.6}, m.wood, SceneBuilder::outward, {false, false, false, false, cut_floor, false});
  return b;
}

// The mean irradiance over the band 15 cm wide around the box's foot, from the lit
// mesh (a grid of 1 cm). Near the foot the light falls steeply: at one point, two
// meshes of the same surfaces differ by their interpolation (up to 10% at 0.25 m
// patches); over the band they agree, and the dark fringe of floor left under the
// box shows.
double band_mean(const Lit& lit) {
  double sum = 0;
  int n = 0;
  for (double x = 0.455; x < 1.55; x += 0.01)
    for (double y = 0.455; y < 1.55; y += 0.01) {
      if (x > 0.6 && x < 1.4 && y > 0.6 && y < 1.4) continue;
      const auto e = floor_irradiance(lit, x, y);
      EXPECT_TRUE(e) << "no floor at (" << x << ", " << y << ")";
      if (!e) continue;
      sum += *e;
      ++n;
    }
  return sum / n;
}

struct BoxCase {
  Method method;
  double patch;
  int level;
};

class BoxOnTheFloor : public ::testing::TestWithParam<BoxCase> {};
// Adaptive subdivision only: the band's mean converges slowly with the mesh, and the
// other methods need meshes too fine for a test to agree to 1% between two meshings of
// the same surfaces (progressive: 1.3% at 0.25 m patches, 0.3% at 0.125 m in 70 s;
// dynamic with its defaults scatters by 1.5-3%).
INSTANTIATE_TEST_SUITE_P(Methods, BoxOnTheFloor, ::testing::Values(BoxCase{Method::adaptive, 0.5, 2}),
                         [](const auto& param_info) { return std::string(method_name(param_info.param.method)); });

TEST_P(BoxOnTheFloor, BesideItTheFloorIsLitAsBesideOneCutIn) {
  const BoxCase c = GetParam();
  const Lit cut = solve(room_with_box(true).soup(), c.method, true, c.patch, c.level);
  const Lit standing = solve(room_with_box(false).soup(), c.method, true, c.patch, c.level);
  const double reference = band_mean(cut);
  EXPECT_NEAR(band_mean(standing), reference, 0.01 * reference);
  // No floor under the box.
  for (double x = 0.65; x < 1.4; x += 0.1)
    for (double y = 0.65; y < 1.4; y += 0.1) EXPECT_FALSE(floor_irradiance(standing, x, y)) << x << ", " << y;
  // Without imprinting the floor under the box stays, dark, and darkens the band.
  const Lit raw = solve(room_with_box(false).soup(), c.method, false, c.patch, c.level);
  EXPECT_LT(band_mean(raw), 0.95 * reference);
}

}  // namespace
}  // namespace dynrad::rad

namespace dynrad::rad {
namespace {

// The generated storey (samples/make_storey.py) lights: every room's floor is lit by its
// lamp, light leaves through the windows, the balance holds.
TEST(Storey, EveryRoomIsLitAndTheBalanceHolds) {
  // By the pipeline `dynrad solve --converge 0.05` calls.
  rad::SceneRequest request;
  request.path = test::sample("storey.obj");
  request.simplify.enabled = true;
  request.settings.converge = 0.05;
  rad::PreparedScene prepared = rad::prepare_scene(request);
  const rad::SolvedScene solved = rad::solve_scene(prepared);
  const SceneMesh& mesh = *prepared.scene.mesh;
  const EnergyBalance& e = solved.report.energy;
  EXPECT_NEAR(e.absorbed.r + e.escaped.r + e.unshot.r, e.emitted.r, 1e-9 * e.emitted.r);
  EXPECT_GT(e.escaped.r, 0.0);
  const Solver::Output& out = solved.output;
  for (const Rgb& b : out.radiosity) ASSERT_TRUE(b.is_finite());
  // Room centres (under the lamps) and a point by a wall of each room, on the floor.
  for (const auto& p : std::vector<std::array<double, 2>>{
           {3.3, 2.5}, {9.2, 2.5}, {3.0, 6.9}, {9.0, 6.9}, {0.25, 2.5}, {11.75, 1.0}, {0.25, 6.0}, {11.75, 6.0}}) {
    const auto b = probe(mesh, out.split, out.radiosity, {p[0], p[1], 0}, {0, 0, 1});
    ASSERT_TRUE(b) << "no floor at (" << p[0] << ", " << p[1] << ")";
    EXPECT_GT(b->r, 0.0) << "(" << p[0] << ", " << p[1] << ")";
  }
}

}  // namespace
}  // namespace dynrad::rad
