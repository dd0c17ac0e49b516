// Daylight (radiosity/sources/sky.h, daylight.h): sky models against their closed forms, the
// sun's position against published ones, the sky through a roof opening against
// pi L F, a sun beam through a window where the geometry puts it, and glazing's
// transmittance scaling the light inside.
#include "mesh/core/error.h"
#include "mesh/load.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/sources/glass.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/sources/sky.h"
#include "radiosity/transfer/visibility.h"
#include "scene_builder.h"
#include "test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace dynrad {
namespace {

using test::SceneBuilder;

TEST(Sky, OvercastAndUniformHorizontalIlluminanceMatchTheirClosedForms) {
  rad::SkyModel sky;
  sky.zenith_luminance = 1000;
  sky.type = rad::SkyModel::Type::cie_overcast;
  EXPECT_NEAR(sky.horizontal_illuminance(), 7 * M_PI * 1000 / 9, 1e-6 * 1000);
  sky.type = rad::SkyModel::Type::uniform;
  EXPECT_NEAR(sky.horizontal_illuminance(), M_PI * 1000, 1e-6 * 1000);
  // CIE type 5 has no gradation and no indicatrix: uniform too, wherever the sun is.
  sky.type = rad::SkyModel::Type::cie;
  sky.cie_type = 5;
  sky.sun = Vec3d(0.3, -0.5, 0.8).normalized();
  EXPECT_NEAR(sky.horizontal_illuminance(), M_PI * 1000, 1e-6 * 1000);
}

TEST(Sky, MeanLuminanceAtAnElevationMatchesTheClosedForms) {
  // Overcast: L = Lz (1 + 2 sin e) / 3, the same all round; uniform: Lz. With y as up the
  // ring is taken about y. (The horizon itself, e = 0, belongs to the ground.)
  rad::SkyModel sky;
  sky.zenith_luminance = 1000;
  sky.type = rad::SkyModel::Type::cie_overcast;
  for (double e : {5.0, 10.0, 45.0, 89.0})
    EXPECT_NEAR(sky.mean_luminance_at(e), 1000 * (1 + 2 * std::sin(e * M_PI / 180)) / 3, 1e-9) << e;
  sky.up = Vec3d(0, 1, 0);
  EXPECT_NEAR(sky.mean_luminance_at(10), 1000 * (1 + 2 * std::sin(10 * M_PI / 180)) / 3, 1e-9);
  sky.type = rad::SkyModel::Type::uniform;
  EXPECT_NEAR(sky.mean_luminance_at(30), 1000, 1e-9);
}

TEST(Sky, HorizonOverZenithFollowsTheGradation) {
  rad::SkyModel sky;
  const Vec3d horizon = Vec3d(1, 0, 1e-9).normalized(), zenith(0, 0, 1);
  sky.type = rad::SkyModel::Type::cie_overcast;
  EXPECT_NEAR(sky.relative(horizon), 1.0 / 3.0, 1e-6);
  EXPECT_NEAR(sky.relative(zenith), 1.0, 1e-12);
  sky.type = rad::SkyModel::Type::cie;
  sky.cie_type = 1;  // phi(90 deg) / phi(0) = 1 / (1 + 4 exp(-0.7))
  EXPECT_NEAR(sky.relative(horizon), 1 / (1 + 4 * std::exp(-0.7)), 1e-6);
  // Clear sky (type 12): brightest near the sun, darker opposite it at the same altitude.
  sky.cie_type = 12;
  sky.sun = Vec3d(0, -std::cos(M_PI / 4), std::sin(M_PI / 4));
  const Vec3d near_sun = Vec3d(0, -1, 1.1).normalized(), away = Vec3d(0, 1, 1.1).normalized();
  EXPECT_GT(sky.relative(near_sun), 3 * sky.relative(away));
  EXPECT_THROW(rad::cie_sky_parameters(16), std::invalid_argument);
}

TEST(Sun, PositionMatchesPublishedOnes) {
  // NREL SPA's worked example (Reda and Andreas 2004): Golden, Colorado,
  // 2003-10-17 12:30:30 local (UTC-7): zenith 50.11162, azimuth 194.34024 degrees.
  rad::LocalTime t = rad::parse_local_time("2003-10-17T12:30:30", -7);
  const rad::SunPosition p = rad::sun_position(39.742476, -105.1786, t);
  EXPECT_NEAR(p.zenith, 50.11162, 0.02);
  EXPECT_NEAR(p.azimuth, 194.34024, 0.02);
  // Greenwich at the June solstice of 2026, noon UTC: altitude 90 - 51.4769 + 23.436
  // (the declination) plus 0.009 of refraction; the sun just east of south (solar noon
  // comes about 2 minutes later).
  t = rad::parse_local_time("2026-06-21T12:00", 0);
  const rad::SunPosition g = rad::sun_position(51.4769, 0.0, t);
  EXPECT_NEAR(90 - g.zenith, 90 - 51.4769 + 23.436 + 0.009, 0.03);
  EXPECT_NEAR(g.declination, 23.436, 0.01);
  EXPECT_GT(g.azimuth, 179.0);
  EXPECT_LT(g.azimuth, 180.0);
  // Directions: azimuth 90 (east) is +x when north is +y and up +z.
  rad::SunPosition east;
  east.zenith = 60;
  east.azimuth = 90;
  const Vec3d d = rad::sun_direction(east, Vec3d(0, 0, 1), Vec3d(0, 1, 0));
  EXPECT_NEAR(d[0], std::sin(M_PI / 3), 1e-12);
  EXPECT_NEAR(d[1], 0, 1e-12);
  EXPECT_NEAR(d[2], 0.5, 1e-12);
  EXPECT_THROW(rad::parse_local_time("2026-02-30T12:00", 0), std::invalid_argument);
  EXPECT_THROW(rad::parse_local_time("2026-06-21 12:00", 0), std::invalid_argument);
}

// A 4 x 4 x 3 room facing inwards whose ceiling has a 1 x 1 opening over [1.5, 2.5]^2,
// glazed with transmittance `glass` (0: open).
LoadedScene roof_opening_room(double glass) {
  SceneBuilder b;
  const std::uint32_t wall = b.material("wall", 0.5);
  b.box(Vec3d(0, 0, 0), Vec3d(4, 4, 3), wall, SceneBuilder::inward, {false, false, false, false, false, true});
  const double z = 3;
  auto down = [&](double x0, double y0, double x1, double y1) {  // a ceiling piece facing down
    b.quad(Vec3d(x0, y0, z), Vec3d(x0, y1, z), Vec3d(x1, y1, z), Vec3d(x1, y0, z), wall);
  };
  down(0, 0, 1.5, 4);
  down(2.5, 0, 4, 4);
  down(1.5, 0, 2.5, 1.5);
  down(1.5, 2.5, 2.5, 4);
  PolygonSoup soup = b.soup();
  if (glass > 0) {
    soup.materials.push_back(Material{"glass", Rgb(0.0), Rgb(0.0), "test", true, Rgb(glass)});
    const auto m = static_cast<std::uint32_t>(soup.materials.size() - 1);
    const auto base = static_cast<std::uint32_t>(soup.points.size());
    for (const Vec3d& p : {Vec3d(1.5, 1.5, z), Vec3d(1.5, 2.5, z), Vec3d(2.5, 2.5, z), Vec3d(2.5, 1.5, z)})
      soup.points.push_back(p);
    soup.polygons.push_back({base, base + 1, base + 2, base + 3});
    soup.material.push_back(m);
    soup.group.push_back(0);
    soup.origin.push_back(SourceRef{0, 0, static_cast<std::uint32_t>(soup.polygons.size() - 1)});
  }
  return load_soup(soup, "roof opening");
}

std::vector<rad::Luminaire> sky_from(const test::TempDir& dir, const std::string& sky,
                                     const std::vector<GlazingTriangle>& glazing,
                                     const std::vector<std::array<Vec3d, 3>>& openings = {}) {
  return rad::read_daylight(dir.write("sky.json", "{\"sky\": " + sky + "}"), glazing, openings);
}

TEST(Daylight, SkyThroughARoofOpeningIsPiLTimesTheFormFactor) {
  test::TempDir dir;
  const LoadedScene room = roof_opening_room(0);
  EXPECT_TRUE(room.glazing.empty());
  const rad::Visibility visibility(*room.mesh);
  ASSERT_EQ(room.openings.size(), 2u);  // the opening, triangulated
  const auto sources = sky_from(dir, R"({"type": "uniform", "zenith_luminance": 1000})", {}, room.openings);
  ASSERT_EQ(sources.size(), 1u);
  const rad::Luminaire& sky = sources[0];
  double worst = 0, worst_default = 0;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{2, 2}, {1, 1}, {2.5, 1.2}, {0.4, 3.3}, {3, 2}}) {
    const double exact = 1000 * M_PI * test::parallel_rectangle(x, y, 1.5, 1.5, 2.5, 2.5, 3.0);
    const Vec3d p(x, y, 0), up(0, 0, 1);
    const double fine = rad::daylight_illuminance(&visibility, sky, p, up, nullptr, 48);  // as grids gather
    const double coarse = rad::daylight_illuminance(&visibility, sky, p, up, nullptr);  // the solve's 32 x 32
    worst = std::max(worst, std::abs(fine / exact - 1));
    worst_default = std::max(worst_default, std::abs(coarse / exact - 1));
  }
  // Through the opening as a portal; sampling the whole hemisphere instead, the errors
  // were 0.26% and 1.1%.
  EXPECT_LT(worst, 0.0005);         // 48 x 48: what the grids gather with
  EXPECT_LT(worst_default, 0.001);  // 32 x 32: the solve's own
  std::printf("sky through a roof opening: worst error %.3f%% at 48x48 directions, %.3f%% at 32x32\n", 100 * worst,
              100 * worst_default);
  // Unobstructed, the uniform sky gives pi L on a horizontal plane.
  double open = 0;
  rad::daylight_illuminance(nullptr, sky, Vec3d(2, 2, 0), Vec3d(0, 0, 1), &open);
  EXPECT_NEAR(open, 1000 * M_PI, 1e-9 * 1000);
}

