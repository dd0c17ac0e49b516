// Daylight coefficients (radiosity/climate/sky_patches.h, daylight_coefficients.h): the
// patches tile the sky, a sky vector keeps a sky's light, and at points in a room the
// product of an hour's sky vector with the coefficients is the direct computation of
// that hour's sky.
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "radiosity/climate/coefficient_solve.h"
#include "radiosity/climate/daylight_coefficients.h"
#include "radiosity/climate/sky_patches.h"
#include "radiosity/climate/vertex_coefficients.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/analysis/grid.h"
#include "radiosity/analysis/lit_scene.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/solver/settings.h"
#include "radiosity/solver/solver.h"
#include "radiosity/sources/sky.h"
#include "radiosity/transfer/visibility.h"
#include "test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace dynrad {
namespace {

TEST(SkyPatches, TregenzaAndReinhartCountsAndTheyTileTheSky) {
  for (const auto& [n, count] : std::vector<std::pair<int, std::size_t>>{{1, 145}, {2, 577}, {4, 2305}}) {
    const rad::SkyPatches patches(n, Vec3d(0, 0, 1), Vec3d(0, 1, 0));
    EXPECT_EQ(patches.size(), count);
    double solid = 0, projected = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      solid += patches.solid_angle(i);
      projected += patches.projected_solid_angle(i);
      EXPECT_EQ(patches.index(patches.centre(i)), i) << "MF:" << n << " patch " << i;
    }
    EXPECT_NEAR(solid, 2 * M_PI, 1e-9);
    EXPECT_NEAR(projected, M_PI, 1e-9);
  }
  // Directions map to the patch whose bounds hold them; the first patch is centred on
  // north and the next is east of it; below the horizon is the ground.
  const rad::SkyPatches t(1, Vec3d(0, 0, 1), Vec3d(0, 1, 0));
  EXPECT_EQ(t.index(Vec3d(0, 1, 0.01).normalized()), 0u);
  EXPECT_EQ(t.index(Vec3d(0.2, 1, 0.01).normalized()), 1u);   // 11 degrees east of north: the next
  EXPECT_EQ(t.index(Vec3d(-0.2, 1, 0.01).normalized()), 29u);  // and west of it: the row's last
  EXPECT_EQ(t.index(Vec3d(0, 0, 1)), 144u);
  EXPECT_EQ(t.index(Vec3d(1, 0, -0.1).normalized()), t.ground());
  std::uint64_t state = 7;
  for (int k = 0; k < 20000; ++k) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double u = static_cast<double>(state >> 11) / 9007199254740992.0;
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double v = static_cast<double>(state >> 11) / 9007199254740992.0;
    const double altitude = std::asin(u), azimuth = 2 * M_PI * v;
    const std::size_t i = t.index(t.direction(altitude, azimuth));
    const rad::SkyPatches::Bounds b = t.bounds(i);
    EXPECT_GE(altitude, b.altitude0 - 1e-12);
    EXPECT_LE(altitude, b.altitude1 + 1e-12);
    if (i != 144) {
      const double a = std::remainder(azimuth - (b.azimuth0 + b.azimuth1) / 2, 2 * M_PI);
      EXPECT_LE(std::abs(a), (b.azimuth1 - b.azimuth0) / 2 + 1e-12);
    }
  }
  // A north other than +y turns the numbering with it.
  const rad::SkyPatches turned(1, Vec3d(0, 0, 1), Vec3d(1, 0, 0));
  EXPECT_EQ(turned.index(Vec3d(1, 0, 0.01).normalized()), 0u);
  EXPECT_EQ(turned.index(Vec3d(1, -0.2, 0.01).normalized()), 1u);  // east is north x up = -y
  EXPECT_EQ(turned.index(Vec3d(0.2, -1, 0.01).normalized()), 7u);  // 79 degrees east: 78-90
}

