// The lighting designer's checks (radiosity/design/): cylindrical illuminance, EN 12464-1
// room surfaces, EN 1838 routes, against closed forms computed here.
#include "mesh/core/error.h"
#include "radiosity/design/check.h"
#include "radiosity/design/emergency.h"
#include "radiosity/design/light_scenes.h"
#include "radiosity/design/room_checks.h"
#include "radiosity/analysis/grid.h"
#include "radiosity/analysis/grid_scene.h"
#include "radiosity/sources/luminaire.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace dynrad {
namespace {

// A lit scene built from quads (corner, two edge vectors; the front is u x v), each of
// uniform radiosity, no emission.
struct QuadScene {
  rad::LitScene scene;
  void quad(const Vec3d& corner, const Vec3d& u, const Vec3d& v, double radiosity = 0) {
    const auto base = static_cast<std::uint32_t>(scene.positions.size());
    for (const Vec3d& p : {corner, corner + u, corner + u + v, corner + v}) {
      scene.positions.push_back(p);
      scene.radiosity.push_back(Rgb(radiosity, radiosity, radiosity));
    }
    scene.triangles.push_back({base, base + 1, base + 2});
    scene.triangles.push_back({base, base + 2, base + 3});
    scene.emission.resize(scene.triangles.size());
  }
  // A closed box [0, x] x [0, y] x [0, z] seen from inside.
  void box(double x, double y, double z, double radiosity = 0) {
    quad({0, 0, 0}, {x, 0, 0}, {0, y, 0}, radiosity);  // floor, facing up
    quad({0, 0, z}, {0, y, 0}, {x, 0, 0}, radiosity);  // ceiling, facing down
    quad({0, 0, 0}, {0, 0, z}, {x, 0, 0}, radiosity);  // y = 0, facing +y
    quad({0, y, 0}, {x, 0, 0}, {0, 0, z}, radiosity);  // y = y, facing -y
    quad({0, 0, 0}, {0, y, 0}, {0, 0, z}, radiosity);  // x = 0, facing +x
    quad({x, 0, 0}, {0, 0, z}, {0, y, 0}, radiosity);  // x = x, facing -x
  }
  void point_source(const Vec3d& at, double candela, double emergency = 0) {
    rad::Luminaire l;
    l.kind = rad::Luminaire::Kind::point;
    l.name = "P" + std::to_string(scene.luminaires.size() + 1);
    l.position = at;
    l.intensity = candela;
    l.emergency = emergency;
    scene.luminaires.push_back(l);
  }
};

// Solid angle of the rectangle [0, a] x [0, b] seen from a point at distance d above its
// corner (0, 0).
double corner_solid_angle(double a, double b, double d) {
  return std::atan(a * b / (d * std::sqrt(a * a + b * b + d * d)));
}
// ... of [x0, x1] x [y0, y1] from a point at distance d above (0, 0) (x0 < 0 < x1 and
// y0 < 0 < y1).
double rectangle_solid_angle(double x0, double x1, double y0, double y1, double d) {
  return corner_solid_angle(x1, y1, d) + corner_solid_angle(-x0, y1, d) + corner_solid_angle(x1, -y0, d) +
         corner_solid_angle(-x0, -y0, d);
}

TEST(DesignChecks, CheckVerdictsAndMargins) {
  const rad::Check least{"task area", "Em", 550, true, "lx", rad::Check::Relation::at_least, 500, 0, ""};
  EXPECT_TRUE(least.met());
  EXPECT_NEAR(least.margin(), 0.10, 1e-12);
  const rad::Check most{"observers", "UGR", 21, true, "", rad::Check::Relation::at_most, 19, 0, ""};
  EXPECT_FALSE(most.met());
  EXPECT_NEAR(most.margin(), -2.0 / 19, 1e-12);
  const rad::Check within{"task area", "Ez/Eh", 0.66, true, "", rad::Check::Relation::within, 0.3, 0.6, ""};
  EXPECT_FALSE(within.met());
  EXPECT_NEAR(within.margin(), -0.1, 1e-12);
  rad::Check undefined = least;
  undefined.defined = false;
  EXPECT_FALSE(undefined.met());
  EXPECT_FALSE(rad::all_met({least, undefined}));
  EXPECT_DOUBLE_EQ(rad::surrounding_illuminance(1000), 500);
  EXPECT_DOUBLE_EQ(rad::surrounding_illuminance(500), 300);
  EXPECT_DOUBLE_EQ(rad::surrounding_illuminance(300), 200);
  EXPECT_DOUBLE_EQ(rad::surrounding_illuminance(100), 100);
}

// Over a black floor, a point source's cylindrical illuminance is I sin(theta) / (pi d^2)
// exactly: nothing else sends light.
TEST(DesignChecks, CylindricalIlluminanceOfAPointSourceIsISinThetaOverPiDSquared) {
  QuadScene q;
  q.quad({-20, -20, 0}, {40, 0, 0}, {0, 40, 0});
  q.point_source({0, 0, 3}, 1000);
  q.scene.prepare();
  const Vec3d up(0, 0, 1);
  for (const Vec3d& p : {Vec3d(2, 0, 1.2), Vec3d(-1, 3, 1.6), Vec3d(0.5, 0.5, 0.3)}) {
    const Vec3d d = Vec3d(0, 0, 3) - p;
    const double sine = std::hypot(d[0], d[1]) / d.norm();
    const double exact = 1000 * sine / (M_PI * d.sqrnorm());
    const rad::GridPointResult r = rad::gather_cylindrical(q.scene, p, up, {}, 7);
    EXPECT_NEAR(r.illuminance, exact, 1e-9 * exact) << p;
    EXPECT_EQ(r.indirect, 0);
  }
  // Straight below: no light on any vertical plane.
  EXPECT_EQ(rad::gather_cylindrical(q.scene, Vec3d(0, 0, 1), up, {}, 7).illuminance, 0);
}

// Inside an enclosure of uniform radiosity B, every plane gets E = B, and so does a
// cylinder: Ez = B, whatever the stratified directions.
TEST(DesignChecks, CylindricalIlluminanceInAUniformEnclosureEqualsItsRadiosity) {
  QuadScene q;
  q.box(4, 3, 2.5, 10.0);
  q.scene.prepare();
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const rad::GridPointResult z = rad::gather_cylindrical(q.scene, Vec3d(1.3, 1.1, 1.2), Vec3d(0, 0, 1), {}, seed);
    EXPECT_NEAR(z.illuminance, 10.0, 0.1) << seed;  // 1%: the stratified sine weights' noise
    EXPECT_NEAR(z.indirect, z.illuminance, 1e-12);
  }
}

