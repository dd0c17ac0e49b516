// Seeded random numbers for the solver, luminaires and grids: SplitMix64, a small,
// well-mixed hash. Each sampled thing (a receiver and sender, a grid point, a row of
// directions) draws from a seed of its own, so results do not depend on threads.
#pragma once

#include "mesh/core/types.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace dynrad::rad {

inline std::uint64_t mix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Advances `state` and returns a double uniform in [0, 1).
inline double uniform(std::uint64_t& state) {
  state = mix(state);
  return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
}

// A seeded stream of its own: each (receiver, sender) pair draws its own samples.
struct Rng {
  std::uint64_t state;
  double uniform() { return rad::uniform(state); }
};

// The strata of `count` visibility rays over a sender: rows x columns, the square
// root's both ways (at most 16), or 2 x 1 for two rays.
inline void strata(int count, int& rows, int& columns) {
  const int root = static_cast<int>(std::lround(std::sqrt(static_cast<double>(count))));
  rows = count == 2 ? 2 : std::clamp(root, 1, 16);
  columns = count == 2 ? 1 : rows;
}

// An index drawn in proportion to nonnegative weights: the first k whose running sum
// weight(0) + ... + weight(k) exceeds `target` (uniform in [0, their total)); rounding
// at the end gives the last index with a weight above zero.
template <class Weight>
std::size_t pick_by_weight(std::size_t count, double target, const Weight& weight) {
  double running = 0;
  std::size_t k = 0;
  for (; k + 1 < count; ++k) {
    running += weight(k);
    if (running > target) break;
  }
  while (k > 0 && !(weight(k) > 0)) --k;
  return k;
}

// Uniform in the triangle for (u, v) uniform in the unit square, kept a hundredth of
// the way off the edges: a point on an edge lies in the neighbouring face's plane, and
// a ray from there slips out through the seam.
inline Vec3d point_on_triangle(const std::array<Vec3d, 3>& c, double u, double v) {
  const double s = std::sqrt(u);
  const Vec3d p = c[0] * (1 - s) + c[1] * (s * (1 - v)) + c[2] * (s * v);
  const Vec3d centroid = (c[0] + c[1] + c[2]) / 3.0;
  return p + (centroid - p) * 1e-2;
}

// A direction about the unit normal n, cosine-weighted for (u1, u2) uniform in the unit
// square (Malley's method: a uniform point on the disc lifted onto the hemisphere).
inline Vec3d cosine_direction(const Vec3d& n, double u1, double u2) {
  const Vec3d t = OpenMesh::cross(std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0), n).normalized();
  const Vec3d b = OpenMesh::cross(n, t);
  const double r = std::sqrt(u1), phi = 2 * M_PI * u2;
  return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - u1));
}

}  // namespace dynrad::rad