// A patch holds its mean luminance; its light on a horizontal plane is then that times
// its projected solid angle, which is off where the luminance changes across the patch
// (by 0.4% for the overcast sky's Tregenza patches, a quarter of that at MF:2).
TEST(SkyPatches, SkyVectorKeepsTheSkysHorizontalIlluminance) {
  for (const int n : {1, 2}) {
    const rad::SkyPatches patches(n);
    rad::SkyModel overcast;
    overcast.type = rad::SkyModel::Type::cie_overcast;
    overcast.zenith_luminance = 1000;
    overcast.ground_luminance = 123;
    const std::vector<double> v = rad::sky_vector(patches, overcast);
    ASSERT_EQ(v.size(), patches.size() + 1);
    EXPECT_EQ(v.back(), 123);
    double horizontal = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) horizontal += v[i] * patches.projected_solid_angle(i);
    const double bound = 0.005 / (n * n);
    EXPECT_NEAR(horizontal / (7 * M_PI * 1000 / 9), 1, bound) << "MF:" << n;
    rad::SkyModel clear;
    clear.type = rad::SkyModel::Type::cie;
    clear.cie_type = 12;
    clear.sun = Vec3d(0.3, -0.6, 0.74).normalized();
    const std::vector<double> c = rad::sky_vector(patches, clear);
    horizontal = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) horizontal += c[i] * patches.projected_solid_angle(i);
    EXPECT_NEAR(horizontal / clear.horizontal_illuminance(), 1, bound) << "MF:" << n;
  }
}

// A 4 x 5 x 3 room of grey walls whose south facade (y = 0) has a 2 x 1.2 m window
// over (1, 0.9)-(3, 2.1), glazed at 0.8, under a 4 m x 1 m overhang at 2.4 m: points
// see the sky through the glass, past the overhang, and the ground.
std::string south_room(const test::TempDir& dir, const std::string& sky) {
  std::string obj = "mtllib room.mtl\nusemtl grey\n";
  int v = 0;
  auto quad = [&](std::array<Vec3d, 4> c) {
    for (const Vec3d& p : c) obj += fmt::format("v {} {} {}\n", p[0], p[1], p[2]);
    obj += fmt::format("f {} {} {} {}\n", v + 1, v + 2, v + 3, v + 4);
    v += 4;
  };
  quad({Vec3d(0, 0, 0), Vec3d(4, 0, 0), Vec3d(4, 5, 0), Vec3d(0, 5, 0)});  // floor, up
  quad({Vec3d(0, 0, 3), Vec3d(0, 5, 3), Vec3d(4, 5, 3), Vec3d(4, 0, 3)});  // ceiling, down
  quad({Vec3d(0, 0, 0), Vec3d(0, 5, 0), Vec3d(0, 5, 3), Vec3d(0, 0, 3)});  // west wall, +x
  quad({Vec3d(4, 0, 0), Vec3d(4, 0, 3), Vec3d(4, 5, 3), Vec3d(4, 5, 0)});  // east wall, -x
  quad({Vec3d(0, 5, 0), Vec3d(4, 5, 0), Vec3d(4, 5, 3), Vec3d(0, 5, 3)});  // north wall, -y
  auto facade = [&](double x0, double z0, double x1, double z1) {            // facing +y
    quad({Vec3d(x0, 0, z0), Vec3d(x0, 0, z1), Vec3d(x1, 0, z1), Vec3d(x1, 0, z0)});
  };
  facade(0, 0, 1, 3);
  facade(3, 0, 4, 3);
  facade(1, 0, 3, 0.9);
  facade(1, 2.1, 3, 3);
  quad({Vec3d(0, -1, 2.4), Vec3d(0, 0, 2.4), Vec3d(4, 0, 2.4), Vec3d(4, -1, 2.4)});  // overhang, down
  obj += "usemtl glass\n";
  quad({Vec3d(1, 0, 0.9), Vec3d(1, 0, 2.1), Vec3d(3, 0, 2.1), Vec3d(3, 0, 0.9)});
  dir.write("room.obj", obj);
  dir.write("room.mtl", "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl glass\nKd 0 0 0\nd 0.2\n");
  return dir.write("room.json", R"({"meshes": [{"file": "room.obj"}], "sky": )" + sky + "}");
}