TEST(Daylight, GlassScalesTheSkyByItsTransmittanceAtTheAnglesItIsSeenAt) {
  test::TempDir dir;
  const LoadedScene open_room = roof_opening_room(0), glazed_room = roof_opening_room(0.6);
  ASSERT_EQ(glazed_room.glazing.size(), 2u);  // the pane, triangulated
  EXPECT_EQ(open_room.mesh->face_count(), glazed_room.mesh->face_count());  // not part of the lit mesh
  const rad::Visibility a(*open_room.mesh), b(*glazed_room.mesh);
  // The open room's portal is the pane's triangles as an opening, and the glazed
  // room's the pane (the opening it covers is left out): the same directions.
  ASSERT_EQ(open_room.openings.size(), 2u);
  std::vector<std::array<Vec3d, 3>> pane;
  for (const GlazingTriangle& t : glazed_room.glazing) pane.push_back(t.corners);
  const auto open_sky = sky_from(dir, R"({"type": "cie_overcast"})", {}, pane);
  const auto glazed_sky = sky_from(dir, R"({"type": "cie_overcast"})", glazed_room.glazing, glazed_room.openings);
  // The ratio of glazed to open is a mean of the pane's transmittance over the
  // directions the point sees it in: between its least and its most over the pane (on a
  // 100 x 100 grid of it), and below 0.6 (face on).
  const rad::GlassPane glass(0.6);
  for (const Vec3d& p : {Vec3d(2, 2, 0), Vec3d(1, 3, 0), Vec3d(3.9, 2, 1.5)}) {
    const Vec3d n = p[0] > 3.8 ? Vec3d(-1, 0, 0) : Vec3d(0, 0, 1);
    const double e_open = rad::daylight_illuminance(&a, open_sky[0], p, n, nullptr);
    const double e_glazed = rad::daylight_illuminance(&b, glazed_sky[0], p, n, nullptr);
    ASSERT_GT(e_open, 0);
    double least = 1, most = 0;
    for (int i = 0; i < 100; ++i)
      for (int j = 0; j < 100; ++j) {
        const Vec3d d = Vec3d(1.5 + (i + 0.5) / 100, 1.5 + (j + 0.5) / 100, 3) - p;
        const double t = glass.transmittance(d[2] / d.norm());
        least = std::min(least, t);
        most = std::max(most, t);
      }
    EXPECT_GE(e_glazed / e_open, least - 1e-9) << p;
    EXPECT_LE(e_glazed / e_open, most + 1e-9) << p;
    EXPECT_LT(e_glazed / e_open, 0.6) << p;
  }
}

