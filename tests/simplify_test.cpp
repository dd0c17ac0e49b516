// Lossless simplification of flat regions (mesh/repair/simplify.h): same surface, same area
// per material, same openings and material borders, far fewer triangles, a conforming
// mesh, and the same lighting.
#include "mesh/repair/simplify.h"
#include "mesh/load.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace dynrad {
namespace {

// Writes an OBJ (with its MTL) of axis-aligned rectangles, each cut into a grid of
// cells of two triangles. `material_of(i, j)` names a cell's material; "" leaves the
// cell out (an opening).
class GridObj {
 public:
  void rect(const Vec3d& origin, const Vec3d& u, const Vec3d& v, int nu, int nv,
            const std::function<std::string(int, int)>& material_of) {
    const std::size_t base = points_.size();
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) points_.push_back(origin + u * (double(i) / nu) + v * (double(j) / nv));
    auto at = [&](int i, int j) { return base + j * (nu + 1) + i + 1; };
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        const std::string m = material_of(i, j);
        if (m.empty()) continue;
        faces_[m].push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        faces_[m].push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  void transform(const std::function<Vec3d(const Vec3d&)>& f) {
    for (Vec3d& p : points_) p = f(p);
  }
  // A closed room [0,X]x[0,Y]x[0,Z] with faces pointing in, cells of about `cell`.
  void room(double X, double Y, double Z, double cell, const std::string& floor, const std::string& wall,
            const std::function<std::string(int, int)>& ceiling, const std::function<std::string(int, int)>& wall_y0) {
    const int nx = int(std::ceil(X / cell - 1e-9)), ny = int(std::ceil(Y / cell - 1e-9)),
              nz = int(std::ceil(Z / cell - 1e-9));
    auto plain = [](const std::string& m) { return [m](int, int) { return m; }; };
    rect({0, 0, 0}, {X, 0, 0}, {0, Y, 0}, nx, ny, plain(floor));
    rect({0, 0, Z}, {0, Y, 0}, {X, 0, 0}, ny, nx, ceiling);
    rect({0, 0, 0}, {0, 0, Z}, {X, 0, 0}, nz, nx, wall_y0);
    rect({0, Y, 0}, {X, 0, 0}, {0, 0, Z}, nx, nz, plain(wall));
    rect({0, 0, 0}, {0, Y, 0}, {0, 0, Z}, ny, nz, plain(wall));
    rect({X, 0, 0}, {0, 0, Z}, {0, Y, 0}, nz, ny, plain(wall));
  }
  std::string write(const test::TempDir& dir, const std::string& name) const {
    std::ostringstream obj, mtl;
    obj << "mtllib " << name << ".mtl\n";
    char line[128];
    for (const Vec3d& p : points_) {
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
      obj << line;
    }
    for (const auto& [material, faces] : faces_) {
      obj << "usemtl " << material << "\n";
      for (const auto& f : faces) obj << "f " << f[0] << " " << f[1] << " " << f[2] << "\n";
      mtl << "newmtl " << material << "\nKd 0.6 0.6 0.6\n";
      if (material == "lamp") mtl << "Kd 0 0 0\nKe 40 40 40\n";
    }
    dir.write(name + ".mtl", mtl.str());
    return dir.write(name + ".obj", obj.str());
  }

