// Helpers of the hostile-input tests (hostile_input_test.cpp: geometry;
// hostile_files_test.cpp: materials and file formats): models written as OBJ, solved
// through the command line, and the checks every case must pass.
#pragma once

#include "test_support.h"

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace dynrad::hostile {


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

inline std::vector<Rgb> read_radiosity(const std::string& path, std::vector<Vec3d>* positions = nullptr) {
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

inline Solution solve(const TempDir& dir, const std::string& input, const std::string& options) {
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

inline Rgb channel_array(const json& j) { return Rgb(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

// No NaN anywhere, nothing negative, and every watt accounted for.
inline void expect_sane(const Solution& s) {
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

inline double mean_green(const std::vector<Rgb>& values) {
  double sum = 0;
  for (const Rgb& b : values) sum += b.g;
  return values.empty() ? 0 : sum / values.size();
}

inline json info(const std::string& input) {
  const auto r = test::run_dynrad("info --json '" + input + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return r.exit_code == 0 ? json::parse(r.output.substr(r.output.find('{'))) : json();
}

// ---------------------------------------------------------------------------

}  // namespace dynrad::hostile
