// The layers point one way (the brief, and radiosity/CMakeLists.txt): plugin/ -> radiosity/
// -> mesh/, and inside radiosity/ transfer <- sources <- solver <- analysis <- design,
// climate, and pipeline above design and climate. Every #include of the project's own headers in mesh/ and
// radiosity/ is read and checked against the folders its file may use; mesh/ also names
// no radiosity word.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace dynrad {
namespace {

namespace fs = std::filesystem;
const fs::path kRoot = DYNRAD_SOURCE_DIR;

// The part of the project a file belongs to: "plugin", "mesh/FOLDER" or "radiosity/FOLDER";
// "mesh" for mesh/load.*, the input path above mesh/'s three libraries.
std::string layer_of(const std::string& path) {
  const auto slash = path.find('/');
  const std::string top = path.substr(0, slash);
  if (top != "radiosity" && top != "mesh") return top;
  const auto next = path.find('/', slash + 1);
  if (next != std::string::npos) return path.substr(0, next);
  // radiosity/shoot.cpp, the paper's Figure 5, is the solver's (at the top, where a
  // reader starts).
  return top == "mesh" ? "mesh" : "radiosity/solver";
}

std::vector<fs::path> sources_under(const std::string& folder) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(kRoot / folder))
    if (e.is_regular_file() && (e.path().extension() == ".h" || e.path().extension() == ".cpp"))
      out.push_back(e.path());
  return out;
}

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Layering, EveryIncludePointsDownTheLayers) {
  std::map<std::string, std::set<std::string>> allowed = {
      {"mesh", {"mesh"}},
      {"mesh/core", {"mesh/core"}},
      {"mesh/repair", {"mesh/core", "mesh/repair"}},
      {"mesh/io", {"mesh/core", "mesh/io"}},
      {"radiosity/transfer", {"mesh", "radiosity/transfer"}},
      {"radiosity/sources", {"mesh", "radiosity/transfer", "radiosity/sources"}},
      {"radiosity/solver", {"mesh", "radiosity/transfer", "radiosity/sources", "radiosity/solver"}},
      {"radiosity/analysis",
       {"mesh", "radiosity/transfer", "radiosity/sources", "radiosity/solver", "radiosity/analysis"}},
      {"radiosity/design",
       {"mesh", "radiosity/transfer", "radiosity/sources", "radiosity/solver", "radiosity/analysis",
        "radiosity/design"}},
      {"radiosity/climate",
       {"mesh", "radiosity/transfer", "radiosity/sources", "radiosity/solver", "radiosity/analysis",
        "radiosity/climate"}},
      {"radiosity/pipeline",
       {"mesh", "radiosity/transfer", "radiosity/sources", "radiosity/solver", "radiosity/analysis",
        "radiosity/design", "radiosity/climate", "radiosity/pipeline"}},
  };
  // "mesh" above: all of mesh/ (its three libraries and load.h, which uses them all).
  for (auto& [layer, uses] : allowed)
    if (uses.erase("mesh") > 0) uses.insert({"mesh", "mesh/core", "mesh/repair", "mesh/io"});
  const std::regex include(R"re(#include\s+"((mesh|radiosity|plugin)/[^"]+)")re");
  std::size_t files = 0, includes = 0;
  for (const char* folder : {"mesh", "radiosity"})
    for (const fs::path& file : sources_under(folder)) {
      const std::string relative = fs::relative(file, kRoot).generic_string();
      const std::string layer = layer_of(relative);
      ASSERT_TRUE(allowed.count(layer)) << relative << " lies outside every layer";
      ++files;
      const std::string text = read(file);
      for (std::sregex_iterator m(text.begin(), text.end(), include), end; m != end; ++m) {
        ++includes;
        const std::string target = (*m)[1];
        EXPECT_TRUE(fs::exists(kRoot / target)) << relative << " includes " << target << ", which does not exist";
        EXPECT_TRUE(allowed.at(layer).count(layer_of(target)))
            << relative << " (" << layer << ") includes " << target << " (" << layer_of(target) << ")";
      }
    }
  EXPECT_GT(files, 150u);
  EXPECT_GT(includes, 300u);
}

TEST(Layering, MeshNamesNoRadiosity) {
  // mesh/ is geometry, cleanup, refinement and I/O: no radiosity, luminaire or sky in
  // its code (comments may say what uses it).
  const std::regex word(R"(\b(radiosity|luminaire|Luminaire|rad::)\b)");
  for (const fs::path& file : sources_under("mesh")) {
    std::istringstream lines(read(file));
    std::string line;
    int number = 0;
    while (std::getline(lines, line)) {
      ++number;
      const auto comment = line.find("//");
      const std::string code = comment == std::string::npos ? line : line.substr(0, comment);
      EXPECT_FALSE(std::regex_search(code, word)) << file.generic_string() << ":" << number << ": " << line;
    }
  }
}

}  // namespace
}  // namespace dynrad
