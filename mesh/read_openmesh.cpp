// PLY, OFF and STL through OpenMesh's readers. OpenMesh normally builds a half-edge
// mesh while reading and drops faces that would make it non-manifold; we read into
// our own BaseImporter instead, so every face reaches cleanup as a polygon soup.
#include "mesh/error.h"
#include "mesh/import.h"
#include "mesh/io_util.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/IO/reader/OFFReader.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string_view>

#include <OpenMesh/Core/System/omstream.hh>

namespace dynrad {
namespace detail {
PolygonSoup read_openmesh(const std::string& path, const ReadOptions& options);
}

namespace {

constexpr double kMaxColourReflectance = 0.95;

using OpenMesh::FaceHandle;
using OpenMesh::VertexHandle;

// Collects points, polygons and face colours; remembers the first invalid index.
class SoupImporter final : public OpenMesh::IO::BaseImporter {
 public:
  std::vector<Vec3d> points;
  std::vector<std::vector<std::uint32_t>> polygons;
  std::vector<Rgb> face_color;  // linear; valid where has_color
  std::vector<char> has_color;
  std::size_t declared_vertices = 0, declared_faces = 0;
  bool reserved = false;
  std::size_t bad_face = SIZE_MAX;  // first face with an out-of-range index
  std::size_t bad_index = 0;
  std::size_t capacity = SIZE_MAX;  // refuse to grow past this many vertices or faces
  bool overflow = false;

