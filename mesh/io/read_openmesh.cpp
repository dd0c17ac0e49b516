// PLY, OFF and STL through OpenMesh's readers. OpenMesh normally builds a half-edge
// mesh while reading and drops faces that would make it non-manifold; we read into
// our own BaseImporter instead, so every face reaches cleanup as a polygon soup.
#include "mesh/io/openmesh_checks.h"
#include "mesh/core/error.h"
#include "mesh/io/import.h"
#include "mesh/io/io_util.h"

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