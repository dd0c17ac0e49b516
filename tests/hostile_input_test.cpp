// Hostile geometry through the command line (docs/import-and-repair.md, "Hostile input"): each case must
// finish without a crash, write no NaN, keep the energy balance (emitted = absorbed +
// escaped + unshot), and do what that page says it does.
#include "test_support.h"

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace dynrad {
namespace {

using json = nlohmann::json;
using test::TempDir;

// ---------------------------------------------------------------------------
// Generated models.

struct ObjBuilder {
  std::ostringstream obj, mtl;
  std::size_t vertices = 0;
  double scale = 1;
  Vec3d offset{0.0};

  ObjBuilder() {
    obj.precision(17);
    obj << "mtllib model.mtl\n";
    material("wall", 0.5, 0);
    material("lamp", 0.2, 10);
  }
  void material(const std::string& name, double reflectance, double emission) {
    mtl << "newmtl " << name << "\nKd " << reflectance << " " << reflectance << " " << reflectance << "\n";
    if (emission > 0) mtl << "Ke " << emission << " " << emission << " " << emission << "\n";
  }
  std::size_t vertex(double x, double y, double z) {
    obj << "v " << offset[0] + scale * x << " " << offset[1] + scale * y << " " << offset[2] + scale * z << "\n";
    return ++vertices;
  }
  // A polygon through the given points, counter-clockwise seen from its front.
  void face(const std::string& material, const std::vector<Vec3d>& corners) {
    std::vector<std::size_t> ids;
    for (const Vec3d& c : corners) ids.push_back(vertex(c[0], c[1], c[2]));
    obj << "usemtl " << material << "\nf";
    for (auto id : ids) obj << " " << id;
    obj << "\n";
  }
  // The unit room's six walls, facing in (or out), and a lamp panel below the ceiling
  // facing down (or up).
  void room(bool inward = true, const std::string& material = "wall") {
    const std::vector<std::vector<Vec3d>> walls = {
        {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}},
        {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}},
        {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}};
    for (auto w : walls) {
      if (!inward) std::reverse(w.begin(), w.end());
      face(material, w);
    }
  }
  void lamp(bool down = true) {
    std::vector<Vec3d> panel = {{0.4, 0.4, 0.9}, {0.4, 0.6, 0.9}, {0.6, 0.6, 0.9}, {0.6, 0.4, 0.9}};
    if (!down) std::reverse(panel.begin(), panel.end());
    face("lamp", panel);
  }
  std::string write(const TempDir& dir, const std::string& name = "model") const {
    dir.write("model.mtl", mtl.str());
    return dir.write(name + ".obj", obj.str());
  }
};

// ---------------------------------------------------------------------------
// Running a solve and reading what it wrote.

using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<>;

struct Solution {
  test::CommandResult run;
  json report;
  std::vector<Rgb> radiosity;  // per output vertex
  std::vector<Vec3d> position;
};

std::vector<Rgb> read_radiosity(const std::string& path, std::vector<Vec3d>* positions = nullptr) {
  ReadMesh mesh;
  OpenMesh::IO::Options io = OpenMesh::IO::Options::Custom;
  EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, path, io)) << path;
  OpenMesh::VPropHandleT<float> channel[3];
  const char* names[3] = {"radiosity_r", "radiosity_g", "radiosity_b"};
  std::vector<Rgb> out;
  for (int c = 0; c < 3; ++c)
    if (!mesh.get_property_handle(channel[c], names[c])) {
      ADD_FAILURE() << path << " has no " << names[c];
      return out;
    }
  for (auto v : mesh.vertices()) {
    out.emplace_back(mesh.property(channel[0], v), mesh.property(channel[1], v), mesh.property(channel[2], v));
    if (positions) positions->push_back(Vec3d(mesh.point(v)));
  }
  return out;
}

Solution solve(const TempDir& dir, const std::string& input, const std::string& options) {
  Solution s;
  const std::string out = dir.path("lit.ply"), report = dir.path("report.json");
  std::filesystem::remove(out);
  std::filesystem::remove(report);
  s.run = test::run_dynrad("solve '" + input + "' -o '" + out + "' --report '" + report + "' " + options);
  if (s.run.exit_code != 0) return s;
  s.report = json::parse(test::read_text(report));
  s.radiosity = read_radiosity(out, &s.position);
  return s;
}