  VertexHandle add_vertex(const OpenMesh::Vec3f& p) override { return add_vertex(OpenMesh::Vec3d(p)); }
  VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
    if (points.size() >= capacity) {
      overflow = true;
      return VertexHandle();
    }
    points.push_back(p);
    return VertexHandle(static_cast<int>(points.size() - 1));
  }
  VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0.0)); }
  FaceHandle add_face(const VHandles& indices) override {
    if (polygons.size() >= capacity) {
      overflow = true;
      return FaceHandle();
    }
    std::vector<std::uint32_t> poly;
    poly.reserve(indices.size());
    for (const auto& vh : indices) {
      if (vh.idx() < 0 || static_cast<std::size_t>(vh.idx()) >= points.size()) {
        if (bad_face == SIZE_MAX) {
          bad_face = polygons.size();
          bad_index = static_cast<std::size_t>(vh.idx());
        }
        poly.clear();
        break;
      }
      poly.push_back(static_cast<std::uint32_t>(vh.idx()));
    }
    polygons.push_back(std::move(poly));
    face_color.emplace_back();
    has_color.push_back(0);
    return FaceHandle(static_cast<int>(polygons.size() - 1));
  }
  void set_point(VertexHandle vh, const OpenMesh::Vec3f& p) override {
    if (valid(vh)) points[vh.idx()] = OpenMesh::Vec3d(p);
  }
  void set_color(FaceHandle fh, const OpenMesh::Vec3uc& c) override {
    set_face_rgb(fh, Rgb(detail::srgb_to_linear(c[0] / 255.0), detail::srgb_to_linear(c[1] / 255.0),
                         detail::srgb_to_linear(c[2] / 255.0)));
  }
  void set_color(FaceHandle fh, const OpenMesh::Vec4uc& c) override {
    set_color(fh, OpenMesh::Vec3uc(c[0], c[1], c[2]));
  }
  void set_color(FaceHandle fh, const OpenMesh::Vec3f& c) override { set_face_rgb(fh, Rgb(c[0], c[1], c[2])); }
  void set_color(FaceHandle fh, const OpenMesh::Vec4f& c) override { set_face_rgb(fh, Rgb(c[0], c[1], c[2])); }
  void reserve(unsigned int nv, unsigned int /*ne*/, unsigned int nf) override {
    declared_vertices = nv;
    declared_faces = nf;
    reserved = true;
    if (nv <= capacity) points.reserve(nv);
    if (nf <= capacity) polygons.reserve(nf);
  }
  size_t n_vertices() const override { return points.size(); }
  size_t n_faces() const override { return polygons.size(); }
  size_t n_edges() const override { return 0; }

  // Everything below carries data we do not use (normals, texture coordinates,
  // vertex and edge colours, status flags, raw half-edge construction).
  OpenMesh::HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return OpenMesh::HalfedgeHandle(); }
  FaceHandle add_face(OpenMesh::HalfedgeHandle) override { return FaceHandle(); }
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, OpenMesh::HalfedgeHandle) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3d&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(OpenMesh::HalfedgeHandle, OpenMesh::HalfedgeHandle) override {}
  void set_face(OpenMesh::HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(OpenMesh::HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(OpenMesh::EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  bool valid(VertexHandle vh) const { return vh.idx() >= 0 && static_cast<std::size_t>(vh.idx()) < points.size(); }
  void set_face_rgb(FaceHandle fh, const Rgb& c) {
    if (fh.idx() < 0 || static_cast<std::size_t>(fh.idx()) >= polygons.size()) return;
    face_color[fh.idx()] = c;
    has_color[fh.idx()] = 1;
  }
};

// What the first bytes say the file is, to catch mislabelled files before a reader
// produces a confusing failure.
std::string sniff_format(const std::string& head) {
  if (head.rfind("ply", 0) == 0) return ".ply";
  if (head.rfind("OFF", 0) == 0 || head.rfind("COFF", 0) == 0 || head.rfind("NOFF", 0) == 0 ||
      head.rfind("CNOFF", 0) == 0 || head.rfind("STOFF", 0) == 0)
    return ".off";
  if (head.rfind("solid", 0) == 0) return ".stl";
  return "";
}

// For line-based ASCII formats: the 1-based line of every data line after the header
// (OFF: after the counts line, skipping comments; PLY: after end_header), so messages
// about vertex k or face f can name their line.
std::vector<std::uint32_t> ascii_data_lines(const std::string& text, const std::string& ext) {
  std::vector<std::uint32_t> lines;
  std::istringstream in(text);
  std::uint32_t line_no = 0;
  bool in_data = false;
  int off_header_lines = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    if (in_data) {
      lines.push_back(line_no);
    } else if (ext == ".ply") {
      in_data = line.rfind("end_header", 0) == 0;
    } else if (++off_header_lines == 2) {  // the keyword, then "nv nf ne" (check_declared_counts)
      in_data = true;
    }
  }
  return lines;
}

// Whether OpenMesh reads an OFF file as binary: its first line is [ST][C][N]OFF, any one
// character, then BINARY. Anything else it reads as ASCII, so the checks must too.
bool off_is_binary(const std::string& text) {
  std::size_t p = 0;
  if (text.compare(p, 2, "ST") == 0) p += 2;
  if (text.compare(p, 1, "C") == 0) ++p;
  if (text.compare(p, 1, "N") == 0) ++p;
  if (text.compare(p, 3, "OFF") != 0) return false;
  p += 4;
  return p <= text.size() && text.compare(p, 6, "BINARY") == 0 && text.find('\n') > p;
}

// Comments ('#' to the end of the line) replaced by nothing, line breaks kept.
std::string strip_comments(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool comment = false;
  for (char c : text) {
    if (c == '#') comment = true;
    if (c == '\n') comment = false;
    if (!comment) out.push_back(c);
  }
  return out;
}

// A PLY header, parsed and checked before OpenMesh sees it: OpenMesh's reader writes
// through a property line that no element line precedes (a crash), and reads counts
// that do not fit its 32-bit integers as whatever they wrap to.
struct PlyProperty {
  std::string name;
  int size = 0;        // bytes of a scalar, or of each list item
  int count_size = 0;  // bytes of a list's count; 0 for scalars
  bool floating = false;
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};
struct PlyHeader {
  std::string format;  // ascii, binary_little_endian, binary_big_endian
  std::vector<PlyElement> elements;
  std::size_t body = 0;   // offset of the first byte after end_header's line
  std::size_t lines = 0;  // lines up to and including end_header
  std::vector<std::string> warnings;  // lines skipped: neither a PLY keyword nor a comment
};

// Header keywords after the first line ("ply"). Blender, MeshLab and assimp skip lines
// with any other keyword, so dynrad does too, with a warning (or refuses them when
// reading strictly).
bool is_ply_keyword(const std::string& key) {
  return key == "format" || key == "element" || key == "property" || key == "end_header" || key == "comment" ||
         key == "obj_info";
}

int ply_type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

// A count: digits only (OpenMesh reads "-2" as 4294967294), at most 18 of them so that
// sums of counts cannot overflow. Whether the file can hold them is checked later.
bool parse_count(const std::string& token, std::uint64_t& count) {
  if (token.empty() || token.size() > 18 || token.find_first_not_of("0123456789") != std::string::npos) return false;
  count = std::stoull(token);
  return true;
}

PlyHeader parse_ply_header(const std::string& path, const std::string& text, bool strict) {
  PlyHeader header;
  std::istringstream in(text);
  bool ended = false;
  for (std::string line; std::getline(in, line);) {
    ++header.lines;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    auto bad = [&](const std::string& what) {
      throw InputError(path, header.lines, "PLY header: " + what + " The file is damaged or not really PLY.");
    };
    if (header.lines == 1) {
      if (key != "ply") bad("the first line must be 'ply'.");
    } else if (key == "end_header") {
      header.body = in.tellg() < 0 ? text.size() : static_cast<std::size_t>(in.tellg());
      ended = true;
      break;
    } else if (key == "format") {
      std::string version;
      words >> header.format >> version;
      if (header.format != "ascii" && header.format != "binary_little_endian" && header.format != "binary_big_endian")
        bad("unknown format '" + header.format + "' (ascii, binary_little_endian or binary_big_endian).");
      if (version != "1.0") bad("unknown version '" + version + "' (1.0).");
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      if (e.name.empty() || !parse_count(count, e.count))
        bad("'" + line + "' must be 'element NAME COUNT' with a whole number as the count.");
      header.elements.push_back(e);
    } else if (key == "property") {
      if (header.elements.empty()) bad("a property comes before any element.");
      std::string type, a, b;
      words >> type >> a;
      PlyProperty p;
      if (type == "list") {
        words >> b >> p.name;
        p.count_size = ply_type_size(a);
        p.size = ply_type_size(b);
        if (p.count_size == 0 || p.size == 0 || p.name.empty()) bad("'" + line + "' is not a valid list property.");
      } else {
        p.name = a;
        p.size = ply_type_size(type);
        p.floating = type.rfind("float", 0) == 0 || type == "double";
        if (p.size == 0 || p.name.empty()) bad("'" + line + "' has an unknown type or no name.");
      }
      header.elements.back().properties.push_back(p);
    } else if (!key.empty() && !is_ply_keyword(key)) {
      if (strict) bad("unknown keyword '" + key + "'.");
      // Text is skipped; control characters in a header are damage (binary data where
      // the header should be, a header cut short).
      for (const char c : line)
        if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == '\x7F')
          bad("unknown keyword in a line that is not text.");
      header.warnings.push_back(path + ":" + std::to_string(header.lines) + ": PLY header line '" +
                                (line.size() > 60 ? line.substr(0, 57) + "..." : line) +
                                "' has an unknown keyword (known: format, element, property, comment, obj_info, "
                                "end_header); skipped.");
      continue;
    }
    // OpenMesh reads the header word by word: a word too many would be read as the
    // next keyword. (Comments, obj_info and skipped lines reach it as comments,
    // header_for_openmesh.)
    std::string extra;
    if (key != "comment" && key != "obj_info" && words >> extra)
      bad("unexpected '" + extra + "' at the end of the line.");
  }
  if (!ended) throw InputError(path, 0, "PLY header has no end_header line: the file is truncated or damaged.");
  if (header.format.empty()) throw InputError(path, 0, "PLY header has no format line.");
  return header;
}

