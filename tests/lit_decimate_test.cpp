// Decimation of lit meshes for viewers (mesh/io/lit_decimate.h): the surface, its outline
// and its creases stay where they were, no face flips, and at every input vertex the
// colour shown stays within the bound, measured here independently (each input vertex
// found in the output triangles and interpolated there).
#include "mesh/io/lit_decimate.h"
#include "mesh/io/read_glb.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <regex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace dynrad {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

struct LitMesh {
  std::vector<Vec3d> positions;
  std::vector<Triangle> triangles;
  VertexValues values;
};

// The display colour (0..255 per channel, before rounding) at a point; quality is its
// first channel over 255, as a float.
using ColourField = std::function<std::array<double, 3>(const Vec3d&)>;

// Builds meshes of n x n grid cells, two triangles each, over origin + s u + t v (s, t
// in [0, 1]), facing u x v. Vertices at the same position are shared.
class GridBuilder {
 public:
  explicit GridBuilder(ColourField colour) : colour_(std::move(colour)) {}

  void rect(const Vec3d& origin, const Vec3d& u, const Vec3d& v, int n) {
    std::vector<std::uint32_t> index((n + 1) * (n + 1));
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) index[j * (n + 1) + i] = vertex(origin + u * (double(i) / n) + v * (double(j) / n));
    auto at = [&](int i, int j) { return index[j * (n + 1) + i]; };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        mesh_.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        mesh_.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  const LitMesh& mesh() const { return mesh_; }

 private:
  std::uint32_t vertex(const Vec3d& p) {
    const auto key = std::make_tuple(std::llround(p[0] * 1e9), std::llround(p[1] * 1e9), std::llround(p[2] * 1e9));
    const auto found = index_.find(key);
    if (found != index_.end()) return found->second;
    const auto i = static_cast<std::uint32_t>(mesh_.positions.size());
    index_.emplace(key, i);
    mesh_.positions.push_back(p);
    const auto c = colour_(p);
    std::array<std::uint8_t, 3> display;
    for (int k = 0; k < 3; ++k) display[k] = static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0, 255.0)));
    mesh_.values.display.push_back(display);
    mesh_.values.linear.push_back(Rgb(c[0] / 255, c[1] / 255, c[2] / 255));
    mesh_.values.quality.push_back(static_cast<float>(c[0] / 255));
    return i;
  }

  ColourField colour_;
  LitMesh mesh_;
  std::map<std::tuple<long long, long long, long long>, std::uint32_t> index_;
};