Rgb channel_array(const json& j) { return Rgb(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

// No NaN anywhere, nothing negative, and every watt accounted for.
void expect_sane(const Solution& s) {
  ASSERT_EQ(s.run.exit_code, 0) << s.run.output;
  ASSERT_FALSE(s.radiosity.empty());
  for (const Rgb& b : s.radiosity) {
    ASSERT_TRUE(b.is_finite());
    ASSERT_GE(b.min_channel(), 0.0);
  }
  const json& e = s.report["energy"];
  const Rgb emitted = channel_array(e["emitted"]), absorbed = channel_array(e["absorbed"]),
            escaped = channel_array(e["escaped"]), unshot = channel_array(e["unshot"]);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(emitted[c], 0.0);
    EXPECT_NEAR(absorbed[c] + escaped[c] + unshot[c], emitted[c], 1e-9 * emitted[c]) << "channel " << c;
    EXPECT_GE(absorbed[c], 0.0);
    EXPECT_GE(escaped[c], 0.0);
    EXPECT_GE(unshot[c], 0.0);
  }
}

double mean_green(const std::vector<Rgb>& values) {
  double sum = 0;
  for (const Rgb& b : values) sum += b.g;
  return values.empty() ? 0 : sum / values.size();
}

json info(const std::string& input) {
  const auto r = test::run_dynrad("info --json '" + input + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return r.exit_code == 0 ? json::parse(r.output.substr(r.output.find('{'))) : json();
}

// ---------------------------------------------------------------------------

TEST(HostileInput, ZeroAreaAndSliverFacesAreDroppedOrLit) {
  TempDir dir;
  ObjBuilder model;
  model.room();
  model.lamp();
  // Zero area: collinear corners, a repeated corner, all corners in one point.
  model.face("wall", {{0.1, 0.1, 0.5}, {0.5, 0.1, 0.5}, {0.9, 0.1, 0.5}});
  model.face("wall", {{0.2, 0.3, 0.4}, {0.2, 0.3, 0.4}, {0.3, 0.3, 0.4}});
  model.face("wall", {{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}});
  // Slivers with area but almost no width, facing up: a needle across the room and a
  // thin wedge.
  model.face("wall", {{0.05, 0.5, 0.3}, {0.95, 0.5, 0.3}, {0.5, 0.5 + 1e-7, 0.3}});
  model.face("wall", {{0.2, 0.2, 0.2}, {0.8, 0.2, 0.2}, {0.8, 0.2 + 1e-5, 0.2}});
  const std::string input = model.write(dir);
  const json counts = info(input);
  EXPECT_EQ(counts["repairs"]["degenerate_polygons"].get<int>(), 3) << counts.dump(2);
  for (const char* method : {"progressive", "dynamic"}) {
    const Solution s = solve(dir, input, std::string("--iterations 60 --method ") + method);
    expect_sane(s);
    // The slivers face the lamp: they are lit like the floor below them.
    EXPECT_GT(mean_green(s.radiosity), 0.0);
  }
}

TEST(HostileInput, ExactDuplicatesAreDroppedAndCoincidentSurfacesShareTheLight) {
  TempDir dir;
  ObjBuilder plain;
  plain.room();
  plain.lamp();
  const Solution reference = solve(dir, plain.write(dir, "plain"), "--iterations 80");
  expect_sane(reference);

  // The floor twice more: once with the same corners (an exact duplicate), once as a
  // separate copy of the same polygon. Both are duplicates after merging points.
  ObjBuilder doubled;
  doubled.room();
  doubled.lamp();
  doubled.face("wall", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  doubled.obj << "f 17 18 19 20\n";  // the floor's own vertices (the fifth wall's)
  const std::string input = doubled.write(dir, "doubled");
  EXPECT_EQ(info(input)["repairs"]["duplicate_triangles"].get<int>(), 4);
  const Solution twice = solve(dir, input, "--iterations 80");
  expect_sane(twice);
  ASSERT_EQ(twice.radiosity.size(), reference.radiosity.size());
  for (std::size_t v = 0; v < twice.radiosity.size(); ++v) EXPECT_EQ(twice.radiosity[v], reference.radiosity[v]);

  // Half the floor again with other corners: whichever surface stays where they
  // coincide (imprinting keeps the smaller; cleanup's T-junction repair can make the two
  // identical, and one copy is dropped), the floor is lit and no brighter than one.
  ObjBuilder overlap;
  overlap.room();
  overlap.lamp();
  overlap.face("wall", {{0, 0, 0}, {0.5, 0, 0}, {0.5, 1, 0}, {0, 1, 0}});
  const Solution shared = solve(dir, overlap.write(dir, "overlap"), "--iterations 80");
  expect_sane(shared);
  double floor_max = 0;
  for (std::size_t v = 0; v < shared.radiosity.size(); ++v)
    if (shared.position[v][2] == 0) floor_max = std::max(floor_max, double(shared.radiosity[v].g));
  double reference_floor_max = 0;
  for (std::size_t v = 0; v < reference.radiosity.size(); ++v)
    if (reference.position[v][2] == 0)
      reference_floor_max = std::max(reference_floor_max, double(reference.radiosity[v].g));
  EXPECT_GT(floor_max, 0.0);
  // Never brighter than the single floor: the copies do not create light.
  EXPECT_LE(floor_max, 1.05 * reference_floor_max);
}

// Backs are black (docs/scene-files.md, "Facing"): in a room modelled inside out, the lamp's light
// lands on the ceiling's back and is absorbed there. Nothing is lit, nothing escapes.
TEST(HostileInput, InsideOutRoomAbsorbsAllLightOnBlackBacks) {
  TempDir dir;
  ObjBuilder model;
  model.room(/*inward=*/false);
  model.lamp(/*down=*/false);  // points up, at the ceiling's back
  const Solution s = solve(dir, model.write(dir), "--method dynamic");
  expect_sane(s);
  const json& e = s.report["energy"];
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(e["absorbed"][c].get<double>(), e["emitted"][c].get<double>(), 1e-9 * e["emitted"][c].get<double>());
    EXPECT_EQ(e["escaped"][c].get<double>(), 0.0);
  }
  EXPECT_EQ(s.report["stopped_by"], "converged");
  // Nothing is reflected: once each lamp patch has shot, nothing is left to shoot.
  for (int c = 0; c < 3; ++c) EXPECT_EQ(e["unshot"][c].get<double>(), 0.0);
  // Walls see only the backs of other walls and of the lamp: all black.
  std::size_t walls = 0;
  for (std::size_t v = 0; v < s.radiosity.size(); ++v) {
    if (s.position[v][2] > 0.85 && s.position[v][2] < 0.95) continue;  // the lamp
    EXPECT_EQ(s.radiosity[v].g, 0.0f) << "vertex " << v;
    ++walls;
  }
  EXPECT_GT(walls, 0u);
}

TEST(HostileInput, OpenSceneAccountsForEscapedLight) {
  TempDir dir;
  ObjBuilder model;
  model.face("wall", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});  // a floor under the sky
  model.lamp();
  const Solution s = solve(dir, model.write(dir), "--converge 1e-4");
  expect_sane(s);
  const json& e = s.report["energy"];
  for (int c = 0; c < 3; ++c) {
    const double emitted = e["emitted"][c].get<double>(), escaped = e["escaped"][c].get<double>();
    // The lamp's light that misses the floor, and all the floor reflects, escapes.
    EXPECT_GT(escaped, 0.3 * emitted);
    EXPECT_GT(e["absorbed"][c].get<double>(), 0.1 * emitted);
  }
  EXPECT_EQ(s.report["stopped_by"], "converged");
}

// Radiosity (W/m²) does not depend on the model's units or position. Without refinement
// the meshes are the same, so the sorted vertex values must agree; with dynamic
// refinement, rounding may tip an oracle decision here and there, so the distribution
// is compared.
TEST(HostileInput, ScaleAndFarOffsetsGiveTheUnitScaleAnswer) {
  TempDir dir;
  auto run = [&](double scale, Vec3d offset, const std::string& options) {
    ObjBuilder model;
    model.scale = scale;
    model.offset = offset;
    model.room();
    model.lamp();
    Solution s = solve(dir, model.write(dir), options);
    expect_sane(s);
    return s;
  };
  auto sorted_green = [](const Solution& s) {
    std::vector<float> out;
    for (const Rgb& b : s.radiosity) out.push_back(float(b.g));
    std::sort(out.begin(), out.end());
    return out;
  };
  auto absorbed_fraction = [](const Solution& s) {
    return s.report["energy"]["absorbed"][1].get<double>() / s.report["energy"]["emitted"][1].get<double>();
  };
  const std::string progressive = "--iterations 60 --method progressive", dynamic = "--iterations 60 --method dynamic --max-level 2";
  const Solution unit = run(1, Vec3d(0.0), progressive), unit_dynamic = run(1, Vec3d(0.0), dynamic);
  const std::vector<float> unit_sorted = sorted_green(unit);
  // 1e-8 and 1e20 once lost most of the light through the walls: Embree saw the model
  // in its own units, where the ray offsets were far too large or too small.
  for (const auto& [scale, offset] :
       {std::pair{1e6, Vec3d(0.0)}, std::pair{1e-4, Vec3d(0.0)}, std::pair{1.0, Vec3d(1e6, -1e6, 1e6)},
        std::pair{1e-4, Vec3d(1e3, 0, 0)}, std::pair{1e-8, Vec3d(0.0)}, std::pair{1e20, Vec3d(0.0)}}) {
    SCOPED_TRACE("scale " + std::to_string(scale) + ", offset " + std::to_string(offset[0]));
    const Solution s = run(scale, offset, progressive);
    EXPECT_NEAR(absorbed_fraction(s), absorbed_fraction(unit), 1e-3);
    const std::vector<float> sorted = sorted_green(s);
    ASSERT_EQ(sorted.size(), unit_sorted.size());
    for (std::size_t v = 0; v < sorted.size(); ++v) ASSERT_NEAR(sorted[v], unit_sorted[v], 0.01 * unit_sorted.back());

    const Solution d = run(scale, offset, dynamic);
    EXPECT_NEAR(absorbed_fraction(d), absorbed_fraction(unit_dynamic), 1e-3);
    EXPECT_NEAR(double(d.radiosity.size()), double(unit_dynamic.radiosity.size()),
                0.02 * unit_dynamic.radiosity.size());
    EXPECT_NEAR(mean_green(d.radiosity), mean_green(unit_dynamic.radiosity), 0.01 * mean_green(unit_dynamic.radiosity));
  }
}

// Finite numbers whose products are not: refused before the solver computes with inf.
TEST(HostileInput, OverflowingEmissionOrSizeIsRefused) {
  TempDir dir;
  ObjBuilder hot;
  hot.scale = 100;  // the sun's 400 m² times 1e308 W/m²
  hot.material("sun", 0.1, 1e308);
  hot.room();
  hot.face("sun", {{0.4, 0.4, 0.9}, {0.4, 0.6, 0.9}, {0.6, 0.6, 0.9}, {0.6, 0.4, 0.9}});
  const auto r = test::run_dynrad("solve '" + hot.write(dir) + "' -o '" + dir.path("out.ply") + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("material 'sun'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("model.mtl:"), std::string::npos) << r.output;
  EXPECT_FALSE(test::file_exists(dir.path("out.ply")));

  ObjBuilder huge;
  huge.scale = 1e200;  // finite coordinates, but areas of 1e400
  huge.room();
  huge.lamp();
  const auto big = test::run_dynrad("solve '" + huge.write(dir) + "' -o '" + dir.path("out.ply") + "'");
  EXPECT_EQ(big.exit_code, 2) << big.output;
  EXPECT_NE(big.output.find("too large"), std::string::npos) << big.output;
  ObjBuilder tiny;
  tiny.scale = 1e-200;  // areas of 1e-400: zero
  tiny.room();
  tiny.lamp();
  const auto small = test::run_dynrad("solve '" + tiny.write(dir) + "' -o '" + dir.path("out.ply") + "'");
  EXPECT_EQ(small.exit_code, 2) << small.output;
  EXPECT_NE(small.output.find("too small"), std::string::npos) << small.output;
}

TEST(HostileInput, HundredThousandMaterialsLoadInSeconds) {
  TempDir dir;
  ObjBuilder model;
  model.room();
  model.lamp();
  // A carpet just above the floor, clear of the walls, as a 250 x 400 grid of quads with a material each.
  const int nx = 250, ny = 400;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) model.vertex(0.01 + 0.98 * i / nx, 0.01 + 0.98 * j / ny, 0.01);
  const std::size_t base = model.vertices - (nx + 1) * (ny + 1);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int m = j * nx + i;
      model.mtl << "newmtl tile" << m << "\nKd " << 0.1 + 0.8 * (m % 97) / 97.0 << " 0.4 0.4\n";
      const std::size_t a = base + 1 + j * (nx + 1) + i;
      model.obj << "usemtl tile" << m << "\nf " << a << " " << a + 1 << " " << a + nx + 2 << " " << a + nx + 1 << "\n";
    }
  const std::string input = model.write(dir);
  // Loading (read, cleanup, patches): about 2 s in a release build, 20 in a sanitizer
  // build; lookups by name that were quadratic took more than 5 minutes.
  const auto start = std::chrono::steady_clock::now();
  const json counts = info(input);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 100.0);
  EXPECT_EQ(counts["materials"].size(), std::size_t(nx * ny + 2));
  EXPECT_EQ(counts["faces"].get<int>(), 2 * (nx * ny + 7));
  // And the solve copes with them.
  const Solution s = solve(dir, input, "--iterations 1");
  expect_sane(s);
}

