// Calculation grids (radiosity/analysis/grid.h) against closed forms and hand-computed figures.
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "radiosity/analysis/grid.h"
#include "radiosity/analysis/grid_scene.h"
#include "radiosity/analysis/probe.h"
#include "radiosity/solver/settings.h"
#include "radiosity/solver/solver.h"
#include "scene_builder.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace dynrad {
namespace {

using test::SceneBuilder;

struct Solved {
  LoadedScene scene;
  std::unique_ptr<ElementHierarchy> hierarchy;
  std::unique_ptr<rad::Solver> solver;
  rad::Solver::Output output;
};

Solved solve(const SceneBuilder& b) {
  Solved s;
  s.scene = load_soup(b.soup(), "grid test");
  rad::RefineSettings refine;
  refine.method = rad::Method::dynamic;
  rad::SolveOptions options;
  options.ambient_display = true;
  const rad::AppliedSettings applied = rad::apply_settings(*s.scene.mesh, {}, refine, options);
  make_patches(*s.scene.mesh, applied.patch_size);
  s.hierarchy = std::make_unique<ElementHierarchy>(*s.scene.mesh, refinement_for_patch_size(applied.patch_size));
  s.solver = std::make_unique<rad::Solver>(*s.scene.mesh, *s.hierarchy, options, refine);
  s.solver->run();
  s.output = s.solver->output();
  return s;
}

// A 1 x 1 m panel emitting M = 100 W/m^2 downwards 3 m up, over a black floor: a grid
// facing up at 0.8 m sees the panel only, so E = M F(point -> panel) exactly; the
// grid's statistics are those of the points computed here.
TEST(Grid, EmittingPanelOverAPlaneGivesMTimesTheFormFactor) {
  SceneBuilder b;
  b.rectangle(-10, -10, 10, 10, 0, +1, b.material("black", 0.0));
  b.rectangle(-0.5, -0.5, 0.5, 0.5, 3, -1, b.material("panel", 0.0, 100.0));
  Solved s = solve(b);
  const rad::LitScene lit = rad::lit_scene(*s.scene.mesh, s.output.split, s.output.radiosity, {}, 1.0, false);
  rad::GridSpec spec;
  spec.name = "plane";
  spec.polygon = {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};
  spec.height = 0.8;
  spec.spacing = 1.0;
  const rad::GridResult r = rad::gather_grid(lit, spec);
  ASSERT_EQ(r.count, 16u);
  EXPECT_EQ(r.masked, 0u);
  double sum = 0, lo = 1e300, hi = 0;
  for (const rad::GridPointResult& p : r.points) {
    const double exact = 100 * test::parallel_rectangle(p.position[0], p.position[1], -0.5, -0.5, 0.5, 0.5, 2.2);
    EXPECT_NEAR(p.illuminance, exact, 0.005 * exact) << "at (" << p.position[0] << ", " << p.position[1] << ")";
    EXPECT_NEAR(p.position[2], 0.8, 1e-12);
    sum += exact;
    lo = std::min(lo, exact);
    hi = std::max(hi, exact);
  }
  EXPECT_NEAR(r.e_avg, sum / 16, 0.005 * sum / 16);
  EXPECT_NEAR(r.e_min, lo, 0.005 * lo);
  EXPECT_NEAR(r.e_max, hi, 0.005 * hi);
  EXPECT_NEAR(r.u0, lo / (sum / 16), 0.01 * lo / (sum / 16));
  EXPECT_NEAR(r.min_over_max, lo / hi, 0.01 * lo / hi);
}

// On a surface, the gathered illuminance is that surface's own (B - E) / rho, within
// the mesh's error and the gather's noise.
TEST(Grid, OnTheFloorItAgreesWithTheSolvedFloor) {
  SceneBuilder b;
  b.box({0, 0, 0}, {5, 4, 3}, b.material("walls", 0.6), SceneBuilder::inward);
  b.rectangle(2, 1.5, 3, 2.5, 2.999, -1, b.material("panel", 0.0, 200.0));
  Solved s = solve(b);
  const rad::LitScene lit = rad::lit_scene(*s.scene.mesh, s.output.split, s.output.radiosity, {}, 1.0, false);
  rad::GatherOptions options;
  int compared = 0;
  for (double x = 0.5; x < 5; x += 1.0)
    for (double y = 0.5; y < 4; y += 1.0) {
      const Vec3d p(x, y, 0.0);
      const auto solved = rad::probe(*s.scene.mesh, s.output.split, s.output.irradiance, p, {0, 0, 1});
      ASSERT_TRUE(solved.has_value());
      const rad::GridPointResult g = rad::gather_point(lit, p, {0, 0, 1}, options, 7 + compared);
      EXPECT_FALSE(g.masked);
      EXPECT_NEAR(g.illuminance, solved->luminance(), 0.02 * solved->luminance()) << "at (" << x << ", " << y << ")";
      ++compared;
    }
  EXPECT_EQ(compared, 20);
}

// The gather's noise: one point gathered with 16 seeds; the relative standard deviation
// of the total, in a room where most light is indirect.
TEST(Grid, GatherNoiseIsBelowOnePercent) {
  SceneBuilder b;
  b.box({0, 0, 0}, {5, 4, 3}, b.material("walls", 0.7), SceneBuilder::inward);
  b.rectangle(0.2, 0.2, 0.7, 0.7, 2.999, -1, b.material("panel", 0.0, 200.0));
  Solved s = solve(b);
  const rad::LitScene lit = rad::lit_scene(*s.scene.mesh, s.output.split, s.output.radiosity, {}, 1.0, false);
  double sum = 0, sum2 = 0, indirect = 0;
  for (int seed = 0; seed < 16; ++seed) {
    const rad::GridPointResult g = rad::gather_point(lit, {3.5, 2.5, 0.8}, {0, 0, 1}, {}, 1000 + seed);
    sum += g.illuminance;
    sum2 += g.illuminance * g.illuminance;
    indirect += g.indirect / g.illuminance / 16;
  }
  const double mean = sum / 16, sd = std::sqrt(std::max(0.0, sum2 / 16 - mean * mean));
  std::printf("gather noise: %.3f%% (indirect share %.0f%%)\n", 100 * sd / mean, 100 * indirect);
  EXPECT_GT(indirect, 0.5);
  EXPECT_LT(sd / mean, 0.01);
}

// Points inside a solid (a cupboard the work plane passes through) are masked and
// counted, the rest are not.
TEST(Grid, PointsInsideASolidAreMaskedAndCounted) {
  SceneBuilder b;
  b.box({0, 0, 0}, {6, 4, 3}, b.material("walls", 0.5), SceneBuilder::inward);
  b.rectangle(2.5, 1.5, 3.5, 2.5, 2.999, -1, b.material("panel", 0.0, 100.0));
  b.box({0.05, 0.05, 0}, {1.95, 1.95, 2}, b.material("cupboard", 0.5));  // holds grid points with x, y < 2
  Solved s = solve(b);
  const rad::LitScene lit = rad::lit_scene(*s.scene.mesh, s.output.split, s.output.radiosity, {}, 1.0, false);
  rad::GridSpec spec;
  spec.polygon = {{0, 0}, {6, 0}, {6, 4}, {0, 4}};
  spec.height = 0.8;
  spec.spacing = 0.5;
  const rad::GridResult r = rad::gather_grid(lit, spec);
  ASSERT_EQ(r.points.size(), 96u);  // 12 x 8 cells
  std::size_t expected_masked = 0;
  for (const rad::GridPointResult& p : r.points) {
    const bool inside = p.position[0] < 1.95 && p.position[1] < 1.95;
    expected_masked += inside;
    EXPECT_EQ(p.masked, inside) << "at (" << p.position[0] << ", " << p.position[1] << ")";
    if (!inside) {
      EXPECT_GT(p.illuminance, 0);
    }
  }
  EXPECT_EQ(expected_masked, 16u);
  EXPECT_EQ(r.masked, 16u);
  EXPECT_EQ(r.count, 80u);
}

// EN 12464-1's automatic spacing, cell centres and the border band.
TEST(Grid, SpacingRuleCellCentresAndBorder) {
  EXPECT_NEAR(rad::automatic_spacing(1), 0.2, 1e-12);
  EXPECT_NEAR(rad::automatic_spacing(10), 1.0, 1e-12);
  EXPECT_NEAR(rad::automatic_spacing(100), 5.0, 1e-12);
  EXPECT_NEAR(rad::automatic_spacing(1000), 10.0, 1e-12);  // at most 10 m
  rad::GridSpec spec;
  spec.polygon = {{0, 0}, {10, 0}, {10, 5}, {0, 5}};
  double spacing = 0;
  const auto all = rad::grid_points(spec, &spacing);
  EXPECT_NEAR(spacing, 1.0, 1e-12);
  ASSERT_EQ(all.size(), 50u);
  EXPECT_NEAR(all.front()[0], 0.5, 1e-12);
  EXPECT_NEAR(all.front()[1], 0.5, 1e-12);
  spec.border = 0.5;
  const auto inner = rad::grid_points(spec);
  ASSERT_EQ(inner.size(), 36u);  // 9 x 4 cells over 9 x 4 m
  for (const Vec3d& p : inner) {
    EXPECT_GE(p[0], 0.5);
    EXPECT_LE(p[0], 9.5);
    EXPECT_GE(p[1], 0.5);
    EXPECT_LE(p[1], 4.5);
  }
  // An L-shaped room: the cells whose centres lie outside it are left out.
  spec.border = 0;
  spec.polygon = {{0, 0}, {10, 0}, {10, 5}, {5, 5}, {5, 10}, {0, 10}};
  EXPECT_EQ(rad::grid_points(spec).size(), 75u);
}

// The scene file's "grids" and the command line: results per grid in JSON with the
// issue's key names, CSV per point.
TEST(Grid, SceneFileGridsAreSolvedAndWritten) {
  test::TempDir dir;
  const std::string scene = test::write_lamp_room(dir, R"([{"name": "office", "polygon": [[0, 0], [4, 0], [4, 3], [0, 3]],
    "height": 0.8, "spacing": "auto", "border": 0.5}])");
  const auto r = test::run_dynrad("solve -q '" + scene + "' -o '" + dir.path("lit.ply") + "' --report '" +
                                  dir.path("report.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto grids = nlohmann::json::parse(test::read_text(dir.path("lit_grids.json")))["grids"];
  ASSERT_EQ(grids.size(), 1u);
  const auto& g = grids[0];
  EXPECT_EQ(g["name"], "office");
  for (const char* key : {"Eavg", "Emin", "Emax", "U0", "Emin/Emax", "count"}) EXPECT_TRUE(g.contains(key)) << key;
  EXPECT_GT(g["Eavg"].get<double>(), 0);
  EXPECT_LE(g["Emin"].get<double>(), g["Eavg"].get<double>());
  EXPECT_NEAR(g["U0"].get<double>(), g["Emin"].get<double>() / g["Eavg"].get<double>(), 1e-9);
  const std::string picture = test::read_text(dir.path("lit_grid_office.png"));
  ASSERT_GT(picture.size(), 1000u);
  EXPECT_EQ(picture.substr(1, 3), "PNG");
  EXPECT_EQ(g["picture"], dir.path("lit_grid_office.png"));
  const std::string csv = test::read_text(dir.path("lit_grid_office.csv"));
  EXPECT_EQ(static_cast<int>(std::count(csv.begin(), csv.end(), '\n')), g["count"].get<int>() + 1);
  // The points nearest the foot of the source are 0.25 m from it along x and y, 1.9 m
  // below it: at least the direct 300 cos^3 / d^2 there.
  const auto report = nlohmann::json::parse(test::read_text(dir.path("report.json")));
  EXPECT_EQ(report["grids"].size(), 1u);
  EXPECT_GT(g["Emax"].get<double>(), 300 * 1.9 / std::pow(1.9 * 1.9 + 2 * 0.25 * 0.25, 1.5));
  // `dynrad grid` over the lit PLY: the scene's grids again (from the PLY's float
  // radiosity: the same figures to 0.1%), and one given on the command line.
  const auto again = test::run_dynrad("grid -q '" + dir.path("lit.ply") + "' --model '" + scene + "' -o '" +
                                      dir.path("again") + "'");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  const auto regrid = nlohmann::json::parse(test::read_text(dir.path("again_grids.json")))["grids"][0];
  for (const char* key : {"Eavg", "Emin", "Emax"})
    EXPECT_NEAR(regrid[key].get<double>(), g[key].get<double>(), 1e-3 * g[key].get<double>()) << key;
  EXPECT_EQ(regrid["count"], g["count"]);
  const auto desk = test::run_dynrad("grid -q '" + dir.path("lit.ply") + "' --model '" + scene +
                                     "' --grid 1,1,2,2 --height 0.75 --spacing 0.25 --name desk -o '" +
                                     dir.path("desk") + "'");
  ASSERT_EQ(desk.exit_code, 0) << desk.output;
  const auto d = nlohmann::json::parse(test::read_text(dir.path("desk_grids.json")))["grids"][0];
  EXPECT_EQ(d["name"], "desk");
  EXPECT_EQ(d["count"], 16);
  EXPECT_TRUE(test::file_exists(dir.path("desk_grid_desk.png")));
  // A bad grid entry is refused before any work, naming it.
  const std::string bad = dir.write("bad.json", R"({"meshes": [{"file": "room.obj"}],
    "luminaires": [{"type": "point", "intensity": 300, "position": [2, 1.5, 2.7]}],
    "grids": [{"name": "desk", "rectangle": [1, 1, 0, 2]}]})");
  const auto refused = test::run_dynrad("solve -q '" + bad + "' -o '" + dir.path("bad.ply") + "'");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.output.find("grids[0] (\"desk\").rectangle"), std::string::npos) << refused.output;
  EXPECT_FALSE(test::file_exists(dir.path("bad.ply")));
}

