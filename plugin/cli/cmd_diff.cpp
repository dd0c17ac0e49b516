// `dynrad diff A.ply B.ply -o diff.ply`: the paper's Figure 9, the difference between
// two lit meshes as a mesh coloured by |A - B|, with summary numbers.
//
// A and B may have different refinements (adaptive and dynamic subdivision refine
// differently): at each vertex of A, B is interpolated inside its face that holds the
// vertex on the same surface (same facing, same side of any border).
#include "mesh/core/error.h"
#include "mesh/io/atomic_file.h"
#include "mesh/io/export.h"
#include "plugin/cli/commands.h"
#include "radiosity/analysis/tonemap.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <unordered_map>

namespace dynrad::cli {
namespace {

using LitMesh = OpenMesh::TriMesh_ArrayKernelT<>;

struct Lit {
  LitMesh mesh;
  std::vector<Rgb> value;
  std::vector<LitMesh::Point> inward;  // per vertex: unit direction from it into its faces
  bool photometric = false;  // written with --units photometric: it has `luminance`, radiosity in lm/m^2
};

Lit read_lit(const std::string& path) {
  Lit lit;
  lit.mesh.request_face_normals();
  lit.mesh.request_vertex_normals();
  OpenMesh::IO::Options io = OpenMesh::IO::Options::Custom;
  if (!OpenMesh::IO::read_mesh(lit.mesh, path, io))
    throw InputError(path, 0, "could not be read as a mesh (is it a PLY written by dynrad solve?).");
  OpenMesh::VPropHandleT<float> channel[3];
  const char* names[3] = {"radiosity_r", "radiosity_g", "radiosity_b"};
  for (int c = 0; c < 3; ++c)
    if (!lit.mesh.get_property_handle(channel[c], names[c]))
      throw InputError(path, 0, std::string("has no '") + names[c] +
                                    "' vertex property; diff compares PLY files written by dynrad solve.");
  OpenMesh::VPropHandleT<float> luminance;
  lit.photometric = lit.mesh.get_property_handle(luminance, "luminance");
  lit.mesh.update_normals();
  for (auto v : lit.mesh.vertices())
    lit.value.emplace_back(lit.mesh.property(channel[0], v), lit.mesh.property(channel[1], v),
                           lit.mesh.property(channel[2], v));
  // Two outputs can hold vertices at one position with one normal: a lamp's border and
  // the ceiling around it. The side their faces lie on tells them apart.
  lit.inward.assign(lit.mesh.n_vertices(), LitMesh::Point(0, 0, 0));
  for (auto f : lit.mesh.faces()) {
    const auto c = lit.mesh.calc_face_centroid(f);
    for (auto v : lit.mesh.fv_range(f)) lit.inward[v.idx()] += (c - lit.mesh.point(v)).normalized();
  }
  for (auto& d : lit.inward)
    if (d.norm() > 0) d.normalize();
  return lit;
}

struct DiffOptions {
  std::string a, b, output;
  bool ascii = false;
};

int run_diff(const DiffOptions& options) {
  check_output_writable(options.output);
  const Lit a = read_lit(options.a);
  const Lit b = read_lit(options.b);
  if (a.photometric != b.photometric)
    throw InputError(options.b, 0,
                     std::string("holds ") + (b.photometric ? "photometric (lm/m^2)" : "radiometric (W/m^2)") +
                         " values and " + options.a + " " + (a.photometric ? "photometric" : "radiometric") +
                         " ones: solve both with the same --units to compare them.");
  // B's faces in a uniform grid (cells of B's longest edge), by bounding box.
  double cell = 0;
  for (auto e : b.mesh.edges()) cell = std::max(cell, static_cast<double>(b.mesh.calc_edge_length(e)));
  cell = std::max(cell, 1e-12);
  auto cell_of = [cell](double x) { return static_cast<long long>(std::floor(x / cell)); };
  auto cell_key = [](long long x, long long y, long long z) { return (x * 73856093) ^ (y * 19349663) ^ (z * 83492791); };
  std::unordered_multimap<long long, int> grid;
  for (auto f : b.mesh.faces()) {
    const auto c = b.mesh.calc_face_centroid(f);
    grid.emplace(cell_key(cell_of(c[0]), cell_of(c[1]), cell_of(c[2])), f.idx());
  }

  // B at A's vertex: the face of B that contains a point a hair into A's own faces
  // (so a ceiling vertex on a lamp's border reads the ceiling), facing the same way;
  // B's corner values interpolated at the vertex.
  auto sample_b = [&](const LitMesh::Point& p, const LitMesh::Point& n, const LitMesh::Point& inward, Rgb& out) {
    const LitMesh::Point q = p + inward * static_cast<float>(1e-4 * cell);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto range = grid.equal_range(cell_key(cell_of(q[0]) + dx, cell_of(q[1]) + dy, cell_of(q[2]) + dz));
          for (auto it = range.first; it != range.second; ++it) {
            const OpenMesh::FaceHandle f(it->second);
            const auto fn = b.mesh.normal(f);
            if ((fn | n) < std::cos(30.0 * M_PI / 180.0)) continue;
            LitMesh::Point c[3];
            int corner[3], k = 0;
            for (auto v : b.mesh.fv_range(f)) {
              corner[k] = v.idx();
              c[k++] = b.mesh.point(v);
            }
            if (std::abs((q - c[0]) | fn) > 1e-3 * cell) continue;  // not in this face's plane
            const double area = ((c[1] - c[0]) % (c[2] - c[0])) | fn;
            double w[3], wp[3];
            bool inside = true;
            for (int i = 0; i < 3; ++i) {
              w[i] = (((c[(i + 1) % 3] - q) % (c[(i + 2) % 3] - q)) | fn) / area;
              wp[i] = (((c[(i + 1) % 3] - p) % (c[(i + 2) % 3] - p)) | fn) / area;
              inside = inside && w[i] >= -1e-6;
            }
            if (!inside) continue;
            out = Rgb();
            for (int i = 0; i < 3; ++i) out += b.value[corner[i]] * std::clamp(wp[i], 0.0, 1.0);
            return true;
          }
        }
    return false;
  };

