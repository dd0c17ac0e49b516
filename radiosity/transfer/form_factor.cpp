#include "radiosity/transfer/form_factor.h"

#include <cmath>
#include <vector>

namespace dynrad::rad {

// The angle between two directions from |cross| = y >= 0 and dot = x, what
// std::atan2(y, x) gives, about three times faster (it was a seventh of a solve's time).
// The angle is reduced to [0, pi/4], then by the nearest multiple of pi/8 (tan(a - b) =
// (tan a - tan b) / (1 + tan a tan b)) to within pi/16 of it, where the arctangent's
// Taylor series to x^17 is below 3e-15 from the truth.
double angle_between(double y, double x) {
  constexpr double kTanPi16 = 0.19891236737965800691, kTan3Pi16 = 0.66817863791929891999;
  constexpr double kTanPi8 = 0.41421356237309504880;
  auto atan01 = [](double t) {  // t in [0, 1]
    double base = 0, c = 0;
    if (t >= kTan3Pi16) {
      base = M_PI / 4;
      c = 1;
    } else if (t >= kTanPi16) {
      base = M_PI / 8;
      c = kTanPi8;
    }
    const double r = c == 0 ? t : (t - c) / (1 + t * c);
    const double r2 = r * r;
    double series = 1.0 / 17;
    for (int k = 15; k >= 1; k -= 2) series = 1.0 / k - r2 * series;
    return base + r * series;
  };
  const double ax = std::abs(x);
  double angle = y <= ax ? atan01(y / ax) : M_PI / 2 - atan01(ax / y);
  return x < 0 ? M_PI - angle : angle;
}

double point_to_polygon(const Vec3d& x, const Vec3d& n, const Vec3d* corners, int count, const Vec3d& front) {
  if (OpenMesh::dot(front, x - corners[0]) <= 0) return 0.0;  // x is behind the sender

  // Clip to x's upper hemisphere: keep the part with (p - x) . n >= 0 (Sutherland-Hodgman
  // against one plane; a convex polygon gains at most one corner).
  Vec3d clipped[9];
  int m = 0;
  for (int i = 0; i < count; ++i) {
    const Vec3d& p = corners[i];
    const Vec3d& q = corners[(i + 1) % count];
    const double dp = OpenMesh::dot(p - x, n), dq = OpenMesh::dot(q - x, n);
    if (dp >= 0) clipped[m++] = p;
    if ((dp >= 0) != (dq >= 0)) clipped[m++] = p + (q - p) * (dp / (dp - dq));
  }
  if (m < 3) return 0.0;

  // Lambert: F = 1/(2 pi) sum_i gamma_i n . (R_i x R_i+1) / |R_i x R_i+1|, with gamma_i
  // the angle between the directions R_i, R_i+1 from x to consecutive corners.
  double sum = 0;
  for (int i = 0; i < m; ++i) {
    const Vec3d r0 = clipped[i] - x;
    const Vec3d r1 = clipped[(i + 1) % m] - x;
    const Vec3d c = OpenMesh::cross(r0, r1);
    const double length = c.norm();
    if (length <= 0) continue;  // x on the line of this edge: it subtends no angle
    const double gamma = angle_between(length, OpenMesh::dot(r0, r1));
    sum += gamma * OpenMesh::dot(n, c) / length;
  }
  return std::abs(sum) / (2.0 * M_PI);
}

namespace {

// One edge's term of Lambert's sum, gamma n . (R0 x R1) / |R0 x R1|, for the edge a -> b
// seen from x.
double lambert_term(const Vec3d& x, const Vec3d& n, const Vec3d& a, const Vec3d& b) {
  const Vec3d r0 = a - x, r1 = b - x;
  const Vec3d c = OpenMesh::cross(r0, r1);
  const double length = c.norm();
  if (length <= 0) return 0.0;
  return angle_between(length, OpenMesh::dot(r0, r1)) * OpenMesh::dot(n, c) / length;
}

// (i, j) -> node index, nodes listed by i then j (i + j <= 4).
constexpr int node_index(int i, int j) {
  int index = 0;
  for (int a = 0; a < i; ++a) index += 5 - a;
  return index + j;
}

}  // namespace

double point_to_quartered_triangle(const Vec3d& x, const Vec3d& n, const Vec3d* corners, const double* weight,
                                   const Vec3d& front) {
  const Vec3d& c0 = corners[0];
  const Vec3d& c1 = corners[1];
  const Vec3d& c2 = corners[2];
  const Vec3d m01 = (c0 + c1) * 0.5, m12 = (c1 + c2) * 0.5, m20 = (c2 + c0) * 0.5;
  if (OpenMesh::dot(front, x - c0) <= 0) return 0.0;  // x is behind the sender
  const bool clips = OpenMesh::dot(c0 - x, n) < 0 || OpenMesh::dot(c1 - x, n) < 0 || OpenMesh::dot(c2 - x, n) < 0;
  if (clips) {
    const Vec3d parts[4][3] = {{c0, m01, m20}, {m01, c1, m12}, {m20, m12, c2}, {m01, m12, m20}};
    double f = 0;
    for (int s = 0; s < 4; ++s) f += weight[s] * point_to_polygon(x, n, parts[s], 3, front);
    return f;
  }
  // Unclipped, every part's sum has the sign of the whole triangle's (they are all
  // counter-clockwise and seen from the same side), so the weighted sum of their
  // absolute values is that sign times the weighted sum of their edge terms. Each
  // boundary half-edge belongs to one corner part; each inner edge is walked one way by
  // a corner part and the other way by the middle part.
  const double b0 = lambert_term(x, n, c0, m01), b1 = lambert_term(x, n, m01, c1);
  const double b2 = lambert_term(x, n, c1, m12), b3 = lambert_term(x, n, m12, c2);
  const double b4 = lambert_term(x, n, c2, m20), b5 = lambert_term(x, n, m20, c0);
  const double whole = b0 + b1 + b2 + b3 + b4 + b5;
  const double sum = weight[0] * (b0 + b5) + weight[1] * (b1 + b2) + weight[2] * (b3 + b4) +
                     (weight[0] - weight[3]) * lambert_term(x, n, m01, m20) +
                     (weight[1] - weight[3]) * lambert_term(x, n, m12, m01) +
                     (weight[2] - weight[3]) * lambert_term(x, n, m20, m12);
  return (whole < 0 ? -sum : sum) / (2.0 * M_PI);
}

const std::array<std::array<int, 3>, kTriangleParts>& triangle_part_nodes() {
  static const std::array<std::array<int, 3>, kTriangleParts> nodes = [] {
    std::array<std::array<int, 3>, kTriangleParts> out{};
    int s = 0;
    for (int i = 0; i <= 3; ++i)
      for (int j = 0; i + j <= 3; ++j) out[s++] = {node_index(i, j), node_index(i + 1, j), node_index(i, j + 1)};
    for (int i = 0; i <= 2; ++i)
      for (int j = 0; i + j <= 2; ++j) out[s++] = {node_index(i + 1, j), node_index(i + 1, j + 1), node_index(i, j + 1)};
    return out;
  }();
  return nodes;
}

namespace {

// An edge of the 16-part grid, from node a to node b: walked that way by part `left`
// (counter-clockwise) and the other way by part `right` (-1 on the boundary).
struct GridEdge {
  int a, b, left, right;
};

// The grid's 30 edges, a shared one once.
const std::vector<GridEdge>& grid_edges() {
  static const std::vector<GridEdge> edges = [] {
    const auto& nodes = triangle_part_nodes();
    std::vector<GridEdge> out;
    for (int s = 0; s < kTriangleParts; ++s)
      for (int k = 0; k < 3; ++k) {
        const int a = nodes[s][k], b = nodes[s][(k + 1) % 3];
        int right = -1;  // the part that walks b -> a
        for (int r = 0; r < kTriangleParts; ++r)
          for (int q = 0; q < 3; ++q)
            if (nodes[r][q] == b && nodes[r][(q + 1) % 3] == a) right = r;
        if (right < 0 || s < right) out.push_back({a, b, s, right});  // a shared edge once
      }
    return out;
  }();
  return edges;
}

}  // namespace

void triangle_nodes(const Vec3d* corners, Vec3d* node) {
  const Vec3d u = (corners[1] - corners[0]) * 0.25, v = (corners[2] - corners[0]) * 0.25;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; i + j <= 4; ++j) node[node_index(i, j)] = corners[0] + u * i + v * j;
  static_assert(kGridCorners[0] == node_index(0, 0) && kGridCorners[1] == node_index(4, 0) &&
                kGridCorners[2] == node_index(0, 4));
  for (int k = 0; k < 3; ++k) node[kGridCorners[k]] = corners[k];  // not sums of quarters
}