TEST(DaylightCoefficients, AnHoursSkyVectorTimesTheCoefficientsIsItsDirectSky) {
  test::TempDir dir;
  const std::vector<std::string> skies = {
      R"({"type": "cie_overcast", "horizontal_illuminance": 10000, "ground_reflectance": 0.2})",
      R"({"type": "cie", "number": 12, "horizontal_illuminance": 12000, "ground_reflectance": 0.2,
          "sun": {"altitude": 35, "azimuth": 160, "direct_normal": 60000}})",
      R"({"type": "cie", "number": 7, "horizontal_illuminance": 20000, "ground_reflectance": 0.2,
          "sun": {"altitude": 60, "azimuth": 200, "direct_normal": 40000}})",
      R"({"type": "cie", "number": 13, "horizontal_illuminance": 15000, "ground_reflectance": 0.2,
          "sun": {"altitude": 15, "azimuth": 120, "direct_normal": 30000}})",
  };
  // The geometry is the same for every sky: one set of coefficients per point.
  const std::string first = south_room(dir, skies[0]);
  const LoadedScene room = load_scene(dir.path("room.obj"));
  ASSERT_FALSE(room.glazing.empty());
  const rad::Visibility visibility(*room.mesh);
  const auto sources = rad::read_daylight(first, room.glazing, room.openings);
  std::vector<Vec3d> points;
  for (double y : {0.25, 0.75, 1.5, 2.5, 4.0})
    for (double x : {0.3, 1.0, 2.0, 3.4}) points.emplace_back(x, y, 0.85);
  const Vec3d up(0, 0, 1);
  for (const int n : {1, 2, 4}) {
    const rad::SkyPatches patches(n);
    std::vector<rad::SkyCoefficients> coefficients;
    for (const Vec3d& p : points)
      coefficients.push_back(rad::direct_sky_coefficients(visibility, sources.back(), patches, p, up, 48));
    double worst = 0;
    for (const std::string& sky : skies) {
      const auto hour = rad::read_daylight(south_room(dir, sky), room.glazing, room.openings);
      const rad::Luminaire& hour_sky = hour.back();
      const std::vector<double> vector = rad::sky_vector(patches, hour_sky.daylight->sky);
      for (std::size_t k = 0; k < points.size(); ++k) {
        const double exact = rad::daylight_illuminance(&visibility, hour_sky, points[k], up, nullptr, 48);
        const double product = coefficients[k].illuminance(vector);
        worst = std::max(worst, std::abs(product / exact - 1));
        if (n == 4) {
          EXPECT_NEAR(product / exact, 1, 0.01) << sky << " at " << points[k];
        }
      }
    }
    std::printf("direct sky from MF:%d coefficients: worst %.3f%% over %zu points and %zu skies\n", n, 100 * worst,
                points.size(), skies.size());
  }
}

// A solve of `luminaires` in the room of `obj` (grey: the coefficients' condition), to
// 0.4% unshot, at annual daylight's patch size; with `channels`, carrying them.
struct Solved {
  LoadedScene scene;
  std::unique_ptr<ElementHierarchy> hierarchy;
  std::unique_ptr<rad::Solver> solver;
  rad::Solver::Output output;
  rad::LitScene lit;
};
std::unique_ptr<Solved> solve_room(const std::string& obj, std::vector<rad::Luminaire> luminaires,
                                   const std::function<rad::Solver::CoefficientChannels(const rad::Visibility&)>& channels,
                                   double converge = 0.004) {
  auto out = std::make_unique<Solved>();
  out->scene = load_scene(obj);
  SceneMesh& mesh = *out->scene.mesh;
  rad::RefineSettings refine;
  rad::SolveOptions options;
  rad::SettingsRequest request;
  request.converge = converge;
  request.patch_scale = rad::CoefficientOptions{}.patch_factor;  // annual daylight's patch size, for both
  const rad::AppliedSettings applied = rad::apply_settings(mesh, request, refine, options);
  options.emission_scale = rad::kLumensPerWatt;
  options.min_reflectance = 1e-4;
  make_patches(mesh, applied.patch_size);
  out->hierarchy = std::make_unique<ElementHierarchy>(mesh, refinement_for_patch_size(applied.patch_size));
  out->solver = std::make_unique<rad::Solver>(mesh, *out->hierarchy, options, refine, luminaires);
  std::unique_ptr<rad::Visibility> visibility;
  if (channels) {
    visibility = std::make_unique<rad::Visibility>(mesh);
    out->solver->carry_coefficients(channels(*visibility));
  }
  out->solver->run();
  out->output = out->solver->output();
  out->lit = rad::lit_scene(mesh, out->output.split, out->output.radiosity, luminaires, options.emission_scale, true);
  return out;
}