TEST(HostileInput, EmitterCoveringEverythingIsAFurnace) {
  TempDir dir;
  ObjBuilder model;
  model.material("glow", 0.5, 1);
  model.room(true, "glow");
  // Every surface emits E = 1 and reflects 0.5: B = E / (1 - 0.5) = 2 everywhere.
  const Solution s = solve(dir, model.write(dir), "--converge 1e-4 --patch-size 0.3");
  expect_sane(s);
  for (const Rgb& b : s.radiosity) ASSERT_NEAR(b.g, 2.0, 0.01 * 2.0);  // 1%: vertex discretisation, coarse patches
  const json& e = s.report["energy"];
  EXPECT_NEAR(e["escaped"][1].get<double>(), 0.0, 1e-9 * e["emitted"][1].get<double>());
}

TEST(HostileInput, ZeroAreaEmittersAreDroppedWithAWarning) {
  TempDir dir;
  ObjBuilder model;
  model.room();
  const std::string text = model.obj.str();
  const auto face_line = std::count(text.begin(), text.end(), '\n') + 5;    // after 3 `v` and a `usemtl`
  model.face("lamp", {{0.3, 0.3, 0.9}, {0.5, 0.5, 0.9}, {0.7, 0.7, 0.9}});  // a lamp modelled as a line
  const std::string input = model.write(dir);
  const auto r = test::run_dynrad("solve '" + input + "' -o '" + dir.path("out.ply") + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no face emits light"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 emitting face was dropped"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("model.obj:" + std::to_string(face_line)), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'lamp'"), std::string::npos) << r.output;
  EXPECT_FALSE(test::file_exists(dir.path("out.ply")));

  // With a real lamp as well, the solve goes ahead and still warns.
  model.lamp();
  const Solution s = solve(dir, model.write(dir), "--iterations 20");
  expect_sane(s);
  EXPECT_NE(s.run.output.find("1 emitting face was dropped"), std::string::npos) << s.run.output;
}

// ---------------------------------------------------------------------------
// Lenient where Blender, MeshLab and assimp are lenient (docs/import-and-repair.md, "Hostile input"): read
// with a warning naming the file and line or the material; --strict refuses.

constexpr auto npos = std::string::npos;

// 1-based line of the first `needle` in `text`.
std::size_t line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, npos) << needle;
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + std::min(at, text.size()), '\n'));
}