// A point source in the middle of a black box room: the walls' mean illuminance is the
// flux they catch over their area, I x (their solid angle) / area, and the ceiling's
// likewise (the mean over the cell centres is a midpoint rule, within 2%). The floor and
// the ceiling are found by rays.
TEST(DesignChecks, WallsAndCeilingOfARoomMatchTheFluxTheyCatch) {
  const double x = 4, y = 3, z = 2.5, I = 1000;
  QuadScene q;
  q.box(x, y, z);
  const Vec3d c(x / 2, y / 2, z / 2);
  q.point_source(c, I);
  q.scene.prepare();
  rad::GridResult task;
  task.spec.name = "room";
  task.spec.polygon = {{0, 0}, {x, 0}, {x, y}, {0, y}};
  task.spec.height = 0.8;
  task.spec.room.walls = true;
  task.spec.room.ceiling = true;
  rad::GatherOptions few;
  few.side = 4;  // black walls: nothing indirect to gather
  const rad::RoomResult room = rad::check_room(q.scene, task, {}, few);
  EXPECT_NEAR(room.floor, 0, 1e-6);  // (single-precision rays)
  EXPECT_NEAR(room.ceiling, z, 1e-6);
  // Solid angles from the centre: a wall x wide, z high at distance y / 2, and so on.
  const double wall_x = rectangle_solid_angle(-x / 2, x / 2, -z / 2, z / 2, y / 2);
  const double wall_y = rectangle_solid_angle(-y / 2, y / 2, -z / 2, z / 2, x / 2);
  const double ceiling = rectangle_solid_angle(-x / 2, x / 2, -y / 2, y / 2, z / 2);
  EXPECT_NEAR(2 * wall_x + 2 * wall_y + 2 * ceiling, 4 * M_PI, 1e-9);  // (the test's own closed form)
  // Walls: their points are spread per wall by the spacing rule, so the mean over them
  // weighs each wall by its count of points; the test takes the area-weighted mean, the
  // standard's intent, and allows for the difference.
  const double walls_mean = I * (2 * wall_x + 2 * wall_y) / (2 * x * z + 2 * y * z);
  EXPECT_NEAR(room.walls.e_avg, walls_mean, 0.04 * walls_mean);
  EXPECT_NEAR(room.ceiling_surface.e_avg, I * ceiling / (x * y), 0.02 * I * ceiling / (x * y));
  // The brightest ceiling point is near the middle, at most I / (z/2)^2.
  EXPECT_LE(room.ceiling_surface.e_max, I / (z / 2 * z / 2) * (1 + 1e-9));
  EXPECT_GT(room.ceiling_surface.e_max, 0.8 * I / (z / 2 * z / 2));
  ASSERT_EQ(room.checks.size(), 4u);
  EXPECT_EQ(room.checks[0].area, "walls");
  EXPECT_EQ(room.checks[0].met(), room.walls.e_avg >= 75);
  EXPECT_EQ(room.checks[2].area, "ceiling");
  EXPECT_EQ(room.checks[3].met(), room.ceiling_surface.u0 >= 0.1);
}