// The channels carry the steering sky's own light: weighted by its luminances (1 per sky
// patch, its ground's for the ground, 0 for the suns), a point's coefficients give the
// steering solve's own gather, direct and indirect, whatever the solve's accuracy (a
// short solve: this runs sanitized too).
TEST(DaylightCoefficients, TheSteeringSkyThroughItsChannelsIsItsOwnSolve) {
  test::TempDir dir;
  south_room(dir, R"({"type": "cie_overcast"})");
  const std::string obj = dir.path("room.obj");
  const LoadedScene room = load_scene(obj);
  const auto scene_sky = rad::read_daylight(dir.path("room.json"), room.glazing, room.openings).back();
  const rad::CoefficientOptions options;
  const rad::Luminaire steering = rad::steering_sky(scene_sky.daylight->glazing, Vec3d(0, 0, 1), options.steering_ground);
  const rad::SkyPatches fine(options.fine_subdivision), indirect(options.indirect_subdivision);
  std::vector<rad::SunNodes> nodes;
  const std::vector<Vec3d> suns =
      rad::sun_positions(indirect, options.sun_spacing, {Vec3d(0.3, -0.7, 0.6).normalized()}, &nodes);
  ASSERT_EQ(suns.size(), 4u);  // the corners of its cell
  const auto solved = solve_room(
      obj, {steering},
      [&](const rad::Visibility& v) { return rad::coefficient_channels(v, steering, indirect, suns, options); }, 0.05);
  EXPECT_EQ(solved->solver->coefficient_count(), indirect.size() + 1 + suns.size());
  const rad::HourSky uniform = rad::hour_sky(steering.daylight->sky, Vec3d(0, 0, 1), 0, fine, indirect, {});
  rad::GatherOptions gather;
  gather.side = 16;
  rad::CoefficientOptions at_points = options;
  at_points.point_side = 16;
  double sun_light = 0;
  for (double y : {0.5, 2.5, 4.5})
    for (double x : {0.5, 3.5}) {
      const Vec3d p(x, y, 0.85), up(0, 0, 1);
      const rad::PointCoefficients c = rad::point_coefficients(solved->lit, *solved->scene.mesh, *solved->solver,
                                                               steering, fine, indirect, p, up, at_points, 7);
      const rad::GridPointResult g = rad::gather_point(solved->lit, p, up, gather, 7);
      const rad::HourIlluminance e = rad::hour_illuminance(c, uniform, 0);
      EXPECT_NEAR(e.indirect / g.indirect, 1, 1e-4) << p;
      EXPECT_NEAR(e.sky_direct / g.direct, 1, 0.01) << p;
      for (std::size_t k = 0; k < suns.size(); ++k) sun_light += c.indirect[indirect.size() + 1 + k];
    }
  EXPECT_GT(sun_light, 0);  // the suns' light came in through the window and was carried
  // At the vertices too: the steering sky through their coefficients is the solve's own
  // radiosity there; the suns' channels carry light (their interreflection) but no
  // vertex on the ceiling holds a sun's direct light, which a shadow ray gives instead.
  const rad::VertexCoefficients vertices =
      rad::vertex_coefficients(*solved->scene.mesh, *solved->solver, solved->output, indirect.size() + 1,
                               options.steering_ground);
  ASSERT_EQ(vertices.size(), solved->output.radiosity.size());
  ASSERT_EQ(vertices.count, solved->solver->coefficient_count());
  const std::vector<double> steered = rad::vertex_hour(vertices, uniform, *solved->lit.visibility, nullptr);
  double worst = 0, ceiling_sun = 0, sun_interreflected = 0;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const double own = solved->output.radiosity[v].luminance();
    if (own > 0) worst = std::max(worst, std::abs(steered[v] / own - 1));
    for (std::size_t k = indirect.size() + 1; k < vertices.count; ++k) {
      sun_interreflected += vertices.at(v)[k];
      if (vertices.point[v][2] > 2.99) ceiling_sun = std::max(ceiling_sun, double(vertices.at(v)[k]));
    }
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(sun_interreflected, 0);
  // The ceiling sees no sun; all its sun light is interreflected, and small: per lx of
  // direct normal sun, well below what a floor in the sun would reflect (0.5 x cos).
  EXPECT_GT(ceiling_sun, 0);
  EXPECT_LT(ceiling_sun, 0.05);
}