TEST(Daylight, SunBeamThroughAWindowLandsWhereTheGeometrySays) {
  // A 4 x 4 x 3 room; its south wall (y = 0) has a window over x in [1, 3], z in [1, 2],
  // glazed at 0.8. The sun is due south at 45 degrees: the beam reaches the floor over
  // x in [1, 3], y in [1, 2] with E = E_n sin 45 x 0.8, nothing elsewhere.
  SceneBuilder b;
  const std::uint32_t wall = b.material("wall", 0.5);
  b.box(Vec3d(0, 0, 0), Vec3d(4, 4, 3), wall, SceneBuilder::inward, {false, false, true, false, false, false});
  auto south = [&](double x0, double z0, double x1, double z1) {  // facing +y
    b.quad(Vec3d(x1, 0, z0), Vec3d(x0, 0, z0), Vec3d(x0, 0, z1), Vec3d(x1, 0, z1), wall);
  };
  south(0, 0, 4, 1);
  south(0, 2, 4, 3);
  south(0, 1, 1, 2);
  south(3, 1, 4, 2);
  PolygonSoup soup = b.soup();
  soup.materials.push_back(Material{"glass", Rgb(0.0), Rgb(0.0), "test", true, Rgb(0.8)});
  const auto base = static_cast<std::uint32_t>(soup.points.size());
  for (const Vec3d& p : {Vec3d(3, 0, 1), Vec3d(1, 0, 1), Vec3d(1, 0, 2), Vec3d(3, 0, 2)}) soup.points.push_back(p);
  soup.polygons.push_back({base, base + 1, base + 2, base + 3});
  soup.material.push_back(static_cast<std::uint32_t>(soup.materials.size() - 1));
  soup.group.push_back(0);
  soup.origin.push_back(SourceRef{0, 0, static_cast<std::uint32_t>(soup.polygons.size() - 1)});
  const LoadedScene room = load_soup(soup, "sun room");
  const rad::Visibility visibility(*room.mesh);
  test::TempDir dir;
  const auto sources =
      sky_from(dir, R"({"sun": {"altitude": 45, "azimuth": 180, "direct_normal": 50000}})", room.glazing);
  ASSERT_EQ(sources.size(), 2u);
  const rad::Luminaire& sun = sources[0];
  ASSERT_EQ(sun.kind, rad::Luminaire::Kind::sun);
  const Vec3d up(0, 0, 1);
  // The beam meets the pane at 45 degrees: the pane passes less than its 0.8 face on.
  const double lit = 50000 * std::sin(M_PI / 4) * rad::GlassPane(0.8).transmittance(std::cos(M_PI / 4));
  EXPECT_LT(lit, 50000 * std::sin(M_PI / 4) * 0.8);
  for (double x : {1.1, 2.0, 2.9})
    for (double y : {1.05, 1.5, 1.95})
      EXPECT_NEAR(rad::daylight_illuminance(&visibility, sun, Vec3d(x, y, 0), up, nullptr), lit, 1e-6 * lit)
          << x << ", " << y;
  for (const Vec3d& dark : {Vec3d(2, 0.95, 0), Vec3d(2, 2.05, 0), Vec3d(0.9, 1.5, 0), Vec3d(3.1, 1.5, 0)})
    EXPECT_EQ(rad::daylight_illuminance(&visibility, sun, dark, up, nullptr), 0.0) << dark;
  // A surface facing away from the sun gets none, whatever the geometry.
  EXPECT_EQ(rad::daylight_illuminance(nullptr, sun, Vec3d(2, 3, 1), Vec3d(0, 1, 0), nullptr), 0.0);
}