 private:
  std::vector<Vec3d> points_;
  std::map<std::string, std::vector<std::array<std::size_t, 3>>> faces_;
};

// The test room: 4 x 3 x 2.4 with a lamp in the ceiling, optionally a window in the
// wall at y = 0 (x in [1.2, 2.8], z in [0.8, 1.6]).
std::string test_room(const test::TempDir& dir, const std::string& name, double cell, bool window) {
  GridObj obj;
  const double X = 4, Y = 3;
  obj.room(
      X, Y, 2.4, cell, "floor", "wall",
      [&](int iy, int ix) {  // ceiling cells: u along y, v along x
        const double x = (ix + 0.5) * cell, y = (iy + 0.5) * cell;
        return (x > 1.6 && x < 2.4 && y > 1.2 && y < 1.8) ? "lamp" : "ceiling";
      },
      [&](int iz, int ix) {  // wall y = 0: u along z, v along x
        const double x = (ix + 0.5) * cell, z = (iz + 0.5) * cell;
        return (window && x > 1.2 && x < 2.8 && z > 0.8 && z < 1.6) ? "" : "wall";
      });
  return obj.write(dir, name);
}

LoadedScene load(const std::string& path, bool simplify) {
  SimplifyOptions options;
  options.enabled = simplify;
  return load_scene(path, {}, options);
}

std::map<std::string, double> area_per_material(const SceneMesh& scene) {
  std::map<std::string, double> area;
  for (auto f : scene.mesh().faces()) area[scene.material(f).name] += scene.area(f);
  return area;
}

// Distance from p to the triangle abc.
double point_triangle_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  auto segment = [&](const Vec3d& s, const Vec3d& e) {
    const Vec3d d = e - s;
    const double t = std::clamp(OpenMesh::dot(p - s, d) / d.sqrnorm(), 0.0, 1.0);
    return (p - (s + d * t)).norm();
  };
  const Vec3d n = OpenMesh::cross(b - a, c - a);
  const double n2 = n.sqrnorm();
  const Vec3d q = p - n * (OpenMesh::dot(p - a, n) / n2);  // p projected onto the plane
  // Inside if q is on the inner side of all three edges.
  const bool inside = OpenMesh::dot(OpenMesh::cross(b - a, q - a), n) >= 0 &&
                      OpenMesh::dot(OpenMesh::cross(c - b, q - b), n) >= 0 &&
                      OpenMesh::dot(OpenMesh::cross(a - c, q - c), n) >= 0;
  if (inside) return std::abs(OpenMesh::dot(p - a, n)) / std::sqrt(n2);
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

double distance_to_surface(const Vec3d& p, const SceneMesh& scene) {
  const TriMesh& mesh = scene.mesh();
  double best = INFINITY;
  for (auto f : mesh.faces()) {
    auto it = mesh.cfv_iter(f);
    const Vec3d& a = mesh.point(*it);
    const Vec3d& b = mesh.point(*++it);
    const Vec3d& c = mesh.point(*++it);
    best = std::min(best, point_triangle_distance(p, a, b, c));
  }
  return best;
}

using Segment = std::pair<std::array<double, 3>, std::array<double, 3>>;
Segment segment_of(const TriMesh& mesh, OpenMesh::HalfedgeHandle h) {
  const Vec3d a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h));
  return {{a[0], a[1], a[2]}, {b[0], b[1], b[2]}};
}

// The boundary as directed segments between exact positions.
std::multiset<Segment> boundary_segments(const SceneMesh& scene) {
  const TriMesh& mesh = scene.mesh();
  std::multiset<Segment> out;
  for (auto h : mesh.halfedges())
    if (mesh.is_boundary(h)) out.insert(segment_of(mesh, h));
  return out;
}

// Edges between two materials, as directed segments seen from the face with the
// smaller material id.
std::multiset<Segment> material_borders(const SceneMesh& scene) {
  const TriMesh& mesh = scene.mesh();
  std::multiset<Segment> out;
  for (auto h : mesh.halfedges()) {
    const auto opposite = mesh.opposite_halfedge_handle(h);
    if (mesh.is_boundary(h) || mesh.is_boundary(opposite)) continue;
    if (scene.material_id(mesh.face_handle(h)) < scene.material_id(mesh.face_handle(opposite)))
      out.insert(segment_of(mesh, h));
  }
  return out;
}

