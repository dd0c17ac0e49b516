// OBJ + MTL through tinyobjloader. The text is decoded first (a UTF-8 or UTF-16
// byte-order mark, io_util.h), and so are the MTL libraries, which tinyobjloader gets
// through a MaterialReader of ours. A first pass over the text validates every `v` and
// `f` statement (so errors carry line numbers, which tinyobjloader does not report)
// and checks that each `mtllib` exists (a warning, or an error when reading strictly);
// tinyobjloader then does the actual parse.
#include "mesh/core/error.h"
#include "mesh/io/import.h"
#include "mesh/io/io_util.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <sstream>
#include <unordered_map>

namespace dynrad {
namespace detail {
PolygonSoup read_obj(const std::string& path, const ReadOptions& options);
}

namespace {

struct ObjLines {
  std::vector<std::uint32_t> face_lines;    // line of each `f`, in file order
  std::vector<std::uint32_t> face_usemtl;   // index into usemtl_names, or UINT32_MAX
  std::vector<std::string> usemtl_names;    // in order of first use
  std::vector<std::uint32_t> usemtl_lines;  // line of first use
  std::size_t vertex_count = 0;             // `v` statements
  std::vector<std::string> warnings;        // missing material libraries
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
ObjLines scan_obj(const std::string& path, const std::string& text, const ReadOptions& options) {
  namespace fs = std::filesystem;
  if (text.find('\0') != std::string::npos)
    throw InputError(path, 0,
                     "contains binary data, so it is not a text OBJ file. Is it mislabelled "
                     "(a PLY or STL saved as .obj)? Rename it to its real extension.");
  ObjLines result;
  std::size_t vertex_count = 0;
  std::size_t line_no = 0;
  std::uint32_t current_material = UINT32_MAX;
  std::unordered_map<std::string, std::uint32_t> usemtl_index;  // models with 10^5 materials exist
  std::istringstream in(text);
  const fs::path dir = fs::path(path).parent_path();
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto tokens = split_ws(line);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    // Control characters (a vertical tab, a form feed...) are whitespace to this check
    // but not to tinyobjloader, so the two would read different statements.
    for (const char c : line)
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t') {
        char code[8];
        std::snprintf(code, sizeof code, "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(c)));
        throw InputError(path, line_no,
                         std::string("contains the control character ") + code +
                             ", which OBJ readers do not agree on. Remove it (only spaces and tabs separate words).");
      }
    const std::string& key = tokens[0];
    const auto at = static_cast<std::uint32_t>(line_no);
    if (key == "v") {
      if (tokens.size() < 4)
        throw InputError(
            path, line_no,
            "vertex has " + std::to_string(tokens.size() - 1) + " coordinates, 3 are needed (is the file truncated?).");
      for (int i = 1; i <= 3; ++i) {
        double value = 0;
        if (!parse_double(tokens[i], value))
          throw InputError(path, line_no, "vertex coordinate '" + tokens[i] + "' is not a number.");
        if (!std::isfinite(value))
          throw InputError(
              path, line_no,
              "vertex coordinate '" + tokens[i] + "' is not finite. Fix or remove this vertex in the modelling tool.");
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
        if (fs::exists(lib)) continue;
        if (options.strict)
          throw InputError(path, line_no,
                           "material library '" + tokens[i] + "' not found (looked for " + lib.string() +
                               "). Put the .mtl file next to the .obj or remove the mtllib line.");
        result.warnings.push_back(path + ":" + std::to_string(line_no) + ": material library '" + tokens[i] +
                                  "' not found (looked for " + lib.string() +
                                  "); the materials it should define get the default (grey, reflectance 0.5, no "
                                  "emission) unless a scene file defines them.");
      }
    } else if (key == "usemtl" && tokens.size() >= 2) {
      const auto [it, added] = usemtl_index.emplace(tokens[1], static_cast<std::uint32_t>(result.usemtl_names.size()));
      current_material = it->second;
      if (added) {
        result.usemtl_names.push_back(tokens[1]);
        result.usemtl_lines.push_back(at);
      }
    }
  }
  result.vertex_count = vertex_count;
  return result;
}

// Line of the first `newmtl NAME` of every material in an MTL file's text, for
// messages about that material. One pass per file: looking each material up separately
// would read the file once per material.
std::unordered_map<std::string, std::size_t> newmtl_lines(const std::string& mtl_text) {
  std::unordered_map<std::string, std::size_t> lines;
  std::istringstream in(mtl_text);
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto tokens = split_ws(line);
    if (tokens.size() >= 2 && tokens[0] == "newmtl") lines.emplace(tokens[1], line_no);
  }
  return lines;
}

// Hands tinyobjloader each `mtllib` library as decoded text, and remembers the ones it
// read (in order) with their `newmtl` lines. A library that is missing or not a file is
// left out (scan_obj has warned, or refused when reading strictly); one that cannot be
// read or decoded is an error, kept until tinyobjloader has returned.
class MtlLibraries final : public tinyobj::MaterialReader {
 public:
  explicit MtlLibraries(std::filesystem::path dir) : dir_(std::move(dir)) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* index, std::string* warn, std::string* err) override {
    const std::string lib_path = (dir_ / name).string();
    std::error_code ec;
    if (error || !std::filesystem::is_regular_file(lib_path, ec)) return false;
    try {
      const std::string text = detail::read_text_file(lib_path);
      std::istringstream stream(text);
      tinyobj::LoadMtl(index, materials, &stream, warn, err);
      loaded.emplace_back(lib_path, newmtl_lines(text));
    } catch (...) {
      error = std::current_exception();
      return false;
    }
    return true;
  }