std::size_t occurrences(const std::string& text, const std::string& needle) {
  std::size_t count = 0;
  for (std::size_t at = text.find(needle); at != npos; at = text.find(needle, at + 1)) ++count;
  return count;
}

// The same vertices lit the same: two runs that must have read the same model.
void expect_same_light(const Solution& a, const Solution& b) {
  ASSERT_EQ(a.radiosity.size(), b.radiosity.size());
  for (std::size_t v = 0; v < a.radiosity.size(); ++v)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(a.radiosity[v][c], b.radiosity[v][c], 1e-6 * std::max(1.0, std::abs(b.radiosity[v][c])))
          << "vertex " << v << " channel " << c;
}

// A material of `info --json`, by name.
json material_named(const json& counts, const std::string& name) {
  for (const json& m : counts["materials"])
    if (m["name"] == name) return m;
  ADD_FAILURE() << "no material '" << name << "' in " << counts.dump(2);
  return json();
}

void expect_refused_strictly(const TempDir& dir, const std::string& input, const std::vector<std::string>& mentions) {
  const std::string out = dir.path("strict.ply");
  const auto r = test::run_dynrad("solve '" + input + "' -o '" + out + "' --strict");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const std::string& text : mentions) EXPECT_NE(r.output.find(text), npos) << r.output;
  EXPECT_FALSE(test::file_exists(out));
}