// A damaged header can declare billions of elements; readers would then allocate or
// loop until the machine gives up. Refuse counts the file's size cannot hold.
struct DeclaredCounts {
  std::uint64_t vertices = 0, faces = 0;
};

// The header as OpenMesh should read it (the body is not part of it), with as many
// lines as the file's, so that line numbers stay those of the file:
// - "ply", then the format line: OpenMesh reads the second and third words after "ply"
//   as the format, whatever line they are on;
// - then comments, obj_info and skipped lines, all as comments, and blank lines:
//   OpenMesh reads a comment to the end of its line but any other line word by word,
//   where a word like "element" would be taken as a keyword;
// - then element and property lines in their order, and end_header. In binary files
//   OpenMesh finds the data by assuming that the line before end_header ends right
//   after its last word, which a comment line (read with its line break) or a blank
//   line breaks by a byte.
std::string header_for_openmesh(const std::string& text, const PlyHeader& header) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (lines.size() < header.lines && start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  std::string format, comments, structure;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::string key;
    std::istringstream(lines[i]) >> key;
    if (key == "format" && format.empty())
      format = lines[i] + "\n";
    else if (key == "element" || key == "property" || key == "end_header" || key == "format")
      structure += lines[i] + "\n";
    else if (key.empty() || key == "comment")
      comments += lines[i] + "\n";
    else  // obj_info, or a line skipped with a warning
      comments += "comment " + lines[i] + "\n";
  }
  return (lines.empty() ? std::string() : lines.front() + "\n") + format + comments + structure;
}

// Binary OFF as OpenMesh 9 reads it, every value 4 bytes: a vertex is x y z, then a
// normal (3) with 'N' in the keyword, a colour (3) with 'C', texture coordinates (2)
// with "ST"; a face is its corner count n, n indices, and a colour (3) with 'C' (read
// because dynrad asks for face colours). OpenMesh takes n as it comes and reads n indices
// past the end of the file (a damaged count of 4 billion ran until the fuzzer's
// timeout), so each face's record is walked here and must fit in the file.
void check_binary_off_faces(const std::string& path, const std::string& text, std::size_t body,
                            std::uint64_t vertices, std::uint64_t faces) {
  std::size_t p = 0;
  bool tex = false, colour = false, normal = false;
  if (text.compare(p, 2, "ST") == 0) tex = true, p += 2;
  if (text.compare(p, 1, "C") == 0) colour = true, ++p;
  if (text.compare(p, 1, "N") == 0) normal = true, ++p;
  const std::uint64_t vertex_bytes = 4 * (3 + (normal ? 3 : 0) + (colour ? 3 : 0) + (tex ? 2 : 0));
  const std::uint64_t size = text.size();
  if (vertices > (size - std::min<std::uint64_t>(size, body)) / vertex_bytes)
    throw InputError(path, 0,
                     "binary OFF declares " + std::to_string(vertices) + " vertices of " +
                         std::to_string(vertex_bytes) + " bytes each, more than the file holds: it is truncated.");
  std::uint64_t at = body + vertices * vertex_bytes;
  for (std::uint64_t f = 0; f < faces; ++f) {
    std::uint32_t corners = 0;
    if (at + 4 > size)
      throw InputError(path, 0,
                       "binary OFF declares " + std::to_string(faces) + " faces but the file ends in face " +
                           std::to_string(f) + ": it is truncated.");
    std::memcpy(&corners, text.data() + at, 4);
    const std::uint64_t record = 4 * (1 + static_cast<std::uint64_t>(corners) + (colour ? 3 : 0));
    if (record > size - at)
      throw InputError(path, 0,
                       "binary OFF face " + std::to_string(f) + " declares " + std::to_string(corners) +
                           " corners, more than the rest of the file holds: the file is damaged.");
    at += record;
  }
}

