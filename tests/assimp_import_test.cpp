// Models through assimp (mesh/io/read_assimp.cpp): an IFC house from Debian's assimp test
// models, a lit model's own .glb read back, and broken files refused by name.
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

namespace dynrad {
namespace {

const char* kHouse = "/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc";  // package assimp-testmodels

nlohmann::json info_json(const std::string& arguments) {
  const auto r = test::run_dynrad("info " + arguments + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto start = r.output.find('{');
  return start == std::string::npos ? nlohmann::json() : nlohmann::json::parse(r.output.substr(start));
}

TEST(AssimpImport, IfcHouseHasItsElementsStandsUpAndLights) {
  ASSERT_TRUE(std::filesystem::exists(kHouse)) << "install assimp-testmodels (scripts/install-deps.sh does)";
  const nlohmann::json j = info_json(std::string("'") + kHouse + "'");
  const auto& types = j["ifc_types"];
  EXPECT_GE(types.value("IfcWallStandardCase", 0), 10) << types;
  EXPECT_GE(types.value("IfcSlab", 0), 3) << types;
  EXPECT_GE(types.value("IfcFurnishingElement", 0), 10) << types;
  EXPECT_GE(types.value("IfcDoor", 0), 1) << types;
  EXPECT_GT(j["glazing_triangles"].get<int>(), 0);  // the windows' glass (opacity below 1)
  // Turned to z up: a two-storey house is lower than it is wide.
  const auto lo = j["bounds"]["min"], hi = j["bounds"]["max"];
  const double dx = hi[0].get<double>() - lo[0].get<double>(), dz = hi[2].get<double>() - lo[2].get<double>();
  EXPECT_LT(dz, 0.6 * dx) << j["bounds"];
  // It lights: a lamp in the ground floor, a few shots.
  test::TempDir dir;
  const std::string scene = dir.write(
      "house.json", std::string(R"({"meshes": [{"file": ")") + kHouse +
                        R"("}], "luminaires": [{"type": "point", "intensity": 300, "position": [4, 4, 2.0]}]})");
  const auto r = test::run_dynrad("solve '" + scene + "' -o '" + dir.path("house.ply") +
                                  "' --method progressive --iterations 3 --report '" + dir.path("r.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto report = nlohmann::json::parse(test::read_text(dir.path("r.json")));
  EXPECT_GT(report["energy"]["absorbed"][1].get<double>(), 0);
}

TEST(AssimpImport, ALitGlbReadsBackWithItsGroupsWhereItWas) {
  test::TempDir dir;
  const std::string box = test::sample("cornell_box.obj");
  const auto r = test::run_dynrad("solve '" + box + "' --up y -o '" + dir.path("box.glb") + "' --quality draft");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json original = info_json("'" + box + "' --up y");
  const nlohmann::json back = info_json("'" + dir.path("box.glb") + "'");  // glTF: y up, turned back
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(back["bounds"]["min"][k].get<double>(), original["bounds"]["min"][k].get<double>(), 1e-2);
    EXPECT_NEAR(back["bounds"]["max"][k].get<double>(), original["bounds"]["max"][k].get<double>(), 1e-2);
  }
  std::vector<std::string> groups;
  for (const auto& item : back["groups"].items()) groups.push_back(item.key());
  EXPECT_EQ(groups, (std::vector<std::string>{"back_wall", "ceiling", "floor", "green_wall", "light", "red_wall",
                                              "short_block", "tall_block"}));
  EXPECT_NEAR(back["total_area"].get<double>(), original["total_area"].get<double>(),
              1e-3 * original["total_area"].get<double>());
}

TEST(AssimpImport, BrokenFilesAreRefusedByName) {
  test::TempDir dir;
  const std::string truncated = dir.write("cut.glb", std::string("glTF\x02\x00\x00\x00\xff\x00\x00\x00JSON", 16));
  auto r = test::run_dynrad("solve '" + truncated + "' -o '" + dir.path("out.ply") + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cut.glb"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("assimp"), std::string::npos) << r.output;
  EXPECT_FALSE(test::file_exists(dir.path("out.ply")));
  const std::string gltf = dir.write("bad.gltf", R"({"asset": {"version": "2.0"}, "meshes": [{"primitives": [)"
                                                 R"({"attributes": {"POSITION": 7}}]}]})");
  r = test::run_dynrad("info '" + gltf + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.gltf"), std::string::npos) << r.output;
  // Found by the gltf fuzz target: a vertex that is NaN once its node's transform places
  // it (it reached cleanup's k-d tree, whose assertion ended the process).
  r = test::run_dynrad("info '" DYNRAD_TEST_DATA_DIR "/nan_vertex.gltf'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("is not a finite number"), std::string::npos) << r.output;
  r = test::run_dynrad("info '" + dir.write("x.xyz1", "nothing") + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("unsupported file type"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace dynrad