// The roof-opening room as files for the command line: OBJ and MTL, the opening glazed
// (MTL d = 1 - transmittance) or open.
std::string roof_room_files(const test::TempDir& dir, const std::string& name, double glass) {
  std::string obj = "mtllib " + name + ".mtl\nusemtl wall\n";
  int v = 0;
  auto quad = [&](std::array<Vec3d, 4> c) {
    for (const Vec3d& p : c) obj += fmt::format("v {} {} {}\n", p[0], p[1], p[2]);
    obj += fmt::format("f {} {} {} {}\n", v + 1, v + 2, v + 3, v + 4);
    v += 4;
  };
  const double W = 4, H = 3;
  quad({Vec3d(0, 0, 0), Vec3d(W, 0, 0), Vec3d(W, W, 0), Vec3d(0, W, 0)});  // floor, up
  quad({Vec3d(W, 0, 0), Vec3d(0, 0, 0), Vec3d(0, 0, H), Vec3d(W, 0, H)});  // south, +y
  quad({Vec3d(0, W, 0), Vec3d(W, W, 0), Vec3d(W, W, H), Vec3d(0, W, H)});  // north, -y
  quad({Vec3d(0, 0, 0), Vec3d(0, W, 0), Vec3d(0, W, H), Vec3d(0, 0, H)});  // west, +x
  quad({Vec3d(W, W, 0), Vec3d(W, 0, 0), Vec3d(W, 0, H), Vec3d(W, W, H)});  // east, -x
  auto down = [&](double x0, double y0, double x1, double y1) {
    quad({Vec3d(x0, y0, H), Vec3d(x0, y1, H), Vec3d(x1, y1, H), Vec3d(x1, y0, H)});
  };
  down(0, 0, 1.5, W);
  down(2.5, 0, W, W);
  down(1.5, 0, 2.5, 1.5);
  down(1.5, 2.5, 2.5, W);
  if (glass > 0) {
    obj += "usemtl glass\n";
    down(1.5, 1.5, 2.5, 2.5);
  }
  dir.write(name + ".obj", obj);
  dir.write(name + ".mtl", fmt::format("newmtl wall\nKd 0.6 0.6 0.6\nnewmtl glass\nKd 0 0 0\nd {}\n", 1 - glass));
  return dir.write(name + ".json", "{\"meshes\": [{\"file\": \"" + name +
                                       ".obj\"}], \"sky\": {\"type\": \"cie_overcast\", \"horizontal_illuminance\": "
                                       "10000}, \"grids\": [{\"name\": \"floor\", \"rectangle\": [0, 0, 4, 4], "
                                       "\"height\": 0.8, \"spacing\": 0.5}]}");
}

