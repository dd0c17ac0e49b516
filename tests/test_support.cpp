#include "test_support.h"

#include <png.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynrad::test {

Picture read_png(const std::string& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  Picture p;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return p;
  image.format = PNG_FORMAT_RGB;
  p.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, p.rgb.data(), 0, nullptr)) return Picture{};
  p.width = static_cast<int>(image.width);
  p.height = static_cast<int>(image.height);
  return p;
}

TempDir::TempDir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "dynrad-test-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
  dir_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

std::string TempDir::path(const std::string& name) const { return dir_ + "/" + name; }

std::string TempDir::write(const std::string& name, const std::string& content) const {
  const std::string p = path(name);
  std::ofstream out(p, std::ios::binary);
  out << content;
  return p;
}

CommandResult run_shell(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("popen failed");
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

CommandResult run_dynrad(const std::string& arguments) {
  return run_shell(std::string("'") + DYNRAD_EXE + "' " + arguments);
}

CommandResult run_dynrad_and_signal(const std::string& arguments, double seconds, const std::string& signal_name,
                                    const std::string& ready) {
  TempDir dir;
  const std::string log = dir.path("log.txt");
  // Up to 10 minutes for loading (sanitizer builds on a busy machine are slow).
  return run_shell("( '" + std::string(DYNRAD_EXE) + "' " + arguments + " > '" + log + "' 2>&1 & pid=$!; " +
                   "for i in $(seq 3000); do grep -qF '" + ready + "' '" + log +
                   "' && break; kill -0 $pid 2>/dev/null || break; "
                   "sleep 0.2; done; sleep " +
                   std::to_string(seconds) + "; kill -" + signal_name + " $pid; wait $pid; " + "status=$?; cat '" +
                   log + "'; echo exit=$status )");
}

std::string sample(const std::string& name) { return std::string(DYNRAD_SAMPLES_DIR) + "/" + name; }

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool file_exists(const std::string& path) { return std::filesystem::exists(path); }

double polygon_area(const PolygonSoup& soup) {
  double total = 0;
  for (const auto& poly : soup.polygons) {
    Vec3d n(0.0);
    for (std::size_t i = 0; i < poly.size(); ++i)
      n += OpenMesh::cross(soup.points[poly[i]], soup.points[poly[(i + 1) % poly.size()]]);
    total += 0.5 * n.norm();
  }
  return total;
}

}  // namespace dynrad::test

#include "mesh/core/scene_mesh.h"

#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace dynrad::test {

std::size_t count_t_vertices(const SceneMesh& scene, double relative_tolerance) {
  // Vertices binned in a uniform grid; each edge looks only at the cells its box covers.
  const TriMesh& mesh = scene.mesh();
  const Bounds bounds = scene.bounds();
  const double tol = relative_tolerance * bounds.diagonal();
  double mean_edge = 0;
  for (auto e : mesh.edges()) mean_edge += mesh.calc_edge_length(e);
  mean_edge /= std::max<std::size_t>(1, mesh.n_edges());
  const double cell = std::max(mean_edge, 1e-12 * bounds.diagonal());
  auto cell_of = [&](double x, int axis) { return static_cast<long>(std::floor((x - bounds.lo[axis]) / cell)); };
  std::unordered_map<long long, std::vector<VertexHandle>> grid;
  auto key = [](long i, long j, long k) {
    return (static_cast<long long>(i) * 73856093) ^ (static_cast<long long>(j) * 19349663) ^
           (static_cast<long long>(k) * 83492791);
  };
  for (auto v : mesh.vertices()) {
    const Vec3d p = mesh.point(v);
    grid[key(cell_of(p[0], 0), cell_of(p[1], 1), cell_of(p[2], 2))].push_back(v);
  }
  std::size_t count = 0;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const VertexHandle va = mesh.from_vertex_handle(h), vb = mesh.to_vertex_handle(h);
    const Vec3d a = mesh.point(va), b = mesh.point(vb), d = b - a;
    long lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
      lo[c] = cell_of(std::min(a[c], b[c]) - tol, c);
      hi[c] = cell_of(std::max(a[c], b[c]) + tol, c);
    }
    std::unordered_set<int> seen;
    for (long i = lo[0]; i <= hi[0]; ++i)
      for (long j = lo[1]; j <= hi[1]; ++j)
        for (long k = lo[2]; k <= hi[2]; ++k) {
          auto it = grid.find(key(i, j, k));
          if (it == grid.end()) continue;
          for (auto v : it->second) {
            if (v == va || v == vb || !seen.insert(v.idx()).second) continue;
            const Vec3d w = mesh.point(v) - a;
            const double t = OpenMesh::dot(w, d) / d.sqrnorm();
            if (t <= 1e-9 || t >= 1 - 1e-9) continue;
            if ((w - d * t).norm() <= tol) ++count;
          }
        }
  }
  return count;
}

// Form factor from a point to a parallel rectangle [x0, x1] x [y0, y1] at height h
// above it, facing it: the classic sum over the four corners of the rectangle relative
// to the point (Hottel's corner formula), written here independently of the solver's
// contour integral.
static double corner_factor(double a, double b, double h) {
  // F from a point under the corner of an a x b rectangle at height h.
  const double x = a / h, y = b / h;
  return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
         (2 * M_PI);
}

std::string box_room_obj(double w, double d, double h) {
  std::ostringstream obj;
  obj << "mtllib room.mtl\nusemtl wall\n";
  for (double z : {0.0, h}) obj << "v 0 0 " << z << "\nv " << w << " 0 " << z << "\nv " << w << ' ' << d << ' ' << z << "\nv 0 " << d << ' ' << z << '\n';
  obj << "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n";
  return obj.str();
}

std::string write_lamp_room(const TempDir& dir, const std::string& grids) {
  dir.write("room.obj", box_room_obj(4, 3, 2.8));
  dir.write("room.mtl", "newmtl wall\nKd 0.6 0.6 0.6\n");
  return dir.write("scene.json", R"({"meshes": [{"file": "room.obj"}],
    "luminaires": [{"type": "point", "intensity": 300, "position": [2, 1.5, 2.7]}],
    "grids": )" + grids + "}");
}

double parallel_rectangle(double px, double py, double x0, double y0, double x1, double y1, double h) {
  auto signed_corner = [&](double x, double y) {
    const double a = x - px, b = y - py;
    const double f = corner_factor(std::abs(a), std::abs(b), h);
    return (a < 0) != (b < 0) ? -f : f;
  };
  return signed_corner(x1, y1) - signed_corner(x0, y1) - signed_corner(x1, y0) + signed_corner(x0, y0);
}

}  // namespace dynrad::test