TEST(HostileInput, MissingMtlLibraryAndUndefinedMaterialsGetTheDefaultMaterial) {
  TempDir dir;
  ObjBuilder model;
  model.room(true, "plaster");  // six `usemtl plaster`, defined nowhere
  model.lamp();                 // defined in model.mtl
  std::string text = model.obj.str();
  text.insert(text.find('\n') + 1, "mtllib gone.mtl\n");  // line 2
  dir.write("model.mtl", model.mtl.str());
  const std::string input = dir.write("model.obj", text);

  const Solution s = solve(dir, input, "--iterations 40");
  expect_sane(s);
  const std::string& log = s.run.output;
  EXPECT_NE(log.find("model.obj:2: material library 'gone.mtl' not found (looked for " + dir.path("gone.mtl")), npos)
      << log;
  EXPECT_EQ(occurrences(log, "'plaster' is used but defined nowhere"), 1u) << log;
  EXPECT_NE(log.find("model.obj:" + std::to_string(line_of(text, "usemtl plaster")) + ": material 'plaster'"), npos)
      << log;
  const json plaster = material_named(info(input), "plaster");
  EXPECT_EQ(plaster["reflectance"], json({0.5, 0.5, 0.5}));
  EXPECT_EQ(plaster["emission"], json({0.0, 0.0, 0.0}));

  // The same light as with plaster defined as the default, grey 0.5.
  TempDir stated_dir;
  stated_dir.write("model.mtl", model.mtl.str());
  stated_dir.write("gone.mtl", "newmtl plaster\nKd 0.5 0.5 0.5\n");
  const Solution stated = solve(stated_dir, stated_dir.write("model.obj", text), "--iterations 40");
  expect_sane(stated);
  EXPECT_EQ(stated.run.output.find("defined nowhere"), npos) << stated.run.output;
  EXPECT_EQ(stated.run.output.find("not found"), npos) << stated.run.output;
  expect_same_light(s, stated);

  expect_refused_strictly(dir, input, {"model.obj:2", "gone.mtl", "not found"});
  dir.write("gone.mtl", "# plaster is still missing\n");
  expect_refused_strictly(dir, input, {"'plaster'", "defined nowhere"});
}

