// Solver::update_direct_gaps: how far each leaf element's linear interpolation misses
// the sources' own light at its centroid, the part of the mesh's error that the
// hierarchical surplus cannot see.
//
// The surplus (estimate_error()) compares a leaf with its parent's interpolation: it
// sees how much the values still bend where the mesh was refined. An element that was
// never refined, or whose corners all see a source while a shadow's edge crosses its
// inside, has no surplus, yet its interpolated values are wrong (the obstructed 1990
// room at the defaults: a floor point 0.08 m into a partition's umbra came out 32% too
// bright while its element's corners were lit, and the estimate said 0.93%).
//
// So at each leaf's centroid the direct light of the primary sources (the luminaires
// but the sky, and the emitting patches when at most kDirectPatches of them hold
// kDirectShare of the emitted power) is computed as the shots compute it
// at a corner: closed form times the fraction of seeded rays that arrive. Its
// difference from the mean of the corners' direct light, times the reflectance, is
// what linear interpolation gets wrong there. For a smooth field that is the
// interpolation error at the worst point of the element (the centroid of a triangle
// under a quadratic); for a shadow crossing the inside it is the jump.
//
// The corners' direct light is computed once per receiver, the centroid's once per
// element: elements and receivers never move, and the sources do not change, so the
// values are kept and only new leaves are computed at the next look. The sky is left
// out: it is soft, and a hemisphere per point would cost more than the solve.
#include "radiosity/form_factor.h"
#include "radiosity/random.h"
#include "radiosity/solver.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dynrad::rad {

void Solver::choose_direct_sources() {
  direct_sources_.clear();
  for (std::size_t k = 0; k < luminaires_.size(); ++k)
    if (luminaires_[k].kind != Luminaire::Kind::sky)
      direct_sources_.push_back(static_cast<std::uint32_t>(patches_.size() + k));
  std::vector<std::uint32_t> emitting;
  for (std::uint32_t j = 0; j < patches_.size(); ++j)
    if (patches_[j].emission.luminance() > 0) emitting.push_back(j);
  auto power = [this](std::uint32_t j) { return patches_[j].emission.luminance() * patches_[j].area; };
  // The brightest first; ties to the lower id (the same choice on every run).
  std::stable_sort(emitting.begin(), emitting.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return power(a) > power(b); });
  // Emission spread over many patches (a luminous ceiling, a furnace) gives light that
  // a few of them do not stand for: then no patch is looked at. (In a furnace whose
  // every face emits, the 16 brightest patches' light alone is uneven where the whole
  // is even, and ranked its vertices by that.)
  double all = 0, kept = 0;
  for (std::size_t k = 0; k < emitting.size(); ++k) {
    all += power(emitting[k]);
    if (k < kDirectPatches) kept += power(emitting[k]);
  }
  if (kept >= kDirectShare * all && emitting.size() <= kDirectPatches)
    direct_sources_.insert(direct_sources_.end(), emitting.begin(), emitting.end());
  else if (kept >= kDirectShare * all)
    direct_sources_.insert(direct_sources_.end(), emitting.begin(), emitting.begin() + kDirectPatches);
  direct_sources_chosen_ = true;
}

bool Solver::primary_sources_shot() {
  if (!direct_sources_chosen_) choose_direct_sources();
  for (const std::uint32_t id : direct_sources_)
    if (is_luminaire(id) ? id - patches_.size() >= next_luminaire_ : patches_[id].shot.is_zero()) return false;
  return true;
}

Rgb Solver::direct_light(const Vec3d& x, const Vec3d& n, std::uint64_t key) const {
  Rgb sum;
  Vec3d targets[kDirectRays];
  for (const std::uint32_t id : direct_sources_) {
    const std::uint64_t seed = mix(options_.seed ^ mix((key << 32) ^ id ^ 0x5eedd1ec7ULL));
    if (is_luminaire(id)) {
      sum += luminaire(id).colour * luminaire_illuminance(x, n, id, seed, true, nullptr);
      continue;
    }
    const Patch& s = patches_[id];
    if (OpenMesh::dot(n, s.normal) > 1 - 1e-9) continue;  // facing the same way: nothing arrives
    const double f = point_to_triangle(x, n, s.corners[0], s.corners[1], s.corners[2], s.normal);
    if (!(f > 0)) continue;
    // Four stratified rays first; sixteen more where they disagree (a penumbra).
    Rng rng{seed};
    int visible = 0, cast = 0;
    auto pass = [&](int rays) {
      int rows = 1, columns = 1, count = 0;
      strata(rays, rows, columns);
      for (int i = 0; i < rows; ++i)
        for (int j = 0; j < columns; ++j) {
          const Vec3d t = point_on_triangle(s.corners, (i + rng.uniform()) / rows, (j + rng.uniform()) / columns);
          if (OpenMesh::dot(n, t - x) > 0) targets[count++] = t;
        }
      visible += visibility_->visible_count(x, n, targets, count, s.normal);
      cast += count;
    };
    pass(4);
    if (visible > 0 && visible < cast) pass(kDirectRays);
    if (cast > 0) sum += s.emission * (f * visible / cast);
  }
  return sum;
}

void Solver::update_direct_gaps() {
  if (!options_.direct_check) return;
  if (!direct_sources_chosen_) choose_direct_sources();
  const std::size_t elements = hierarchy_.element_count();
  if (direct_gap_.size() == elements && receiver_direct_.size() == receivers_.size()) return;
  direct_gap_.resize(elements, -1.0f);
  receiver_direct_.resize(receivers_.size(), Rgb(-1, -1, -1));
  // The receivers and leaves not yet looked at, in id order.
  std::vector<char> wanted(receivers_.size(), 0);
  std::vector<ElementId> leaves;
  for (ElementId e = 0; e < elements; ++e) {
    if (direct_gap_[e] >= 0 || !hierarchy_.element(e).is_leaf()) continue;
    leaves.push_back(e);
    for (std::uint32_t r : corner_receiver_[e])
      if (receiver_direct_[r].r < 0) wanted[r] = 1;
  }
  std::vector<std::uint32_t> todo;
  for (std::uint32_t r = 0; r < wanted.size(); ++r)
    if (wanted[r]) todo.push_back(r);
  tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t k) {
    const Receiver& r = receivers_[todo[k]];
    receiver_direct_[todo[k]] = direct_light(r.point, patches_[r.patch].normal, todo[k]);
  });
  tbb::parallel_for(std::size_t(0), leaves.size(), [&](std::size_t k) {
    const ElementId e = leaves[k];
    const Element& el = hierarchy_.element(e);
    const Patch& patch = patches_[el.patch];
    const Vec3d centroid =
        (hierarchy_.position(el.corners[0]) + hierarchy_.position(el.corners[1]) + hierarchy_.position(el.corners[2])) /
        3.0;
    const Rgb here = direct_light(centroid, patch.normal, (std::uint64_t{1} << 31) + e);
    const auto& c = corner_receiver_[e];
    const Rgb line = (receiver_direct_[c[0]] + receiver_direct_[c[1]] + receiver_direct_[c[2]]) * (1.0 / 3);
    direct_gap_[e] = static_cast<float>(std::abs((patch.reflectance * (here - line)).luminance()));
  });
}

double Solver::direct_gap(ElementId e) const {
  return e < direct_gap_.size() && direct_gap_[e] > 0 ? direct_gap_[e] : 0.0;
}

}  // namespace dynrad::rad