DeclaredCounts check_declared_counts(const std::string& path, const std::string& text, const std::string& ext,
                                     const PlyHeader& header) {
  std::uint64_t vertices = 0, faces = 0;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> records;  // (count, least bytes per record)
  std::string others;    // PLY elements other than vertex and face, for the message
  std::size_t body = 0;  // offset where element data starts
  if (ext == ".ply") {
    for (const PlyElement& e : header.elements) {
      if (e.name == "vertex") vertices = e.count;
      if (e.name == "face") faces = e.count;
      if (e.name != "vertex" && e.name != "face" && e.count > 0)
        others += ", " + std::to_string(e.count) + " " + e.name + " elements";
      // Every property value takes a byte at least (a digit and a separator in ASCII).
      records.emplace_back(e.count, std::max<std::uint64_t>(1, e.properties.size()));
    }
    body = header.body;
  } else if (ext == ".off") {
    if (off_is_binary(text)) {
      // Binary OFF as OpenMesh reads and writes it: after the first line, three 32-bit
      // little-endian counts (vertices, faces, edges); a vertex is at least 3 floats, a
      // face at least a count and 3 indices. OpenMesh loops over whatever they say.
      body = text.find('\n');
      std::int32_t counts[3] = {0, 0, 0};
      if (body == std::string::npos || text.size() < body + 1 + sizeof counts)
        throw InputError(path, 0, "binary OFF without vertex and face counts: the file is truncated.");
      std::memcpy(counts, text.data() + body + 1, sizeof counts);
      if (counts[0] < 0 || counts[1] < 0)
        throw InputError(path, 0,
                         "binary OFF declares " + std::to_string(counts[0]) + " vertices and " +
                             std::to_string(counts[1]) +
                             " faces: the header is damaged (or big-endian, which "
                             "dynrad does not read; convert the file to PLY).");
      vertices = static_cast<std::uint64_t>(counts[0]);
      faces = static_cast<std::uint64_t>(counts[1]);
      body += 1 + sizeof counts;
      records = {{vertices, 12}, {faces, 16}};
      check_binary_off_faces(path, text, body, vertices, faces);
    } else {
      // OpenMesh takes the whole first line as the keyword and the next three words as
      // the counts, wherever they are. Both are held to one line each here, so that
      // what OpenMesh reads and what is checked (and the line numbers) agree.
      const std::string stripped = strip_comments(text);
      std::istringstream in(stripped);
      std::string magic_line, counts_line;
      std::getline(in, magic_line);
      std::istringstream magic_words(magic_line);
      std::string magic, rest;
      magic_words >> magic >> rest;
      static const std::set<std::string> keywords = {"OFF",   "COFF",   "NOFF",   "CNOFF",
                                                     "STOFF", "STCOFF", "STNOFF", "STCNOFF"};
      if (!keywords.count(magic) || !rest.empty())
        throw InputError(path, 1,
                         "the first line must hold only the keyword (OFF, COFF, NOFF, CNOFF or STOFF), not '" +
                             magic_line + "'. Put the counts on the next line.");
      std::size_t counts_line_no = 1;
      while (std::getline(in, counts_line)) {
        ++counts_line_no;
        if (counts_line.find_first_not_of(" \t\r") != std::string::npos) break;
      }
      std::istringstream count_words(counts_line);
      std::string v, f, e, extra;
      count_words >> v >> f >> e >> extra;
      std::uint64_t edges = 0;
      if (!parse_count(v, vertices) || !parse_count(f, faces) || !parse_count(e, edges) || !extra.empty())
        throw InputError(path, counts_line_no,
                         "the line after the keyword must hold three whole numbers, the vertex, face and edge "
                         "counts (found '" +
                             counts_line + "').");
      body = in.tellg() < 0 ? text.size() : static_cast<std::size_t>(in.tellg());
      records = {{vertices, 3}, {faces, 4}};  // "x y z", and "3 a b c" at the least
    }
  } else {
    return {};  // STL: the count is implied by the size (binary) or absent (ASCII)
  }
  const std::uint64_t room = text.size() > body ? text.size() - body : 0;
  std::uint64_t needed = 0;
  bool fits = true;
  for (const auto& [count, bytes] : records) {
    fits = fits && count <= (room - needed) / bytes;
    if (fits) needed += count * bytes;
  }
  if (!fits)
    throw InputError(path, 0,
                     "the header declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                         " faces" + others + ", more than the " + std::to_string(room) +
                         " bytes after it can hold: the file is truncated or its header is damaged.");
  return {vertices, faces};
}

