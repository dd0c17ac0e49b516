// Flattening of near-planar polygons: see flatten.h.
#include "mesh/flatten.h"

#include "mesh/polygon_triangulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace dynrad {
namespace {

struct Plane {
  Vec3d normal;   // unit
  double offset;  // normal . p on the plane
};

// Eigen-decomposition of a symmetric 3x3 matrix by Jacobi rotations: a = V diag(w) V^T,
// eigenvectors in the columns of v.
void symmetric_eigen(std::array<std::array<double, 3>, 3> a, std::array<double, 3>& w,
                     std::array<std::array<double, 3>, 3>& v) {
  v = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = std::abs(a[0][1]) + std::abs(a[0][2]) + std::abs(a[1][2]);
    if (off <= 1e-300) break;
    for (int p = 0; p < 2; ++p) {
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // a <- a J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // a <- J^T a
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {  // v <- v J
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  for (int k = 0; k < 3; ++k) w[k] = a[k][k];
}

// The point nearest to p0 among those nearest to all `planes` (least squares), where
// planes that are almost parallel count as one direction: an eigenvalue of sum n n^T
// below kParallel leaves p0's position along its eigenvector (two planes 2.6 degrees
// apart would otherwise put the point on their intersection line, far away).
constexpr double kParallel = 1e-3;
Vec3d nearest_to_planes(const Vec3d& p0, const std::vector<Plane>& planes) {
  std::array<std::array<double, 3>, 3> a{};
  Vec3d residual(0.0);  // sum n (offset - n . p0)
  for (const Plane& plane : planes) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) a[r][c] += plane.normal[r] * plane.normal[c];
    residual += plane.normal * (plane.offset - OpenMesh::dot(plane.normal, p0));
  }
  std::array<double, 3> w;
  std::array<std::array<double, 3>, 3> v;
  symmetric_eigen(a, w, v);
  Vec3d move(0.0);
  for (int k = 0; k < 3; ++k) {
    if (w[k] < kParallel) continue;
    const Vec3d e(v[0][k], v[1][k], v[2][k]);
    move += e * (OpenMesh::dot(e, residual) / w[k]);
  }
  return p0 + move;
}

enum class Shape { planar, near_planar, warped, skipped };

struct PolygonPlane {
  Shape shape = Shape::skipped;
  Plane plane{};
  double width = 0;  // area / bounding-box diagonal
  double size = 0;   // bounding-box diagonal
};

PolygonPlane fit_plane(const std::vector<Vec3d>& points, const std::vector<std::uint32_t>& loop,
                       double relative_tolerance) {
  PolygonPlane result;
  if (loop.size() < 4) return result;
  const Vec3d n2 = newell_normal(points, loop);
  const double twice_area = n2.norm();
  if (!(twice_area > 0)) return result;
  Bounds box;
  Vec3d centroid(0.0);
  double magnitude = 0;  // of the coordinates: what rounding is relative to
  for (auto i : loop) {
    box.extend(points[i]);
    centroid += points[i];
    for (int k = 0; k < 3; ++k) magnitude = std::max(magnitude, std::abs(points[i][k]));
  }
  centroid /= static_cast<double>(loop.size());
  result.plane.normal = n2 / twice_area;
  result.plane.offset = OpenMesh::dot(result.plane.normal, centroid);
  result.size = box.diagonal();
  result.width = 0.5 * twice_area / result.size;
  double deviation = 0;
  for (auto i : loop)
    deviation = std::max(deviation, std::abs(OpenMesh::dot(result.plane.normal, points[i]) - result.plane.offset));
  if (deviation <= 1e-12 * result.size + 1e-14 * magnitude)
    result.shape = Shape::planar;
  else if (deviation <= relative_tolerance * result.width)
    result.shape = Shape::near_planar;
  else
    result.shape = Shape::warped;
  return result;
}

}  // namespace

FlattenReport flatten_polygons(std::vector<Vec3d>& points, const std::vector<std::vector<std::uint32_t>>& polygons,
                               const std::vector<char>& keep, const FlattenOptions& options) {
  FlattenReport report;
  std::vector<PolygonPlane> fits(polygons.size());
  std::vector<std::size_t> near_planar;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    if (!keep[p]) continue;
    fits[p] = fit_plane(points, polygons[p], options.relative_tolerance);
    if (fits[p].shape == Shape::near_planar) near_planar.push_back(p);
    if (fits[p].shape == Shape::warped) ++report.warped_polygons;
  }
  if (near_planar.empty()) return report;

  // The polygons with a plane (planar or near-planar) around each corner of a
  // near-planar polygon: the planes that corner must stay on.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> around;
  for (auto p : near_planar)
    for (auto v : polygons[p]) around.emplace(v, std::vector<std::uint32_t>{});
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    if (fits[p].shape != Shape::planar && fits[p].shape != Shape::near_planar) continue;
    for (auto v : polygons[p]) {
      auto it = around.find(v);
      if (it != around.end() && (it->second.empty() || it->second.back() != p))
        it->second.push_back(static_cast<std::uint32_t>(p));
    }
  }
  std::vector<std::uint32_t> corners;
  corners.reserve(around.size());
  for (const auto& entry : around) corners.push_back(entry.first);
  std::sort(corners.begin(), corners.end());  // the same result whatever the hash order

  const std::vector<Vec3d> original = points;
  // A few rounds: each refits the planes to the moved corners. Corners where three or
  // fewer planes meet are exact after the first.
  std::vector<Plane> planes;
  for (int round = 0; round < 3; ++round) {
    for (auto v : corners) {
      planes.clear();
      double allowed = std::numeric_limits<double>::infinity();
      for (auto p : around[v]) {
        planes.push_back(fits[p].plane);
        if (fits[p].shape == Shape::near_planar)
          allowed = std::min(allowed, options.relative_tolerance * fits[p].width);
      }
      const Vec3d moved = nearest_to_planes(points[v], planes);
      if ((moved - original[v]).norm() <= allowed) points[v] = moved;
    }
    bool all_flat = true;
    for (auto p : near_planar) {
      const PolygonPlane refit = fit_plane(points, polygons[p], options.relative_tolerance);
      if (refit.shape != Shape::planar) {
        all_flat = false;
        fits[p].plane = refit.plane;
      }
    }
    if (all_flat) break;
  }
  for (auto p : near_planar)
    if (fit_plane(points, polygons[p], options.relative_tolerance).shape == Shape::planar) ++report.flattened_polygons;
  for (auto v : corners) report.largest_move = std::max(report.largest_move, (points[v] - original[v]).norm());
  return report;
}

}  // namespace dynrad