// The south room's surfaces inside (not the glass, not the overhang and the facade's
// outside): each one's mean of a per-vertex value over its triangles, by area.
std::map<std::string, double> surface_means(const rad::LitScene& lit, const std::vector<double>& value) {
  std::map<std::string, std::pair<double, double>> sum;
  for (const auto& t : lit.triangles) {
    const Vec3d& a = lit.positions[t[0]];
    const Vec3d& b = lit.positions[t[1]];
    const Vec3d& c = lit.positions[t[2]];
    const Vec3d centre = (a + b + c) / 3.0, cross = OpenMesh::cross(b - a, c - a);
    const double area = cross.norm() / 2;
    const Vec3d n = cross.normalized();
    std::string name;
    if (centre[1] < 1e-6 && n[1] < 0.5) continue;  // outside, the overhang or the glass's back
    if (n[2] > 0.9) name = "floor";
    else if (n[2] < -0.9) name = "ceiling";
    else if (n[0] > 0.9) name = "west wall";
    else if (n[0] < -0.9) name = "east wall";
    else if (n[1] < -0.9) name = "north wall";
    else if (n[1] > 0.9 && !(centre[0] > 1 && centre[0] < 3 && centre[2] > 0.9 && centre[2] < 2.1)) name = "facade";
    else continue;
    sum[name].first += area * (value[t[0]] + value[t[1]] + value[t[2]]) / 3;
    sum[name].second += area;
  }
  std::map<std::string, double> out;
  for (const auto& [name, s] : sum) out[name] = s.first / s.second;
  return out;
}

