// Everything a user can type is documented, and the documentation holds together:
// - every long option of a command (from the command's own --help) is on that command's
//   page, docs/commands/COMMAND.md, and the README links to every command's page;
// - every key of the scene file (from the readers' own "unknown key ... (known keys:
//   ...)" errors, so no list here can drift from the code) is on some page;
// - README.md stays a front page (at most 12,000 bytes) and no page of docs/ grows past
//   15,000 bytes, nor bench/README.md or a page of bench/results/;
// - every relative Markdown link in README.md, docs/**/*.md, bench/README.md and
//   bench/results/*.md names a file that exists.
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
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

const fs::path kRoot = DYNRAD_SOURCE_DIR;
const std::vector<std::string> kCommands = {"solve", "grid",  "annual", "view", "probe",
                                            "diff",  "info", "clean",  "plot", "validate"};

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// README.md and every page under docs/, docs/commands/ included, in a fixed order.
std::vector<fs::path> doc_pages() {
  std::vector<fs::path> pages;
  for (const auto& e : fs::recursive_directory_iterator(kRoot / "docs"))
    if (e.is_regular_file() && e.path().extension() == ".md") pages.push_back(e.path());
  std::sort(pages.begin(), pages.end());
  pages.insert(pages.begin(), kRoot / "README.md");
  return pages;
}

// bench/README.md and every page under bench/results/, in a fixed order.
std::vector<fs::path> bench_pages() {
  std::vector<fs::path> pages;
  for (const auto& e : fs::directory_iterator(kRoot / "bench" / "results"))
    if (e.is_regular_file() && e.path().extension() == ".md") pages.push_back(e.path());
  std::sort(pages.begin(), pages.end());
  pages.insert(pages.begin(), kRoot / "bench" / "README.md");
  return pages;
}

// The pages held to the size and link rules: docs' and the benchmarks'.
std::vector<fs::path> all_pages() {
  std::vector<fs::path> pages = doc_pages();
  const std::vector<fs::path> bench = bench_pages();
  pages.insert(pages.end(), bench.begin(), bench.end());
  return pages;
}

std::string all_docs() {
  std::string text;
  for (const fs::path& page : doc_pages()) text += "\n" + read(page);
  return text;
}

// The long options `dynrad COMMAND --help` lists (--help itself left out).
std::vector<std::string> long_options(const std::string& command) {
  const auto help = test::run_dynrad(command + " --help");
  EXPECT_EQ(help.exit_code, 0) << command << "\n" << help.output;
  const std::regex option_line(R"(^\s+(?:-\w,)?(--[a-z0-9][a-z0-9-]*))");
  std::vector<std::string> options;
  std::istringstream lines(help.output);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, option_line) && m[1] != "--help") options.push_back(m[1]);
  }
  return options;
}

// `text` names `option` as a whole word: --pdf is not found in --pdf-width.
bool mentions(const std::string& text, const std::string& option) {
  return std::regex_search(text, std::regex(std::regex_replace(option, std::regex("-"), "\\-") + "(?![a-z0-9-])"));
}

TEST(Docs, EveryCommandHasAPageTheReadmeLinksTo) {
  const std::string readme = read(kRoot / "README.md");
  for (const std::string& command : kCommands) {
    const std::string page = "docs/commands/" + command + ".md";
    EXPECT_TRUE(fs::is_regular_file(kRoot / page)) << "dynrad " << command << " has no page " << page;
    EXPECT_NE(readme.find("(" + page + ")"), std::string::npos) << "README.md does not link to " << page;
  }
}

TEST(Docs, EveryCommandLineOptionIsOnItsCommandsPage) {
  std::size_t options = 0;
  for (const std::string& command : kCommands) {
    const fs::path page = kRoot / "docs" / "commands" / (command + ".md");
    const std::string text = read(page);
    const std::vector<std::string> found = long_options(command);
    for (const std::string& option : found)
      EXPECT_TRUE(mentions(text, option)) << "dynrad " << command << " " << option << " is not on " << page.string();
    EXPECT_GT(found.size(), 0u) << command;
    options += found.size();
  }
  EXPECT_GT(options, 100u);
}

TEST(Docs, PagesStayShort) {
  // The README is the front page; a topic or command page that grows past this is two.
  constexpr std::uintmax_t kReadme = 12000, kPage = 15000;
  for (const fs::path& page : all_pages()) {
    const std::uintmax_t limit = page.filename() == "README.md" && page.parent_path() == kRoot ? kReadme : kPage;
    EXPECT_LE(fs::file_size(page), limit) << page.string() << " is over " << limit << " bytes";
  }
}

TEST(Docs, EveryRelativeLinkPointsAtAFile) {
  const std::regex fenced("```[\\s\\S]*?```");  // code blocks hold no links
  const std::regex link(R"(\]\(([^)\s]+)\))");
  const std::regex scheme("^[a-zA-Z][a-zA-Z0-9+.-]*:");
  std::size_t links = 0;
  for (const fs::path& page : all_pages()) {
    const std::string text = std::regex_replace(read(page), fenced, "");
    for (std::sregex_iterator m(text.begin(), text.end(), link), end; m != end; ++m) {
      const std::string target = (*m)[1];
      if (std::regex_search(target, scheme)) continue;  // https:, mailto:
      const std::string path = target.substr(0, target.find('#'));
      if (path.empty()) continue;  // an anchor on the same page
      ++links;
      EXPECT_TRUE(fs::exists(page.parent_path() / path))
          << page.string() << " links to " << target << ", and " << (page.parent_path() / path).lexically_normal().string()
          << " does not exist";
    }
  }
  EXPECT_GT(links, 50u);
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
