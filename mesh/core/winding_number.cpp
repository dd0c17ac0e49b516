// Winding numbers through a bounding-volume tree with far nodes expanded to first order
// (see winding_number.h).
#include "mesh/core/winding_number.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dynrad {
namespace {

// The solid angle of triangle (a, b, c) seen from x, positive when x is behind it (the
// side its corners' order turns away from), by Van Oosterom and Strackee (1983).
double triangle_solid_angle(const std::array<Vec3d, 3>& t, const Vec3d& x) {
  const Vec3d a = t[0] - x, b = t[1] - x, c = t[2] - x;
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = OpenMesh::dot(a, OpenMesh::cross(b, c));
  const double denominator =
      la * lb * lc + OpenMesh::dot(a, b) * lc + OpenMesh::dot(b, c) * la + OpenMesh::dot(c, a) * lb;
  return 2 * std::atan2(numerator, denominator);
}

}  // namespace

// What the build needs per triangle, by its original index; `order` is the tree's
// permutation of those indices, each node a range of it.
struct WindingNumber::Build {
  std::vector<Vec3d> centroid, area;
  std::vector<std::uint32_t> order;
};

WindingNumber::WindingNumber(const std::vector<std::array<Vec3d, 3>>& triangles, const WindingNumberOptions& options)
    : options_(options) {
  options_.leaf_triangles = std::max(options_.leaf_triangles, 1);
  if (triangles.empty()) return;
  Build b;
  b.centroid.resize(triangles.size());
  b.area.resize(triangles.size());
  b.order.resize(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    b.centroid[i] = (t[0] + t[1] + t[2]) / 3.0;
    b.area[i] = OpenMesh::cross(t[1] - t[0], t[2] - t[0]) * 0.5;
  }
  std::iota(b.order.begin(), b.order.end(), 0u);
  nodes_.reserve(2 * triangles.size() / options_.leaf_triangles + 2);
  build(b, triangles, 0, static_cast<std::uint32_t>(triangles.size()));
  triangles_.reserve(triangles.size());
  for (std::uint32_t i : b.order) triangles_.push_back(triangles[i]);  // leaves' ranges in tree order
}

// Splits at the median centroid along the widest axis of the centroids' box (ties by
// index, so the tree is the same on any machine); returns the node's index.
std::uint32_t WindingNumber::build(Build& b, const std::vector<std::array<Vec3d, 3>>& triangles, std::uint32_t first,
                                   std::uint32_t count) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Node node;
  node.first = first;
  node.count = count;
  const auto range_begin = b.order.begin() + first, range_end = range_begin + count;
  double total = 0;
  Vec3d weighted(0, 0, 0), lo = b.centroid[*range_begin], hi = lo;
  for (auto it = range_begin; it != range_end; ++it) {
    const double a = b.area[*it].norm();
    total += a;
    weighted += b.centroid[*it] * a;
    node.area += b.area[*it];
    lo.minimize(b.centroid[*it]);
    hi.maximize(b.centroid[*it]);
  }
  node.centre = total > 0 ? weighted / total : (lo + hi) * 0.5;
  for (auto it = range_begin; it != range_end; ++it) {
    const Vec3d d = b.centroid[*it] - node.centre;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) node.spread[3 * r + c] += d[r] * b.area[*it][c];
    for (const Vec3d& p : triangles[*it]) node.radius = std::max(node.radius, (p - node.centre).norm());
  }
  if (count > static_cast<std::uint32_t>(options_.leaf_triangles)) {
    const Vec3d extent = hi - lo;
    const int axis = extent[0] >= extent[1] && extent[0] >= extent[2] ? 0 : (extent[1] >= extent[2] ? 1 : 2);
    const std::uint32_t half = count / 2;
    std::nth_element(range_begin, range_begin + half, range_end, [&](std::uint32_t x, std::uint32_t y) {
      return b.centroid[x][axis] < b.centroid[y][axis] || (b.centroid[x][axis] == b.centroid[y][axis] && x < y);
    });
    node.left = build(b, triangles, first, half);
    node.right = build(b, triangles, first + half, count - half);
  }
  nodes_[index] = node;
  return index;
}

// The node's solid angle from the kernel's Taylor expansion about its centre: with
// y = centre - x, the area term G(y).A with G(y) = y/|y|^3, and the spread term
// <J(y), D> with J = I/|y|^3 - 3 y y^T/|y|^5 (each triangle's spread is exact at first
// order: the integral of (p - centre) over it is its area times its centroid's offset).
double WindingNumber::node_solid_angle(const Node& node, const Vec3d& x) const {
  const Vec3d y = node.centre - x;
  const double r2 = y.sqrnorm(), r = std::sqrt(r2), r3 = r2 * r, r5 = r3 * r2;
  const auto& D = node.spread;
  const double trace = D[0] + D[4] + D[8];
  double yDy = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) yDy += y[i] * D[3 * i + j] * y[j];
  return OpenMesh::dot(y, node.area) / r3 + trace / r3 - 3 * yDy / r5;
}

double WindingNumber::at(const Vec3d& x) const {
  if (nodes_.empty()) return 0;
  double solid_angle = 0;
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if ((x - node.centre).norm() > options_.far_ratio * node.radius) {
      solid_angle += node_solid_angle(node, x);
    } else if (node.left == 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
        solid_angle += triangle_solid_angle(triangles_[i], x);
    } else {
      stack[top++] = node.right;
      stack[top++] = node.left;
    }
  }
  return solid_angle / (4 * M_PI);
}

double WindingNumber::exact(const std::vector<std::array<Vec3d, 3>>& triangles, const Vec3d& x) {
  double solid_angle = 0;
  for (const auto& t : triangles) solid_angle += triangle_solid_angle(t, x);
  return solid_angle / (4 * M_PI);
}

}  // namespace dynrad