LitMesh square(int n, const ColourField& colour) {
  GridBuilder grid(colour);
  grid.rect({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, n);
  return grid.mesh();
}

double double_area(const Vec3d& a, const Vec3d& b, const Vec3d& c) { return OpenMesh::cross(b - a, c - a).norm(); }

Vec3d normal_of(const LitMesh& m, const Triangle& t) {
  return OpenMesh::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
}

// The default bound, no triangle count to stop at.
LitDecimateOptions as_far_as_allowed() {
  LitDecimateOptions o;
  o.max_triangles = 0;
  return o;
}

LitDecimateReport decimate(LitMesh& m, const LitDecimateOptions& options = as_far_as_allowed()) {
  return decimate_lit_mesh(m.positions, m.triangles, m.values, options);
}

// The worst error at the input vertices as a fraction of the bound there, found
// independently of the decimator: every output triangle that contains the vertex (within
// 1e-9 of its plane, barycentric coordinates >= -1e-9) is interpolated at it, and each
// must be within the bound. `uncovered` counts input vertices no output triangle holds.
struct Measured {
  double worst_fraction = 0;
  double worst_units = 0;
  std::size_t uncovered = 0;
};

Measured measure(const LitMesh& before, const LitMesh& after, const LitDecimateOptions& o, double quality_floor) {
  Measured m;
  for (std::size_t p = 0; p < before.positions.size(); ++p) {
    const Vec3d& x = before.positions[p];
    bool covered = false;
    for (const Triangle& t : after.triangles) {
      const Vec3d &a = after.positions[t[0]], &b = after.positions[t[1]], &c = after.positions[t[2]];
      const Vec3d n = OpenMesh::cross(b - a, c - a);
      const double n2 = n.sqrnorm();
      if (std::abs(OpenMesh::dot(x - a, n)) / std::sqrt(n2) > 1e-9) continue;
      const double l1 = OpenMesh::dot(OpenMesh::cross(x - a, c - a), n) / n2;
      const double l2 = OpenMesh::dot(OpenMesh::cross(b - a, x - a), n) / n2;
      const double l0 = 1 - l1 - l2;
      if (std::min({l0, l1, l2}) < -1e-9) continue;
      covered = true;
      for (int k = 0; k < 3; ++k) {
        const double shown = l0 * after.values.display[t[0]][k] + l1 * after.values.display[t[1]][k] +
                             l2 * after.values.display[t[2]][k];
        const double own = before.values.display[p][k];
        const double error = std::abs(shown - own);
        m.worst_units = std::max(m.worst_units, error);
        m.worst_fraction = std::max(m.worst_fraction, error / std::max(o.colour_units, o.colour_fraction * own));
      }
      const double shown =
          l0 * after.values.quality[t[0]] + l1 * after.values.quality[t[1]] + l2 * after.values.quality[t[2]];
      const double own = before.values.quality[p];
      m.worst_fraction = std::max(m.worst_fraction,
                                  std::abs(shown - own) / std::max(o.quality_fraction * std::abs(own), quality_floor));
    }
    m.uncovered += !covered;
  }
  return m;
}

// Kept vertices keep their values exactly: each output vertex is an input vertex at the
// same position with the same display, linear and quality values.
void expect_values_kept(const LitMesh& before, const LitMesh& after) {
  std::map<std::tuple<double, double, double>, std::size_t> input;
  for (std::size_t i = 0; i < before.positions.size(); ++i)
    input[{before.positions[i][0], before.positions[i][1], before.positions[i][2]}] = i;
  ASSERT_EQ(after.values.display.size(), after.positions.size());
  ASSERT_EQ(after.values.linear.size(), after.positions.size());
  ASSERT_EQ(after.values.quality.size(), after.positions.size());
  for (std::size_t v = 0; v < after.positions.size(); ++v) {
    const auto found = input.find({after.positions[v][0], after.positions[v][1], after.positions[v][2]});
    ASSERT_NE(found, input.end()) << "output vertex " << v << " is no input vertex";
    EXPECT_EQ(after.values.display[v], before.values.display[found->second]);
    EXPECT_EQ(after.values.linear[v], before.values.linear[found->second]);
    EXPECT_EQ(after.values.quality[v], before.values.quality[found->second]);
  }
}

double total_area(const LitMesh& m) {
  double sum = 0;
  for (const Triangle& t : m.triangles)
    sum += 0.5 * double_area(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  return sum;
}

// Undirected edges with the number of triangles using each.
std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_uses(const LitMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  return uses;
}

// The square [0,1]^2: area 1, and its outline is the square's: boundary edges lie on
// the four sides and add up to length 4.
void expect_unit_square(const LitMesh& m) {
  EXPECT_NEAR(total_area(m), 1.0, 1e-12);
  double outline = 0;
  for (const auto& [edge, uses] : edge_uses(m)) {
    if (uses != 1) continue;
    const Vec3d &a = m.positions[edge.first], &b = m.positions[edge.second];
    const bool on_side = (a[0] == b[0] && (a[0] == 0 || a[0] == 1)) || (a[1] == b[1] && (a[1] == 0 || a[1] == 1));
    EXPECT_TRUE(on_side) << "boundary edge inside the square: " << a << " - " << b;
    outline += (b - a).norm();
  }
  EXPECT_NEAR(outline, 4.0, 1e-12);
  for (const Triangle& t : m.triangles) EXPECT_GT(normal_of(m, t)[2], 0) << "a flipped or degenerate triangle";
}

TEST(LitDecimate, ConstantSquareShrinksToAHandful) {
  const LitMesh input = square(40, [](const Vec3d&) { return std::array<double, 3>{120, 80, 40}; });
  LitMesh m = input;
  const LitDecimateReport r = decimate(m);
  EXPECT_EQ(r.triangles_before, 3200u);
  EXPECT_LE(r.triangles_after, 4u);
  EXPECT_EQ(r.triangles_after, m.triangles.size());
  EXPECT_EQ(r.vertices_after, m.positions.size());
  EXPECT_LT(r.worst_colour_error, 1e-9);
  expect_unit_square(m);
  expect_values_kept(input, m);
  const Measured e = measure(input, m, {}, r.quality_floor);
  EXPECT_EQ(e.uncovered, 0u);
  EXPECT_LT(e.worst_units, 1e-9);
}

// A ramp in x (rounded to 8 bits, so not quite linear) is shown by a handful of
// triangles within a unit.
TEST(LitDecimate, LinearSquareShrinksWithinTheBound) {
  const LitMesh input = square(40, [](const Vec3d& p) {
    return std::array<double, 3>{10 + 200 * p[0], 50 + 100 * p[0], 30};
  });
  LitMesh m = input;
  const LitDecimateReport r = decimate(m);
  EXPECT_LE(r.triangles_after, 4u);
  EXPECT_GT(r.worst_colour_error, 0.0);  // the rounding
  EXPECT_LE(r.worst_error_fraction, 1.0);
  expect_unit_square(m);
  expect_values_kept(input, m);
  const Measured e = measure(input, m, {}, r.quality_floor);
  EXPECT_EQ(e.uncovered, 0u);
  EXPECT_LE(e.worst_fraction, 1.0 + 1e-9);
  EXPECT_NEAR(e.worst_units, r.worst_colour_error, 1e-6);
}

// A Gaussian spot of light on a dark square.
constexpr double kSigma = 0.06;
std::array<double, 3> spot(const Vec3d& p) {
  const double r2 = (p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5);
  const double g = std::exp(-r2 / (2 * kSigma * kSigma));
  return {20 + 220 * g, 20 + 150 * g, 20 + 60 * g};
}

TEST(LitDecimate, SpotStaysDenseWhereTheColourChanges) {
  const LitMesh input = square(100, spot);
  LitMesh m = input;
  const LitDecimateReport r = decimate(m);
  EXPECT_EQ(r.triangles_before, 20000u);
  EXPECT_LT(r.triangles_after, 5000u);
  EXPECT_LE(r.worst_error_fraction, 1.0);
  expect_unit_square(m);
  expect_values_kept(input, m);
  const Measured e = measure(input, m, {}, r.quality_floor);
  EXPECT_EQ(e.uncovered, 0u);
  EXPECT_LE(e.worst_fraction, 1.0 + 1e-9);
  EXPECT_NEAR(e.worst_units, r.worst_colour_error, 1e-6);
  // Triangles per area within 2 sigma of the spot and beyond 5 sigma.
  std::size_t near = 0, far = 0;
  for (const Triangle& t : m.triangles) {
    const Vec3d c = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0;
    const double d = std::hypot(c[0] - 0.5, c[1] - 0.5);
    near += d < 2 * kSigma;
    far += d > 5 * kSigma;
  }
  const double near_area = M_PI * 4 * kSigma * kSigma, far_area = 1 - M_PI * 25 * kSigma * kSigma;
  EXPECT_GT(near / near_area, 20 * (far / far_area)) << near << " near, " << far << " far";
}

// An L: a floor and a wall sharing the crease y axis, with a colour that changes along
// the crease and away from it.
TEST(LitDecimate, CreaseStaysStraightAndPlanesKeepTheirAreas) {
  GridBuilder grid([](const Vec3d& p) {
    return std::array<double, 3>{60 + 100 * p[1], 60 + 50 * p[0], 60 + 50 * p[2]};
  });
  grid.rect({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 20);  // floor z = 0, facing up
  grid.rect({0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 20);  // wall x = 0, facing +x
  const LitMesh input = grid.mesh();
  LitMesh m = input;
  const LitDecimateReport r = decimate(m);
  EXPECT_LE(r.triangles_after, 8u);
  double floor_area = 0, wall_area = 0;
  std::vector<int> plane_of(m.triangles.size());
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const Triangle& t = m.triangles[i];
    const bool on_floor = m.positions[t[0]][2] == 0 && m.positions[t[1]][2] == 0 && m.positions[t[2]][2] == 0;
    const bool on_wall = m.positions[t[0]][0] == 0 && m.positions[t[1]][0] == 0 && m.positions[t[2]][0] == 0;
    ASSERT_TRUE(on_floor != on_wall) << "triangle " << i << " is in neither plane";
    const double a = 0.5 * double_area(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
    (on_floor ? floor_area : wall_area) += a;
    plane_of[i] = on_floor ? 0 : 1;
    const Vec3d n = normal_of(m, t);
    EXPECT_GT(on_floor ? n[2] : n[0], 0) << "triangle " << i << " flipped";
  }
  EXPECT_NEAR(floor_area, 1.0, 1e-12);
  EXPECT_NEAR(wall_area, 1.0, 1e-12);
  // The edges shared by a floor and a wall triangle lie on the y axis and cover it.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<int>> planes_at;
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      planes_at[std::minmax(m.triangles[i][k], m.triangles[i][(k + 1) % 3])].push_back(plane_of[i]);
  double crease = 0;
  for (const auto& [edge, planes] : planes_at) {
    if (planes.size() != 2 || planes[0] == planes[1]) continue;
    const Vec3d &a = m.positions[edge.first], &b = m.positions[edge.second];
    EXPECT_TRUE(a[0] == 0 && a[2] == 0 && b[0] == 0 && b[2] == 0) << a << " - " << b;
    crease += (b - a).norm();
  }
  EXPECT_NEAR(crease, 1.0, 1e-12);
  const Measured e = measure(input, m, {}, r.quality_floor);
  EXPECT_EQ(e.uncovered, 0u);
  EXPECT_LE(e.worst_fraction, 1.0 + 1e-9);
}

// A closed unit cube, faces outwards: stays closed, every triangle in a face of the
// cube with the normal pointing out, each face of area 1.
TEST(LitDecimate, ClosedBoxStaysABox) {
  GridBuilder grid([](const Vec3d& p) {
    return std::array<double, 3>{100 + 20 * p[0], 100 + 20 * p[1], 100 + 20 * p[2]};
  });
  const int n = 12;
  grid.rect({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, n);  // z = 0, facing -z
  grid.rect({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, n);  // z = 1, facing +z
  grid.rect({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, n);  // y = 0, facing -y
  grid.rect({0, 1, 0}, {0, 0, 1}, {1, 0, 0}, n);  // y = 1, facing +y
  grid.rect({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, n);  // x = 0, facing -x
  grid.rect({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, n);  // x = 1, facing +x
  const LitMesh input = grid.mesh();
  for (const auto& [edge, uses] : edge_uses(input)) ASSERT_EQ(uses, 2);
  LitMesh m = input;
  const LitDecimateReport r = decimate(m);
  EXPECT_EQ(r.triangles_before, 6u * 2 * n * n);
  EXPECT_LE(r.triangles_after, 24u);
  for (const auto& [edge, uses] : edge_uses(m)) EXPECT_EQ(uses, 2) << "open or non-manifold edge";
  std::map<std::pair<int, int>, double> face_area;  // (axis, side)
  for (const Triangle& t : m.triangles) {
    const Vec3d n_t = normal_of(m, t);
    int axis = -1;
    for (int a = 0; a < 3; ++a)
      if (m.positions[t[0]][a] == m.positions[t[1]][a] && m.positions[t[1]][a] == m.positions[t[2]][a]) axis = a;
    ASSERT_GE(axis, 0) << "a triangle off the cube's faces";
    const int side = m.positions[t[0]][axis] == 1 ? 1 : 0;
    EXPECT_GT(side ? n_t[axis] : -n_t[axis], 0) << "a flipped triangle";
    face_area[{axis, side}] += 0.5 * n_t.norm();
  }
  ASSERT_EQ(face_area.size(), 6u);
  for (const auto& [face, area] : face_area) EXPECT_NEAR(area, 1.0, 1e-12);
  const Measured e = measure(input, m, {}, r.quality_floor);
  EXPECT_EQ(e.uncovered, 0u);
  EXPECT_LE(e.worst_fraction, 1.0 + 1e-9);
}

// Labels: a square in two halves keeps both halves and their straight border.
TEST(LitDecimate, LabelsKeepTheirRegions) {
  LitMesh m = square(20, [](const Vec3d&) { return std::array<double, 3>{90, 90, 90}; });
  std::vector<std::uint32_t> labels;
  for (const Triangle& t : m.triangles)
    labels.push_back((m.positions[t[0]][0] + m.positions[t[1]][0] + m.positions[t[2]][0]) / 3 < 0.5 ? 0 : 1);
  const LitDecimateReport r = decimate_lit_mesh(m.positions, m.triangles, labels, m.values, as_far_as_allowed());
  ASSERT_EQ(labels.size(), m.triangles.size());
  EXPECT_LE(r.triangles_after, 8u);
  double area[2] = {0, 0};
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const Triangle& t = m.triangles[i];
    for (std::uint32_t v : t) EXPECT_TRUE(labels[i] == 0 ? m.positions[v][0] <= 0.5 : m.positions[v][0] >= 0.5);
    area[labels[i]] += 0.5 * double_area(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  }
  EXPECT_NEAR(area[0], 0.5, 1e-12);
  EXPECT_NEAR(area[1], 0.5, 1e-12);
}

// A needle strip (1e-9 wide, as rounding leaves beside a wall's edge in the IFC house)
// beside a square, with vertices of its own: narrower than the flatness tolerance, it
// has no plane to keep, so it is kept as it is while the square is decimated.
TEST(LitDecimate, NeedlesAreKeptAsTheyAre) {
  LitMesh m = square(10, [](const Vec3d&) { return std::array<double, 3>{100, 100, 100}; });
  const auto first = static_cast<std::uint32_t>(m.positions.size());
  const int n = 10;
  for (int j = 0; j <= n; ++j)
    for (int side = 0; side < 2; ++side) {
      m.positions.push_back(Vec3d(1 + side * 1e-9, double(j) / n, 0));
      m.values.display.push_back({static_cast<std::uint8_t>(j % 2 ? 7 : 30), 4, 1});
      m.values.linear.push_back(Rgb(0.01));
      m.values.quality.push_back(0.01f);
    }
  std::vector<Triangle> needle;
  for (int j = 0; j < n; ++j) {
    const std::uint32_t a = first + 2 * j, b = a + 1, c = a + 2, d = a + 3;
    needle.push_back({a, b, d});
    needle.push_back({a, d, c});
  }
  m.triangles.insert(m.triangles.end(), needle.begin(), needle.end());
  const LitMesh input = m;
  const LitDecimateReport r = decimate(m);
  EXPECT_EQ(r.triangles_kept_as_they_are, needle.size());
  EXPECT_EQ(r.triangles_after, 2 + needle.size());
  // The needle's triangles come last, as they were (their vertices renumbered).
  for (std::size_t k = 0; k < needle.size(); ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(m.positions[m.triangles[2 + k][c]], input.positions[needle[k][c]]) << "needle triangle " << k;
  const Measured e = measure(input, m, {}, r.quality_floor);
  EXPECT_EQ(e.uncovered, 0u);
}

TEST(LitDecimate, StopsAtMaxTriangles) {
  LitMesh m = square(100, spot);
  LitDecimateOptions o;
  o.max_triangles = 10000;
  const LitDecimateReport r = decimate(m, o);
  EXPECT_TRUE(r.reached_target);
  EXPECT_LE(r.triangles_after, 10000u);
  EXPECT_GE(r.triangles_after, 9999u);  // a collapse removes two triangles (one on the boundary)
  EXPECT_LT(r.worst_error_fraction, 1.0);
  // The spot cannot be shown with 10 triangles: stops where the bound allows no more.
  LitMesh tight = square(100, spot);
  o.max_triangles = 10;
  const LitDecimateReport t = decimate(tight, o);
  EXPECT_FALSE(t.reached_target);
  EXPECT_GT(t.triangles_after, 10u);
  EXPECT_LE(t.worst_error_fraction, 1.0);
}

TEST(LitDecimate, SameInputSameOutput) {
  LitMesh a = square(60, spot), b = square(60, spot);
  const LitDecimateReport ra = decimate(a), rb = decimate(b);
  EXPECT_EQ(ra.collapses, rb.collapses);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.values.display, b.values.display);
}

// A tighter bound keeps more triangles and keeps to it.
TEST(LitDecimate, TighterBoundKeepsMore) {
  const LitMesh input = square(60, spot);
  LitMesh loose = input, tight = input;
  LitDecimateOptions o = as_far_as_allowed();
  const LitDecimateReport rl = decimate(loose, o);
  o.colour_units = 0.5;
  o.colour_fraction = 0.002;
  const LitDecimateReport rt = decimate(tight, o);
  EXPECT_GT(rt.triangles_after, rl.triangles_after);
  const Measured e = measure(input, tight, o, rt.quality_floor);
  EXPECT_LE(e.worst_fraction, 1.0 + 1e-9);
  EXPECT_LE(e.worst_units, 0.5 + 1e-9);
}

TEST(LitDecimate, BadSizesAreRefused) {
  const LitMesh good = square(2, spot);
  {
    LitMesh m = good;
    m.values.display.pop_back();
    EXPECT_THROW(decimate(m), std::invalid_argument);
  }
  {
    LitMesh m = good;
    m.values.quality.push_back(0);
    EXPECT_THROW(decimate(m), std::invalid_argument);
  }
  {
    LitMesh m = good;
    m.values.scalars.emplace_back("illuminance", std::vector<float>(3, 0.0f));
    EXPECT_THROW(decimate(m), std::invalid_argument);
  }
  {
    LitMesh m = good;
    m.triangles.push_back({0, 1, static_cast<std::uint32_t>(m.positions.size())});
    EXPECT_THROW(decimate(m), std::invalid_argument);
  }
  {
    LitMesh m = good;
    std::vector<std::uint32_t> labels(m.triangles.size() - 1, 0);
    EXPECT_THROW(decimate_lit_mesh(m.positions, m.triangles, labels, m.values), std::invalid_argument);
  }
  {
    LitMesh m = good;  // no linear values and no quality: allowed
    m.values.linear.clear();
    m.values.quality.clear();
    EXPECT_NO_THROW(decimate(m));
  }
}

// `dynrad solve --max-triangles`: the log's line, the file's triangles, and small
// models untouched by default.
using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<>;

std::pair<std::size_t, std::size_t> ply_size(const std::string& path) {
  ReadMesh mesh;
  EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, path)) << path;
  return {mesh.n_vertices(), mesh.n_faces()};
}

TEST(LitDecimateCli, SolveDecimatesToMaxTriangles) {
  test::TempDir dir;
  const std::string common = "solve '" + test::sample("cornell_box.obj") + "' --iterations 40 ";
  const auto full = test::run_dynrad(common + "-o '" + dir.path("full.ply") + "'");
  ASSERT_EQ(full.exit_code, 0) << full.output;
  const auto r = test::run_dynrad(common + "--max-triangles 200 -o '" + dir.path("small.ply") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(r.output, match, std::regex(R"(decimated for viewers: (\d+) -> (\d+) triangles)")))
      << r.output;
  const std::size_t before = std::stoul(match[1]), after = std::stoul(match[2]);
  EXPECT_EQ(before, ply_size(dir.path("full.ply")).second);
  EXPECT_EQ(after, ply_size(dir.path("small.ply")).second);
  EXPECT_LT(after, before / 2);
  if (after > 200) {
    EXPECT_NE(r.output.find("the colour bound allows no fewer"), std::string::npos) << r.output;
  }
  EXPECT_NE(r.output.find("worst colour error"), std::string::npos) << r.output;
}

TEST(LitDecimateCli, SmallModelsAreUntouchedByDefault) {
  test::TempDir dir;
  const std::string common = "solve '" + test::sample("cornell_box.obj") + "' --iterations 20 ";
  const auto by_default = test::run_dynrad(common + "-o '" + dir.path("default.ply") + "'");
  ASSERT_EQ(by_default.exit_code, 0) << by_default.output;
  EXPECT_EQ(by_default.output.find("decimated"), std::string::npos) << by_default.output;
  const auto never = test::run_dynrad(common + "--max-triangles 0 -o '" + dir.path("never.ply") + "'");
  ASSERT_EQ(never.exit_code, 0) << never.output;
  EXPECT_EQ(ply_size(dir.path("default.ply")), ply_size(dir.path("never.ply")));
}

// A decimated .glb keeps one mesh per group.
TEST(LitDecimateCli, GlbKeepsItsGroups) {
  test::TempDir dir;
  const std::string common = "solve '" + test::sample("cornell_box.obj") + "' --iterations 20 ";
  ASSERT_EQ(test::run_dynrad(common + "-o '" + dir.path("full.glb") + "'").exit_code, 0);
  const auto r = test::run_dynrad(common + "--max-triangles 1000 -o '" + dir.path("small.glb") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const GlbSummary full = read_glb_summary(dir.path("full.glb")), small = read_glb_summary(dir.path("small.glb"));
  EXPECT_EQ(small.meshes, full.meshes);
  EXPECT_EQ(small.primitives, full.primitives);
  EXPECT_LT(small.triangles, full.triangles / 2);
  EXPECT_NEAR(small.bounds.diagonal(), full.bounds.diagonal(), 1e-6 * full.bounds.diagonal());
}

}  // namespace
}  // namespace dynrad