// The surrounding band lies between the task area and the room's edge: a source high
// above the middle of a black 10 x 10 m floor lights it less than the task area's
// middle and more than the floor's corner.
TEST(DesignChecks, SurroundingBandLiesBetweenTheTaskAreaAndTheEdge) {
  QuadScene q;
  q.quad({0, 0, 0}, {10, 0, 0}, {0, 10, 0});
  q.point_source({5, 5, 4}, 10000);
  q.scene.prepare();
  rad::GridSpec spec;
  spec.name = "office";
  spec.polygon = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  spec.height = 0.8;
  spec.border = 1.0;
  spec.target_eavg = 500;
  spec.room.surrounding = 0.5;
  rad::GatherOptions few;
  few.side = 4;
  const rad::GridResult task = rad::gather_grid(q.scene, spec, few);
  const rad::RoomResult room = rad::check_room(q.scene, task, {}, few);
  auto exact = [](double px, double py) {
    const double h = 4 - 0.8, d2 = (px - 5) * (px - 5) + (py - 5) * (py - 5) + h * h;
    return 10000 * h / (d2 * std::sqrt(d2));
  };
  ASSERT_GT(room.surrounding.count, 20u);
  // Band points lie 0.5 to 1 m from the edges: between a corner point 0.5 m in and an
  // edge middle 1 m in.
  EXPECT_GE(room.surrounding.e_min, exact(0.5, 0.5) * (1 - 1e-9));
  EXPECT_LE(room.surrounding.e_max, exact(1.0, 5.0) * (1 + 1e-9));
  EXPECT_LT(room.surrounding.e_avg, task.e_avg);
  // Its target comes from the task's by the standard's table: 300 lx for 500.
  bool found = false;
  for (const rad::Check& c : room.checks)
    if (c.area == "surrounding" && c.quantity == "Em") {
      found = true;
      EXPECT_DOUBLE_EQ(c.target, 300);
    }
  EXPECT_TRUE(found);
}

TEST(DesignChecks, RoomUgrIsTheWorstObserverStandingInIt) {
  QuadScene q;
  q.box(5, 5, 3);
  q.scene.prepare();
  rad::GridResult task;
  task.spec.name = "office";
  task.spec.polygon = {{0, 0}, {5, 0}, {5, 5}, {0, 5}};
  task.spec.room.ugr = 19;
  const std::vector<rad::ObserverGlare> observers = {
      {"desk", Vec3d(1, 1, 1.2), 17.5, true}, {"door", Vec3d(4, 4, 1.2), 18.5, true}, {"next room", Vec3d(7, 1, 1.2), 25, true}};
  const rad::RoomResult room = rad::check_room(q.scene, task, observers);
  ASSERT_EQ(room.checks.size(), 1u);
  EXPECT_DOUBLE_EQ(room.checks[0].value, 18.5);
  EXPECT_TRUE(room.checks[0].met());
  EXPECT_EQ(room.observers, (std::vector<std::string>{"desk", "door"}));
  const rad::RoomResult empty = rad::check_room(q.scene, task, {observers[2]});
  EXPECT_FALSE(empty.checks[0].met());
  EXPECT_NE(empty.checks[0].note.find("no observer"), std::string::npos);
}