TEST(Daylight, GlazingScalesTheWholeSolveAndTheBalanceHolds) {
  test::TempDir dir;
  nlohmann::json grids[2], reports[2];
  for (int k = 0; k < 2; ++k) {
    const std::string name = k ? "glazed" : "open";
    const std::string scene = roof_room_files(dir, name, k ? 0.7 : 0.0);
    const auto r = test::run_dynrad("solve '" + scene + "' -o '" + dir.path(name + ".ply") + "' --report '" +
                                    dir.path(name + "_report.json") + "' --quality draft");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    reports[k] = nlohmann::json::parse(test::read_text(dir.path(name + "_report.json")));
    grids[k] = reports[k]["grids"][0];
    const auto& e = reports[k]["energy"];
    for (int c = 0; c < 3; ++c) {
      const double emitted = e["emitted"][c].get<double>();
      EXPECT_NEAR(e["absorbed"][c].get<double>() + e["escaped"][c].get<double>() + e["unshot"][c].get<double>(),
                  emitted, 1e-6 * emitted);
    }
  }
  // Glass of 0.7 face on passes less at the angles the work plane sees it at: from the
  // grid's corner (0, 0, 0.8) its far corner (2.5, 2.5, 3) is 58 degrees off its normal.
  const double ratio = grids[1]["Eavg"].get<double>() / grids[0]["Eavg"].get<double>();
  EXPECT_LT(ratio, 0.7);
  EXPECT_GT(ratio, rad::GlassPane(0.7).transmittance(2.2 / Vec3d(2.5, 2.5, 2.2).norm()));
  // Under the sky alone the grid reports daylight factors: 100 E / 10000 lx.
  const nlohmann::json& df = grids[0]["daylight_factor"];
  ASSERT_TRUE(df.is_object());
  EXPECT_NEAR(df["DFavg"].get<double>(), grids[0]["Eavg"].get<double>() / 100, 1e-9 * df["DFavg"].get<double>());
  EXPECT_NEAR(df["sky_component"].get<double>() + df["externally_reflected_component"].get<double>() +
                  df["internally_reflected_component"].get<double>(),
              df["DFavg"].get<double>(), 1e-6 * df["DFavg"].get<double>());
}