// Each of the first `count` data lines must hold finite numbers only.
void check_ascii_vertices(const std::string& path, const std::string& text,
                          const std::vector<std::uint32_t>& data_lines, std::size_t count) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    lines.push_back(std::string_view(text).substr(start, end - start));
    start = end + 1;
  }
  for (std::size_t k = 0; k < count && k < data_lines.size(); ++k) {
    const std::string line(lines[data_lines[k] - 1]);
    std::istringstream in(line);
    for (std::string token; in >> token;) {
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0')
        throw InputError(path, data_lines[k], "vertex " + std::to_string(k) + ": '" + token + "' is not a number.");
      if (!std::isfinite(value))
        throw InputError(path, data_lines[k],
                         "vertex " + std::to_string(k) + " has a coordinate that is not finite ('" + token +
                             "'). Fix it in the modelling tool.");
    }
  }
}

// Walks the PLY body (ASCII or binary) before OpenMesh does, for two things OpenMesh
// gets wrong:
// - a list count is believed whatever it says: OpenMesh appends that many indices,
//   reading past the line or the end of the file, until memory runs out;
// - float face colours become bytes without clamping (1.5 becomes 126/255, -0.5
//   becomes 129/255), so a colour outside [0, 1] would silently become another.
// Both are refused naming the element. A body that simply ends early ends the walk
// quietly: the reader's own truncation checks then name what is missing.
void check_ply_body(const std::string& path, const std::string& text, const PlyHeader& header) {
  auto is_colour = [](const std::string& name) {
    return name == "red" || name == "green" || name == "blue" || name == "diffuse_red" || name == "diffuse_green" ||
           name == "diffuse_blue";
  };
  if (header.body > text.size()) return;
  auto check_colour = [&](const PlyElement& e, const PlyProperty& p, std::uint64_t record, std::size_t line,
                          double value) {
    if (e.name != "face" || !p.floating || !is_colour(p.name) || (value >= 0 && value <= 1)) return;
    std::ostringstream v;
    v << value;
    throw InputError(path, line,
                     "face " + std::to_string(record) + " has colour " + p.name + " = " + v.str() +
                         ", outside [0, 1]. Float colours are display colours from 0 to 1; fix the file, or give "
                         "the faces a material in a scene file.");
  };
  auto refuse_list = [&](const PlyElement& e, const PlyProperty& p, std::uint64_t record, std::size_t line,
                         const std::string& count) {
    throw InputError(path, line,
                     e.name + " " + std::to_string(record) + ": the list '" + p.name + "' declares " + count +
                         " entries, more than the " + (line > 0 ? "line" : "file") + " holds. The file is damaged.");
  };

  if (header.format == "ascii") {
    std::istringstream in(text.substr(header.body));
    std::size_t line_no = header.lines;
    for (const PlyElement& e : header.elements) {
      for (std::uint64_t r = 0; r < e.count; ++r) {
        std::string line;
        do {
          if (!std::getline(in, line)) return;
          ++line_no;
        } while (line.find_first_not_of(" \t\r") == std::string::npos);
        std::vector<std::string> tokens;
        std::istringstream words(line);
        for (std::string t; words >> t;) tokens.push_back(t);
        std::size_t next = 0;
        for (const PlyProperty& p : e.properties) {
          if (next >= tokens.size()) break;  // a short line: the reader reports it
          const std::string& token = tokens[next++];
          if (p.count_size > 0) {
            char* end = nullptr;
            const long long n = std::strtoll(token.c_str(), &end, 10);
            if (*end != '\0' || n < 0 || static_cast<unsigned long long>(n) > tokens.size() - next)
              refuse_list(e, p, r, line_no, token);
            // Each entry a number of the list's type: OpenMesh reads an integer entry into
            // an int, and one that does not fit fails its stream, after which every later
            // count it reads is garbage (a 4 GB list: found by fuzzing).
            for (std::size_t k = next; k < next + static_cast<std::size_t>(n); ++k) {
              const std::string& item = tokens[k];
              char* stop = nullptr;
              bool fits = false;
              if (p.floating) {
                std::strtod(item.c_str(), &stop);
                fits = *stop == '\0';
              } else {
                errno = 0;
                const long long v = std::strtoll(item.c_str(), &stop, 10);
                fits = *stop == '\0' && errno == 0 && v >= std::numeric_limits<std::int32_t>::min() &&
                       v <= std::numeric_limits<std::int32_t>::max();
              }
              if (!fits)
                throw InputError(path, line_no,
                                 e.name + " " + std::to_string(r) + ": entry '" + item + "' of the list '" + p.name +
                                     "' is not " + (p.floating ? "a number" : "a whole number that fits in 32 bits") +
                                     ". The file is damaged.");
            }
            next += static_cast<std::size_t>(n);
            continue;
          }
          char* end = nullptr;
          const double value = std::strtod(token.c_str(), &end);  // strtod reads "nan" and "inf" too
          if (*end != '\0')
            throw InputError(path, line_no,
                             e.name + " " + std::to_string(r) + ": '" + token + "' is not a number (" + p.name + ").");
          check_colour(e, p, r, line_no, value);
        }
        // OpenMesh reads the values as one stream of words, not line by line: a value
        // too many on one line shifts every later record (a face count read from a
        // colour, then billions of indices: found by fuzzing).
        if (next < tokens.size())
          throw InputError(path, line_no,
                           e.name + " " + std::to_string(r) + " holds " + std::to_string(tokens.size()) +
                               " values, more than its properties take (" + std::to_string(next) +
                               "). Is a property line in the header misspelt or missing?");
      }
    }
    return;
  }
  const bool big_endian = header.format == "binary_big_endian";
  std::size_t at = header.body;
  auto read_bytes = [&](int size, unsigned char* out) {  // little-endian into `out`
    if (at + size > text.size()) return false;
    for (int i = 0; i < size; ++i) out[i] = static_cast<unsigned char>(text[at + (big_endian ? size - 1 - i : i)]);
    at += size;
    return true;
  };
  for (const PlyElement& e : header.elements) {
    if (e.properties.empty()) continue;
    for (std::uint64_t r = 0; r < e.count; ++r) {
      for (const PlyProperty& p : e.properties) {
        unsigned char bytes[8] = {};
        if (p.count_size > 0) {
          if (!read_bytes(p.count_size, bytes)) return;
          // Counts are read as unsigned: a negative int count is a huge one, and refused.
          std::uint64_t n = 0;
          for (int i = p.count_size - 1; i >= 0; --i) n = (n << 8) | bytes[i];
          if (n > (text.size() - at) / p.size) refuse_list(e, p, r, 0, std::to_string(n));
          at += n * p.size;
          continue;
        }
        if (!read_bytes(p.size, bytes)) return;
        if (!p.floating) continue;
        double value = 0;  // the bytes are little-endian now, as on every machine we build for
        if (p.size == 4) {
          float f = 0;
          std::memcpy(&f, bytes, 4);
          value = f;
        } else {
          std::memcpy(&value, bytes, 8);
        }
        check_colour(e, p, r, 0, value);
      }
    }
  }
}