TEST(HostileInput, ReflectanceOfOneOrMoreIsLoweredTo095WithAWarning) {
  TempDir dir;
  ObjBuilder model;
  model.mtl << "newmtl snow\nKd 1 1.2 0.5\n";
  model.room(true, "snow");
  model.lamp();
  const std::string input = model.write(dir);
  const std::string defined_at = dir.path("model.mtl") + ":" + std::to_string(line_of(model.mtl.str(), "newmtl snow"));

  const Solution s = solve(dir, input, "--iterations 40");
  expect_sane(s);
  EXPECT_NE(s.run.output.find("material 'snow' (" + defined_at + "): reflectance (1, 1.2, 0.5) is 1 or more"), npos)
      << s.run.output;
  EXPECT_NE(s.run.output.find("lowered to (0.95, 0.95, 0.5)"), npos) << s.run.output;
  EXPECT_EQ(material_named(info(input), "snow")["reflectance"], json({0.95, 0.95, 0.5}));

  // The same light as Kd 0.95 0.95 0.5 written in the file.
  TempDir stated_dir;
  ObjBuilder stated;
  stated.mtl << "newmtl snow\nKd 0.95 0.95 0.5\n";
  stated.room(true, "snow");
  stated.lamp();
  const Solution exact = solve(stated_dir, stated.write(stated_dir), "--iterations 40");
  expect_sane(exact);
  expect_same_light(s, exact);

  expect_refused_strictly(dir, input, {"'snow'", defined_at, "below 1"});
}

// A furnace of Kd 1 (every face emits E = 1): with the reflectance lowered to 0.95,
// B = E / (1 - 0.95) = 20 everywhere; a reflectance of 1 would have no answer, and 0.9
// would give 10. At 0.95 the discretisation's error is amplified twenty times (1%
// at 0.5 becomes about 1.3% at the worst vertex, 0.25% on average).
TEST(HostileInput, FurnaceOfWhiteMaterialConvergesAtTheLoweredReflectance) {
  TempDir dir;
  ObjBuilder model;
  model.mtl << "newmtl white_glow\nKd 1 1 1\nKe 1 1 1\n";
  model.room(true, "white_glow");
  const Solution s = solve(dir, model.write(dir), "--converge 1e-3 --ambient --patch-size 0.5");
  expect_sane(s);
  Rgb sum;
  for (const Rgb& b : s.radiosity) {
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[c], 20.0, 0.025 * 20.0) << "channel " << c;
    sum += b;
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / s.radiosity.size(), 20.0, 0.005 * 20.0) << "channel " << c;
}

TEST(HostileInput, ReflectanceOfOneInSceneFilesIsLoweredEvenWhenUnusedAndNegativeIsRefused) {
  TempDir dir;
  ObjBuilder model;
  model.room();
  model.lamp();
  model.write(dir);
  auto scene_with = [&](const std::string& materials) {
    return dir.write("s.json", R"({"meshes": [{"file": "model.obj"}], "materials": {)" + materials + "}}");
  };
  for (const std::string value : {"1.0", "[0.5, 1.2, 0.5]"}) {
    const std::string scene = scene_with(R"("unused_chrome": {"reflectance": )" + value + "}");
    const Solution s = solve(dir, scene, "--iterations 5");
    expect_sane(s);
    EXPECT_NE(s.run.output.find("material 'unused_chrome' (" + scene + " (materials.unused_chrome)): reflectance"),
              npos)
        << s.run.output;
    EXPECT_NE(s.run.output.find("lowered to"), npos) << s.run.output;
    expect_refused_strictly(dir, scene, {"'unused_chrome'", "s.json", "below 1"});
  }
  // Used: the walls are lit as reflecting 0.95.
  EXPECT_EQ(material_named(info(scene_with(R"("wall": {"reflectance": 1.5})")), "wall")["reflectance"],
            json({0.95, 0.95, 0.95}));
  // Negative is refused, --strict or not.
  const std::string negative = scene_with(R"("unused_chrome": {"reflectance": -0.1})");
  const auto r = test::run_dynrad("solve '" + negative + "' -o '" + dir.path("out.ply") + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'unused_chrome'"), npos) << r.output;
  EXPECT_NE(r.output.find("must not be negative"), npos) << r.output;
  EXPECT_FALSE(test::file_exists(dir.path("out.ply")));
  expect_refused_strictly(dir, negative, {"'unused_chrome'", "must not be negative"});
}

// Lines with unknown keywords are skipped with a warning naming the line; obj_info is a
// PLY keyword and read silently. Neither may shift what OpenMesh reads: a word like
// "element" in them is not a keyword, and a skipped line just before end_header of a
// binary file must not move the data by a byte.
TEST(HostileInput, UnknownPlyHeaderLinesAreSkippedWithAWarning) {
  TempDir dir;
  const std::string ascii = dir.write(
      "h.ply",
      "ply\nformat ascii 1.0\nobj_info scanned: element vertex 99\nfoo bar\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nfoo element 12\nend_header\n"
      "0 0 0\n2 0 0\n0 3 0\n3 0 1 2 128 64 32\n");
  const json counts = info(ascii);
  EXPECT_EQ(counts["faces"].get<int>(), 1);
  EXPECT_EQ(counts["bounds"]["max"], json({2.0, 3.0, 0.0}));
  const Rgb colour = channel_array(counts["materials"][0]["reflectance"]);
  auto linear = [](double byte) { return std::pow((byte / 255 + 0.055) / 1.055, 2.4); };
  EXPECT_NEAR(colour.r, linear(128), 1e-6);
  EXPECT_NEAR(colour.b, linear(32), 1e-6);
  const std::string warnings = counts["warnings"].dump();
  EXPECT_EQ(counts["warnings"].size(), 2u) << warnings;  // obj_info is not warned about
  EXPECT_NE(warnings.find(ascii + ":4: PLY header line 'foo bar' has an unknown keyword"), npos) << warnings;
  EXPECT_NE(warnings.find(ascii + ":14: PLY header line 'foo element 12'"), npos) << warnings;
  EXPECT_EQ(warnings.find("obj_info scanned"), npos) << warnings;

  std::string binary =
      "ply\ncomment before the format\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
      "made_by some scanner\nend_header\n";
  for (float x : {0.f, 0.f, 0.f, 2.f, 0.f, 0.f, 0.f, 3.f, 0.f}) binary.append(reinterpret_cast<const char*>(&x), 4);
  binary += '\3';
  for (std::int32_t i : {0, 1, 2}) binary.append(reinterpret_cast<const char*>(&i), 4);
  const std::string binary_path = dir.write("b.ply", binary);
  const json binary_counts = info(binary_path);
  EXPECT_EQ(binary_counts["bounds"]["max"], json({2.0, 3.0, 0.0}));
  EXPECT_NEAR(binary_counts["total_area"].get<double>(), 3.0, 1e-12);
  EXPECT_NE(binary_counts["warnings"].dump().find(binary_path + ":10: PLY header line 'made_by some scanner'"), npos)
      << binary_counts.dump(2);

  for (const std::string& path : {ascii, binary_path}) {
    const auto r = test::run_dynrad("info '" + path + "' --strict");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("unknown keyword"), npos) << r.output;
  }
  const auto obj_info_only = test::run_dynrad(
      "info --strict '" +
      dir.write("o.ply",
                "ply\nformat ascii 1.0\nobj_info element face 7\nelement vertex 3\nproperty float x\n"
                "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n") +
      "'");
  EXPECT_EQ(obj_info_only.exit_code, 0) << obj_info_only.output;
  EXPECT_EQ(obj_info_only.output.find("warning"), npos) << obj_info_only.output;
}