// CIE 171:2006 test 5.11's kind of room: black, 4 x 4 x 3 m, with an unglazed 2 x 1 m
// opening over x in [1, 3], z in [1, 2] in its wall y = 0 (no thickness), under the
// traditional CIE overcast sky of 10,000 lx and a black ground. The floor's illuminance
// is the sky component alone.
// With `overhang` 1 (after the room) or -1 (before it), a black plate 1 m deep over the
// opening's head (z = 2, x in [0, 4], y in [-1, 0]), as in test 5.13.
std::string facade_room_files(const test::TempDir& dir, int overhang = 0) {
  std::string obj = "mtllib facade.mtl\nusemtl black\n";
  int v = 0;
  auto quad = [&](std::array<Vec3d, 4> c) {
    for (const Vec3d& p : c) obj += fmt::format("v {} {} {}\n", p[0], p[1], p[2]);
    obj += fmt::format("f {} {} {} {}\n", v + 1, v + 2, v + 3, v + 4);
    v += 4;
  };
  auto plate = [&] { quad({Vec3d(0, -1, 2), Vec3d(0, 0, 2), Vec3d(4, 0, 2), Vec3d(4, -1, 2)}); };  // facing down
  if (overhang < 0) plate();
  quad({Vec3d(0, 0, 0), Vec3d(4, 0, 0), Vec3d(4, 4, 0), Vec3d(0, 4, 0)});  // floor, up
  quad({Vec3d(0, 0, 3), Vec3d(0, 4, 3), Vec3d(4, 4, 3), Vec3d(4, 0, 3)});  // ceiling, down
  quad({Vec3d(0, 0, 0), Vec3d(0, 4, 0), Vec3d(0, 4, 3), Vec3d(0, 0, 3)});  // +x
  quad({Vec3d(4, 0, 0), Vec3d(4, 0, 3), Vec3d(4, 4, 3), Vec3d(4, 4, 0)});  // -x
  quad({Vec3d(0, 4, 0), Vec3d(4, 4, 0), Vec3d(4, 4, 3), Vec3d(0, 4, 3)});  // -y
  auto facade = [&](double x0, double z0, double x1, double z1) {  // facing +y
    quad({Vec3d(x0, 0, z0), Vec3d(x0, 0, z1), Vec3d(x1, 0, z1), Vec3d(x1, 0, z0)});
  };
  facade(0, 0, 1, 3);
  facade(3, 0, 4, 3);
  facade(1, 0, 3, 1);
  facade(1, 2, 3, 3);
  if (overhang > 0) plate();
  dir.write("facade.obj", obj);
  dir.write("facade.mtl", "newmtl black\nKd 0 0 0\n");
  return dir.write("facade.json", R"({"meshes": [{"file": "facade.obj"}],
    "sky": {"type": "cie_overcast", "horizontal_illuminance": 10000, "ground_reflectance": 0}})");
}

// The sky component at floor point (x, y) of that room: L cos(at the floor) cos(at the
// opening) / r^2 summed over an nu x nu / 2 grid of the opening (midpoint rule); with
// `overhang`, cells whose ray meets the plate count nothing.
double facade_sky_component(double x, double y, bool overhang = false, int nu = 400) {
  const double zenith = 9 * 10000 / (7 * M_PI);  // the overcast sky's Lz for 10,000 lx
  const int nv = nu / 2;
  const double cell = 2.0 / nu * (1.0 / nv);
  double sum = 0;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double dx = 1 + 2 * (i + 0.5) / nu - x, dy = -y, dz = 1 + (j + 0.5) / nv;
      if (overhang) {
        const double t = 2 / dz;  // along (dx, dy, dz) from the floor point to the plate's plane
        const double px = x + t * dx, py = y + t * dy;
        if (px >= 0 && px <= 4 && py >= -1 && py <= 0) continue;
      }
      const double r2 = dx * dx + dy * dy + dz * dz, r = std::sqrt(r2);
      const double luminance = zenith * (1 + 2 * dz / r) / 3;
      sum += luminance * (dz / r) * (-dy / r) / r2 * cell;
    }
  return sum;
}

