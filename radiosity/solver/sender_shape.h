// Shaped senders (SolveOptions::shaped_senders): a patch's unshot radiosity across its
// surface, not only its mean, shapes what it sends. Used by the solver's shots
// (solver_shape.cpp), its groups of patches and its new elements' gathering.
//
// A sender's shape: its unshot radiosity, the mean m plus the deviation of
// the unshot values at the 15 nodes of a quarter grid on it (values there minus
// Patch::shot_at_nodes; a node's value comes from the elements below it, so a refined
// sender is shaped by more than its corners) from their mean, linear on each of the
// grid's 16 parts (triangle_parts()). Each part gets a weight w = its mean unshot
// radiosity / m (the parts have equal areas and the mean of w is 1: the power shot is
// the same). F to the shaped sender is the sum of w times F to each part: the parts'
// closed forms within kShapeNear sender radii (point_to_parted_triangle); beyond, F
// to the whole plus the parts' corrections (w - 1) times their point-to-area forms,
// to first order in the parts' offsets: the gradient of the point-to-area form at
// the sender's centroid times the weights' dipole, sum (w - 1) (part centroid -
// centroid) / 16 (relative error about (sender radius / distance)^2). A quarter grid,
// not the midpoints' four parts: on the 1990 room at --quality high the largest error
// falls from 2.7% to 0.7% (the walls' radiosity bends within a patch toward the
// ceiling, which four linear parts miss).
//   Where the unshot values bend too little within the midpoint parts to need the
// grid (at most kShapeBend m off the line between the nodes beside them), the shape
// is linear on the four midpoint parts and receivers near the sender see those four
// (point_to_quartered_triangle: 9 Lambert terms, not up to 30).
#pragma once

#include "mesh/core/types.h"
#include "radiosity/transfer/form_factor.h"

#include <array>

namespace dynrad::rad {

struct SenderShape {
  bool on = false;
  bool fine = false;  // the 16 parts, not the 4 midpoint ones
  std::array<double, kTriangleParts> weight{};
  std::array<double, 4> coarse{};  // the midpoint parts' (point_to_quartered_triangle)
  Vec3d centroid, dipole;
  double max_weight = 1;
};

// Within 1.5 radii the parts are summed. On the 1990 room's 2 m patches with uniform
// receivers (measured with the corners-only shape), 1 radius leaves 0.29% from the
// reference, 1.5, 2 and 3 all 0.24%.
inline constexpr double kShapeNear = 1.5;
// The bend that takes the 16 parts: 2% of the shot's mean. On the 1990 room at
// --quality high it gives what the 16 parts always give (largest error 0.72%); the
// generated storey's solve takes 2-5% longer than with the midpoint parts alone,
// against 6-9% with the 16 parts for every shot (more Lambert terms near senders,
// and the larger weights cull fewer receivers).
inline constexpr double kShapeBend = 0.02;

// The shape of values b at the 15 nodes (form_factor.h's numbering) about mean m,
// with `fine` its SenderShape::fine; off where the parts' means are within 0.1% of m.
SenderShape shape_from_nodes(const std::array<Vec3d, 3>& corners, const double* b, double m, bool fine);
// F from x (normal n) to a triangle sender with `shape` (the parted closed form
// near it, the dipole's first-order correction beyond).
double shaped_closed_form(const Vec3d& x, const Vec3d& n, const std::array<Vec3d, 3>& corners,
                          const Vec3d& centre, double radius, double area, const Vec3d& normal,
                          const SenderShape& shape);

}  // namespace dynrad::rad
