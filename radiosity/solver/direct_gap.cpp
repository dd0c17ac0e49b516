// Solver::update_direct_gaps: how far each leaf element's linear interpolation misses
// a shadow at its centroid, the part of the mesh's error that the hierarchical surplus
// cannot see.
//
// The surplus (estimate_error()) compares a leaf with its parent's interpolation: it
// sees how much the values still bend where the mesh was refined. An element whose
// corners all see a source while a shadow falls on its inside has no surplus to show
// (it was never split for that shadow), yet its interpolated values are wrong there: a
// small object's shadow on a large patch, or a thin occluder between two lit corners.
//
// So at each leaf's centroid the direct light of the primary sources (the luminaires
// but the sky, and the emitting patches when at most kDirectPatches of them hold
// kDirectShare of the emitted power) is computed as the shots compute it at a corner:
// the unoccluded closed form, and the share of it that arrives through seeded rays. The
// interpolation assumes the centroid gets the mean of the corners' shares; the gap is
// the difference from what it does get, times the unoccluded light there and the
// reflectance. Only the shares are compared, not the light itself: how smooth light
// bends across an element is the surplus's part, and counting it twice made the 1990
// room's estimate 3.2 times its measured error (2.6 before).
//
// The corners' shares are computed once per receiver, the centroid's once per element:
// elements and receivers never move, and the sources do not change, so the values are
// kept and only new leaves are computed at the next look. The sky is left out: it is
// soft, and a hemisphere per point would cost more than the solve.
//
// On the IFC house (3 lamps) this adds 1% to the rays and 0.17% to the estimate; the
// solve stops by the rest (ErrorEstimate::stop_measure()), since shooting on changes
// no shadow's mesh.
#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/random.h"
#include "radiosity/solver/solver.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace dynrad::rad {

namespace {

// Direct light at a point (Solver::direct_light).
constexpr std::size_t kDirectPatches = 16;  // the brightest emitting patches looked at
constexpr double kDirectShare = 0.9;        // of the patches' emitted power, or none
constexpr int kDirectRays = 16;             // per emitting patch and point, after 4 that disagree

}  // namespace

void Solver::choose_direct_sources() {
  direct_sources_.clear();
  // (Luminaires and the sun are exact at the vertices under RefineSettings::
  // exact_direct, their display gap is exact_direct.cpp's; they shoot first anyway.)
  for (std::size_t k = 0; k < luminaires_.size(); ++k)
    if (luminaires_[k].kind != Luminaire::Kind::sky && !refine_.exact_direct)
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
  if (kept >= kDirectShare * all) {
    const auto count = static_cast<std::ptrdiff_t>(std::min(emitting.size(), kDirectPatches));
    direct_sources_.insert(direct_sources_.end(), emitting.begin(), emitting.begin() + count);
  }
  direct_sources_chosen_ = true;
}

bool Solver::primary_sources_shot() {
  if (!direct_sources_chosen_) choose_direct_sources();
  if (next_luminaire_ < luminaires_.size()) return false;
  // A dim one may wait: what the primary patches that have not shot emit, at most the
  // error target's share of what they all emit.
  double waiting = 0, all = 0;
  for (const std::uint32_t id : direct_sources_) {
    if (is_luminaire(id)) continue;
    const double power = patches_[id].emission.luminance() * patches_[id].area;
    all += power;
    if (patches_[id].shot.is_zero()) waiting += power;
  }
  return waiting <= options_.error_target * all;
}

bool Solver::primary_patch_unshot(std::uint32_t i) {
  if (is_luminaire(i) || is_cluster(i) || !patches_[i].shot.is_zero()) return false;
  if (!direct_sources_chosen_) choose_direct_sources();
  return std::find(direct_sources_.begin(), direct_sources_.end(), i) != direct_sources_.end();
}

Solver::DirectLight Solver::direct_light(const Vec3d& x, const Vec3d& n, std::uint64_t key) const {
  DirectLight sum;
  for (const std::uint32_t id : direct_sources_) {
    const std::uint64_t seed = mix(options_.seed ^ mix((key << 32) ^ id ^ 0x5eedd1ec7ULL));
    if (is_luminaire(id)) {
      double open = 0;
      const double seen = luminaire_illuminance(x, n, id, seed, true, &open);
      sum.seen += luminaire(id).colour * seen;
      sum.open += luminaire(id).colour * open;
      continue;
    }
    const Patch& s = patches_[id];
    if (OpenMesh::dot(n, s.normal) > 1 - 1e-9) continue;  // facing the same way: nothing arrives
    const double f = point_to_triangle(x, n, s.corners[0], s.corners[1], s.corners[2], s.normal);
    if (!(f > 0)) continue;
    // Four stratified rays first; sixteen more where they disagree (a penumbra).
    std::uint64_t state = seed;
    int visible = 0, cast = 0;
    cast_to_patch(s, x, n, 4, state, visible, cast);
    if (visible > 0 && visible < cast) cast_to_patch(s, x, n, kDirectRays, state, visible, cast);
    sum.open += s.emission * f;
    sum.seen += s.emission * (cast > 0 ? f * visible / cast : f);
  }
  return sum;
}

void Solver::update_direct_gaps() {
  if (!options_.direct_check) return;
  if (!direct_sources_chosen_) choose_direct_sources();
  const std::size_t elements = hierarchy_.element_count();
  if (direct_gap_.size() == elements && receiver_seen_.size() == receivers_.size()) return;
  direct_gap_.resize(elements, -1.0f);
  receiver_seen_.resize(receivers_.size(), -1.0f);
  // The receivers and leaves not yet looked at, in id order.
  std::vector<char> wanted(receivers_.size(), 0);
  std::vector<ElementId> leaves;
  for (ElementId e = 0; e < elements; ++e) {
    if (direct_gap_[e] >= 0 || !hierarchy_.element(e).is_leaf()) continue;
    leaves.push_back(e);
    for (std::uint32_t r : corner_receiver_[e])
      if (receiver_seen_[r] < 0) wanted[r] = 1;
  }
  std::vector<std::uint32_t> todo;
  for (std::uint32_t r = 0; r < wanted.size(); ++r)
    if (wanted[r]) todo.push_back(r);
  tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t k) {
    const Receiver& r = receivers_[todo[k]];
    receiver_seen_[todo[k]] = static_cast<float>(direct_light(r.point, patches_[r.patch].normal, todo[k]).seen_fraction());
  });
  tbb::parallel_for(std::size_t(0), leaves.size(), [&](std::size_t k) {
    const ElementId e = leaves[k];
    const Element& el = hierarchy_.element(e);
    const Patch& patch = patches_[el.patch];
    const Vec3d centroid =
        (hierarchy_.position(el.corners[0]) + hierarchy_.position(el.corners[1]) + hierarchy_.position(el.corners[2])) /
        3.0;
    const DirectLight here = direct_light(centroid, patch.normal, (std::uint64_t{1} << 31) + e);
    const auto& c = corner_receiver_[e];
    const double line = (receiver_seen_[c[0]] + receiver_seen_[c[1]] + receiver_seen_[c[2]]) / 3.0;
    direct_gap_[e] = static_cast<float>((patch.reflectance * here.open).luminance() * std::abs(here.seen_fraction() - line));
  });
}

double Solver::direct_gap(ElementId e) const {
  return e < direct_gap_.size() && direct_gap_[e] > 0 ? direct_gap_[e] : 0.0;
}

}  // namespace dynrad::rad