// A corridor lit by one emergency point source above its middle: the centre line's
// least illuminance is at the ends, f I h / d^3; only emergency luminaires count.
TEST(DesignChecks, EscapeRouteMinimaAreAtTheEndsOfItsCentreLine) {
  QuadScene q;
  q.quad({-1, -5, 0}, {12, 0, 0}, {0, 10, 0});
  const double I = 100, f = 0.5, z = 2.5;
  q.point_source({5, 0, z}, I, f);
  q.point_source({2, 0, z}, 5000);  // not an emergency luminaire
  q.scene.prepare();
  rad::EmergencyArea route;
  route.name = "corridor";
  route.points = {{0, 0}, {10, 0}};
  route.width = 2;
  const rad::EmergencyResult r = rad::check_emergency(q.scene, route);
  const double h = z - 0.01;  // points 1 cm above the floor
  auto e = [&](double dx, double dy) {
    const double d2 = dx * dx + dy * dy + h * h;
    return f * I * h / (d2 * std::sqrt(d2));
  };
  EXPECT_NEAR(r.e_min, e(5, 0), 1e-9 * e(5, 0));
  EXPECT_NEAR(r.e_max, e(0, 0), 1e-9 * e(0, 0));
  EXPECT_NEAR(r.band_min, e(5, 0.5), 1e-9 * e(5, 0.5));  // the band's edge is w / 4 off the line
  EXPECT_NEAR(r.length, 10, 1e-12);
  EXPECT_EQ(r.luminaires, (std::vector<std::string>{"P1"}));
  ASSERT_EQ(r.checks.size(), 3u);
  EXPECT_EQ(r.checks[0].met(), e(5, 0) >= 1);
  EXPECT_EQ(r.checks[1].met(), e(5, 0.5) >= 0.5);
  EXPECT_NEAR(r.checks[2].value, e(0, 0) / e(5, 0), 1e-9);
  EXPECT_EQ(r.checks[2].met(), e(0, 0) / e(5, 0) <= 40);
}

// An open area leaves out a 0.5 m border: its darkest point is 0.5 m in from a corner.
TEST(DesignChecks, OpenAreaLeavesOutItsBorder) {
  QuadScene q;
  q.quad({-1, -1, 0}, {8, 0, 0}, {0, 8, 0});
  q.point_source({3, 3, 3}, 200, 1.0);
  q.scene.prepare();
  rad::EmergencyArea hall;
  hall.kind = rad::EmergencyArea::Kind::open_area;
  hall.points = {{0, 0}, {6, 0}, {6, 6}, {0, 6}};
  const rad::EmergencyResult r = rad::check_emergency(q.scene, hall);
  const double h = 3 - 0.01;
  auto e = [&](double px, double py) {
    const double d2 = (px - 3) * (px - 3) + (py - 3) * (py - 3) + h * h;
    return 200 * h / (d2 * std::sqrt(d2));
  };
  ASSERT_GT(r.points, 0u);
  EXPECT_GE(r.e_min, e(0.5, 0.5) * (1 - 1e-9));
  EXPECT_LE(r.e_max, e(3, 3) * (1 + 1e-9));
  EXPECT_EQ(r.checks[0].met(), r.e_min >= 0.5);
}

TEST(DesignChecks, SceneFileErrorsNameTheFileAndTheEntry) {
  test::TempDir dir;
  auto error_of = [&](const std::string& text, auto read) {
    const std::string path = dir.write("scene.json", text);
    try {
      read(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto grids = [](const std::string& p) { rad::read_grids(p); };
  auto areas = [](const std::string& p) { rad::read_emergency_areas(p); };
  const std::string band = error_of(R"({"grids": [{"name": "a", "rectangle": [0, 0, 4, 4], "target": {"Eavg": 500,
      "surrounding": true}}]})", grids);
  EXPECT_NE(band.find("scene.json"), std::string::npos) << band;
  EXPECT_NE(band.find("surrounding needs a \"border\""), std::string::npos) << band;
  const std::string ez = error_of(R"({"grids": [{"rectangle": [0, 0, 4, 4], "target": {"Ez": {"U0": 0.1}}}]})", grids);
  EXPECT_NE(ez.find("target.Ez"), std::string::npos) << ez;
  const std::string walls = error_of(R"({"grids": [{"rectangle": [0, 0, 4, 4], "target": {"walls": {"Em": 50}}}]})", grids);
  EXPECT_NE(walls.find("unknown key \"Em\""), std::string::npos) << walls;
  const std::string path = error_of(R"({"routes": [{"name": "r", "path": [[0, 0]]}]})", areas);
  EXPECT_NE(path.find("routes[0] (\"r\").path"), std::string::npos) << path;
  const std::string twice = error_of(R"({"routes": [{"name": "r", "path": [[0, 0], [1, 0]]}],
      "open_areas": [{"name": "r", "rectangle": [0, 0, 2, 2]}]})", areas);
  EXPECT_NE(twice.find("two emergency areas are named \"r\""), std::string::npos) << twice;
  // A valid grid reads its room targets.
  const std::string ok = dir.write("ok.json", R"({"grids": [{"rectangle": [0, 0, 4, 4], "border": 0.5, "target":
      {"Eavg": 500, "surrounding": {"width": 0.5}, "walls": true, "Ez": {"Eavg": 150, "height": 1.6}, "UGR": 19}}]})");
  const std::vector<rad::GridSpec> g = rad::read_grids(ok);
  ASSERT_EQ(g.size(), 1u);
  EXPECT_DOUBLE_EQ(g[0].room.surrounding, 0.5);
  EXPECT_TRUE(g[0].room.walls);
  EXPECT_FALSE(g[0].room.ceiling);
  EXPECT_DOUBLE_EQ(g[0].room.ez, 150);
  EXPECT_DOUBLE_EQ(g[0].room.ez_height, 1.6);
  EXPECT_DOUBLE_EQ(g[0].room.ugr, 19);
}