  std::vector<std::pair<std::string, std::unordered_map<std::string, std::size_t>>> loaded;
  std::exception_ptr error;

 private:
  std::filesystem::path dir_;
};

}  // namespace

PolygonSoup detail::read_obj(const std::string& path, const ReadOptions& options) {
  namespace fs = std::filesystem;
  const std::string text = detail::read_text_file(path);
  const ObjLines lines = scan_obj(path, text, options);

  const fs::path dir = fs::path(path).parent_path();
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string parse_warnings, parse_error;
  std::istringstream stream(text);
  MtlLibraries libraries(dir);
  const bool parsed = tinyobj::LoadObj(&attrib, &shapes, &materials, &parse_warnings, &parse_error, &stream, &libraries,
                                       /*triangulate=*/false,  // CGAL triangulates, concave ones too
                                       /*default_vcols_fallback=*/false);
  if (libraries.error) std::rethrow_exception(libraries.error);
  if (!parsed) throw InputError(path, 0, "OBJ parse failed: " + parse_error);

  PolygonSoup soup;
  soup.files.push_back(path);
  soup.warnings = lines.warnings;
  if (attrib.vertices.size() / 3 != lines.vertex_count)
    throw InputError(path, 0,
                     "found " + std::to_string(lines.vertex_count) + " vertex statements but the OBJ parser read " +
                         std::to_string(attrib.vertices.size() / 3) + " vertices; the file may be malformed.");
  soup.points.reserve(attrib.vertices.size() / 3);
  for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
    soup.points.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);

  // Materials: tinyobjloader's list, then undefined names that `usemtl` refers to.
  std::unordered_map<std::string, std::uint32_t> material_index;
  for (const auto& m : materials) {
    Material mat;
    mat.name = m.name;
    mat.reflectance = Rgb(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    mat.emission = Rgb(m.emission[0], m.emission[1], m.emission[2]);
    // Glass: `d` (dissolve, the opacity) below 1 makes it transmit 1 - d, tinted by
    // `Tf` when that is given (many exporters write `Tf 1 1 1` for every material, so
    // Tf alone does not make a window).
    if (m.dissolve < 1.0 && m.dissolve >= 0.0) {
      Rgb filter(1.0);
      if (m.transmittance[0] > 0 || m.transmittance[1] > 0 || m.transmittance[2] > 0)
        filter = Rgb(std::min(1.0, static_cast<double>(m.transmittance[0])),
                     std::min(1.0, static_cast<double>(m.transmittance[1])),
                     std::min(1.0, static_cast<double>(m.transmittance[2])));
      mat.transmittance = filter * (1.0 - m.dissolve);
      if (mat.transmittance.max_channel() >= 1.0) mat.transmittance = mat.transmittance * (0.999 / mat.transmittance.max_channel());
    }
    mat.origin = libraries.loaded.empty() ? path : libraries.loaded.front().first;
    for (const auto& [lib_path, lines_of] : libraries.loaded) {
      const auto at = lines_of.find(m.name);
      if (at != lines_of.end()) {
        mat.origin = lib_path + ":" + std::to_string(at->second);
        break;
      }
    }
    material_index.emplace(mat.name, static_cast<std::uint32_t>(soup.materials.size()));
    soup.materials.push_back(mat);
  }
  // Each `usemtl` name maps to a material; names no MTL defines stay as placeholders
  // (defined == false) that a scene file may still define.
  std::vector<std::uint32_t> usemtl_material(lines.usemtl_names.size());
  for (std::size_t u = 0; u < lines.usemtl_names.size(); ++u) {
    const auto known = material_index.find(lines.usemtl_names[u]);
    if (known != material_index.end()) {
      usemtl_material[u] = known->second;
      continue;
    }
    Material undefined;
    undefined.name = lines.usemtl_names[u];
    undefined.defined = false;
    undefined.origin = path + ":" + std::to_string(lines.usemtl_lines[u]);
    usemtl_material[u] = static_cast<std::uint32_t>(soup.materials.size());
    soup.materials.push_back(undefined);
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
  for (const auto& shape : shapes) total_faces += shape.mesh.num_face_vertices.size();
  if (total_faces != lines.face_lines.size())
    throw InputError(path, 0,
                     "found " + std::to_string(lines.face_lines.size()) + " face statements but the OBJ parser read " +
                         std::to_string(total_faces) + " faces; the file may be malformed.");

  std::size_t face = 0;
  std::unordered_map<std::string, std::uint32_t> group_index;
  for (const auto& shape : shapes) {
    const std::string& group_name = shape.name.empty() ? std::string("default") : shape.name;
    const auto [known, added] = group_index.emplace(group_name, static_cast<std::uint32_t>(soup.group_names.size()));
    if (added) soup.group_names.push_back(group_name);
    const std::uint32_t group = known->second;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face) {
      const std::size_t n = shape.mesh.num_face_vertices[f];
      std::vector<std::uint32_t> poly(n);
      for (std::size_t k = 0; k < n; ++k) {
        const int index = shape.mesh.indices[offset + k].vertex_index;
        if (index < 0 || static_cast<std::size_t>(index) >= soup.points.size())
          throw InputError(path, lines.face_lines[face], "face refers to a vertex the OBJ parser did not read.");
        poly[k] = static_cast<std::uint32_t>(index);
      }
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
