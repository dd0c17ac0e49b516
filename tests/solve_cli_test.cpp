// `dynrad solve` end to end: report contents, refusals, interruption, threads.
#include "test_support.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>

namespace dynrad {
namespace {

using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// Per-vertex radiosity_g of a written PLY.
std::vector<float> read_green(const std::string& path) {
  ReadMesh mesh;
  OpenMesh::IO::Options io = OpenMesh::IO::Options::Custom;
  EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, path, io)) << path;
  OpenMesh::VPropHandleT<float> g;
  EXPECT_TRUE(mesh.get_property_handle(g, "radiosity_g")) << path;
  std::vector<float> out;
  if (!g.is_valid()) return out;
  for (auto v : mesh.vertices()) out.push_back(mesh.property(g, v));
  return out;
}

TEST(SolveCommand, WritesLitMeshAndReport) {
  test::TempDir dir;
  const auto r = test::run_dynrad("solve '" + test::sample("cornell_box.obj") + "' -o '" + dir.path("lit.ply") +
                                  "' --iterations 40 --report '" + dir.path("report.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(test::read_text(dir.path("report.json")));
  for (const char* key : {"method", "iterations", "energy_transfers", "patch_element_transfers", "visibility_rays",
                          "elements", "patches", "unshot_fraction", "seconds", "unshot_history"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["method"], "dynamic");  // the default
  for (const char* key : {"quality", "error_target", "mean_free_path", "patch_size", "patch_size_rule", "max_level",
                          "pushdown_error", "pushdown_floor", "memory_budget_mib"})
    EXPECT_TRUE(j["settings"].contains(key)) << key;
  EXPECT_EQ(j["settings"]["quality"], "normal");
  EXPECT_GT(j["estimated_error"]["total"].get<double>(), 0.0);
  EXPECT_EQ(j["iterations"].get<int>(), 40);
  EXPECT_EQ(j["unshot_history"].size(), 40u);
  EXPECT_EQ(j["stopped_by"], "iterations");
  // Unshot power never grows.
  double previous = 1;
  for (double u : j["unshot_history"]) {
    EXPECT_LE(u, previous + 1e-12);
    previous = u;
  }
  const auto green = read_green(dir.path("lit.ply"));
  ASSERT_FALSE(green.empty());
  EXPECT_GT(*std::max_element(green.begin(), green.end()), 0.0f);
  EXPECT_NE(r.output.find("stopped by iterations"), std::string::npos) << r.output;
}

// The report's phases: every phase a lamp-lit solve with a grid passes through, in the
// order they ran, their seconds adding up to no more than the run's wall time (each is
// a slice of it, none counted twice) and to most of the solve's own seconds, each with
// the process's memory when it ended (the peak never below what was resident then,
// and never falling).
TEST(SolveCommand, ReportsWhereItsTimeAndMemoryWent) {
  test::TempDir dir;
  const std::string scene =
      test::write_lamp_room(dir, R"([{"name": "desk", "rectangle": [0.5, 0.5, 3.5, 2.5], "height": 0.8}])");
  const auto start = std::chrono::steady_clock::now();
  const auto r = test::run_dynrad("solve -q '" + scene + "' -o '" + dir.path("lit.ply") + "' --report '" +
                                  dir.path("report.json") + "'");
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(test::read_text(dir.path("report.json")));
  ASSERT_TRUE(j.contains("phases"));
  std::vector<std::string> names;
  double sum = 0, solver = 0, peak = 0;
  for (const auto& phase : j["phases"]) {
    names.push_back(phase["name"].get<std::string>());
    const double seconds = phase["seconds"].get<double>();
    EXPECT_GE(seconds, 0.0) << names.back();
    sum += seconds;
    if (names.back().find("shots") != std::string::npos || names.back().find("refinement") == 0) solver += seconds;
    const double resident = phase["resident_mib"].get<double>(), now_peak = phase["peak_mib"].get<double>();
    EXPECT_GT(resident, 0.0) << names.back();
    EXPECT_GE(now_peak, resident) << names.back();
    EXPECT_GE(now_peak, peak) << names.back();
    peak = now_peak;
  }
  const std::vector<std::string> in_order = {"read and repair", "solver set-up", "shots of luminaires and the sun",
                                             "shots", "refinement for direct light and the estimate",
                                             "values per vertex", "grids", "writing the lit mesh"};
  auto at = names.begin();
  for (const std::string& name : in_order) {
    at = std::find(at, names.end(), name);
    EXPECT_NE(at, names.end()) << name << " missing or out of order";
  }
  EXPECT_LE(sum, wall);
  // The solver's three phases are the solve's seconds, measured by the solver itself.
  EXPECT_NEAR(solver, j["seconds"].get<double>(), 0.05 * j["seconds"].get<double>() + 0.01);
}

// --flat-senders reaches the solver: the report says so, and the light differs (the
// Cornell box's walls reflect unevenly) while staying the same picture.
TEST(SolveCommand, FlatSendersOption) {
  test::TempDir dir;
  auto solve = [&](const std::string& name, const std::string& extra) {
    const auto r = test::run_dynrad("solve '" + test::sample("cornell_box.obj") + "' -o '" + dir.path(name + ".ply") +
                                    "' --method progressive --iterations 200 --report '" + dir.path(name + ".json") + "'" + extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return nlohmann::json::parse(test::read_text(dir.path(name + ".json")));
  };
  EXPECT_EQ(solve("shaped", "")["shaped_senders"], true);
  EXPECT_EQ(solve("flat", " --flat-senders")["shaped_senders"], false);
  const auto shaped = read_green(dir.path("shaped.ply")), flat = read_green(dir.path("flat.ply"));
  ASSERT_EQ(shaped.size(), flat.size());
  ASSERT_FALSE(shaped.empty());
  double largest = 0, sum_shaped = 0, sum_flat = 0;
  for (std::size_t i = 0; i < shaped.size(); ++i) {
    largest = std::max(largest, double(std::abs(shaped[i] - flat[i])));
    sum_shaped += shaped[i];
    sum_flat += flat[i];
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_NEAR(sum_shaped, sum_flat, 0.05 * sum_flat);
}

TEST(SolveCommand, RefusesASceneWithoutLight) {
  test::TempDir dir;
  const std::string input = dir.write("dark.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const auto r = test::run_dynrad("solve '" + input + "' -o '" + dir.path("out.ply") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no face emits light"), std::string::npos) << r.output;
  EXPECT_FALSE(test::file_exists(dir.path("out.ply")));
}

TEST(SolveCommand, RefusesUnknownMethods) {
  test::TempDir dir;
  const std::string in = "'" + test::sample("cornell_box.obj") + "' -o '" + dir.path("out.ply") + "'";
  const auto r = test::run_dynrad("solve " + in + " --method radiant");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("available: progressive, adaptive, dynamic"), std::string::npos) << r.output;
  EXPECT_FALSE(test::file_exists(dir.path("out.ply")));
}

// The paper's claim in one run each: dynamic subdivision performs far fewer
// patch-element transfers than adaptive subdivision at the same level and shots. The
// sample's triangles are the paper's 768 patches, so they are kept as they are
// (--no-simplify): merged, the flat walls would be re-cut into a different 828.
TEST(SolveCommand, DynamicNeedsFarFewerTransfersThanAdaptive) {
  test::TempDir dir;
  auto transfers = [&](const std::string& method) {
    const auto r = test::run_dynrad("solve '" + test::sample("paper_empty_room_small_source.obj") + "' -o '" +
                                    dir.path(method + ".ply") + "' --patch-size 1.1 --max-level 2 --iterations 100 --no-simplify --pushdown-error 0.04 "
                                    "--pushdown-floor 0.02 --method " +
                                    method + " --report '" + dir.path(method + ".json") + "'");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return nlohmann::json::parse(test::read_text(dir.path(method + ".json")));
  };
  const auto adaptive = transfers("adaptive"), dynamic = transfers("dynamic");
  EXPECT_EQ(adaptive["patches"].get<int>(), 768);  // the paper's empty room
  EXPECT_GT(adaptive["energy_transfers"].get<double>(), 2.0 * dynamic["energy_transfers"].get<double>());
  EXPECT_GT(adaptive["patch_element_transfers"].get<double>(), 20.0 * dynamic["patch_element_transfers"].get<double>());
}

// Ctrl-C stops at the next shot and still writes a complete, readable file.
TEST(SolveCommand, InterruptWritesTheCurrentSolution) {
  test::TempDir dir;
  const std::string out = dir.path("partial.ply");
  const auto r = test::run_dynrad_and_signal("solve '" + test::sample("globillum_room_obstructed.obj") + "' -o '" +
                                                 out + "' --patch-size 0.15 --converge 1e-9 --time-limit 600",
                                             2.0, "INT");
  EXPECT_NE(r.output.find("exit=3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("interrupted"), std::string::npos) << r.output;
  const auto green = read_green(out);
  ASSERT_FALSE(green.empty());
  EXPECT_GT(*std::max_element(green.begin(), green.end()), 0.0f);
}

TEST(SolveCommand, SameAnswerForOneAndTwoThreads) {
  test::TempDir dir;
  const std::string in = "'" + test::sample("globillum_room_obstructed.obj") +
                         "' --iterations 60 --patch-size 0.5 --method dynamic --max-level 2";
  ASSERT_EQ(test::run_dynrad("solve " + in + " --threads 1 -o '" + dir.path("one.ply") + "'").exit_code, 0);
  ASSERT_EQ(test::run_dynrad("solve " + in + " --threads 2 -o '" + dir.path("two.ply") + "'").exit_code, 0);
  const auto one = read_green(dir.path("one.ply")), two = read_green(dir.path("two.ply"));
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) EXPECT_EQ(one[i], two[i]) << "vertex " << i;
}

}  // namespace
}  // namespace dynrad


namespace dynrad {
namespace {

// Mean of all channels of an 8-bit RGB PNG.
double mean_brightness(const std::string& path) {
  const test::Picture picture = test::read_png(path);
  EXPECT_GT(picture.width, 0) << path;
  double sum = 0;
  for (auto p : picture.rgb) sum += p;
  return picture.rgb.empty() ? 0 : sum / static_cast<double>(picture.rgb.size());
}

TEST(SolveCommand, PreviewIsNotBlankAndFollowsTheLight) {
  test::TempDir dir;
  // The same box lit at full and at half emission, rendered with one fixed exposure.
  dir.write("half.json", std::string(R"({"meshes": [{"file": ")") + test::sample("cornell_box.obj") +
                             R"("}], "materials": {"light": {"emission": [26.7, 18.85, 6.28]}}})");
  const std::string common = " --iterations 200 --exposure 0.5 --preview-width 160";
  auto r = test::run_dynrad("solve '" + test::sample("cornell_box.obj") + "' -o '" + dir.path("full.ply") +
                            "' --preview '" + dir.path("full.png") + "'" + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::run_dynrad("solve '" + dir.path("half.json") + "' -o '" + dir.path("half.ply") + "' --preview '" +
                       dir.path("half.png") + "'" + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double full = mean_brightness(dir.path("full.png")), half = mean_brightness(dir.path("half.png"));
  EXPECT_GT(full, 20.0);        // not blank
  EXPECT_GT(full, 1.2 * half);  // brighter where the solution is brighter
}

}  // namespace
}  // namespace dynrad

namespace dynrad {
namespace {

double relative_rms(const std::string& output) {
  const auto at = output.find("relative rms");
  return at == std::string::npos ? -1 : std::atof(output.c_str() + at + 12);
}

TEST(DiffCommand, ZeroAgainstItselfAndHalfForHalfTheLight) {
  test::TempDir dir;
  dir.write("half.json", std::string(R"({"meshes": [{"file": ")") + test::sample("cornell_box.obj") +
                             R"("}], "materials": {"light": {"emission": [26.7, 18.85, 6.28]}}})");
  const std::string common = " --iterations 300 --method dynamic --max-level 1";
  ASSERT_EQ(test::run_dynrad("solve '" + test::sample("cornell_box.obj") + "' -o '" + dir.path("full.ply") + "'" + common)
                .exit_code,
            0);
  ASSERT_EQ(test::run_dynrad("solve '" + dir.path("half.json") + "' -o '" + dir.path("half.ply") + "'" + common).exit_code,
            0);
  const auto same = test::run_dynrad("diff '" + dir.path("full.ply") + "' '" + dir.path("full.ply") + "' -o '" +
                                     dir.path("same.ply") + "'");
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NEAR(relative_rms(same.output), 0.0, 1e-6) << same.output;
  EXPECT_NE(same.output.find("0 unmatched"), std::string::npos) << same.output;
  // Radiosity is linear in emission: halving the light halves every lit value.
  const auto half = test::run_dynrad("diff '" + dir.path("full.ply") + "' '" + dir.path("half.ply") + "' -o '" +
                                     dir.path("half_diff.ply") + "'");
  ASSERT_EQ(half.exit_code, 0) << half.output;
  EXPECT_NEAR(relative_rms(half.output), 50.0, 10.0) << half.output;
  EXPECT_TRUE(test::file_exists(dir.path("half_diff.ply")));
  // Not a lit mesh: a clear refusal.
  const auto bad = test::run_dynrad("diff '" + test::sample("scene_room/room.off") + "' '" + dir.path("full.ply") +
                                    "' -o '" + dir.path("x.ply") + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("radiosity_r"), std::string::npos) << bad.output;
  // Units: W/m2 for radiometric meshes, lm/m2 for photometric ones, and no comparison
  // of one with the other.
  EXPECT_NE(half.output.find("(luminance, W/m2)"), std::string::npos) << half.output;
  ASSERT_EQ(test::run_dynrad("solve '" + test::sample("cornell_box.obj") + "' -o '" + dir.path("lux.ply") + "'" +
                             common + " --units photometric")
                .exit_code,
            0);
  const auto lux = test::run_dynrad("diff '" + dir.path("lux.ply") + "' '" + dir.path("lux.ply") + "' -o '" +
                                    dir.path("lux_diff.ply") + "'");
  ASSERT_EQ(lux.exit_code, 0) << lux.output;
  EXPECT_NE(lux.output.find("(luminance, lm/m2)"), std::string::npos) << lux.output;
  const auto mixed = test::run_dynrad("diff '" + dir.path("full.ply") + "' '" + dir.path("lux.ply") + "' -o '" +
                                      dir.path("mixed.ply") + "'");
  EXPECT_EQ(mixed.exit_code, 2) << mixed.output;
  EXPECT_NE(mixed.output.find("same --units"), std::string::npos) << mixed.output;
  EXPECT_FALSE(test::file_exists(dir.path("mixed.ply")));
}

}  // namespace
}  // namespace dynrad

