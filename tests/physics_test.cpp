// Physics of the progressive solver: closed-form furnace answers, energy conservation
// after every shot, no light through a wall, colour bleeding where it belongs.
#include "mesh/cleanup.h"
#include "mesh/load.h"
#include "mesh/refinement.h"
#include "radiosity/progressive.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace dynrad::rad {
namespace {

// Adds an axis-aligned box room [lo, hi] with its six faces facing inward.
// `materials[k]` for faces -x, +x, -y, +y, -z, +z (index into soup.materials).
void add_room(PolygonSoup& soup, const Vec3d& lo, const Vec3d& hi, const std::array<std::uint32_t, 6>& materials) {
  auto corner = [&](int i, int j, int k) {
    soup.points.emplace_back(i ? hi[0] : lo[0], j ? hi[1] : lo[1], k ? hi[2] : lo[2]);
    return static_cast<std::uint32_t>(soup.points.size() - 1);
  };
  const std::uint32_t c000 = corner(0, 0, 0), c100 = corner(1, 0, 0), c010 = corner(0, 1, 0), c110 = corner(1, 1, 0),
                      c001 = corner(0, 0, 1), c101 = corner(1, 0, 1), c011 = corner(0, 1, 1), c111 = corner(1, 1, 1);
  // Loops counter-clockwise seen from inside.
  const std::array<std::vector<std::uint32_t>, 6> faces = {{{c000, c010, c011, c001},   // x = lo, faces +x
                                                             {c100, c101, c111, c110},   // x = hi, faces -x
                                                             {c000, c001, c101, c100},   // y = lo, faces +y
                                                             {c010, c110, c111, c011},   // y = hi, faces -y
                                                             {c000, c100, c110, c010},   // z = lo, faces +z
                                                             {c001, c011, c111, c101}}};  // z = hi, faces -z
  for (int k = 0; k < 6; ++k) {
    soup.polygons.push_back(faces[k]);
    soup.material.push_back(materials[k]);
    soup.group.push_back(0);
    soup.origin.push_back(SourceRef{0, 0, static_cast<std::uint32_t>(soup.polygons.size() - 1)});
  }
}

PolygonSoup empty_soup(std::vector<Material> materials) {
  PolygonSoup soup;
  soup.materials = std::move(materials);
  soup.group_names.push_back("room");
  soup.files.push_back("generated");
  return soup;
}

struct Solved {
  std::unique_ptr<SceneMesh> scene;
  std::unique_ptr<ElementHierarchy> hierarchy;
  std::unique_ptr<ProgressiveSolver> solver;
};

Solved prepare(const PolygonSoup& soup, double patch_size, SolveOptions options) {
  TriangleSoup clean;
  cleanup(soup, clean);
  Solved s;
  s.scene = std::make_unique<SceneMesh>(clean);
  make_patches(*s.scene, patch_size);
  s.hierarchy = std::make_unique<ElementHierarchy>(*s.scene);
  s.solver = std::make_unique<ProgressiveSolver>(*s.scene, *s.hierarchy, options);
  return s;
}

TEST(Physics, FurnaceGivesEOverOneMinusRho) {
  // Every surface emits E = 1 and reflects rho = 0.5: B = 2 everywhere, any geometry.
  PolygonSoup soup = empty_soup({Material{"glow", Rgb(0.5), Rgb(1.0), "test", true}});
  add_room(soup, {0, 0, 0}, {2, 1, 1}, {0, 0, 0, 0, 0, 0});
  SolveOptions options;
  options.converge = 1e-5;
  Solved s = prepare(soup, 0.3, options);
  const SolveReport report = s.solver->run();
  EXPECT_EQ(report.stopped_by, "converged");
  for (const Rgb& b : s.solver->radiosity()) {
    EXPECT_NEAR(b.r, 2.0, 0.005 * 2.0);
    EXPECT_NEAR(b.b, 2.0, 0.005 * 2.0);
  }
}

TEST(Physics, ClosedRoomReflectsAllPowerUntilAbsorbed) {
  // Emission on one face only, rho = 0.6 everywhere: sum B A = sum E A / (1 - rho).
  PolygonSoup soup = empty_soup({Material{"wall", Rgb(0.6), Rgb(0.0), "test", true},
                                 Material{"lamp", Rgb(0.6), Rgb(10.0), "test", true}});
  add_room(soup, {0, 0, 0}, {3, 2, 1.5}, {0, 0, 0, 0, 0, 1});
  SolveOptions options;
  options.converge = 1e-5;
  Solved s = prepare(soup, 0.4, options);
  s.solver->run();
  // Area-weighted radiosity over faces, each face the mean of its corner nodes.
  const auto& receivers = s.solver->receivers();
  double total = 0, emitted = 0;
  for (auto f : s.scene->mesh().faces()) {
    double mean = 0;
    for (int k = 0; k < 3; ++k) mean += s.solver->radiosity()[receivers.node(f, k)].g / 3;
    total += mean * s.scene->area(f);
    emitted += s.scene->material(f).emission.g * s.scene->area(f);
  }
  EXPECT_NEAR(total, emitted / (1 - 0.6), 0.005 * emitted / (1 - 0.6));
  const EnergyBalance& e = s.solver->energy();
  EXPECT_NEAR(e.escaped.g, 0.0, 1e-12 * e.emitted.g);  // closed: nothing leaves
}

void expect_balance_every_shot(const std::string& sample, std::size_t shots, bool open) {
  LoadedScene loaded = load_scene(test::sample(sample));
  make_patches(*loaded.mesh, default_patch_size(*loaded.mesh));
  ElementHierarchy hierarchy(*loaded.mesh);
  ProgressiveSolver solver(*loaded.mesh, hierarchy, SolveOptions{});
  for (std::size_t shot = 0; shot < shots && solver.shoot_once(); ++shot) {
    const EnergyBalance& e = solver.energy();
    for (int c = 0; c < 3; ++c) {
      const double accounted = e.absorbed[c] + e.escaped[c] + e.unshot[c];
      ASSERT_NEAR(accounted, e.emitted[c], 1e-9 * e.emitted[c]) << sample << " shot " << shot << " channel " << c;
      ASSERT_GE(e.absorbed[c], 0.0);
      ASSERT_GE(e.unshot[c], 0.0);
    }
  }
  const EnergyBalance& e = solver.energy();
  if (open) {
    EXPECT_GT(e.escaped.r, 0.0) << sample;  // the Cornell box is open at the front
  } else {
    EXPECT_EQ(e.escaped.r, 0.0) << sample;
  }
}

TEST(Physics, EnergyIsConservedAfterEveryShot) {
  expect_balance_every_shot("cornell_box.obj", 200, true);
  expect_balance_every_shot("globillum_room_obstructed.obj", 200, false);
}

TEST(Physics, NoLightThroughAWallSharedByTwoRooms) {
  // Two rooms side by side sharing the wall x = 1 (zero thickness: one face each side).
  // Room A's ceiling emits; room B has no light path and must stay black.
  PolygonSoup soup = empty_soup({Material{"wall", Rgb(0.7), Rgb(0.0), "test", true},
                                 Material{"lamp", Rgb(0.7), Rgb(5.0), "test", true}});
  add_room(soup, {0, 0, 0}, {1, 1, 1}, {0, 0, 0, 0, 0, 1});
  add_room(soup, {1, 0, 0}, {2, 1, 1}, {0, 0, 0, 0, 0, 0});
  SolveOptions options;
  options.converge = 1e-3;
  Solved s = prepare(soup, 0.2, options);
  s.solver->run();
  const auto& receivers = s.solver->receivers();
  std::size_t in_b = 0, lit_a = 0;
  for (std::size_t x = 0; x < receivers.size(); ++x) {
    const Vec3d p = receivers.position[x];
    // Room B's surfaces: beyond the wall, or the wall's face looking into B.
    const bool room_b = p[0] > 1 + 1e-9 || (std::abs(p[0] - 1) < 1e-9 && receivers.normal[x][0] > 0.5);
    if (room_b) {
      ++in_b;
      EXPECT_EQ(s.solver->radiosity()[x].g, 0.0) << "leak at (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
    } else {
      lit_a += s.solver->radiosity()[x].g > 0.1;
    }
  }
  EXPECT_GT(in_b, 20u);
  EXPECT_GT(lit_a, 20u);
}

TEST(Physics, CornellFloorIsRedderNextToTheRedWall) {
  LoadedScene loaded = load_scene(test::sample("cornell_box.obj"));
  make_patches(*loaded.mesh, 60.0);
  ElementHierarchy hierarchy(*loaded.mesh);
  SolveOptions options;
  options.converge = 0.02;
  ProgressiveSolver solver(*loaded.mesh, hierarchy, options);
  solver.run();
  // Floor nodes in a band along each side wall (red at x ~ 550, green at x = 0).
  Rgb near_red, near_green;
  const auto& receivers = solver.receivers();
  for (std::size_t x = 0; x < receivers.size(); ++x) {
    const Vec3d p = receivers.position[x];
    if (receivers.normal[x][1] < 0.99 || p[1] > 1e-6 || p[2] < 150 || p[2] > 450) continue;
    if (p[0] > 470) near_red += solver.radiosity()[x];
    if (p[0] < 80) near_green += solver.radiosity()[x];
  }
  ASSERT_GT(near_red.g, 0.0);
  ASSERT_GT(near_green.g, 0.0);
  EXPECT_GT(near_red.r / near_red.g, 1.1 * (near_green.r / near_green.g));
  EXPECT_GT(near_green.g / near_green.r, 1.1 * (near_red.g / near_red.r));
}

}  // namespace
}  // namespace dynrad::rad
