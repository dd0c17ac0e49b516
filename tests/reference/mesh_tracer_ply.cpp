// The PLY reader (read_ply in mesh_tracer.h): the triangles of a file as `dynrad clean`
// writes it, with the vertices' reflectances, in ASCII or binary of either byte order.
#include "reference/mesh_tracer.h"
#include "reference/mesh_tracer_internal.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <istream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace dynrad_test::mesh_tracer {
using namespace detail;

// ---------------------------------------------------------------------------------
// PLY.

namespace {

enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

int size_of(PlyType t) {
  switch (t) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32:
      return 4;
    case PlyType::float64:
      return 8;
  }
  return 0;
}

bool parse_type(const std::string& name, PlyType& t) {
  static const std::pair<const char*, PlyType> names[] = {
      {"char", PlyType::int8},      {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},    {"short", PlyType::int16},     {"int16", PlyType::int16},
      {"ushort", PlyType::uint16},  {"uint16", PlyType::uint16},   {"int", PlyType::int32},
      {"int32", PlyType::int32},    {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
      {"float", PlyType::float32},  {"float32", PlyType::float32}, {"double", PlyType::float64},
      {"float64", PlyType::float64}};
  for (const auto& [text_, type] : names)
    if (name == text_) {
      t = type;
      return true;
    }
  return false;
}

struct PlyProperty {
  std::string name;
  bool list = false;
  PlyType count_type = PlyType::uint8;  // lists only
  PlyType type = PlyType::float32;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { ascii, little_endian, big_endian };

// Reads the values of a PLY's body, one at a time, in the file's format.
class PlyBody {
 public:
  PlyBody(std::istream& in, PlyFormat format) : in_(in), format_(format) {
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    swap_ = (format == PlyFormat::little_endian) != (first == 1);
  }

  // False at the end of the file or on a malformed value.
  bool read(PlyType t, double& value) {
    if (format_ == PlyFormat::ascii) {
      std::string token;
      if (!(in_ >> token)) return false;
      char* end = nullptr;
      value = std::strtod(token.c_str(), &end);
      return end != token.c_str() && *end == '\0';
    }
    unsigned char bytes[8];
    const int n = size_of(t);
    if (!in_.read(reinterpret_cast<char*>(bytes), n)) return false;
    if (swap_) std::reverse(bytes, bytes + n);
    switch (t) {
      case PlyType::int8:
        value = static_cast<std::int8_t>(bytes[0]);
        break;
      case PlyType::uint8:
        value = bytes[0];
        break;
      case PlyType::int16:
        value = as<std::int16_t>(bytes);
        break;
      case PlyType::uint16:
        value = as<std::uint16_t>(bytes);
        break;
      case PlyType::int32:
        value = as<std::int32_t>(bytes);
        break;
      case PlyType::uint32:
        value = as<std::uint32_t>(bytes);
        break;
      case PlyType::float32:
        value = as<float>(bytes);
        break;
      case PlyType::float64:
        value = as<double>(bytes);
        break;
    }
    return true;
  }

 private:
  template <class T>
  static T as(const unsigned char* bytes) {
    T v;
    std::memcpy(&v, bytes, sizeof v);
    return v;
  }
  std::istream& in_;
  PlyFormat format_;
  bool swap_ = false;
};

}  // namespace

Scene read_ply(const std::string& path) {
  auto fail = [&path](const std::string& what) -> void { throw std::runtime_error(path + ": " + what); };
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(std::string("cannot open it (") + std::strerror(errno) + ")");

  // Header.
  std::string line;
  int line_number = 0;
  auto next_line = [&]() -> bool {
    if (!std::getline(in, line)) return false;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  };
  if (!next_line() || line != "ply") fail("not a PLY file (its first line is not \"ply\")");
  PlyFormat format = PlyFormat::ascii;
  bool has_format = false;
  std::vector<PlyElement> elements;
  for (;;) {
    if (!next_line()) fail("the header has no end_header line");
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    const std::string where = "header line " + std::to_string(line_number) + " (\"" + line + "\"): ";
    if (keyword == "end_header") break;
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      std::string name, version;
      words >> name >> version;
      if (name == "ascii") {
        format = PlyFormat::ascii;
      } else if (name == "binary_little_endian") {
        format = PlyFormat::little_endian;
      } else if (name == "binary_big_endian") {
        format = PlyFormat::big_endian;
      } else {
        fail(where + "unknown format \"" + name + "\"");
      }
      has_format = true;
    } else if (keyword == "element") {
      PlyElement e;
      long long count = -1;
      if (!(words >> e.name >> count) || count < 0) fail(where + "an element needs a name and a count");
      e.count = static_cast<std::uint64_t>(count);
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) fail(where + "a property before any element");
      PlyProperty p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> p.name;
        p.list = true;
        if (!parse_type(count_type, p.count_type) || !parse_type(item_type, p.type))
          fail(where + "unknown list types \"" + count_type + "\", \"" + item_type + "\"");
      } else {
        words >> p.name;
        if (!parse_type(type, p.type)) fail(where + "unknown type \"" + type + "\"");
      }
      if (p.name.empty()) fail(where + "a property without a name");
      elements.back().properties.push_back(p);
    } else {
      fail(where + "unknown keyword \"" + keyword + "\"");
    }
  }
  if (!has_format) fail("the header has no format line");

  // Body.
  PlyBody body(in, format);
  std::vector<Vec3> positions;
  std::vector<Rgb> reflectances;
  Scene scene;
  bool seen_vertices = false, seen_faces = false;
  for (const PlyElement& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int role[64];  // vertex: property -> 0..2 position, 3..5 reflectance, -1 other
    int faces_from = -1;
    if (e.properties.size() > 64) fail("element \"" + e.name + "\" has more than 64 properties");
    if (is_vertex) {
      if (seen_faces) fail("the faces come before the vertices");
      static const char* names[6] = {"x", "y", "z", "reflectance_r", "reflectance_g", "reflectance_b"};
      bool found[6] = {};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        role[k] = -1;
        for (int r = 0; r < 6; ++r)
          if (e.properties[k].name == names[r] && !e.properties[k].list) role[k] = r, found[r] = true;
      }
      for (int r = 0; r < 6; ++r)
        if (!found[r])
          fail(std::string("the vertices have no \"") + names[r] + "\" property" +
               (r >= 3 ? " (write the PLY with `dynrad clean`, which adds reflectance_r, _g and _b)" : ""));
      seen_vertices = true;
      positions.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(e.count, 1u << 24)));
      reflectances.reserve(positions.capacity());
    }
    if (is_face) {
      if (!seen_vertices) fail("the faces come before the vertices");
      for (std::size_t k = 0; k < e.properties.size(); ++k)
        if (e.properties[k].list &&
            (e.properties[k].name == "vertex_indices" || e.properties[k].name == "vertex_index"))
          faces_from = static_cast<int>(k);
      if (faces_from < 0) fail("the faces have no vertex_indices list");
      seen_faces = true;
    }
    for (std::uint64_t item = 0; item < e.count; ++item) {
      const std::string where = e.name + " " + std::to_string(item);
      Vec3 position;
      Rgb rho{};
      std::array<double, 3> corner_ids{};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        double value = 0;
        if (!p.list) {
          if (!body.read(p.type, value)) fail("ends early or has a bad value, at " + where + " property " + p.name);
          if (!is_vertex || role[k] < 0) continue;
          if (role[k] < 3) {
            (role[k] == 0 ? position.x : role[k] == 1 ? position.y : position.z) = value;
          } else {
            rho[role[k] - 3] = value;
          }
          continue;
        }
        double count = 0;
        if (!body.read(p.count_type, count) || count < 0 || count != std::floor(count))
          fail("ends early or has a bad list length, at " + where + " property " + p.name);
        const bool corners = is_face && static_cast<int>(k) == faces_from;
        if (corners && count != 3)
          fail(where + " has " + std::to_string(static_cast<long long>(count)) +
               " corners; only triangles are read (write the PLY with `dynrad clean`, which triangulates)");
        for (long long i = 0; i < static_cast<long long>(count); ++i) {
          if (!body.read(p.type, value)) fail("ends early or has a bad value, at " + where + " property " + p.name);
          if (corners) corner_ids[static_cast<std::size_t>(i)] = value;
        }
      }
      if (is_vertex) {
        if (!finite(position)) fail(where + " is at " + text(position));
        for (int c = 0; c < 3; ++c)
          if (!(rho[c] >= 0 && rho[c] <= 1))
            fail(where + " has reflectance " + std::to_string(rho[c]) + " in channel " + std::to_string(c) +
                 ", outside [0, 1]");
        positions.push_back(position);
        reflectances.push_back(rho);
      } else if (is_face) {
        Triangle t;
        for (int c = 0; c < 3; ++c) {
          const double id = corner_ids[static_cast<std::size_t>(c)];
          if (!(id >= 0 && id < static_cast<double>(positions.size())) || id != std::floor(id))
            fail(where + " uses vertex " + std::to_string(static_cast<long long>(id)) + ", but there are " +
                 std::to_string(positions.size()) + " vertices");
          const std::size_t v = static_cast<std::size_t>(id);
          t.corners[static_cast<std::size_t>(c)] = positions[v];
          for (int ch = 0; ch < 3; ++ch) t.reflectance[ch] += reflectances[v][ch] / 3;
        }
        scene.triangles.push_back(t);
      }
    }
  }
  if (!seen_vertices) fail("it has no vertex element");
  if (!seen_faces) fail("it has no face element");
  if (scene.triangles.empty()) fail("it has no faces");
  return scene;
}

}  // namespace dynrad_test::mesh_tracer