TEST(Daylight, FacadeOpeningIsRightBesideTheWall) {
  // Sampling the whole hemisphere, points 0.125-0.25 m from this wall were 27-52% low:
  // they see the opening as a thin sliver beside the wall's plane, which a fixed set of
  // directions misses. The opening is now a portal, sampled over its own solid angle.
  test::TempDir dir;
  const std::string scene = facade_room_files(dir);
  const LoadedScene room = load_scene(dir.path("facade.obj"));
  ASSERT_EQ(room.openings.size(), 2u);
  const rad::Visibility visibility(*room.mesh);
  const auto sky = rad::read_daylight(scene, room.glazing, room.openings);
  ASSERT_EQ(sky.size(), 1u);
  double worst = 0, worst_default = 0;
  std::string points;
  for (double y : {0.125, 0.25, 0.5, 1.0, 2.0, 3.5})
    for (double x : {0.125, 0.25, 0.75, 1.25, 2.0, 2.75, 3.25, 3.75}) {
      const double exact = facade_sky_component(x, y);
      const Vec3d p(x, y, 0), up(0, 0, 1);
      worst = std::max(worst, std::abs(rad::daylight_illuminance(&visibility, sky[0], p, up, nullptr, 48) / exact - 1));
      worst_default = std::max(worst_default, std::abs(rad::daylight_illuminance(&visibility, sky[0], p, up, nullptr) / exact - 1));
      if (y >= 0.25 && y <= 2) points += fmt::format("{} {} 0 0 0 1\n", x, y);
    }
  EXPECT_LT(worst, 0.005);          // 48 x 48, as grids gather
  EXPECT_LT(worst_default, 0.005);  // 32 x 32, the solve's
  std::printf("sky component beside a facade opening: worst error %.3f%% at 48x48, %.3f%% at 32x32\n", 100 * worst,
              100 * worst_default);

  // The lit mesh at the defaults, between its vertices too, from 0.25 m off the walls
  // (closer, at 0.125 m, linear interpolation from the wall's foot, where the sky
  // component is 0, leaves it 3-5% low at the patches' finest level).
  const auto solved = test::run_dynrad("solve -q '" + scene + "' -o '" + dir.path("lit.ply") + "'");
  ASSERT_EQ(solved.exit_code, 0) << solved.output;
  dir.write("points.txt", points);
  const auto probed = test::run_dynrad("probe --json '" + dir.path("lit.ply") + "' --points '" + dir.path("points.txt") + "'");
  ASSERT_EQ(probed.exit_code, 0) << probed.output;
  const auto probes = nlohmann::json::parse(probed.output.substr(probed.output.find('{')))["points"];
  ASSERT_EQ(probes.size(), 32u);
  double worst_mesh = 0;
  for (const auto& p : probes) {
    const double exact = facade_sky_component(p["point"][0].get<double>(), p["point"][1].get<double>());
    worst_mesh = std::max(worst_mesh, std::abs(p["illuminance"].get<double>() / exact - 1));
  }
  EXPECT_LT(worst_mesh, 0.02) << probes;  // CIE 171 cases 5.9-5.14: issue 28 asks 2%
  std::printf("lit mesh beside a facade opening: worst error %.3f%% over 32 floor points\n", 100 * worst_mesh);
}

// Under an overhang the floor near the facade sees the sky only past the plate's ends,
// a sliver of the opening. Its corners were once sampled from whichever corner the model
// listed first, and in one order no stratum saw the sliver: a floor point took half
// its light (CIE 171 test 5.13, bench/results/daylight_portals.md). Now the same in either order, and
// right.
TEST(Daylight, SkyPastAnOverhangIsTheSameWhicheverFaceComesFirst) {
  std::vector<double> values[2];
  double worst = 0;
  for (int order : {1, -1}) {
    test::TempDir dir;
    const std::string scene = facade_room_files(dir, order);
    const LoadedScene room = load_scene(dir.path("facade.obj"));
    ASSERT_EQ(room.openings.size(), 2u);
    const rad::Visibility visibility(*room.mesh);
    const auto sky = rad::read_daylight(scene, room.glazing, room.openings);
    for (double y : {0.25, 0.75})
      for (double x : {0.75, 1.25, 1.75, 2.25, 2.75, 3.25}) {
        const double e = rad::daylight_illuminance(&visibility, sky[0], Vec3d(x, y, 0), Vec3d(0, 0, 1), nullptr);
        values[order > 0].push_back(e);
        if (order > 0) {
          const double exact = facade_sky_component(x, y, true, 2000);
          // Within 2%, or a tenth of a lux where the sky is a sliver of 1-3 lx (the
          // floor reaches 140 lx further in): the grids and `dynrad validate` judge
          // points in such shade against a share of the brightest, as a designer reads.
          EXPECT_LT(std::abs(e - exact), std::max(0.02 * exact, 0.1)) << x << " " << y << ": " << e << " against " << exact;
          worst = std::max(worst, std::abs(e - exact) / exact);
        }
      }
  }
  for (std::size_t k = 0; k < values[0].size(); ++k)
    EXPECT_NEAR(values[0][k], values[1][k], 1e-9 * values[1][k] + 1e-12) << k;
  std::printf("floor under an overhang: worst relative error %.3f%%\n", 100 * worst);
}

