// The winding number of a closed triangle surface about a point (1 inside a solid whose
// triangles face out, 0 outside), for surfaces as large as a building.
//
// Summing every triangle's solid angle costs the surface's size per point, and cleanup
// asks it for every piece inside the surface's box: the square of the building when its
// facades join into one closed surface storey over storey. Here the triangles sit in a
// bounding-volume tree; a node far from the point (its distance over `far_ratio` times
// its radius) adds its first-order expansion (the area vectors' sum, and their spread
// about its centre) instead of its triangles, as in Barill, Dickson, Schmidt, Levin and
// Jacobson, "Fast Winding Numbers for Soups and Clouds" (2018). Near nodes add their
// triangles exactly (Van Oosterom and Strackee's formula), so a point just in front of
// a surface is decided as exactly as before. The expansion's error falls with the
// square of radius over distance: under two hundredths of a turn at the default, against a
// decision made at one half.
//
// Written here: CGAL's point-in-solid test (Side_of_triangle_mesh) needs a manifold
// mesh, and solids joined at an edge, whose winding numbers add, are not one; libigl,
// which has fast winding numbers, is not a Debian package.
#pragma once

#include "mesh/core/types.h"

#include <array>
#include <cstdint>
#include <vector>

namespace dynrad {

struct WindingNumberOptions {
  double far_ratio = 3;     // a node is far when the point is this many radii from its centre
  int leaf_triangles = 8;   // triangles at most per leaf
};

class WindingNumber {
 public:
  explicit WindingNumber(const std::vector<std::array<Vec3d, 3>>& triangles, const WindingNumberOptions& options = {});

  // The number of turns about x (solid angle over 4 pi): near 1 inside, near 0 outside.
  double at(const Vec3d& x) const;

  // The same, triangle by triangle: the reference the tree is tested against.
  static double exact(const std::vector<std::array<Vec3d, 3>>& triangles, const Vec3d& x);

 private:
  struct Node {
    Vec3d centre = Vec3d(0, 0, 0);  // the area-weighted centroid of its triangles
    double radius = 0;              // of the ball about `centre` holding them
    Vec3d area = Vec3d(0, 0, 0);    // the sum of its triangles' area vectors (OpenMesh's are not zeroed)
    std::array<double, 9> spread{};  // sum of (centroid - centre) times area vector, row major
    std::uint32_t first = 0, count = 0;  // its triangles' range in tree order
    std::uint32_t left = 0, right = 0;   // children; left == 0 for a leaf
  };

  struct Build;
  std::uint32_t build(Build& b, const std::vector<std::array<Vec3d, 3>>& triangles, std::uint32_t first,
                      std::uint32_t count);
  double node_solid_angle(const Node& node, const Vec3d& x) const;

  WindingNumberOptions options_;
  std::vector<std::array<Vec3d, 3>> triangles_;  // in tree order
  std::vector<Node> nodes_;
};

}  // namespace dynrad