namespace dynrad {
namespace {

// --max-elements and --memory-budget stop refinement, not the solve, and say so.
TEST(SolveCommand, ElementAndMemoryLimitsStopRefinementOnly) {
  const test::TempDir dir;
  const std::string common = " --method dynamic --iterations 200 --max-level 4";
  const std::string in = "'" + test::sample("paper_empty_room_small_source.obj") + "'";
  auto solve = [&](const std::string& name, const std::string& extra) {
    const auto r = test::run_dynrad("solve " + in + " -o '" + dir.path(name + ".ply") + "' --report '" +
                                    dir.path(name + ".json") + "'" + common + extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return std::make_pair(nlohmann::json::parse(test::read_text(dir.path(name + ".json"))), r.output);
  };
  const auto [free, free_log] = solve("free", "");
  EXPECT_EQ(free["refinement_stopped"], "");
  const std::size_t unlimited = free["elements"];
  const std::size_t cap = unlimited / 3;
  const auto [capped, capped_log] = solve("capped", " --max-elements " + std::to_string(cap));
  EXPECT_EQ(capped["refinement_stopped"], "max elements");
  EXPECT_GE(capped["elements"].get<std::size_t>(), cap);
  EXPECT_LE(capped["elements"].get<std::size_t>(), cap + 64);  // one split's closure at most
  EXPECT_EQ(capped["iterations"], 200);                      // the solve itself went on
  EXPECT_NE(capped_log.find("refinement stopped"), std::string::npos) << capped_log;
  EXPECT_TRUE(test::file_exists(dir.path("capped.ply")));
  // A budget below what the process already uses: refinement stops at the first look
  // (after 4096 new elements), the solve does not.
  const auto [tight, tight_log] = solve("tight", " --memory-budget 1");
  EXPECT_EQ(tight["refinement_stopped"], "memory budget");
  EXPECT_LT(tight["elements"].get<std::size_t>(), unlimited);
  EXPECT_GT(tight["peak_resident_memory"].get<std::size_t>(), 1u << 20);
  EXPECT_EQ(tight["iterations"], 200);
}

}  // namespace
}  // namespace dynrad
