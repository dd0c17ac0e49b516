// OBJ + MTL through tinyobjloader. A first pass over the text validates every `v` and
// `f` statement (so errors carry line numbers, which tinyobjloader does not report)
// and checks that each `mtllib` exists; tinyobjloader then does the actual parse.
#include "mesh/error.h"
#include "mesh/import.h"
#include "mesh/io_util.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>

namespace dynrad {
namespace detail {
PolygonSoup read_obj(const std::string& path);
}

namespace {

struct ObjLines {
  std::vector<std::uint32_t> face_lines;        // line of each `f`, in file order
  std::vector<std::uint32_t> face_usemtl;       // index into usemtl_names, or UINT32_MAX
  std::vector<std::string> usemtl_names;        // in order of first use
  std::vector<std::uint32_t> usemtl_lines;      // line of first use
};

std::vector<std::string> split_ws(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

bool parse_double(const std::string& token, double& value) {
  const char* begin = token.c_str();
  char* end = nullptr;
  value = std::strtod(begin, &end);
  return end != begin && *end == '\0';
}

// Validates the statements we rely on; returns line bookkeeping for later messages.
ObjLines scan_obj(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  if (text.find('\0') != std::string::npos)
    throw InputError(path, 0,
                     "contains binary data, so it is not a text OBJ file. Is it mislabelled "
                     "(a PLY or STL saved as .obj)? Rename it to its real extension.");
  ObjLines result;
  std::size_t vertex_count = 0;
  std::size_t line_no = 0;
  std::uint32_t current_material = UINT32_MAX;
  std::istringstream in(text);
  const fs::path dir = fs::path(path).parent_path();
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto tokens = split_ws(line);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    const std::string& key = tokens[0];
    const auto at = static_cast<std::uint32_t>(line_no);
    if (key == "v") {
      if (tokens.size() < 4)
        throw InputError(path, line_no,
                         "vertex has " + std::to_string(tokens.size() - 1) +
                             " coordinates, 3 are needed (is the file truncated?).");
      for (int i = 1; i <= 3; ++i) {
        double value = 0;
        if (!parse_double(tokens[i], value))
          throw InputError(path, line_no, "vertex coordinate '" + tokens[i] + "' is not a number.");
        if (!std::isfinite(value))
          throw InputError(path, line_no,
                           "vertex coordinate '" + tokens[i] +
                               "' is not finite. Fix or remove this vertex in the modelling tool.");
      }
      ++vertex_count;
    } else if (key == "f") {
      if (tokens.size() < 4)
        throw InputError(path, line_no,
                         "face has " + std::to_string(tokens.size() - 1) +
                             " vertices, at least 3 are needed (is the file truncated?).");
      for (std::size_t i = 1; i < tokens.size(); ++i) {
        const std::string ref = tokens[i].substr(0, tokens[i].find('/'));
        char* end = nullptr;
        const long index = std::strtol(ref.c_str(), &end, 10);
        if (ref.empty() || *end != '\0' || index == 0)
          throw InputError(path, line_no, "face vertex '" + tokens[i] + "' is not a valid vertex reference.");
        const long resolved = index > 0 ? index : static_cast<long>(vertex_count) + 1 + index;
        if (resolved < 1 || resolved > static_cast<long>(vertex_count))
          throw InputError(path, line_no,
                           "face refers to vertex " + std::to_string(index) + " but only " +
                               std::to_string(vertex_count) + " vertices are defined before this line.");
      }
      result.face_lines.push_back(at);
      result.face_usemtl.push_back(current_material);
    } else if (key == "mtllib") {
      for (std::size_t i = 1; i < tokens.size(); ++i) {
        const fs::path lib = dir / tokens[i];
        if (!fs::exists(lib))
          throw InputError(path, line_no,
                           "material library '" + tokens[i] + "' not found (looked for " + lib.string() +
                               "). Put the .mtl file next to the .obj or remove the mtllib line.");
      }
    } else if (key == "usemtl" && tokens.size() >= 2) {
      auto it = std::find(result.usemtl_names.begin(), result.usemtl_names.end(), tokens[1]);
      current_material = static_cast<std::uint32_t>(it - result.usemtl_names.begin());
      if (it == result.usemtl_names.end()) {
        result.usemtl_names.push_back(tokens[1]);
        result.usemtl_lines.push_back(at);
      }
    }
  }
  return result;
}

// Line of `newmtl NAME` in an MTL file, for messages about that material; 0 if not found.
std::size_t find_newmtl_line(const std::string& mtl_path, const std::string& name) {
  std::ifstream in(mtl_path);
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto tokens = split_ws(line);
    if (tokens.size() >= 2 && tokens[0] == "newmtl" && tokens[1] == name) return line_no;
  }
  return 0;
}

std::vector<std::string> mtl_libraries(const std::string& text) {
  std::vector<std::string> libs;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const auto tokens = split_ws(line);
    if (tokens.size() >= 2 && tokens[0] == "mtllib") libs.insert(libs.end(), tokens.begin() + 1, tokens.end());
  }
  return libs;
}

}  // namespace