// The issue's test: the coefficients of one solve, for several hours (skies with and
// without the sun), against a solve of each hour's own sky and sun, at every grid point.
TEST(DaylightCoefficients, OneSolvesCoefficientsGiveEachHoursOwnSolve) {
  test::TempDir dir;
  const std::string overcast = R"({"type": "cie_overcast", "horizontal_illuminance": 10000, "ground_reflectance": 0.2})";
  const std::vector<std::string> hours = {
      overcast,
      R"({"type": "cie", "number": 12, "horizontal_illuminance": 12000, "ground_reflectance": 0.2,
          "sun": {"altitude": 35, "azimuth": 160, "direct_normal": 60000}})",
      R"({"type": "cie", "number": 7, "horizontal_illuminance": 20000, "ground_reflectance": 0.2,
          "sun": {"altitude": 60, "azimuth": 200, "direct_normal": 40000}})",
  };
  south_room(dir, overcast);
  const std::string obj = dir.path("room.obj");
  const LoadedScene room = load_scene(obj);
  const auto scene_sky = rad::read_daylight(dir.path("room.json"), room.glazing, room.openings).back();
  const rad::CoefficientOptions options;
  const rad::Luminaire steering = rad::steering_sky(scene_sky.daylight->glazing, Vec3d(0, 0, 1), options.steering_ground);
  const rad::SkyPatches fine(options.fine_subdivision), indirect(options.indirect_subdivision);
  // The sun positions of the hours.
  std::vector<Vec3d> hour_suns;
  std::vector<std::vector<rad::Luminaire>> hour_sources;
  for (const std::string& sky : hours) {
    dir.write("room.json", R"({"meshes": [{"file": "room.obj"}], "sky": )" + sky + "}");
    hour_sources.push_back(rad::read_daylight(dir.path("room.json"), room.glazing, room.openings));
    hour_suns.push_back(hour_sources.back().size() > 1 ? hour_sources.back().back().daylight->sun : Vec3d(0, 0, -1));
  }
  std::vector<rad::SunNodes> hour_nodes;
  const std::vector<Vec3d> suns = rad::sun_positions(indirect, options.sun_spacing, hour_suns, &hour_nodes);
  const auto coefficient_solve = solve_room(obj, {steering}, [&](const rad::Visibility& v) {
    return rad::coefficient_channels(v, steering, indirect, suns, options);
  });
  std::vector<Vec3d> points;
  for (double y : {0.5, 1.5, 2.5, 4.0})
    for (double x : {0.5, 2.0, 3.5}) points.emplace_back(x, y, 0.85);
  const Vec3d up(0, 0, 1);
  std::vector<rad::PointCoefficients> coefficients;
  for (std::size_t k = 0; k < points.size(); ++k)
    coefficients.push_back(rad::point_coefficients(coefficient_solve->lit, *coefficient_solve->scene.mesh,
                                                   *coefficient_solve->solver, steering, fine, indirect, points[k], up,
                                                   options, 0x5eedull + k));
  // The steering sky itself, through the coefficients, is the steering solve's gather.
  {
    rad::HourSky uniform = rad::hour_sky(steering.daylight->sky, up, 0, fine, indirect, {});
    rad::GatherOptions gather;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const rad::GridPointResult g = rad::gather_point(coefficient_solve->lit, points[k], up, gather, 0x5eedull + k);
      const rad::HourIlluminance e = rad::hour_illuminance(coefficients[k], uniform, 0);
      EXPECT_NEAR(e.indirect / g.indirect, 1, 1e-4) << points[k];
      EXPECT_NEAR(e.sky_direct / g.direct, 1, 0.003) << points[k];
    }
  }
  const rad::VertexCoefficients vertices =
      rad::vertex_coefficients(*coefficient_solve->scene.mesh, *coefficient_solve->solver, coefficient_solve->output,
                               indirect.size() + 1, options.steering_ground);
  double worst = 0, worst_indirect = 0, worst_surface = 0;
  for (std::size_t h = 0; h < hours.size(); ++h) {
    const std::string& sky = hours[h];
    const auto& sources = hour_sources[h];
    const auto own = solve_room(obj, sources, nullptr);
    const rad::Daylight& day = *sources.back().daylight;
    const double sun = sources.size() > 1 ? day.direct_normal : 0.0;
    const rad::HourSky hour = rad::hour_sky(day.sky, day.sun, sun, fine, indirect, hour_nodes[h]);
    rad::GatherOptions gather;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const rad::GridPointResult g = rad::gather_point(own->lit, points[k], up, gather, 0x5eedull + k);
      const double sun_direct = rad::sun_illuminance(*coefficient_solve->lit.visibility, day.glazing.get(), points[k],
                                                     up, day.sun, sun);
      const rad::HourIlluminance e = rad::hour_illuminance(coefficients[k], hour, sun_direct);
      worst = std::max(worst, std::abs(e.total / g.illuminance - 1));
      worst_indirect = std::max(worst_indirect, std::abs(e.indirect / g.indirect - 1));
      EXPECT_NEAR(e.total / g.illuminance, 1, 0.01) << sky << " at " << points[k] << ": direct " << g.direct
                                                    << " vs " << e.sun + e.sky_direct << ", indirect " << g.indirect
                                                    << " vs " << e.indirect;
    }
    // The model itself: each surface's mean radiosity from the vertices' coefficients
    // against the hour's own solve (the meshes differ: each solve refined its own).
    const std::vector<double> at_vertices =
        rad::vertex_hour(vertices, hour, *coefficient_solve->lit.visibility, day.glazing.get());
    std::vector<double> own_values(own->lit.radiosity.size());
    for (std::size_t v = 0; v < own_values.size(); ++v) own_values[v] = own->lit.radiosity[v].luminance();
    const auto from_coefficients = surface_means(coefficient_solve->lit, at_vertices);
    const auto from_own = surface_means(own->lit, own_values);
    for (const auto& [name, mean] : from_own) {
      const double ratio = from_coefficients.at(name) / mean;
      std::printf("  hour %zu, %s: mean radiosity %.2f from the coefficients, %.2f from its own solve (%+.2f%%)\n", h,
                  name.c_str(), from_coefficients.at(name), mean, 100 * (ratio - 1));
      worst_surface = std::max(worst_surface, std::abs(ratio - 1));
      EXPECT_NEAR(ratio, 1, 0.025) << sky << ": " << name;
    }
  }
  std::printf("the model's surfaces from vertex coefficients: worst mean %.3f%%\n", 100 * worst_surface);
  std::printf("coefficients of one solve against each hour's solve: worst %.3f%% (indirect alone %.3f%%) over %zu "
              "points and %zu hours\n",
              100 * worst, 100 * worst_indirect, points.size(), hours.size());
}

}  // namespace
}  // namespace dynrad