// UTF-8 text as UTF-16 with a byte-order mark.
std::string utf16(const std::string& utf8, bool big_endian) {
  std::string out;
  auto unit = [&](std::uint32_t u) {
    const char high = static_cast<char>(u >> 8), low = static_cast<char>(u & 0xFF);
    out += big_endian ? std::string{high, low} : std::string{low, high};
  };
  unit(0xFEFF);
  for (std::size_t i = 0; i < utf8.size();) {
    const auto lead = static_cast<unsigned char>(utf8[i]);
    const int length = lead < 0x80 ? 1 : lead < 0xE0 ? 2 : lead < 0xF0 ? 3 : 4;
    std::uint32_t code_point = length == 1 ? lead : lead & (0x7F >> length);
    for (int k = 1; k < length; ++k) code_point = (code_point << 6) | (static_cast<unsigned char>(utf8[i + k]) & 0x3F);
    i += length;
    if (code_point < 0x10000) {
      unit(code_point);
    } else {
      unit(0xD800 + ((code_point - 0x10000) >> 10));
      unit(0xDC00 + ((code_point - 0x10000) & 0x3FF));
    }
  }
  return out;
}

TEST(HostileInput, Utf16AndUtf8ByteOrderMarksAreDecoded) {
  ObjBuilder model;
  model.material("wand_wei\u00df", 0.6, 0);
  model.obj << "# ein Zimmer \U0001F3E0\n";  // outside the BMP: a surrogate pair in UTF-16
  model.room(true, "wand_wei\u00df");
  model.lamp();
  TempDir plain_dir;
  const Solution plain = solve(plain_dir, model.write(plain_dir), "--iterations 30");
  expect_sane(plain);
  for (const std::string encoding : {"utf-8 with mark", "utf-16le", "utf-16be"}) {
    SCOPED_TRACE(encoding);
    auto encode = [&](const std::string& text) {
      if (encoding == "utf-8 with mark") return "\xEF\xBB\xBF" + text;
      return utf16(text, encoding == "utf-16be");
    };
    TempDir dir;
    dir.write("model.mtl", encode(model.mtl.str()));
    const std::string input = dir.write("model.obj", encode(model.obj.str()));
    const Solution s = solve(dir, input, "--iterations 30 --strict");
    expect_sane(s);
    expect_same_light(s, plain);
    EXPECT_NEAR(material_named(info(input), "wand_wei\u00df")["reflectance"][1].get<double>(), 0.6, 1e-12);
  }

  // Damaged UTF-16 is refused: cut in the middle of a character, or a lone surrogate.
  TempDir dir;
  const std::string text = utf16("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", false);
  const auto cut = test::run_dynrad("info '" + dir.write("cut.obj", text.substr(0, text.size() - 1)) + "'");
  EXPECT_EQ(cut.exit_code, 2) << cut.output;
  EXPECT_NE(cut.output.find("middle of a character"), npos) << cut.output;
  const std::string lone = text.substr(0, 2 + 2 * 16) + std::string("\x00\xD8#\x00\n\x00", 6) + text.substr(2 + 2 * 16);
  const auto surrogate = test::run_dynrad("info '" + dir.write("lone.obj", lone) + "'");
  EXPECT_EQ(surrogate.exit_code, 2) << surrogate.output;
  EXPECT_NE(surrogate.output.find("lone.obj:3"), npos) << surrogate.output;
  EXPECT_NE(surrogate.output.find("lone surrogate"), npos) << surrogate.output;
  // UTF-16 without a mark is not guessed at: its zero bytes make it binary data.
  const auto unmarked = test::run_dynrad("info '" + dir.write("plain16.obj", text.substr(2)) + "'");
  EXPECT_EQ(unmarked.exit_code, 2) << unmarked.output;
  EXPECT_NE(unmarked.output.find("binary data"), npos) << unmarked.output;
}

