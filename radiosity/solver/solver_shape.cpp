// Shaped senders: a patch's radiosity across its surface, not its mean, shapes what
// it sends (sender_shape.h).
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/form_factor.h"

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

double Solver::luminance_at(ElementId root, const Vec3d& p) const {
  double pending = 0;
  ElementId e = root;
  for (;;) {
    const Element& el = hierarchy_.element(e);
    if (el.is_leaf()) return interpolate(e, value_[e], p).luminance() + pending;
    pending += quadratic(pending_[e], barycentric(e, p)).luminance();
    // The child whose triangle holds p (on the split line either one: values agree).
    const ElementId first = el.children[0];
    const Element& c = hierarchy_.element(first);
    const Vec3d& n = hierarchy_.normal(first);
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) {
      const Vec3d a = hierarchy_.position(c.corners[k]), b = hierarchy_.position(c.corners[(k + 1) % 3]);
      inside = OpenMesh::dot(OpenMesh::cross(b - a, p - a), n) >= -1e-12 * (b - a).sqrnorm();
    }
    e = inside ? first : el.children[1];
  }
}

void Solver::shape_sender() {
  shape_.on = false;
  shape_.max_weight = 1;
  if (!options_.shaped_senders) return;
  // (m is below 0 when the sender gives back what an overshoot sent too much; the
  // shape is then that of the excess.)
  shape_ = shape_of(sender_, current_shot_.luminance() / options_.overshoot);
}

SenderShape Solver::shape_of(std::uint32_t patch, double m) {
  Patch& sender = patches_[patch];
  const ElementId root = hierarchy_.patch_root(patch);
  Vec3d node[kTriangleNodes];
  triangle_nodes(sender.corners.data(), node);
  // The unshot radiosity at the nodes (the patch's own corner values at its corners,
  // read through its element tree elsewhere): everything they gained since the sender
  // last shot (its emission, before its first shot), plus what an overshoot left
  // (below 0).
  double b[kTriangleNodes];
  for (int k = 0; k < kTriangleNodes; ++k) {
    const int corner = static_cast<int>(std::find(std::begin(kGridCorners), std::end(kGridCorners), k) -
                                        std::begin(kGridCorners));
    // (with its direct light, which the values leave out: exact_direct.cpp)
    const double now = (corner < 3 ? value_[root][corner].luminance() : luminance_at(root, node[k])) +
                       direct_luminance_at_node(sender, patch, node[k], k);
    b[k] = now - sender.shot_at_nodes[k];
  }
  // The quarter grid's nodes that are not corners or edge midpoints each lie halfway
  // between two that are (kGridHalfway); where the unshot values there are what a line
  // between those gives, the four midpoint parts carry the shape (SenderShape::fine).
  // Otherwise the bend stays unshot, for a later shot to ship when it has grown: what
  // the shots ship then sums to the sender's final values, even shapes cancel.
  double bend = 0;
  for (const auto& h : kGridHalfway) bend = std::max(bend, std::abs(b[h[0]] - 0.5 * (b[h[1]] + b[h[2]])));
  const bool fine = bend > kShapeBend * std::abs(m);
  if (!fine)
    for (const auto& h : kGridHalfway) b[h[0]] = 0.5 * (b[h[1]] + b[h[2]]);
  // What this shot ships moves shot_at_nodes on (all of it when not over-relaxed).
  for (int k = 0; k < kTriangleNodes; ++k) sender.shot_at_nodes[k] += options_.overshoot * b[k];
  return shape_from_nodes(sender.corners, b, m, fine);
}

SenderShape Solver::shipped_shape(std::uint32_t patch) const {
  const Patch& sender = patches_[patch];
  return shape_from_nodes(sender.corners, sender.shot_at_nodes.data(), sender.shot.luminance(), true);
}

SenderShape shape_from_nodes(const std::array<Vec3d, 3>& c, const double* b, double m, bool fine) {
  SenderShape shape;
  if (!(std::abs(m) > 0)) return shape;
  const auto& part_nodes = triangle_part_nodes();
  double part_mean[kTriangleParts], mean = 0;
  for (int s = 0; s < kTriangleParts; ++s) {
    part_mean[s] = (b[part_nodes[s][0]] + b[part_nodes[s][1]] + b[part_nodes[s][2]]) / 3;
    mean += part_mean[s] / kTriangleParts;
  }
  // The shape is the parts' deviation from their mean, added to the mean radiosity m
  // (from the energy the sender received, which also knows its interior). Added, not
  // scaled: over a whole solve the deviations sum to those of the sender's final
  // values, so where the answer is even (a furnace) the shapes cancel.
  double spread = 0;
  for (int s = 0; s < kTriangleParts; ++s) spread = std::max(spread, std::abs(part_mean[s] - mean));
  if (spread < 1e-3 * std::abs(m)) return shape;  // even enough: one closed form
  Vec3d node[kTriangleNodes];
  triangle_nodes(c.data(), node);
  shape.fine = fine;
  shape.centroid = (c[0] + c[1] + c[2]) / 3.0;
  shape.dipole = Vec3d(0, 0, 0);
  for (int s = 0; s < kTriangleParts; ++s) {
    shape.weight[s] = 1 + (part_mean[s] - mean) / m;
    if (fine) shape.max_weight = std::max(shape.max_weight, std::abs(shape.weight[s]));
    const Vec3d part_centroid = (node[part_nodes[s][0]] + node[part_nodes[s][1]] + node[part_nodes[s][2]]) / 3.0;
    shape.dipole += (part_centroid - shape.centroid) * ((shape.weight[s] - 1) / kTriangleParts);
  }
  // The midpoint parts' weights: the means of the small parts in them (a line's mean
  // on a triangle is the mean at its corners, so these are the corner nodes' means).
  if (!fine)
    for (int q = 0; q < 4; ++q) {
      double w = 0;
      for (int k = 0; k < 3; ++k) w += b[kMidpointParts[q][k]];
      shape.coarse[q] = 1 + (w / 3 - mean) / m;
      shape.max_weight = std::max(shape.max_weight, std::abs(shape.coarse[q]));
    }
  shape.on = true;
  return shape;
}

double shaped_closed_form(const Vec3d& x, const Vec3d& n, const std::array<Vec3d, 3>& corners,
                          const Vec3d& centre, double radius, double area, const Vec3d& normal,
                          const SenderShape& shape) {
  if (shape.on && (x - centre).sqrnorm() < kShapeNear * kShapeNear * radius * radius)
    return shape.fine ? point_to_parted_triangle(x, n, corners.data(), shape.weight.data(), normal)
                      : point_to_quartered_triangle(x, n, corners.data(), shape.coarse.data(), normal);
  double f = point_to_triangle(x, n, corners[0], corners[1], corners[2], normal);
  if (shape.on && f > 0) {
    // The parts' corrections (w - 1) K(c_s) with K the point-to-area form of a part
    // of the sender sum to first order to grad K(c) . dipole, the weights' mean being 1.
    const Vec3d d = shape.centroid - x;
    const double r2 = d.sqrnorm(), a = OpenMesh::dot(n, d), b = -OpenMesh::dot(normal, d);
    if (a > 0 && b > 0) {
      const double k = area / (M_PI * r2 * r2);
      const Vec3d gradient = (n * b - normal * a - d * (4 * a * b / r2)) * k;
      f = std::max(0.0, f + OpenMesh::dot(gradient, shape.dipole));
    }
  }
  return f;
}

}  // namespace dynrad::rad