// Every face has three distinct vertices, no face or vertex is left deleted, and every
// edge has one or two faces, each used once per direction.
void expect_valid_half_edge_mesh(const SceneMesh& scene) {
  const TriMesh& mesh = scene.mesh();
  std::set<std::pair<int, int>> directed;
  for (auto f : mesh.all_faces()) {
    EXPECT_FALSE(mesh.status(f).deleted()) << "garbage was not collected";
    std::vector<int> v;
    for (auto x : mesh.fv_range(f)) v.push_back(x.idx());
    ASSERT_EQ(v.size(), 3u);
    EXPECT_TRUE(v[0] != v[1] && v[1] != v[2] && v[0] != v[2]);
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(directed.insert({v[k], v[(k + 1) % 3]}).second) << "edge used twice";
    EXPECT_GT(scene.area(f), 0);
    EXPECT_EQ(scene.patch(f), static_cast<std::uint32_t>(f.idx()));
  }
  for (auto v : mesh.all_vertices()) {
    EXPECT_FALSE(mesh.status(v).deleted()) << "garbage was not collected";
    EXPECT_GT(mesh.valence(v), 0u) << "isolated vertex " << v.idx();
  }
}

TEST(Simplify, OffByDefaultAndOnRequest) {
  test::TempDir dir;
  const std::string path = test_room(dir, "room", 0.2, false);
  const LoadedScene plain = load_scene(path);
  EXPECT_EQ(plain.simplify.faces_before, plain.simplify.faces_after);
  EXPECT_EQ(plain.mesh->face_count(), plain.simplify.faces_before);
  const LoadedScene simple = load(path, true);
  EXPECT_EQ(simple.simplify.faces_before, plain.mesh->face_count());
  EXPECT_EQ(simple.simplify.faces_after, simple.mesh->face_count());
  EXPECT_LT(simple.mesh->face_count() * 10, plain.mesh->face_count());
}

TEST(Simplify, AreaPerMaterialAndSurfaceUnchanged) {
  test::TempDir dir;
  const std::string path = test_room(dir, "room", 0.2, true);
  const LoadedScene before = load(path, false), after = load(path, true);
  const auto a0 = area_per_material(*before.mesh), a1 = area_per_material(*after.mesh);
  ASSERT_EQ(a0.size(), 4u);  // floor, ceiling, lamp, wall
  ASSERT_EQ(a1.size(), a0.size());
  for (const auto& [name, area] : a0) EXPECT_NEAR(a1.at(name), area, 1e-9 * area) << name;
  EXPECT_NEAR(after.mesh->total_area(), before.mesh->total_area(), 1e-9 * before.mesh->total_area());

  const double diagonal = before.mesh->bounds().diagonal();
  double worst = 0;
  for (auto v : before.mesh->mesh().vertices())
    worst = std::max(worst, distance_to_surface(before.mesh->mesh().point(v), *after.mesh));
  EXPECT_LT(worst, 1e-12 * diagonal);
  // And the other way: the simplified surface is made of original points only.
  std::set<std::array<double, 3>> original;
  for (auto v : before.mesh->mesh().vertices()) {
    const Vec3d p = before.mesh->mesh().point(v);
    original.insert({p[0], p[1], p[2]});
  }
  for (auto v : after.mesh->mesh().vertices()) {
    const Vec3d p = after.mesh->mesh().point(v);
    EXPECT_TRUE(original.count({p[0], p[1], p[2]}));
  }
}

TEST(Simplify, FinelyTessellatedBoxShrinksToTwelveTriangles) {
  test::TempDir dir;
  GridObj obj;
  auto wall = [](int, int) { return std::string("wall"); };
  obj.room(2, 1.5, 1, 0.05, "wall", "wall", wall, wall);
  const LoadedScene scene = load(obj.write(dir, "box"), true);
  EXPECT_EQ(scene.simplify.faces_before, 2u * (40 * 30 * 2 + 40 * 20 * 2 + 30 * 20 * 2));
  // The minimum for a closed box: 8 corners, two triangles a side.
  EXPECT_EQ(scene.mesh->face_count(), 12u);
  EXPECT_EQ(scene.mesh->vertex_count(), 8u);
  EXPECT_EQ(scene.simplify.locked_vertices, 0u);
  // Half of the 2 x 1 side: the diagonal squared over twice the area, 5 / 2.
  EXPECT_NEAR(scene.simplify.worst_aspect_after, 2.5, 1e-9);
  expect_valid_half_edge_mesh(*scene.mesh);
}