// PLY float colours are display colours from 0 to 1, like byte ones: white is clamped to
// 0.95 with a warning; values outside [0, 1] are refused naming the face (OpenMesh would
// wrap them around: 1.5 became 0.49).
TEST(HostileInput, PlyFloatColoursOutsideZeroToOneAreRefused) {
  TempDir dir;
  auto ply = [&](const std::string& colour) {
    return dir.write("c.ply",
                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                     "property float red\nproperty float green\nproperty float blue\nend_header\n"
                     "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.5 0.5 0.5\n3 0 2 1 " +
                         colour + "\n");
  };
  const json white = info(ply("1 1 1"));
  ASSERT_EQ(white["materials"].size(), 2u) << white.dump(2);
  EXPECT_EQ(white["materials"][1]["reflectance"][0].get<double>(), 0.95);
  EXPECT_NE(white["warnings"].dump().find("clamped"), std::string::npos) << white.dump(2);

  for (const char* colour : {"1.5 0.5 0.5", "0.5 -0.5 0.5", "0.5 0.5 nan", "0.5 0.5 inf"}) {
    const auto r = test::run_dynrad("info '" + ply(colour) + "'");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("c.ply:17"), std::string::npos) << r.output;  // face 1's line
    EXPECT_NE(r.output.find("face 1 has colour"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("outside [0, 1]"), std::string::npos) << r.output;
  }
}

// An ASCII PLY face whose vertex index does not fit in an int is refused naming its line:
// OpenMesh's stream failed on it and then read every later list count as garbage,
// allocating 4 GB (found by the ply fuzz target).
TEST(HostileInput, PlyListEntryTooLargeForAnIntIsRefused) {
  TempDir dir;
  const std::string path = dir.write("big.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                                     "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 22222222222222222222 1\n");
  const auto r = test::run_dynrad("info '" + path + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("big.ply:14"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fits in 32 bits"), std::string::npos) << r.output;
  const auto letters = test::run_dynrad(
      "info '" + dir.write("word.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                       "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 one 2\n") + "'");
  EXPECT_EQ(letters.exit_code, 2) << letters.output;
  EXPECT_NE(letters.output.find("entry 'one'"), std::string::npos) << letters.output;
}

// The same check on binary PLY, where OpenMesh's conversion is the same.
TEST(HostileInput, BinaryPlyFloatColoursAreCheckedToo) {
  TempDir dir;
  auto binary_ply = [&](float red, bool big_endian) {
    std::string text = std::string("ply\nformat binary_") + (big_endian ? "big" : "little") +
                       "_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 1\nproperty list uchar int vertex_indices\nproperty float red\n"
                       "property float green\nproperty float blue\nend_header\n";
    auto put = [&](const void* p, std::size_t n) {
      std::string bytes(static_cast<const char*>(p), n);
      if (big_endian) std::reverse(bytes.begin(), bytes.end());
      text += bytes;
    };
    const float points[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    for (float x : points) put(&x, 4);
    text += '\3';
    for (std::int32_t i : {0, 1, 2}) put(&i, 4);
    for (float c : {red, 0.5f, 0.5f}) put(&c, 4);
    return dir.write("b.ply", text);
  };
  for (bool big : {false, true}) {
    EXPECT_EQ(info(binary_ply(0.25f, big))["materials"].size(), 1u);
    const auto r = test::run_dynrad("info '" + binary_ply(3.0f, big) + "'");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("face 0 has colour red = 3"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace dynrad