void triangle_parts(const Vec3d* corners, Vec3d (*parts)[3]) {
  Vec3d node[kTriangleNodes];
  triangle_nodes(corners, node);
  const auto& nodes = triangle_part_nodes();
  for (int s = 0; s < kTriangleParts; ++s)
    for (int k = 0; k < 3; ++k) parts[s][k] = node[nodes[s][k]];
}

double point_to_parted_triangle(const Vec3d& x, const Vec3d& n, const Vec3d* corners, const double* weight,
                                const Vec3d& front) {
  if (OpenMesh::dot(front, x - corners[0]) <= 0) return 0.0;  // x is behind the sender
  Vec3d node[kTriangleNodes];
  triangle_nodes(corners, node);
  // Parts wholly above x's horizon are summed by their edges; parts across it are
  // clipped (point_to_polygon); parts wholly below see nothing of x.
  const auto& nodes = triangle_part_nodes();
  double height[kTriangleNodes];
  for (int k = 0; k < kTriangleNodes; ++k) height[k] = OpenMesh::dot(node[k] - x, n);
  bool above[kTriangleParts];
  double f = 0;
  for (int s = 0; s < kTriangleParts; ++s) {
    const double h0 = height[nodes[s][0]], h1 = height[nodes[s][1]], h2 = height[nodes[s][2]];
    above[s] = h0 >= 0 && h1 >= 0 && h2 >= 0;
    const bool below = h0 <= 0 && h1 <= 0 && h2 <= 0;
    if (!above[s] && !below) {
      const Vec3d part[3] = {node[nodes[s][0]], node[nodes[s][1]], node[nodes[s][2]]};
      f += weight[s] * point_to_polygon(x, n, part, 3, front);
    }
  }
  // Every part above the horizon has an edge sum of the same sign (all are
  // counter-clockwise and seen from the same side), so their weighted sum of absolute
  // values is that sign times the weighted sum of their edge terms. A Lambert term
  // changes sign with the edge's direction, so each grid edge is taken once, with the
  // weight of the part on its left minus that of the part on its right (0 for no part,
  // or one not above).
  double whole = 0, sum = 0;
  for (const GridEdge& e : grid_edges()) {
    const bool left = above[e.left], right = e.right >= 0 && above[e.right];
    if (left == right && (!left || weight[e.left] == weight[e.right])) continue;  // cancels
    const double t = lambert_term(x, n, node[e.a], node[e.b]);
    sum += ((left ? weight[e.left] : 0.0) - (right ? weight[e.right] : 0.0)) * t;
    whole += ((left ? 1.0 : 0.0) - (right ? 1.0 : 0.0)) * t;
  }
  return f + (whole < 0 ? -sum : sum) / (2.0 * M_PI);
}

}  // namespace dynrad::rad
