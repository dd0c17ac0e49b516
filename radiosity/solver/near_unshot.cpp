// Solver::near_unshot: the unshot light of the patches beside a receiver, where the
// ambient term's one mean is wrong.
//
// The ambient term (Cohen et al. 1988) gives every point the unshot power per area of
// the whole scene, as if each point saw every patch's unshot radiosity in proportion
// to its area. Far from a point that holds: its view is spread over many patches,
// whose deviations from the mean cancel (they sum to 0 over the scene, area-weighted).
// Near a concave edge it does not: a vertex on a floor-wall edge takes half its light
// from the strip of wall along the edge, a few patches, and what those few still hold
// is not the mean (a 2 x 1.5 x 1 furnace at the defaults' stop kept an edge vertex
// 1.3% darker than the closed form; 0.6% with this).
//
// So for each receiver, the patches near it that could give it a form factor of at
// least kNearForm are taken at their own unshot radiosity: the first bounce of their
// deviation from the mean, F times (U_j - mean), is added to what the ambient term
// gives. "Near" is within half a patch size (RefineSettings::patch_area is an eighth of
// its square). Further off, each patch's share is small and the deviations cancel.
// Each near patch's F is the closed form times the share of it seen
// (Solver::near_seen_share, 4 rays). Without them a patch behind a partition
// counted in full: the obstructed 1990 room's ceiling corner behind a partition took
// the unshot light of the back wall on the partition's lit side, 33% too bright at
// the draft quality's stop.
//
// The patches are found through a small bounding-volume tree over the patches that
// send on their own (a face cluster's unshot light is its parts'): a node is skipped
// when its box lies beyond the reach, behind the receiver's plane (a floor's own
// patches), or so far that its largest patch cannot give kNearForm. Since the form
// factors of a point sum to at most 1, few patches pass, however dense the model. On
// the IFC house (191,000 receivers, 2 threads) this takes 0.7-0.9 s; scanning a hash
// grid of the patches within reach took 1.8-2.4 s.
#include "radiosity/transfer/form_factor.h"
#include "radiosity/solver/solver.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dynrad::rad {
namespace {

// A patch whose form factor from the receiver is bounded below this (its area over pi
// times the squared distance to its box) is left to the ambient term.
constexpr double kNearForm = 0.03;

struct PatchTree {
  struct Node {
    Bounds box;
    double largest = 0;          // largest patch area below
    std::uint32_t first = 0, count = 0;  // a leaf's patches in `order`
    std::uint32_t right = 0;     // an inner node: its second child (the first follows it)
  };
  std::vector<Node> nodes;
  std::vector<std::uint32_t> order;
};

constexpr std::uint32_t kLeafPatches = 8;

// Squared distance from p to the box (0 inside).
double squared_distance(const Bounds& box, const Vec3d& p) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max({box.lo[k] - p[k], 0.0, p[k] - box.hi[k]});
    d2 += d * d;
  }
  return d2;
}

}  // namespace

std::vector<Rgb> Solver::near_unshot(const std::vector<char>& wanted) const {
  std::vector<Rgb> out(receivers_.size());
  if (!(total_area_ > 0) || !(patch_area_ > 0)) return out;
  const Rgb mean = unshot_staying_ * (1.0 / total_area_);
  const double reach = 0.5 * std::sqrt(8 * patch_area_);

  PatchTree tree;
  for (std::uint32_t j = 0; j < patches_.size(); ++j)
    if (!patches_[j].clustered && patches_[j].area > 0) tree.order.push_back(j);
  if (tree.order.empty()) return out;
  // Built depth first, each node split at the median of its centres along its widest axis.
  auto build = [&](auto&& self, std::uint32_t first, std::uint32_t count) -> void {
    const std::uint32_t n = static_cast<std::uint32_t>(tree.nodes.size());
    tree.nodes.push_back({});
    Bounds box, centres;
    double largest = 0;
    for (std::uint32_t k = first; k < first + count; ++k) {
      const Patch& p = patches_[tree.order[k]];
      for (const Vec3d& c : p.corners) box.extend(c);
      centres.extend(p.centre);
      largest = std::max(largest, p.area);
    }
    tree.nodes[n].box = box;
    tree.nodes[n].largest = largest;
    if (count <= kLeafPatches) {
      tree.nodes[n].first = first;
      tree.nodes[n].count = count;
      return;
    }
    const Vec3d extent = centres.extent();
    const int axis = extent[0] >= extent[1] && extent[0] >= extent[2] ? 0 : extent[1] >= extent[2] ? 1 : 2;
    const std::uint32_t half = count / 2;
    std::nth_element(tree.order.begin() + first, tree.order.begin() + first + half, tree.order.begin() + first + count,
                     [&](std::uint32_t a, std::uint32_t b) { return patches_[a].centre[axis] < patches_[b].centre[axis]; });
    self(self, first, half);
    tree.nodes[n].right = static_cast<std::uint32_t>(tree.nodes.size());
    self(self, first + half, count - half);
  };
  build(build, 0, static_cast<std::uint32_t>(tree.order.size()));

  // Cut short by a stop (the receivers not reached keep the ambient term alone).
  PassProgress progress(options_, "unshot light of near patches (receivers)", receivers_.size());
  tbb::parallel_for(std::size_t(0), receivers_.size(), [&](std::size_t id) {
    progress.add(1);
    if (!wanted[id] || progress.stop()) return;
    const Receiver& r = receivers_[id];
    const Vec3d& n = patches_[r.patch].normal;
    Rgb sum;
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const std::uint32_t at = stack[--top];
      const PatchTree::Node& node = tree.nodes[at];
      const double d2 = squared_distance(node.box, r.point);
      if (d2 > reach * reach || node.largest < kNearForm * M_PI * d2) continue;
      // All of the node on or behind the receiver's plane (a floor's own patches): none sends to it.
      double ahead = -OpenMesh::dot(n, r.point);
      for (int k = 0; k < 3; ++k) ahead += std::max(n[k] * node.box.lo[k], n[k] * node.box.hi[k]);
      if (ahead <= 1e-9 * reach) continue;
      if (node.count == 0) {
        stack[top++] = node.right;
        stack[top++] = at + 1;
        continue;
      }
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        const std::uint32_t j = tree.order[k];
        const Patch& p = patches_[j];
        if (j == r.patch || OpenMesh::dot(n, p.normal) > 1 - 1e-9) continue;  // sends it nothing
        const double gap = std::max(0.0, (p.centre - r.point).norm() - p.radius);
        if (gap > reach || p.area < kNearForm * M_PI * gap * gap) continue;
        // Either side behind the other's plane: no light between them.
        if (OpenMesh::dot(p.normal, r.point - p.centre) <= 0) continue;
        if (std::max({OpenMesh::dot(n, p.corners[0] - r.point), OpenMesh::dot(n, p.corners[1] - r.point),
                      OpenMesh::dot(n, p.corners[2] - r.point)}) <= 0)
          continue;
        const double f = point_to_triangle(r.point, n, p.corners[0], p.corners[1], p.corners[2], p.normal);
        if (!(f > 0) || (p.unshot - mean).is_zero()) continue;
        sum += (p.unshot - mean) * (f * near_seen_share(r.point, n, p));
      }
    }
    out[id] = sum;
  });
  return out;
}

}  // namespace dynrad::rad
