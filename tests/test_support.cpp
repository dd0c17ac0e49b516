#include "test_support.h"

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

#include "mesh/scene_mesh.h"

namespace dynrad::test {

std::size_t count_t_vertices(const SceneMesh& scene, double relative_tolerance) {
  const TriMesh& mesh = scene.mesh();
  const double tol = relative_tolerance * scene.bounds().diagonal();
  std::size_t count = 0;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const Vec3d a = mesh.point(mesh.from_vertex_handle(h));
    const Vec3d b = mesh.point(mesh.to_vertex_handle(h));
    const Vec3d d = b - a;
    for (auto v : mesh.vertices()) {
      if (v == mesh.from_vertex_handle(h) || v == mesh.to_vertex_handle(h)) continue;
      const Vec3d w = mesh.point(v) - a;
      const double t = OpenMesh::dot(w, d) / d.sqrnorm();
      if (t <= 1e-9 || t >= 1 - 1e-9) continue;
      if ((w - d * t).norm() <= tol) ++count;
    }
  }
  return count;
}

}  // namespace dynrad::test
