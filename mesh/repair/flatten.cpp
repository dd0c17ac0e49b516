// Flattening of near-planar polygons: see flatten.h.
#include "mesh/repair/flatten.h"

#include "mesh/core/polygon_triangulation.h"

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

// Where a corner goes: on every plane in `hard` (exactly planar polygons: they stay
// so), and, within that, as near as it can get to the planes in `soft` (the near-planar
// polygons being flattened), least squares. Directions in which the soft planes barely
// pull (eigenvalue of the projected sum n n^T below kParallel: planes almost parallel
// to the freedom left, or to each other) keep p0's position: two planes 2.6 degrees
// apart would otherwise put the point on their intersection line, far away.
constexpr double kParallel = 1e-3;
Vec3d place_corner(const Vec3d& p0, const std::vector<Plane>& hard, const std::vector<Plane>& soft) {
  // An orthonormal basis of the hard planes' normals: the directions p may not move in.
  std::vector<Vec3d> fixed;
  for (const Plane& plane : hard) {
    Vec3d n = plane.normal;
    for (const Vec3d& f : fixed) n -= f * OpenMesh::dot(n, f);
    if (n.norm() > 1e-3) fixed.push_back(n.normalized());
  }
  if (fixed.size() >= 3) return p0;
  auto free_part = [&](Vec3d v) {
    for (const Vec3d& f : fixed) v -= f * OpenMesh::dot(v, f);
    return v;
  };
  std::array<std::array<double, 3>, 3> a{};
  Vec3d pull(0.0);  // sum of (the free part of n) times the distance still to go
  for (const Plane& plane : soft) {
    const Vec3d n = free_part(plane.normal);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) a[r][c] += n[r] * n[c];
    pull += n * (plane.offset - OpenMesh::dot(plane.normal, p0));
  }
  std::array<double, 3> w;
  std::array<std::array<double, 3>, 3> v;
  symmetric_eigen(a, w, v);
  Vec3d move(0.0);
  for (int k = 0; k < 3; ++k) {
    if (w[k] < kParallel) continue;
    const Vec3d e(v[0][k], v[1][k], v[2][k]);
    move += e * (OpenMesh::dot(e, pull) / w[k]);
  }
  return p0 + free_part(move);
}

enum class Shape { planar, near_planar, warped, skipped };

struct PolygonPlane {
  Shape shape = Shape::skipped;
  Plane plane{};
  double width = 0;  // area / bounding-box diagonal
};

// The polygon's shape against its best-fit plane (Newell's normal through the mean of
// its corners).
PolygonPlane classify(const std::vector<Vec3d>& points, const std::vector<std::uint32_t>& loop,
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
  result.width = 0.5 * twice_area / box.diagonal();
  double deviation = 0;
  for (auto i : loop)
    deviation = std::max(deviation, std::abs(OpenMesh::dot(result.plane.normal, points[i]) - result.plane.offset));
  if (deviation <= 1e-12 * box.diagonal() + 1e-14 * magnitude)
    result.shape = Shape::planar;
  else if (deviation <= relative_tolerance * result.width)
    result.shape = Shape::near_planar;
  else
    result.shape = Shape::warped;
  return result;
}

// The plane nearest its corners, weighted: corners that lie on exactly planar polygons
// will hardly move, so the plane is fitted through them first.
Plane weighted_plane(const std::vector<Vec3d>& points, const std::vector<std::uint32_t>& loop,
                     const std::vector<double>& weight, const Vec3d& facing) {
  double total = 0;
  Vec3d centre(0.0);
  for (auto i : loop) {
    total += weight[i];
    centre += points[i] * weight[i];
  }
  centre /= total;
  std::array<std::array<double, 3>, 3> covariance{};
  for (auto i : loop) {
    const Vec3d d = points[i] - centre;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) covariance[r][c] += weight[i] * d[r] * d[c];
  }
  std::array<double, 3> w;
  std::array<std::array<double, 3>, 3> v;
  symmetric_eigen(covariance, w, v);
  const int k = static_cast<int>(std::min_element(w.begin(), w.end()) - w.begin());
  Vec3d normal(v[0][k], v[1][k], v[2][k]);
  if (OpenMesh::dot(normal, facing) < 0) normal = -normal;
  return {normal, OpenMesh::dot(normal, centre)};
}

// Corners on exactly planar polygons weigh this much more in the fit.
constexpr double kPinnedWeight = 1e3;

}  // namespace

FlattenReport flatten_polygons(std::vector<Vec3d>& points, const std::vector<std::vector<std::uint32_t>>& polygons,
                               const std::vector<char>& keep, const FlattenOptions& options) {
  FlattenReport report;
  std::vector<PolygonPlane> fits(polygons.size());
  std::vector<std::size_t> near_planar;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    if (!keep[p]) continue;
    fits[p] = classify(points, polygons[p], options.relative_tolerance);
    if (fits[p].shape == Shape::near_planar) near_planar.push_back(p);
    if (fits[p].shape == Shape::warped) ++report.warped_polygons;
  }
  if (near_planar.empty()) return report;

  // The planar and near-planar polygons around each corner of a near-planar polygon.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> around;
  for (auto p : near_planar)
    for (auto v : polygons[p]) around.emplace(v, std::vector<std::uint32_t>{});
  std::vector<double> weight(points.size(), 1.0);
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    if (fits[p].shape != Shape::planar && fits[p].shape != Shape::near_planar) continue;
    for (auto v : polygons[p]) {
      auto it = around.find(v);
      if (it == around.end()) continue;
      if (it->second.empty() || it->second.back() != p) it->second.push_back(static_cast<std::uint32_t>(p));
      if (fits[p].shape == Shape::planar) weight[v] = kPinnedWeight;
    }
  }
  std::vector<std::uint32_t> corners;
  corners.reserve(around.size());
  for (const auto& entry : around) corners.push_back(entry.first);
  std::sort(corners.begin(), corners.end());  // the same result whatever the hash order

  const std::vector<Vec3d> original = points;
  std::vector<char> flat(polygons.size(), 0);
  std::vector<Plane> hard, soft;
  // Rounds of: fit each polygon's plane to its corners, move the corners onto the
  // planes. Corners where three or fewer planes meet are exact after the first.
  for (int round = 0; round < 5; ++round) {
    for (auto p : near_planar) fits[p].plane = weighted_plane(points, polygons[p], weight, fits[p].plane.normal);
    for (auto v : corners) {
      hard.clear();
      soft.clear();
      double allowed = std::numeric_limits<double>::infinity();
      for (auto p : around[v]) {
        (fits[p].shape == Shape::planar ? hard : soft).push_back(fits[p].plane);
        if (fits[p].shape == Shape::near_planar)
          allowed = std::min(allowed, options.relative_tolerance * fits[p].width);
      }
      const Vec3d moved = place_corner(points[v], hard, soft);
      if (is_finite(moved) && (moved - original[v]).norm() <= allowed) points[v] = moved;
    }
    bool all_flat = true;
    for (auto p : near_planar) {
      flat[p] = classify(points, polygons[p], options.relative_tolerance).shape == Shape::planar;
      all_flat = all_flat && flat[p];
    }
    if (all_flat) break;
  }
  for (auto p : near_planar) report.flattened_polygons += flat[p];
  for (auto v : corners) report.largest_move = std::max(report.largest_move, (points[v] - original[v]).norm());
  return report;
}

}  // namespace dynrad