// Channels: each group's light in one, scaled so that its luminance is the light's; a
// scene's value at a point is the groups' luminances times their levels.
TEST(DesignChecks, LightScenesKeepEachGroupInAChannelOfItsOwn) {
  std::vector<rad::Luminaire> luminaires(4);
  const char* groups[] = {"day", "night", "day", ""};
  for (int k = 0; k < 4; ++k) {
    luminaires[k].name = "L" + std::to_string(k + 1);
    luminaires[k].group = groups[k];
  }
  const rad::ChannelPlan plan = rad::plan_channels("s.json", luminaires, false);
  EXPECT_EQ(plan.channels, (std::vector<std::string>{"day", "night", ""}));
  rad::assign_channels(luminaires, plan);
  for (int k = 0; k < 3; ++k) {
    const Rgb c = rad::channel_colour(k);
    EXPECT_NEAR(c.luminance(), 1.0, 1e-15);
    EXPECT_EQ((c.r > 0) + (c.g > 0) + (c.b > 0), 1);
  }
  EXPECT_EQ(luminaires[2].colour.r, rad::channel_colour(0).r);
  // A point lit 30 lx by the day group, 10 by the night group and 5 by the rest:
  const Rgb point = rad::channel_colour(0) * 30.0 + rad::channel_colour(1) * 10.0 + rad::channel_colour(2) * 5.0;
  const std::array<double, 3> y = rad::channel_luminances(point);
  EXPECT_NEAR(y[0], 30, 1e-12);
  EXPECT_NEAR(y[1], 10, 1e-12);
  EXPECT_NEAR(y[2], 5, 1e-12);
  EXPECT_NEAR(rad::grey(point).g, 45, 1e-12);
  const rad::LightScene evening{"evening", {{"day", 0.5}}};
  const std::array<double, 3> levels = rad::channel_levels(evening, plan);
  EXPECT_EQ(levels, (std::array<double, 3>{0.5, 1, 1}));
  rad::GridResult grid;
  grid.spec.target_eavg = 40;
  rad::GridPointResult p;
  p.colour = point;
  grid.points = {p, p};
  const rad::SceneGrid g = rad::scene_grid(grid, levels);
  EXPECT_NEAR(g.e_avg, 0.5 * 30 + 10 + 5, 1e-12);
  EXPECT_FALSE(g.meets_target);
  // A fourth channel, or a tinted luminaire, cannot be kept apart.
  luminaires.push_back(luminaires[0]);
  luminaires.back().group = "cleaning";
  EXPECT_THROW(rad::plan_channels("s.json", luminaires, false), InputError);
  luminaires.pop_back();
  EXPECT_THROW(rad::plan_channels("s.json", luminaires, false), InputError);  // (coloured now: assigned above)
}

TEST(DesignChecks, LightSceneErrorsNameTheSceneAndTheGroup) {
  test::TempDir dir;
  std::vector<rad::Luminaire> luminaires(1);
  luminaires[0].group = "day";
  auto error_of = [&](const std::string& text) {
    try {
      rad::read_light_scenes(dir.write("scene.json", text), luminaires);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string unknown = error_of(R"({"scenes": [{"name": "eve", "levels": {"night": 1}}]})");
  EXPECT_NE(unknown.find("scenes[0] (\"eve\").levels names group \"night\""), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("groups: day"), std::string::npos) << unknown;
  const std::string level = error_of(R"({"scenes": [{"levels": {"day": 1.5}}]})");
  EXPECT_NE(level.find("from 0 (off) to 1 (full)"), std::string::npos) << level;
  const std::string twice = error_of(R"({"scenes": [{"name": "a", "levels": {}}, {"name": "a", "levels": {}}]})");
  EXPECT_NE(twice.find("two scenes are named \"a\""), std::string::npos) << twice;
  EXPECT_EQ(error_of(R"({"scenes": [{"name": "a", "levels": {"day": 0.2}}]})"), "no error");
}

}  // namespace
}  // namespace dynrad
