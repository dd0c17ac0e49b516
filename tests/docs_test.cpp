// Everything a user can type is documented: every long option of every command (from
// the command's own --help) and every key of the scene file (from the readers' own
// "unknown key ... (known keys: ...)" errors, so no list here can drift from the code)
// appears in README.md or docs/*.md.
#include "test_support.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace dynrad {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// README.md and every page of docs/.
std::string all_docs() {
  const fs::path root = DYNRAD_SOURCE_DIR;
  std::string text = read(root / "README.md");
  for (const auto& e : fs::directory_iterator(root / "docs"))
    if (e.path().extension() == ".md") text += "\n" + read(e.path());
  return text;
}

TEST(Docs, EveryCommandLineOptionIsDocumented) {
  const std::string docs = all_docs();
  const std::regex option_line(R"(^\s+(?:-\w,)?(--[a-z0-9][a-z0-9-]*))");
  std::size_t options = 0;
  for (const char* command : {"solve", "grid", "annual", "view", "probe", "diff", "info", "clean", "plot", "validate"}) {
    const auto help = test::run_dynrad(std::string(command) + " --help");
    ASSERT_EQ(help.exit_code, 0) << command << "\n" << help.output;
    std::istringstream lines(help.output);
    std::string line;
    std::size_t found = 0;
    while (std::getline(lines, line)) {
      std::smatch m;
      if (!std::regex_search(line, m, option_line) || m[1] == "--help") continue;
      ++found;
      const std::regex mentioned(std::regex_replace(m[1].str(), std::regex("-"), "\\-") + R"((?![a-z0-9-]))");
      EXPECT_TRUE(std::regex_search(docs, mentioned)) << "dynrad " << command << " " << m[1] << " is in no page of docs/";
    }
    EXPECT_GT(found, 0u) << command;
    options += found;
  }
  EXPECT_GT(options, 100u);
}

// The keys a scene-file reader knows, from its error for an unknown key in `scene`.
std::vector<std::string> known_keys(const test::TempDir& dir, const std::string& scene, std::string* where) {
  const std::string path = dir.write("probe.json", scene);
  const auto run = test::run_dynrad("solve '" + path + "' -o '" + dir.path("out.ply") + "'");
  EXPECT_EQ(run.exit_code, 2) << scene << "\n" << run.output;
  std::smatch m;
  if (!std::regex_search(run.output, m, std::regex(R"(unknown key "zzz" in (.+?) \(known keys: ([^)]*)\))"))) {
    ADD_FAILURE() << "no list of known keys for " << scene << "\n" << run.output;
    return {};
  }
  *where = m[1];
  std::vector<std::string> keys;
  std::istringstream list(m[2].str());
  std::string key;
  while (std::getline(list, key, ',')) keys.push_back(key.substr(key.find_first_not_of(' ')));
  return keys;
}

TEST(Docs, EverySceneFileKeyIsDocumented) {
  test::TempDir dir;
  dir.write("room.obj", "mtllib room.mtl\nusemtl grey\nv 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 0 0 3\nv 4 0 3\n"
                        "v 4 4 3\nv 0 4 3\nf 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n");
  dir.write("room.mtl", "newmtl grey\nKd 0.5 0.5 0.5\n");
  const std::string mesh = R"("meshes": [{"file": "room.obj"}])";
  const std::string grid = R"({"name": "g", "rectangle": [0.5, 0.5, 3.5, 3.5], "height": 0.8)";
  // One probe per object of the scene file: a valid scene with the unknown key "zzz" in it.
  const std::vector<std::string> probes = {
      "{" + mesh + R"(, "zzz": 1})",
      R"({"meshes": [{"file": "room.obj", "zzz": 1}]})",
      R"({"meshes": [{"file": "room.obj", "transform": {"zzz": 1}}]})",
      "{" + mesh + R"(, "materials": {"grey": {"zzz": 1}}})",
      "{" + mesh + R"(, "luminaires": [{"zzz": 1}]})",
      "{" + mesh + R"(, "sky": {"zzz": 1}})",
      "{" + mesh + R"(, "sky": {"type": "cie", "number": 12, "sun": {"zzz": 1}}})",
      "{" + mesh + R"(, "grids": [{"zzz": 1}]})",
      "{" + mesh + R"(, "grids": [)" + grid + R"(, "target": {"zzz": 1}}]})",
      "{" + mesh + R"(, "grids": [)" + grid + R"(, "target": {"Eavg": 300, "walls": {"zzz": 1}}}]})",
      "{" + mesh + R"(, "grids": [)" + grid + R"(, "target": {"Eavg": 300, "Ez": {"Eavg": 50, "zzz": 1}}}]})",
      "{" + mesh + R"(, "grids": [)" + grid + R"(, "border": 0.5, "target": {"Eavg": 300, "surrounding": {"zzz": 1}}}]})",
      "{" + mesh + R"(, "cameras": [{"zzz": 1}]})",
      "{" + mesh + R"(, "observers": [{"zzz": 1}]})",
      "{" + mesh + R"(, "routes": [{"zzz": 1}]})",
      "{" + mesh + R"(, "open_areas": [{"zzz": 1}]})",
      "{" + mesh + R"(, "materials": {"grey": {"emission": 10}}, "scenes": [{"zzz": 1}]})",
      "{" + mesh + R"(, "project": {"zzz": 1}})",
  };
  const std::string docs = all_docs();
  std::size_t keys = 0;
  for (const std::string& probe : probes) {
    std::string where;
    for (const std::string& key : known_keys(dir, probe, &where)) {
      ++keys;
      // As a JSON key ("key") or in code (`key`, `section.key`, `section[].key`).
      const std::regex named("[\"`.]" + key + "[\"`,:) ]");
      EXPECT_TRUE(std::regex_search(docs, named))
          << "scene-file key \"" << key << "\" (in " << where << ") is in no page of docs/";
    }
  }
  EXPECT_GT(keys, 60u);
}

}  // namespace
}  // namespace dynrad
