// The command line's host-facing commands: `plot` (convergence SVG), `probe`
// (calculation points), and the anytime stop of `solve` under signals.
#include "test_support.h"

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <nlohmann/json.hpp>

#include <regex>
#include <sstream>

namespace dynrad {
namespace {

using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// The numbers of the polyline with this id, as (x, y) pairs.
std::vector<std::pair<double, double>> polyline_points(const std::string& svg, const std::string& id = "unshot") {
  std::smatch m;
  std::vector<std::pair<double, double>> points;
  if (!std::regex_search(svg, m, std::regex("<polyline id=\"" + id + "\"[^>]* points=\"([^\"]*)\""))) return points;
  std::istringstream in(m[1].str());
  for (std::string pair; in >> pair;) {
    const auto comma = pair.find(',');
    points.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
  }
  return points;
}

TEST(PlotCommand, OnePointPerShotFallingWithUnshotPower) {
  test::TempDir dir;
  auto r = test::run_dynrad("solve '" + test::sample("cornell_box.obj") + "' -o '" + dir.path("lit.ply") +
                            "' --iterations 37 --report '" + dir.path("report.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::run_dynrad("plot '" + dir.path("report.json") + "' -o '" + dir.path("plot.svg") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string svg = test::read_text(dir.path("plot.svg"));
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  const auto points = polyline_points(svg);
  ASSERT_EQ(points.size(), 37u);
  // SVG y grows downwards: falling unshot power is a growing y; shots grow along x.
  for (std::size_t k = 1; k < points.size(); ++k) {
    EXPECT_GT(points[k].first, points[k - 1].first) << k;
    EXPECT_GE(points[k].second, points[k - 1].second - 1e-9) << k;
  }
  EXPECT_GT(points.back().second, points.front().second);
  // Transfers so far: one point per shot, never falling (y never grows), ending at the
  // top of the axis (the total).
  const auto transfers_curve = polyline_points(svg, "transfers");
  ASSERT_EQ(transfers_curve.size(), 37u);
  for (std::size_t k = 1; k < transfers_curve.size(); ++k)
    EXPECT_LE(transfers_curve[k].second, transfers_curve[k - 1].second + 1e-9) << k;
  EXPECT_NEAR(transfers_curve.back().second, 50.0, 1e-6);  // the plot's top edge
  const auto report = nlohmann::json::parse(test::read_text(dir.path("report.json")));
  const std::string transfers = std::to_string(report["energy_transfers"].get<std::uint64_t>());
  EXPECT_NE(svg.find("37 shots, " + transfers + " energy transfers"), std::string::npos) << svg.substr(0, 2000);
}

TEST(PlotCommand, RefusesBadReportsAndLeavesNoOutput) {
  test::TempDir dir;
  const std::string existing = dir.write("plot.svg", "old");
  struct Case {
    std::string name, content, message;
  };
  for (const Case& c : {Case{"broken.json", "{\"unshot_history\": [0.5, ", "is not valid JSON"},
                        Case{"other.json", "{\"method\": \"dynamic\"}", "has no 'unshot_history' array"},
                        Case{"damaged.json", "{\"unshot_history\": [0.5, \"x\"]}", "unshot_history[1] is not a number"},
                        Case{"empty.json", "{\"unshot_history\": []}", "nothing to plot"}}) {
    const std::string input = dir.write(c.name, c.content);
    const auto r = test::run_dynrad("plot '" + input + "' -o '" + existing + "'");
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(input + ": "), std::string::npos) << r.output;  // names the file
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
    EXPECT_EQ(test::read_text(existing), "old");
  }
  const auto r = test::run_dynrad("plot '" + dir.path("missing.json") + "' -o '" + dir.path("new.svg") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("cannot be read"), std::string::npos) << r.output;
  EXPECT_FALSE(test::file_exists(dir.path("new.svg")));
}

// A closed box that glows everywhere (E = 1, rho = 0.5), faces inward.
std::string furnace_obj(const test::TempDir& dir) {
  dir.write("furnace.mtl", "newmtl glow\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  return dir.write("furnace.obj",
                   "mtllib furnace.mtl\nusemtl glow\n"
                   "v 0 0 0\nv 2 0 0\nv 0 1 0\nv 2 1 0\nv 0 0 1\nv 2 0 1\nv 0 1 1\nv 2 1 1\n"
                   "f 1 3 7 5\nf 2 6 8 4\nf 1 5 6 2\nf 3 4 8 7\nf 1 2 4 3\nf 5 7 8 6\n");
}

// In the furnace B = E / (1 - rho) = 2 everywhere and H = (B - E) / rho = 2 (B = E +
// rho H). --reflectance assumes no emission, so it reads H = B / rho = 4 instead.
TEST(ProbeCommand, FurnaceBoxGivesClosedFormRadiosityAndIrradiance) {
  test::TempDir dir;
  const std::string model = furnace_obj(dir);
  auto r = test::run_dynrad("solve '" + model + "' -o '" + dir.path("lit.ply") + "' --patch-size 0.3 --converge 1e-4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string points = dir.write("points.txt",
                                       "# x y z nx ny nz\n"
                                       "1 0.5 0  0 0 1   # floor\n"
                                       "\n"
                                       "0.3 0.2 1  0 0 -1  # ceiling\n"
                                       "2 0.7 0.4  -1 0 0 # end wall\n"
                                       "1.5 0.5 0.25  0 0 1 # above the floor\n");
  r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --points '" + points + "' --model '" + model +
                       "' --grid 0.25,0.25,1.75,0.75,0.5,0.5 --json -o '" + dir.path("probe.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(test::read_text(dir.path("probe.json")));
  ASSERT_EQ(j["points"].size(), 4u + 4u * 2u);  // the file's points, then a 4 x 2 grid
  for (const auto& p : j["points"]) {
    ASSERT_FALSE(p["radiosity"].is_null()) << p.dump();
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(p["radiosity"][c].get<double>(), 2.0, 0.01 * 2.0) << p.dump();
      EXPECT_NEAR(p["irradiance"][c].get<double>(), 2.0, 0.02 * 2.0) << p.dump();
    }
    EXPECT_EQ(p["material"], "glow");
  }
  EXPECT_EQ(j["points"][0]["source"], points + ":2");
  EXPECT_NEAR(j["points"][3]["distance"].get<double>(), 0.25, 1e-6);
  EXPECT_NEAR(j["points"][4]["distance"].get<double>(), 0.5, 1e-6);  // the grid's height above the floor
  EXPECT_NEAR(j["points"][4]["surface_point"][2].get<double>(), 0.0, 1e-6);

  r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --points '" + points + "' --reflectance 0.5 --json -o '" +
                       dir.path("assumed.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto assumed = nlohmann::json::parse(test::read_text(dir.path("assumed.json")));
  for (const auto& p : assumed["points"]) EXPECT_NEAR(p["irradiance"][1].get<double>(), 4.0, 0.01 * 4.0) << p.dump();
}

// At a triangle's centroid, probing the solve's own PLY gives the mean of its corner
// values: the interpolation reads exactly what the solver wrote.
TEST(ProbeCommand, ReadsTheLitMeshItself) {
  test::TempDir dir;
  auto r = test::run_dynrad("solve '" + test::sample("cornell_box.obj") + "' -o '" + dir.path("lit.ply") +
                            "' --iterations 150");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ReadMesh mesh;
  OpenMesh::IO::Options io = OpenMesh::IO::Options::Custom;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(mesh, dir.path("lit.ply"), io));
  OpenMesh::VPropHandleT<float> green;
  ASSERT_TRUE(mesh.get_property_handle(green, "radiosity_g"));
  mesh.request_face_normals();
  mesh.update_face_normals();
  std::string points;
  std::vector<double> expected;
  for (auto f : mesh.faces()) {
    if (f.idx() % 23 != 0) continue;
    const auto c = mesh.calc_face_centroid(f), n = mesh.normal(f);
    double mean = 0;
    for (auto v : mesh.fv_range(f)) mean += mesh.property(green, v) / 3.0;
    expected.push_back(mean);
    points += std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + " " +
              std::to_string(n[0]) + " " + std::to_string(n[1]) + " " + std::to_string(n[2]) + "\n";
  }
  ASSERT_GT(expected.size(), 40u);
  dir.write("points.txt", points);
  r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --points '" + dir.path("points.txt") + "' --json -o '" +
                       dir.path("probe.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(test::read_text(dir.path("probe.json")));
  ASSERT_EQ(j["points"].size(), expected.size());
  double largest = 0;
  for (const double e : expected) largest = std::max(largest, e);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto& p = j["points"][i];
    ASSERT_FALSE(p["radiosity"].is_null()) << p.dump();
    // Centroids printed with 6 decimals: the reading moves by at most the gradient
    // times 1e-6 mm.
    EXPECT_NEAR(p["radiosity"][1].get<double>(), expected[i], 1e-4 * largest + 1e-4 * expected[i]) << p.dump();
    EXPECT_LT(p["distance"].get<double>(), 1e-3) << p.dump();
  }
}

// Work-plane points in the plane of a wall that stands on the floor's edge: the ray
// down runs along the wall and along the floor's boundary edge. A lit PLY holds floats,
// so a wall at x = 24.95 sits at 24.950000763 and a point at 24.95 is a hair off the
// floor's edge, on either side (in a generated building, 162 of 6,700 grid points missed
// the floor so). Points within a hair of the edge read the floor: here 0.5 micrometres
// beyond it, beside one wall and in the corner of two. The floor is lit as g = x (1 at
// the wall). Then a 40,000-point grid (one ray each, not a search of every triangle).
TEST(ProbeCommand, PointsInAWallsPlaneReadTheFloorBesideIt) {
  test::TempDir dir;
  // Floor x 0..1, y 0..1 (facing up); walls x = 1 (facing -x) and y = 1 (facing -y), 1 m
  // high, standing on the floor's edges.
  const char* ply =
      "ply\nformat ascii 1.0\nelement vertex 12\nproperty float x\nproperty float y\nproperty float z\n"
      "property float radiosity_r\nproperty float radiosity_g\nproperty float radiosity_b\n"
      "element face 6\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0 0\n1 0 0 1 1 1\n1 1 0 1 1 1\n0 1 0 0 0 0\n"
      "1 0 0 5 5 5\n1 1 0 5 5 5\n1 1 1 5 5 5\n1 0 1 5 5 5\n"
      "0 1 0 7 7 7\n1 1 0 7 7 7\n1 1 1 7 7 7\n0 1 1 7 7 7\n"
      "3 0 1 2\n3 0 2 3\n3 4 5 6\n3 4 6 7\n3 8 10 9\n3 8 11 10\n";
  dir.write("lit.ply", ply);
  dir.write("points.txt",
            "1 0.5 0.8 0 0 1\n1.0000005 0.25 0.3 0 0 1\n0.5 1 0.8 0 0 1\n1.0000005 1.0000005 0.8 0 0 1\n"
            "0.5 0.5 0.8 0 0 1\n");
  auto r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --points '" + dir.path("points.txt") + "' --json -o '" +
                            dir.path("probe.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto j = nlohmann::json::parse(test::read_text(dir.path("probe.json")));
  const double expected[5] = {1.0, 1.0, 0.5, 1.0, 0.5};  // g = x on the floor
  const double height[5] = {0.8, 0.3, 0.8, 0.8, 0.8};
  ASSERT_EQ(j["points"].size(), 5u);
  for (int i = 0; i < 5; ++i) {
    const auto& p = j["points"][i];
    ASSERT_FALSE(p["radiosity"].is_null()) << p.dump();
    EXPECT_NEAR(p["radiosity"][1].get<double>(), expected[i], 1e-5) << p.dump();
    EXPECT_NEAR(p["distance"].get<double>(), height[i], 1e-5) << p.dump();
  }
  r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --grid 0,0,0.995,0.995,0.005,0.5 --json -o '" +
                       dir.path("grid.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  j = nlohmann::json::parse(test::read_text(dir.path("grid.json")));
  ASSERT_EQ(j["points"].size(), 200u * 200u);
  for (const auto& p : j["points"]) {
    ASSERT_FALSE(p["radiosity"].is_null()) << p.dump();
    ASSERT_NEAR(p["radiosity"][1].get<double>(), p["point"][0].get<double>(), 1e-5) << p.dump();
  }
}

// Points on edges and corners shared by faces of different values (a lamp's edge in a
// ceiling; the PLY splits the vertices there): a checkerboard of squares, each with its
// own value and its own vertices, faces in a scrambled order. Every point reads the
// lowest-numbered face that holds it, as a search of every triangle would, not the
// face Embree's tree happens to report (that was another face at 60 of these 105).
TEST(ProbeCommand, PointsOnSharedEdgesReadTheLowestNumberedFace) {
  test::TempDir dir;
  constexpr int kSide = 8;
  constexpr double kH = 0.25;
  std::vector<std::array<double, 2>> points;
  std::vector<double> value;
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j) {
      const int b = static_cast<int>(points.size());
      const double x = i * kH, y = j * kH, g = 1 + (i * 7 + j * 3) % 5;
      for (const auto& p : {std::array<double, 2>{x, y}, {x + kH, y}, {x + kH, y + kH}, {x, y + kH}}) {
        points.push_back(p);
        value.push_back(g);
      }
      if ((i + j) % 2 == 0) {
        faces.push_back({b, b + 1, b + 2});
        faces.push_back({b, b + 2, b + 3});
      } else {
        faces.push_back({b, b + 1, b + 3});
        faces.push_back({b + 1, b + 2, b + 3});
      }
    }
  std::vector<std::array<int, 3>> order(faces.size());  // face k is faces[(37 k) mod n]
  for (std::size_t k = 0; k < faces.size(); ++k) order[k] = faces[(37 * k) % faces.size()];
  std::ostringstream ply;
  ply << "ply\nformat ascii 1.0\nelement vertex " << points.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float radiosity_r\n"
         "property float radiosity_g\nproperty float radiosity_b\nelement face "
      << order.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (std::size_t v = 0; v < points.size(); ++v)
    ply << points[v][0] << " " << points[v][1] << " 0 " << value[v] << " " << value[v] << " " << value[v] << "\n";
  for (const auto& t : order) ply << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  dir.write("lit.ply", ply.str());
  std::vector<std::array<double, 2>> probes;
  for (int i = 1; i < kSide; ++i)
    for (int j = 1; j < kSide; ++j) probes.push_back({i * kH, j * kH});  // corners
  for (int i = 1; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j) probes.push_back({i * kH, (j + 0.5) * kH});  // edges
  std::ostringstream text;
  for (const auto& p : probes) text << p[0] << " " << p[1] << " 0 0 0 1\n";
  dir.write("points.txt", text.str());
  const auto r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --points '" + dir.path("points.txt") +
                                  "' --json -o '" + dir.path("probe.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(test::read_text(dir.path("probe.json")));
  ASSERT_EQ(j["points"].size(), probes.size());
  for (std::size_t n = 0; n < probes.size(); ++n) {
    double expected = -1;
    for (const auto& t : order) {  // the first face that holds the point
      const auto &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
      const double d = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
      const double u = ((probes[n][0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (probes[n][1] - a[1])) / d;
      const double w = ((b[0] - a[0]) * (probes[n][1] - a[1]) - (probes[n][0] - a[0]) * (b[1] - a[1])) / d;
      if (u >= -1e-9 && w >= -1e-9 && u + w <= 1 + 1e-9) {
        expected = value[t[0]];
        break;
      }
    }
    ASSERT_FALSE(j["points"][n]["radiosity"].is_null()) << j["points"][n].dump();
    EXPECT_NEAR(j["points"][n]["radiosity"][1].get<double>(), expected, 1e-6) << j["points"][n].dump();
  }
}

TEST(ProbeCommand, BadPointsNameTheLineAndWriteNothing) {
  test::TempDir dir;
  const std::string model = furnace_obj(dir);
  ASSERT_EQ(test::run_dynrad("solve '" + model + "' -o '" + dir.path("lit.ply") + "' --iterations 5").exit_code, 0);
  struct Case {
    std::string points, message;
  };
  for (const Case& c : {Case{"1 0.5 0 0 0 1\n1 0.5 0 0 0\n", "points.txt:2: expected 6 numbers"},
                        Case{"# only comments\n", "holds no points"},
                        Case{"1 0.5 nan 0 0 1\n", "points.txt:1: 'nan' is not a finite number"},
                        Case{"1 0.5 0 0 0 0\n", "points.txt:1: the normal (nx ny nz) is zero"},
                        Case{"5 5 5 0 0 1\n", "no point found a lit surface"}}) {
    dir.write("points.txt", c.points);
    const auto r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --points '" + dir.path("points.txt") +
                                    "' -o '" + dir.path("out.txt") + "'");
    EXPECT_EQ(r.exit_code, 2) << c.points << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
    EXPECT_FALSE(test::file_exists(dir.path("out.txt")));
  }
  dir.write("points.txt", "1 0.5 0 0 0 1\n");
  auto r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --points '" + dir.path("points.txt") +
                            "' --reflectance 0.5 --model '" + model + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("not both"), std::string::npos) << r.output;
  r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --points '" + dir.path("points.txt") +
                       "' --reflectance 1.2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("(0, 1)"), std::string::npos) << r.output;
  r = test::run_dynrad("probe '" + model + "' --points '" + dir.path("points.txt") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(model), std::string::npos) << r.output;
  r = test::run_dynrad("probe '" + dir.path("lit.ply") + "' --grid 0,0,1,1,0,0.5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("step > 0"), std::string::npos) << r.output;
}

// Anytime stop: the first SIGINT stops at the next shot boundary and writes the
// solution with a warning giving the unshot fraction (exit 3); a second SIGINT ends
// the program at once, writing nothing.
TEST(SolveSignals, FirstInterruptWritesWithUnshotFractionSecondQuits) {
  test::TempDir dir;
  const std::string arguments = "solve '" + test::sample("globillum_room_obstructed.obj") +
                                "' --patch-size 0.15 --converge 1e-9 --time-limit 60 -o ";
  // The first signal 2 s into the solve, once the model is loaded (its log names the
  // patches; before that, loading a sanitized build can take longer than a fixed wait).
  auto r = test::run_dynrad_and_signal(arguments + "'" + dir.path("once.ply") + "'", 2, "INT");
  EXPECT_NE(r.output.find("exit=3"), std::string::npos) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex("interrupted: wrote the solution so far, with [0-9.]+% of the "
                                                     "emitted power not yet shot")))
      << r.output;
  EXPECT_TRUE(test::file_exists(dir.path("once.ply")));

  // The second signal 20 ms after the first: the first is handled by then (the
  // process is still alive), and finishing the shot and writing 76k triangles takes
  // longer than that.
  const std::string log = dir.path("twice.log");
  r = test::run_shell("( '" + std::string(DYNRAD_EXE) + "' " + arguments + "'" + dir.path("twice.ply") + "' > '" + log +
                      "' 2>&1 & pid=$!; for i in $(seq 3000); do grep -q ' patches' '" + log +
                      "' && break; kill -0 $pid 2>/dev/null || break; sleep 0.2; done; sleep 2; kill -INT $pid; "
                      "sleep 0.02; kill -0 $pid && echo alive-after-first; kill -INT $pid; wait $pid; echo exit=$? )");
  EXPECT_NE(r.output.find("alive-after-first"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("exit=130"), std::string::npos) << r.output;  // 128 + SIGINT: killed by the signal
  EXPECT_FALSE(test::file_exists(dir.path("twice.ply")));
}

}  // namespace
}  // namespace dynrad