// ASCII OFF as OpenMesh reads it: each vertex takes three coordinates (six with 'N')
// from the token stream, wherever the line breaks fall, then the rest of its line; each
// face takes its corner count and that many indices from the token stream, and the
// rest of its line only when the keyword has 'C'. So a short vertex line shifts
// everything after it, a corner count is believed (OpenMesh appends that many indices
// until memory runs out), and a colour after a face in a plain "OFF" file is read as
// the next face's corner count. Here every vertex and face line is checked to hold
// what it declares, and without 'C' whatever follows a face's indices is blanked out
// of `parsed` (face colours are not read), so OpenMesh reads what the lines say.
void normalise_ascii_off(const std::string& path, std::string& parsed, const std::vector<std::uint32_t>& data_lines,
                         std::uint64_t vertices, std::uint64_t faces) {
  std::string keyword;
  std::istringstream(parsed.substr(0, parsed.find('\n'))) >> keyword;
  const auto prefix = keyword.substr(0, keyword.size() >= 3 ? keyword.size() - 3 : 0);
  const bool normals = prefix.find('N') != std::string::npos;
  const bool face_rest_read = prefix.find('C') != std::string::npos;
  const std::uint64_t coordinates = normals ? 6 : 3;

  std::vector<std::size_t> line_start = {0};
  for (std::size_t i = 0; i < parsed.size(); ++i)
    if (parsed[i] == '\n') line_start.push_back(i + 1);
  auto line_range = [&](std::size_t line_no) {
    const std::size_t begin = line_start[line_no - 1];
    const std::size_t end = line_no < line_start.size() ? line_start[line_no] - 1 : parsed.size();
    return std::make_pair(begin, end);
  };
  // Token k of a line: where it ends, or npos when the line has fewer.
  auto end_of_token = [&](std::size_t begin, std::size_t end, std::uint64_t k) {
    std::size_t i = begin;
    for (std::uint64_t t = 0; t <= k; ++t) {
      while (i < end && std::isspace(static_cast<unsigned char>(parsed[i]))) ++i;
      if (i == end) return std::string::npos;
      while (i < end && !std::isspace(static_cast<unsigned char>(parsed[i]))) ++i;
    }
    return i;
  };

  for (std::uint64_t v = 0; v < vertices && v < data_lines.size(); ++v) {
    const auto [begin, end] = line_range(data_lines[v]);
    if (end_of_token(begin, end, coordinates - 1) == std::string::npos)
      throw InputError(path, data_lines[v],
                       "vertex " + std::to_string(v) + " must hold " + std::to_string(coordinates) +
                           " numbers on its line (x y z" + (normals ? " and a normal" : "") +
                           "). The file is damaged.");
  }
  for (std::uint64_t f = 0; f < faces && vertices + f < data_lines.size(); ++f) {
    const std::size_t line_no = data_lines[vertices + f];
    const auto [begin, end] = line_range(line_no);
    std::istringstream words(parsed.substr(begin, end - begin));
    std::string count;
    words >> count;
    std::uint64_t n = 0;
    if (!parse_count(count, n))
      throw InputError(path, line_no,
                       "face " + std::to_string(f) + " must start with its number of corners, not '" + count + "'.");
    const std::size_t last = n < end - begin ? end_of_token(begin, end, n) : std::string::npos;
    if (last == std::string::npos) {
      std::uint64_t indices = 0;
      for (std::string t; words >> t;) ++indices;
      throw InputError(path, line_no,
                       "face " + std::to_string(f) + " declares " + std::to_string(n) + " corners but lists " +
                           std::to_string(indices) + ". The file is damaged.");
    }
    // OpenMesh reads each index as far as it parses ("2-4" gives 2, and "-4" becomes the
    // next face's corner count, four billion): every index must be a plain whole number.
    for (std::uint64_t k = 0; k < n; ++k) {
      std::string index;
      words >> index;
      if (index.empty() || !std::all_of(index.begin(), index.end(), [](char c) { return c >= '0' && c <= '9'; }))
        throw InputError(path, line_no,
                         "face " + std::to_string(f) + ": corner " + std::to_string(k) + " is '" + index +
                             "', not a vertex number. The file is damaged.");
    }
    if (!face_rest_read) std::fill(parsed.begin() + static_cast<std::ptrdiff_t>(last),
                                   parsed.begin() + static_cast<std::ptrdiff_t>(end), ' ');
  }
}