  std::vector<Rgb> difference(a.mesh.n_vertices());
  std::size_t unmatched = 0;
  double sum_square = 0, largest = 0, sum_a = 0;
  for (auto v : a.mesh.vertices()) {
    Rgb vb;
    if (!sample_b(a.mesh.point(v), a.mesh.normal(v), a.inward[v.idx()], vb)) {
      ++unmatched;
      continue;
    }
    const Rgb& va = a.value[v.idx()];
    const Rgb d = va - vb;
    difference[v.idx()] = Rgb(std::abs(d.r), std::abs(d.g), std::abs(d.b));
    const double dl = d.luminance();
    sum_square += dl * dl;
    largest = std::max(largest, std::abs(dl));
    sum_a += va.luminance() * va.luminance();
  }
  const std::size_t matched = a.mesh.n_vertices() - unmatched;
  const double rms = matched ? std::sqrt(sum_square / matched) : 0;
  const double rms_a = matched ? std::sqrt(sum_a / matched) : 0;

  // Shown as the paper does: brighter where the difference is larger.
  std::vector<char> all(difference.size(), 1);
  const double exposure = rad::auto_exposure(difference, all);
  VertexValues values = rad::tone_map(difference, exposure, "difference");
  std::vector<Vec3d> positions;
  for (auto v : a.mesh.vertices()) positions.emplace_back(a.mesh.point(v)[0], a.mesh.point(v)[1], a.mesh.point(v)[2]);
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (auto f : a.mesh.faces()) {
    std::array<std::uint32_t, 3> t{};
    int k = 0;
    for (auto v : a.mesh.fv_range(f)) t[k++] = static_cast<std::uint32_t>(v.idx());
    triangles.push_back(t);
  }
  WriteOptions write;
  write.ascii = options.ascii;
  write_triangles_with_values(options.output, positions, triangles, values, write);

  std::cout << fmt::format("vertices     {} in A, {} matched in B, {} unmatched\n", a.mesh.n_vertices(), matched, unmatched);
  std::cout << fmt::format("rms |A-B|    {:.6g} (luminance, {})\n", rms, a.photometric ? "lm/m2" : "W/m2");
  std::cout << fmt::format("max |A-B|    {:.6g}\n", largest);
  std::cout << fmt::format("rms A        {:.6g}\n", rms_a);
  std::cout << fmt::format("relative rms {:.4f}%  (rms |A-B| / rms A)\n", rms_a > 0 ? 100 * rms / rms_a : 0.0);
  spdlog::info("wrote {}", options.output);
  return kExitOk;
}

}  // namespace

Command add_diff_command(CLI::App& app) {
  auto options = std::make_shared<DiffOptions>();
  CLI::App* command = app.add_subcommand("diff", "Difference of two lit meshes (the paper's Figure 9)");
  command->add_option("a", options->a, "Lit PLY written by dynrad solve")->required();
  command->add_option("b", options->b, "Lit PLY to compare with")->required();
  command->add_option("-o,--output", options->output, "Mesh of A coloured by |A - B| (.ply or .off)")->required();
  command->add_flag("--ascii", options->ascii, "Write ASCII PLY instead of binary");
  return [options] { return run_diff(*options); };
}

}  // namespace dynrad::cli