// A model solved with --scale (millimetres to metres) is read back by `grid` the same
// way only when told: without --model-scale the two do not span the same box, and
// `grid` refuses, naming the option, rather than gathering from the wrong emitters.
TEST(Grid, ModelReadBackAsSolveReadItOrRefused) {
  test::TempDir dir;
  dir.write("room_mm.obj",
            "mtllib room_mm.mtl\nusemtl wall\n"
            "v 0 0 0\nv 4000 0 0\nv 4000 3000 0\nv 0 3000 0\n"
            "v 0 0 2800\nv 4000 0 2800\nv 4000 3000 2800\nv 0 3000 2800\n"
            "f 1 2 3 4\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\nusemtl light\nf 5 8 7 6\n");
  dir.write("room_mm.mtl", "newmtl wall\nKd 0.6 0.6 0.6\nnewmtl light\nKd 0.5 0.5 0.5\nKe 10 10 10\n");
  const std::string model = dir.path("room_mm.obj");
  const auto r = test::run_dynrad("solve -q '" + model + "' --scale 0.001 -o '" + dir.path("lit.ply") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string grid = " --grid 1,1,2,2 --height 0.75 --spacing 0.25 --name desk -o '";
  const auto refused = test::run_dynrad("grid -q '" + dir.path("lit.ply") + "' --model '" + model + "'" + grid +
                                        dir.path("mm") + "'");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("--model-scale"), std::string::npos) << refused.output;
  EXPECT_FALSE(test::file_exists(dir.path("mm_grids.json")));
  const auto read = test::run_dynrad("grid -q '" + dir.path("lit.ply") + "' --model '" + model +
                                     "' --model-scale 0.001" + grid + dir.path("m") + "'");
  ASSERT_EQ(read.exit_code, 0) << read.output;
  const auto d = nlohmann::json::parse(test::read_text(dir.path("m_grids.json")))["grids"][0];
  EXPECT_EQ(d["count"], 16);
  EXPECT_GT(d["Eavg"].get<double>(), 0);
  // probe reads its --model the same way.
  const auto probed = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --grid 1,1,2,2,0.5,0 --model '" +
                                       model + "'");
  EXPECT_EQ(probed.exit_code, 2) << probed.output;
  EXPECT_NE(probed.output.find("--model-up and --model-scale"), std::string::npos) << probed.output;
}

}  // namespace
}  // namespace dynrad