bool is_ascii(const std::string& text, const std::string& ext) {
  if (ext == ".off") return !off_is_binary(text);
  if (ext == ".ply") return text.find("format ascii") != std::string::npos;
  return text.rfind("solid", 0) == 0;
}

}  // namespace

PolygonSoup detail::read_openmesh(const std::string& path, const ReadOptions& read_options) {
  const std::string ext = detail::extension_of(path);
  const std::string text = detail::read_file(path);
  const std::string sniffed = sniff_format(text.substr(0, 16));
  const std::string upper = ext == ".ply" ? "PLY" : (ext == ".off" ? "OFF" : "STL");
  if (text.empty()) throw InputError(path, 0, "is empty.");
  if (ext != ".stl" && sniffed != ext)
    throw InputError(path, 0,
                     "does not start like a " + upper + " file" +
                         (sniffed.empty() ? std::string() : " (it looks like " + sniffed + ")") +
                         ". Is it mislabelled or damaged? Rename it to its real extension or re-export it.");

  const PlyHeader ply = ext == ".ply" ? parse_ply_header(path, text, read_options.strict) : PlyHeader();
  const DeclaredCounts declared = check_declared_counts(path, text, ext, ply);
  if (ext == ".ply") check_ply_body(path, text, ply);
  // OFF allows '#' comments, which OpenMesh's reader does not: blank them out
  // (keeping line numbers) and parse from memory. A PLY header is given to OpenMesh as
  // it reads it (header_for_openmesh), with the same number of lines.
  std::string parsed = ext == ".off" ? strip_comments(text) : text;
  if (ext == ".ply") parsed = header_for_openmesh(text, ply) + text.substr(std::min(ply.body, text.size()));
  const bool ascii = ext == ".ply" ? ply.format == "ascii" : is_ascii(text, ext) && ext != ".stl";
  const std::vector<std::uint32_t> data_lines = ascii ? ascii_data_lines(parsed, ext) : std::vector<std::uint32_t>();
  if (ascii && ext == ".off") normalise_ascii_off(path, parsed, data_lines, declared.vertices, declared.faces);

  SoupImporter importer;
  importer.capacity = text.size();  // no format stores an element in less than a byte
  OpenMesh::IO::Options options = OpenMesh::IO::Options::FaceColor;
  // OpenMesh prints its own parse complaints; ours below are more specific.
  omerr().disable();
  bool ok = false;
  const bool binary_off = ext == ".off" && !is_ascii(text, ext);
  if (ext == ".stl" || binary_off) {
    // STL needs the file to tell ASCII from binary; OpenMesh reads binary OFF from a
    // stream as if it were text.
    ok = OpenMesh::IO::IOManager().read(path, importer, options);
  } else {
    if (ext == ".off") {
      // OpenMesh's OFF reader is one object per process that takes its options (binary or
      // not, colours, normals) from the last header it was shown; reading a stream does
      // not show it this one. Without this, an ASCII file read after a binary one was
      // parsed as binary (found by fuzzing). Showing it the file's own first line (the
      // public check reads it from the path) sets them right.
      OpenMesh::IO::OFFReader().can_u_read(path);
    }
    std::istringstream stream(parsed);  // the text already in memory: no second read from disk
    ok = OpenMesh::IO::IOManager().read(stream, ext, importer, options);
  }
  omerr().enable();
  if (importer.overflow) throw InputError(path, 0, "holds more elements than its size allows: the file is damaged.");

  auto data_line = [&](std::size_t k) -> std::size_t { return k < data_lines.size() ? data_lines[k] : 0; };
  auto vertex_location = [&](std::size_t v) { return data_line(v); };
  // OpenMesh's ASCII parsers stop or misread at "nan"/"inf"; check the vertex lines
  // ourselves so the message names the line.
  if (ascii && importer.reserved) check_ascii_vertices(path, parsed, data_lines, importer.declared_vertices);
  if (importer.reserved && importer.points.size() < importer.declared_vertices)
    throw InputError(path, vertex_location(importer.points.size()),
                     "the header declares " + std::to_string(importer.declared_vertices) + " vertices but only " +
                         std::to_string(importer.points.size()) + " could be read (is the file truncated?).");
  if (importer.reserved && importer.polygons.size() < importer.declared_faces)
    throw InputError(path, 0,
                     "the header declares " + std::to_string(importer.declared_faces) + " faces but only " +
                         std::to_string(importer.polygons.size()) + " could be read (is the file truncated?).");
  if (!ok)
    throw InputError(path, 0,
                     "could not be read as " + upper +
                         " (OpenMesh's reader refused it). The file is damaged or not really " + upper + ".");
  if (importer.bad_face != SIZE_MAX) {
    const std::size_t line = data_line(importer.points.size() + importer.bad_face);
    throw InputError(path, line,
                     "face " + std::to_string(importer.bad_face) + " refers to vertex " +
                         std::to_string(importer.bad_index) + " but the file has only " +
                         std::to_string(importer.points.size()) + " vertices (indices start at 0).");
  }
  for (std::size_t v = 0; v < importer.points.size(); ++v)
    if (!is_finite(importer.points[v]))
      throw InputError(path, vertex_location(v),
                       "vertex " + std::to_string(v) +
                           " has a coordinate that is not finite (NaN or infinity). Fix it in the modelling tool.");

  PolygonSoup soup;
  soup.files.push_back(path);
  soup.warnings = ply.warnings;
  soup.points = std::move(importer.points);
  const std::uint32_t group = soup.find_or_add_group(std::filesystem::path(path).stem().string());
  Material fallback;
  fallback.name = "default";
  fallback.origin = "built-in default (grey, reflectance 0.5)";
  // One material per distinct face colour, named after the colour. A PLY can have a
  // million distinct colours, so they are found through a map.
  std::map<std::array<double, 3>, std::uint32_t> colour_materials;
  std::size_t clamped = 0;
  int default_index = -1;
  auto material_for = [&](std::size_t f) -> std::uint32_t {
    if (!importer.has_color[f]) {
      if (default_index < 0) {
        default_index = static_cast<int>(soup.materials.size());
        soup.materials.push_back(fallback);
      }
      return static_cast<std::uint32_t>(default_index);
    }
    // Face colours are display colours, not measured albedo: white would mean a
    // perfect reflector, so each channel is clamped to kMaxColourReflectance.
    const Rgb raw = importer.face_color[f];
    if (!raw.is_finite())
      throw InputError(path, data_line(soup.points.size() + f),
                       "face " + std::to_string(f) +
                           " has a colour that is not a finite number. Fix it in the "
                           "modelling tool.");
    const Rgb c(std::min(raw.r, kMaxColourReflectance), std::min(raw.g, kMaxColourReflectance),
                std::min(raw.b, kMaxColourReflectance));
    if (c != raw) ++clamped;
    const auto [known, added] = colour_materials.emplace(std::array<double, 3>{c.r, c.g, c.b},
                                                         static_cast<std::uint32_t>(soup.materials.size()));
    if (!added) return known->second;
    Material m;
    std::ostringstream name;
    name.precision(3);
    name << "colour_" << c.r << "_" << c.g << "_" << c.b;
    m.name = name.str();
    m.reflectance = c;
    m.origin = path + " face " + std::to_string(f) + " (face colour)";
    soup.materials.push_back(m);
    return known->second;
  };
  for (std::size_t f = 0; f < importer.polygons.size(); ++f) {
    if (importer.polygons[f].size() < 3) continue;  // cleanup counts what it removes; this never held a face
    soup.polygons.push_back(std::move(importer.polygons[f]));
    soup.material.push_back(material_for(f));
    soup.group.push_back(group);
    const std::size_t line = data_line(soup.points.size() + f);
    soup.origin.push_back(SourceRef{0, static_cast<std::uint32_t>(line), static_cast<std::uint32_t>(f)});
  }
  if (clamped > 0)
    soup.warnings.push_back(path + ": " + std::to_string(clamped) + " face colours above " +
                            std::to_string(kMaxColourReflectance).substr(0, 4) +
                            " were clamped to that reflectance (a colour of 255 would reflect all light). "
                            "Assign materials in a scene file to set reflectance exactly.");
  return soup;
}

}  // namespace dynrad