TEST(Simplify, RotatedBoxShrinksDespiteRounding) {
  test::TempDir dir;
  GridObj obj;
  auto wall = [](int, int) { return std::string("wall"); };
  obj.room(2, 1.5, 1, 0.1, "wall", "wall", wall, wall);
  // About an oblique axis, then far from the origin: no coordinate is exact any more.
  const double c = std::cos(0.7), s = std::sin(0.7);
  obj.transform([&](const Vec3d& p) {
    const Vec3d r(c * p[0] - s * p[1], s * c * p[0] + c * c * p[1] - s * p[2], s * s * p[0] + s * c * p[1] + c * p[2]);
    return r + Vec3d(1000, -2000, 500);
  });
  const std::string path = obj.write(dir, "rotated");
  const LoadedScene before = load(path, false), after = load(path, true);
  EXPECT_LE(after.mesh->face_count(), 24u) << "from " << before.mesh->face_count();
  EXPECT_NEAR(after.mesh->total_area(), before.mesh->total_area(), 1e-9 * before.mesh->total_area());
  double worst = 0;
  for (auto v : before.mesh->mesh().vertices())
    worst = std::max(worst, distance_to_surface(before.mesh->mesh().point(v), *after.mesh));
  EXPECT_LT(worst, 1e-9 * before.mesh->bounds().diagonal());
  expect_valid_half_edge_mesh(*after.mesh);
}

TEST(Simplify, OpeningsAndMaterialBordersKeepTheirExactShape) {
  test::TempDir dir;
  const std::string path = test_room(dir, "room", 0.1, true);
  const LoadedScene before = load(path, false), after = load(path, true);
  const auto boundary = boundary_segments(*before.mesh);
  ASSERT_EQ(boundary.size(), 2u * (16 + 8));  // the window, 1.6 x 0.8, in cells of 0.1
  EXPECT_EQ(boundary_segments(*after.mesh), boundary);
  // Material borders may lose vertices where they run straight, but not move: each
  // original border segment lies on a simplified one, facing the same way, and their
  // lengths add up to the same.
  const auto borders = material_borders(*before.mesh), simplified = material_borders(*after.mesh);
  ASSERT_FALSE(borders.empty());
  EXPECT_LT(simplified.size() * 4, borders.size());
  auto point = [](const std::array<double, 3>& a) { return Vec3d(a[0], a[1], a[2]); };
  auto length = [&](const std::multiset<Segment>& segments) {
    double sum = 0;
    for (const auto& [a, b] : segments) sum += (point(b) - point(a)).norm();
    return sum;
  };
  EXPECT_NEAR(length(simplified), length(borders), 1e-12 * length(borders));
  for (const auto& [a, b] : borders) {
    bool covered = false;
    for (const auto& [c, d] : simplified) {
      // (a named copy: a lambda may not capture a structured binding before C++20)
      const Vec3d start = point(c);
      const Vec3d cd = point(d) - start;
      auto on = [&](const Vec3d& p) {
        const double t = OpenMesh::dot(p - start, cd) / cd.sqrnorm();
        return t > -1e-12 && t < 1 + 1e-12 && (p - start - cd * t).norm() < 1e-12;
      };
      covered = covered || (on(point(a)) && on(point(b)) && OpenMesh::dot(point(b) - point(a), cd) > 0);
    }
    EXPECT_TRUE(covered) << "border segment (" << point(a) << ") - (" << point(b) << ") moved";
  }
  EXPECT_GT(after.simplify.locked_vertices, boundary.size());
  EXPECT_LT(after.mesh->face_count() * 10, before.mesh->face_count());
}

TEST(Simplify, ResultIsConforming) {
  test::TempDir dir;
  const std::string path = test_room(dir, "room", 0.1, true);
  const LoadedScene scene = load(path, true);
  expect_valid_half_edge_mesh(*scene.mesh);
  EXPECT_EQ(test::count_t_vertices(*scene.mesh), 0u);
  EXPECT_LE(scene.simplify.worst_aspect_after, SimplifyOptions{}.max_aspect_ratio + 1e-9);
}