PolygonSoup detail::read_obj(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string text = detail::read_file(path);
  const ObjLines lines = scan_obj(path, text);

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // CGAL triangulates, concave polygons included
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config))
    throw InputError(path, 0, "OBJ parse failed: " + reader.Error());

  PolygonSoup soup;
  soup.files.push_back(path);
  const auto& attrib = reader.GetAttrib();
  soup.points.reserve(attrib.vertices.size() / 3);
  for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
    soup.points.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);

  // Materials: tinyobjloader's list, then undefined names that `usemtl` refers to.
  const fs::path dir = fs::path(path).parent_path();
  const auto libs = mtl_libraries(text);
  for (const auto& m : reader.GetMaterials()) {
    Material mat;
    mat.name = m.name;
    mat.reflectance = Rgb(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    mat.emission = Rgb(m.emission[0], m.emission[1], m.emission[2]);
    mat.origin = libs.empty() ? path : (dir / libs.front()).string();
    for (const auto& lib : libs) {
      const std::string lib_path = (dir / lib).string();
      if (std::size_t l = find_newmtl_line(lib_path, m.name)) {
        mat.origin = lib_path + ":" + std::to_string(l);
        break;
      }
    }
    soup.materials.push_back(mat);
  }
  // Each `usemtl` name maps to a material; names no MTL defines stay as placeholders
  // (defined == false) that a scene file may still define.
  std::vector<std::uint32_t> usemtl_material(lines.usemtl_names.size());
  for (std::size_t u = 0; u < lines.usemtl_names.size(); ++u) {
    int index = soup.find_material(lines.usemtl_names[u]);
    if (index < 0) {
      Material undefined;
      undefined.name = lines.usemtl_names[u];
      undefined.defined = false;
      undefined.origin = path + ":" + std::to_string(lines.usemtl_lines[u]);
      soup.materials.push_back(undefined);
      index = static_cast<int>(soup.materials.size() - 1);
    }
    usemtl_material[u] = static_cast<std::uint32_t>(index);
  }
  auto default_material = [&soup, index = -1]() mutable {
    if (index < 0) index = soup.find_material("default");
    if (index < 0) {
      Material fallback;
      fallback.name = "default";
      fallback.origin = "built-in default (grey, reflectance 0.5)";
      soup.materials.push_back(fallback);
      index = static_cast<int>(soup.materials.size() - 1);
    }
    return static_cast<std::uint32_t>(index);
  };

  std::size_t total_faces = 0;
  for (const auto& shape : reader.GetShapes()) total_faces += shape.mesh.num_face_vertices.size();
  if (total_faces != lines.face_lines.size())
    throw InputError(path, 0,
                     "found " + std::to_string(lines.face_lines.size()) + " face statements but the OBJ parser read " +
                         std::to_string(total_faces) + " faces; the file may be malformed.");

  std::size_t face = 0;
  for (const auto& shape : reader.GetShapes()) {
    const std::uint32_t group = soup.find_or_add_group(shape.name.empty() ? "default" : shape.name);
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face) {
      const std::size_t n = shape.mesh.num_face_vertices[f];
      std::vector<std::uint32_t> poly(n);
      for (std::size_t k = 0; k < n; ++k)
        poly[k] = static_cast<std::uint32_t>(shape.mesh.indices[offset + k].vertex_index);
      offset += n;
      const std::uint32_t u = lines.face_usemtl[face];
      soup.polygons.push_back(std::move(poly));
      soup.material.push_back(u == UINT32_MAX ? default_material() : usemtl_material[u]);
      soup.group.push_back(group);
      soup.origin.push_back(SourceRef{0, lines.face_lines[face], static_cast<std::uint32_t>(face)});
    }
  }
  return soup;
}

}  // namespace dynrad