TEST(Daylight, BadSkiesAndGlassAreNamed) {
  test::TempDir dir;
  auto message = [&](const std::string& sky) {
    try {
      sky_from(dir, sky, {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"type": "cie"})").find("needs \"number\""), std::string::npos);
  EXPECT_NE(message(R"({"type": "cie", "number": 16})").find("from 1 to 15"), std::string::npos);
  EXPECT_NE(message(R"({"type": "cie", "number": 12})").find("give \"sun\""), std::string::npos);
  EXPECT_NE(message(R"({"cloudy": true})").find("unknown key \"cloudy\" in sky"), std::string::npos);
  EXPECT_NE(message(R"({"sun": {"latitude": 48, "longitude": 16, "time": "2026-06-21T12:00"}})").find("\"timezone\""),
            std::string::npos);
  EXPECT_NE(message(R"({"sun": {"latitude": 48, "longitude": 16, "time": "noon", "timezone": 1}})").find("sky.sun.time"),
            std::string::npos);
  EXPECT_NE(message(R"({"horizontal_illuminance": 10000, "zenith_luminance": 3000})").find("one of"),
            std::string::npos);
  // Glass in a scene file and in an MTL.
  dir.write("pane.obj", "mtllib pane.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\n"
                        "usemtl wall\nf 1 2 3 4\nf 1 2 6 5\nusemtl glass\nf 4 3 7\n");
  dir.write("pane.mtl", "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl glass\nKd 0 0 0\nd 0.2\nTf 0.5 1 1\n");
  const LoadedScene pane = load_scene(dir.path("pane.obj"));
  ASSERT_EQ(pane.glazing.size(), 1u);
  EXPECT_NEAR(pane.glazing[0].transmittance.r, 0.4, 1e-6);
  EXPECT_NEAR(pane.glazing[0].transmittance.g, 0.8, 1e-6);
  EXPECT_EQ(pane.mesh->face_count(), 4u);  // two quads, the glass left out
  // Found by fuzzing (2026-12-04): a glass face naming a corner twice in a row, or its
  // first corner again at the end, stopped the triangulation on a failed CGAL
  // precondition (a constraint from a vertex to itself). Each is one corner.
  dir.write("repeat.obj", "mtllib pane.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\n"
                          "v 0 1 1\nusemtl wall\nf 1 2 3 4\nf 1 2 6 5\nusemtl glass\nf 4 3 7 8 4\nf 5 6 6 7\n");
  const LoadedScene repeat = load_scene(dir.path("repeat.obj"));
  double glass_area = 0;
  for (const auto& pane_triangle : repeat.glazing) {
    const auto& c = pane_triangle.corners;
    glass_area += 0.5 * OpenMesh::cross(c[1] - c[0], c[2] - c[0]).norm();
  }
  EXPECT_EQ(repeat.glazing.size(), 3u);  // the quad's two triangles and the triangle
  EXPECT_NEAR(glass_area, 1.5, 1e-12);
  const std::string bad = dir.write(
      "bad.json", "{\"meshes\": [{\"file\": \"pane.obj\"}], \"materials\": {\"glass\": {\"transmittance\": 1.2}}}");
  try {
    load_scene(bad);
    ADD_FAILURE() << "a transmittance above 1 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("transmittance"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dynrad