// The generated building (samples/make_building.py): doors, windows, furniture on the
// floor, and cleanup's T-junction repairs, at a small size.
TEST(Simplify, GeneratedBuildingKeepsAreasAndOpenings) {
  test::TempDir dir;
  const std::string path = dir.path("building.obj");
  const auto r = test::run_shell("python3 '" DYNRAD_SAMPLES_DIR "/make_building.py' '" + path +
                                 "' --rooms 2 2 --cell 0.25");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const LoadedScene before = load(path, false), after = load(path, true);
  EXPECT_LT(after.mesh->face_count() * 8, before.mesh->face_count());
  const auto a0 = area_per_material(*before.mesh), a1 = area_per_material(*after.mesh);
  ASSERT_EQ(a1.size(), a0.size());
  for (const auto& [name, area] : a0) EXPECT_NEAR(a1.at(name), area, 1e-9 * area) << name;
  EXPECT_EQ(boundary_segments(*after.mesh), boundary_segments(*before.mesh));
  expect_valid_half_edge_mesh(*after.mesh);
  EXPECT_LE(test::count_t_vertices(*after.mesh), test::count_t_vertices(*before.mesh));
}

// Area-weighted mean green radiosity over the faces of a lit PLY whose normal is
// closest to `direction`.
double mean_radiosity(const std::string& lit, const Vec3d& direction) {
  OpenMesh::TriMesh_ArrayKernelT<> mesh;
  OpenMesh::IO::Options io = OpenMesh::IO::Options::Custom;
  EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, lit, io));
  OpenMesh::VPropHandleT<float> green;
  EXPECT_TRUE(mesh.get_property_handle(green, "radiosity_g"));
  double sum = 0, area = 0;
  for (auto f : mesh.faces()) {
    std::vector<OpenMesh::Vec3f> p;
    double b = 0;
    for (auto v : mesh.fv_range(f)) {
      p.push_back(mesh.point(v));
      b += mesh.property(green, v) / 3.0;
    }
    const auto n = OpenMesh::cross(p[1] - p[0], p[2] - p[0]);
    const double a = 0.5 * n.norm();
    if (a <= 0 || OpenMesh::dot(Vec3d(n[0], n[1], n[2]) / (2 * a), direction) < 0.99) continue;
    sum += a * b;
    area += a;
  }
  return area > 0 ? sum / area : 0;
}

TEST(Simplify, SolveAgreesWithAndWithoutSimplification) {
  test::TempDir dir;
  const std::string path = test_room(dir, "room", 0.2, false);
  for (const std::string flag : {"", " --no-simplify"}) {
    const auto r =
        test::run_dynrad("solve '" + path + "' -o '" + dir.path("lit" + flag + ".ply") + "' --converge 1e-3" + flag);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("simplified") != std::string::npos, flag.empty()) << r.output;
  }
  const std::vector<std::pair<const char*, Vec3d>> surfaces = {
      {"floor", {0, 0, 1}}, {"ceiling", {0, 0, -1}}, {"wall y=0", {0, 1, 0}}, {"wall x=0", {1, 0, 0}}};
  for (const auto& [name, direction] : surfaces) {
    const double simple = mean_radiosity(dir.path("lit.ply"), direction);
    const double full = mean_radiosity(dir.path("lit --no-simplify.ply"), direction);
    ASSERT_GT(full, 0) << name;
    EXPECT_NEAR(simple, full, 0.01 * full) << name;
  }
}

TEST(Simplify, InfoReportsTrianglesBeforeAndAfter) {
  test::TempDir dir;
  const std::string path = test_room(dir, "room", 0.2, false);
  auto r = test::run_dynrad("info --json '" + path + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto j = nlohmann::json::parse(r.output);
  EXPECT_TRUE(j["simplify"]["enabled"].get<bool>());
  EXPECT_EQ(j["simplify"]["triangles_before"], j["faces"]);
  EXPECT_LT(j["simplify"]["triangles_after"].get<int>() * 10, j["faces"].get<int>());
  r = test::run_dynrad("info --json --no-simplify '" + path + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  j = nlohmann::json::parse(r.output);
  EXPECT_FALSE(j["simplify"]["enabled"].get<bool>());
  EXPECT_EQ(j["simplify"]["triangles_after"], j["faces"]);
}

}  // namespace
}  // namespace dynrad
