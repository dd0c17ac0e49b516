// One shot of progressive refinement, for the three methods. The paper's loops:
//
//   Figure 1, progressive        Figure 2, adaptive             Figure 5, dynamic
//   pick brightest patch: i      pick brightest patch: i        pick brightest patch: i
//   for every patch j            for every element q (leaves)   for every patch j
//     shoot(i, j)                  shoot(i, q)                    level = 0
//   update(i)                    update(i)                        do
//                                for every element q (leaves)       for every element q of j on level
//                                  if refineOracle(q, thresh)         shoot(i, q)
//                                    subdivide(q)                     if refineOracle(q, i, thresh)
//                                    (new elements receive              subdivide(q)
//                                     this shot again)              level++
//                                                                 while level < maxLevel
//                                                               update(i)
//
// All three are one walk: each receiving patch's tree is visited level by level from
// its root. At every visited element q, shoot(i, q) computes the radiosity dB this
// sender brings to q's corners; the method then decides whether the shot goes on into
// q's children (subdividing q first if it is a leaf):
//   progressive never goes on;
//   adaptive always goes on while q has children (every shot reaches all leaves), and
//     subdivides a leaf when Figure 3's oracle holds;
//   dynamic goes on only when its oracle holds (Figure 6's, or the push-down oracle
//     that is the default, see oracle.h); where it stops, dB is pushed
//     down to the elements already below q (the paper's "energy transport
//     derivation"), so no rays are spent on them: interpolated from q's corners and
//     edge midpoints by a quadratic (the paper: linearly from the corners; see
//     RefineSettings::quadratic_pushdown).
// Luminaires (luminaire.h) are senders of the same walk: before the first patch, each
// shoots once, exactly; its "form factor" at a corner is the illuminance it gives there
// per unit of its colour (Solver::luminaire_illuminance), so that everything below
// (oracle, push-down, subdivision, energy) is the patches'. Under
// RefineSettings::exact_direct (the default) a luminaire's or the sun's shot stops at
// the patches: it gives each its first bounce and refines nothing, and its light is
// evaluated exactly where it is seen (exact_direct.cpp).
// Subdividing is the paper's 1 -> 4 split: two bisections, so the second half of a
// split is always visited. In dynamic, new elements start from their parent's cumulated
// radiosity, interpolated from its corners (Dubuis & Bieri); in adaptive, their values
// are recalculated from every patch that has shot so far, as Cohen et al. do (and as
// the paper counts against them). Either way they then receive this shot like any other.
//
// Where the shot stops, element q receives the power dB_i * A_q * mean F(q corners);
// the reflected part joins its patch's unshot radiosity, area-weighted (eq. 3). Those
// powers are scaled so that they sum to what the sender can reach (its power times
// 1 - lost_i, lost_i measured once per patch with rays): averaging F over three corners
// is not an exact integral. Corner values use the unscaled F, exact at a point.
//
// Push-down is lazy: where a shot stops, the elements below q are not touched at once;
// q keeps the increment and hands it on when a later walk enters q (see flush()).
//
// Counting, as the paper does: energy_transfers counts shoot(i, q) where the shot
// stops, plus, for dynamic, the elements it passes through at whole paper levels (the
// paper's dynamic shoots to a patch and then to its subpatches); adaptive's interior
// elements only route the walk to the leaves and are not counted.
// patch_element_transfers counts those below patch level.
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/parallel.h"

#include <tbb/task_group.h>

#include <algorithm>

namespace dynrad::rad {

// Figure 5 (and Figures 1 and 2, the same walk; see above).
bool Solver::shoot_once() {
  start_heartbeat();
  // pick brightest patch: i (luminaires first; a patch, a group of patches or a cluster)
  Rgb shot;
  if (!pick_sender(shot)) return false;
  const std::uint32_t i = sender_;
  const ShotRules rules = shot_rules(i);
  ShotWalk walk;
  held_.clear();
  // for every patch j: the root of every patch that can receive from i
  receiving_patches(i, walk.level);
  // level = 0; do ... level++ while level < maxLevel (the walk ends where no element
  // goes on)
  while (!walk.level.empty()) {
    // for every element q of j on level: shoot(i, q); if refineOracle(q, i, thresh) ...
    shoot_level(walk, rules, shot);
    // ... subdivide(q)
    subdivide(walk, shot);
    // level++: the children of the elements the shot goes on into
    next_level(walk, shot);
  }
  // what every element where the shot stopped received, booked (eq. 3)
  account_transfers(walk.terminals, walk.reach, i, shot);
  // update(i)
  update(i, shot);
  return true;
}

bool Solver::pick_sender(Rgb& shot) {
  std::uint32_t i = 0;
  Rgb unshot;  // the sender's, before this shot
  if (next_luminaire_ < luminaires_.size()) {
    // Luminaires shoot first, each once and exactly: the light of a luminaire is all
    // "unshot" until it shoots, and none is left after (no overshoot, no shape).
    const std::size_t k = next_luminaire_++;
    i = static_cast<std::uint32_t>(patches_.size() + k);
    shot = unshot = luminaires_[k].colour;
    sender_ = i;
    current_shot_ = shot;
    shape_.on = false;
    shape_.max_weight = 1;
    sender_members_.clear();
    luminaire_unshot_ = Rgb();
    for (std::size_t m = next_luminaire_; m < luminaires_.size(); ++m)
      luminaire_unshot_ += luminaires_[m].colour * luminaire_flux_[m];
    report_.energy.unshot = report_.energy.unshot - shot * luminaire_flux_[k];
    unshot_staying_ = unshot_staying_ - shot * luminaire_flux_[k];
  } else if (is_cluster(brightest_patch())) {
    // A face cluster sends what its patches reflected, all at once and exactly as it
    // holds it (no overshoot, no shape; see solver.h).
    i = brightest_patch();
    shot = unshot = start_cluster_shot(cluster_index(i));
    if (unshot.is_zero()) return false;
    sender_ = i;
    current_shot_ = shot;
    shape_.on = false;
    shape_.max_weight = 1;
    sender_members_.clear();
    const double lost = cluster_state_[cluster_index(i)].lost;
    report_.energy.unshot = report_.energy.unshot - shot;
    unshot_staying_ = unshot_staying_ - shot * (lost >= 0 ? 1 - lost : 1.0);
  } else if (is_group(brightest_patch())) {
    // A group of patches in one plane sends what they all hold, each its own share
    // (see solver.h, "Sender groups").
    i = brightest_patch();
    sender_ = i;
    unshot = start_group_shot(i);
    if (unshot.is_zero()) return false;
    shot = unshot * options_.overshoot;
    current_shot_ = shot;
    const double area = group_of(i).area, lost = patches_[i].lost >= 0 ? patches_[i].lost : patches_[i].rough_lost;
    report_.energy.unshot = report_.energy.unshot - shot * area;
    unshot_staying_ = unshot_staying_ - shot * (area * (lost >= 0 ? 1 - lost : 1.0));
  } else {
    i = brightest_patch();
    Patch& sender = patches_[i];
    unshot = sender.unshot;
    if (unshot.r == 0 && unshot.g == 0 && unshot.b == 0) return false;
    // With over-relaxation (SolveOptions::overshoot) a little more than the unshot
    // radiosity, or later a correction of the opposite sign.
    shot = unshot * options_.overshoot;
    sender_ = i;
    current_shot_ = shot;
    if (coefficients_.count > 0) {  // its coefficient channels go with it (solver_coefficients.cpp)
      std::fill(coefficient_shot_.begin(), coefficient_shot_.end(), 0.0f);
      shoot_coefficients(i, options_.overshoot, 1);
    }
    sender_members_.clear();
    sender_centre_ = sender.centre;
    sender_radius_ = sender.radius;
    shape_sender();
    sender.unshot = unshot - shot;  // update(i): everything it held is shot now (the excess: below 0)
    report_.energy.unshot = report_.energy.unshot - shot * sender.area;  // kept current for ambient()
    unshot_staying_ = unshot_staying_ - shot * (sender.area * (sender.lost >= 0 ? 1 - sender.lost : 1.0));
    // (sender.shot grows only after this shot's walk, in update(): elements created
    // during the walk gather the shots before this one and then receive this one like
    // the rest.)
  }
  return true;
}

ShotRules Solver::shot_rules(std::uint32_t i) {
  // A luminaire's light is the sharpest a surface receives (a point source's pool,
  // a beam's edge) and the most of it: its shots may refine further, to a tighter
  // push-down error (RefineSettings::luminaire_levels, luminaire_pushdown).
  // (The sky is the exception: its light through a window is as soft as a patch's.)
  // Less on detail (Patch::detail: the facets of frames, radiators, skirting boards,
  // chair parts): RefineSettings::detail_luminaire_levels, the patches' push-down error
  // and no shadow levels.
  // A small area light's first shot, its emission, is as sharp, and its penumbrae get
  // more rays (RefineSettings::sharp_primary_patches, SolveOptions::primary_rays).
  ShotRules r;
  r.from_luminaire = is_luminaire(i);
  r.primary = refine_.sharp_primary_patches && refine_.method == Method::dynamic && primary_patch_unshot(i);
  r.sharp = (r.from_luminaire && luminaire(i).kind != Luminaire::Kind::sky) || r.primary;
  // Exact direct light (exact_direct.cpp): the shot reaches the patches and stops there.
  r.direct = is_direct_sender(i);
  if (r.direct) {
    shot_max_rays_ = options_.max_rays;
    r.oracle = r.detail_oracle = refine_.dynamic;
    return r;  // max_generation 0: nothing is split
  }
  shot_max_rays_ = r.primary ? std::max(options_.max_rays, options_.primary_rays) : options_.max_rays;
  const int sharp_levels = r.primary ? refine_.primary_levels : r.sharp ? refine_.luminaire_levels : 0;
  r.max_generation = 2 * (refine_.max_level + sharp_levels);
  r.detail_generation = 2 * (refine_.max_level + std::min(sharp_levels, refine_.detail_luminaire_levels));
  r.oracle = refine_.dynamic;
  if (r.sharp) r.oracle.pushdown *= refine_.luminaire_pushdown;
  if (r.from_luminaire || r.primary) {
    // The error is estimated wherever the shot reaches (one shot, and a luminaire's
    // closed form is cheap): an element with even corners may hold the peak of a pool
    // of light.
    r.oracle.pushdown_cumulated_gradient = 0;
  }
  r.detail_oracle = r.oracle;
  r.detail_oracle.pushdown = refine_.dynamic.pushdown;
  r.ambient_now = r.oracle.pushdown_ambient ? ambient() : Rgb();
  return r;
}

void Solver::shoot_level(ShotWalk& walk, const ShotRules& rules, const Rgb& shot) {
  const std::vector<ElementId>& level = walk.level;
  walk.next.clear();
  walk.subdivide.clear();
  walk.passed.clear();
  walk.complete_split_next.clear();
  // shoot(i, q), the oracle and the effect on the values, for every q of this level
  // in parallel: each reads and writes only q and q's own children (the next level),
  // so the elements of a level are independent (the form factors at q's corners are
  // shared with its neighbours; see compute_corner_form_factors). The level's lists
  // and counters are built in level order, so that the result does not depend on the
  // number of threads: the level is cut into at most kChunks chunks (by its size
  // alone), each chunk makes its own lists, and the chunks' lists are joined in order.
  // A chunk has at least 4 elements: joining a chunk costs about as much as deciding
  // for a few elements, more when another core wrote it (on the 1990 room's 2.5 m
  // patches, chunks of one element spent 8% of a 2-thread solve in the join).
  if (settles_visibility()) {  // its corners first, all of the level's (see settle_visibility)
    compute_form_factors(level);
    settle_visibility(level);
  }
  const std::size_t chunk = std::max<std::size_t>(4, (level.size() + kChunks - 1) / kChunks);
  const std::size_t chunks = (level.size() + chunk - 1) / chunk;
  if (walk_chunks_.size() < chunks) walk_chunks_.resize(chunks);
  // (a level of fewer than 16 elements is not worth waking the other threads for)
  const std::size_t serial_below = level.size() < 16 ? chunks + 1 : 0;
  parallel_for_index(chunks, serial_below, [&](std::size_t c) {
    WalkChunk& out = walk_chunks_[c];
    out.clear();
    for (std::size_t n = c * chunk; n < std::min(level.size(), (c + 1) * chunk); ++n)
      shoot_element(level[n], rules, shot, walk.complete_split, out);
  });
  walk.ready.clear();
  for (std::size_t c = 0; c < chunks; ++c) {
    const WalkChunk& out = walk_chunks_[c];
    walk.passed.insert(walk.passed.end(), out.passed.begin(), out.passed.end());
    walk.subdivide.insert(walk.subdivide.end(), out.subdivide.begin(), out.subdivide.end());
    walk.ready.insert(walk.ready.end(), out.ready.begin(), out.ready.end());
    walk.terminals.insert(walk.terminals.end(), out.terminals.begin(), out.terminals.end());
    walk.reach.insert(walk.reach.end(), out.reach.begin(), out.reach.end());
    report_.energy_transfers += out.transfers;
    report_.patch_element_transfers += out.patch_transfers;
  }
}

void Solver::shoot_element(ElementId q, const ShotRules& rules, const Rgb& shot,
                           const std::vector<ElementId>& complete_split, WalkChunk& out) {
  const Element& el = hierarchy_.element(q);
  const Patch& patch = patches_[el.patch];
  // Most are known already: level 0's from receiving_patches(), deeper levels'
  // mostly from the overlap with mesh refinement below.
  compute_corner_form_factors(q);
  OracleInputs in{};
  // An element gathered during this shot already holds this shot's transfer.
  const bool holds_shot = gathered_in_[q] == report_.iterations + 1;
  for (int k = 0; k < 3; ++k) {
    in.current[k] = patch.reflectance * shot * form_factor(q, k);
    in.cumulated[k] = value_[q][k] + (holds_shot ? Rgb() : in.current[k]);
  }
  for (int k = 0; k < 3; ++k)  // (exact_direct.cpp; 0 where no direct sender lit it)
    in.direct[k] = (patch.reflectance * receiver_direct(corner_receiver_[q][k])).luminance();
  if (rules.direct) {  // to the patches only, and into no element's values (exact_direct.cpp)
    out.terminals.push_back(q);
    out.reach.push_back(direct_reach(q));
    out.count(el);
    return;
  }
  // Dynamic refines deeper where a shadow's edge crosses q (RefineSettings::shadow_levels).
  const bool detail = rules.sharp && patch.detail;
  const int element_generation = detail ? rules.detail_generation : rules.max_generation;
  const bool deeper = refine_.method == Method::dynamic && refine_.shadow_levels > 0 && !detail &&
                      el.generation >= element_generation && shadow_crosses(q) && !shadow_resolved(q);
  // (the patches of face clusters are not refined: they are small already)
  // No element gets smaller than the smallest a patch of the full patch size may
  // reach (RefineSettings::patch_area): slivers and small parts are fine already.
  const int generations = element_generation + (deeper ? 2 * refine_.shadow_levels : 0);
  // (nor inside the strip along a shadow's outline: its lines are the edge already)
  const bool can_split = !patch.clustered && !el.in_strip && el.generation < generations &&
                         el.area >= std::ldexp(patch_area_, 1 - generations);
  const bool odd = el.generation % 2 == 1;
  // The push-down error costs three closed forms; it is estimated only where the
  // oracle's first condition (the cumulated gradient) holds and it can decide. Its
  // midpoints also give q's mean form factor, should the shot stop at q.
  double mean_form_factor = -1;
  std::array<double, 3> mid{};  // form factors at q's edge midpoints, where known
  in.refined = refine_.refined_pushdown && !el.is_leaf();
  if (refine_.method == Method::dynamic && can_split && !odd &&
      rules.oracle.variant == OracleThresholds::Variant::pushdown &&
      (in.refined || cumulated_gradient(in) > rules.oracle.pushdown_cumulated_gradient)) {
    mean_form_factor = estimate_pushdown_error(q, patch.reflectance, in, mid);
    in.ambient = (patch.reflectance * rules.ambient_now).luminance();
  }
  bool go_on = false;
  switch (refine_.method) {
    case Method::progressive:
      break;
    case Method::adaptive:
      go_on = !el.is_leaf() || (can_split && (std::binary_search(complete_split.begin(), complete_split.end(), q) ||
                                              adaptive_oracle(in, refine_.adaptive_threshold)));
      break;
    case Method::dynamic:
      go_on = can_split && (odd || dynamic_oracle(in, detail ? rules.detail_oracle : rules.oracle));
      break;
  }
  if (go_on) {
    flush(q);  // the children must hold what earlier shots pushed down before they are shot
    out.passed.push_back(q);
    if (el.is_leaf())
      out.subdivide.push_back(q);
    else
      out.ready.insert(out.ready.end(), el.children.begin(), el.children.end());
    // dynamic: a whole paper level the shot passes through
    if (refine_.method == Method::dynamic && !odd) out.count(el);
    return;
  }
  // The shot stops at q: q takes dB, and what is already below q gets it interpolated
  // from q's corners and edge midpoints (push-down) instead of a transfer of its own.
  value_[q] = in.cumulated;
  if (!el.is_leaf()) {
    std::array<Rgb, 6> delta;
    for (int k = 0; k < 3; ++k) delta[k] = in.current[k];
    if (refine_.quadratic_pushdown && refine_.method == Method::dynamic) {
      if (mean_form_factor < 0) midpoint_form_factors(q, mid);
      for (int k = 0; k < 3; ++k) delta[3 + k] = patch.reflectance * shot * mid[k];
    } else {
      for (int k = 0; k < 3; ++k) delta[3 + k] = (in.current[k] + in.current[(k + 1) % 3]) * 0.5;
    }
    push_down(q, delta);
  }
  out.terminals.push_back(q);
  out.reach.push_back(mean_form_factor >= 0 ? mean_form_factor * el.area : element_reach(q));
  out.count(el);
}

void Solver::subdivide(ShotWalk& walk, const Rgb& shot) {
  // New elements start from their parent's values before this shot (dB is added to the
  // parent in next_level()) and receive the shot at the next level.
  // Refining the mesh is serial; meanwhile the other threads compute the form factors
  // of the next level's elements that exist already (that work reads no mesh data and
  // nothing refine() changes; the new elements are numbered only after the join).
  tbb::task_group overlap;
  if (!walk.ready.empty() && !walk.subdivide.empty()) overlap.run([&] { compute_form_factors(walk.ready); });
  try {
    for (ElementId q : walk.subdivide) {
      if (!refinement_allowed()) break;  // a limit: the shot stops at q (next_level())
      const bool starts_split = !std::binary_search(walk.complete_split.begin(), walk.complete_split.end(), q);
      hierarchy_.refine(q);
      const Element& el = hierarchy_.element(q);
      // Adaptive: children of a leaf the oracle split in this shot; the walk splits
      // them again to complete the 1 -> 4 split. (Dynamic needs no marks: it reaches
      // odd generations only by going on from an even one, so it always completes the
      // split.)
      if (refine_.method == Method::adaptive && starts_split && !el.is_leaf())
        walk.complete_split_next.insert(walk.complete_split_next.end(), el.children.begin(), el.children.end());
    }
  } catch (...) {
    overlap.wait();
    throw;
  }
  overlap.wait();
  const std::size_t first_new = initialised_;
  initialise_new_elements();  // all of this level's new elements at once (values do not change in between)
  if (refine_.method == Method::dynamic) restart_split_terminals(first_new, walk.terminals, shot);
}

void Solver::next_level(ShotWalk& walk, const Rgb& shot) {
  for (ElementId q : walk.passed) {
    const Element& el = hierarchy_.element(q);
    if (gathered_in_[q] != report_.iterations + 1) {  // dB, as in the decision pass
      const Patch& patch = patches_[el.patch];
      for (int k = 0; k < 3; ++k) value_[q][k] += patch.reflectance * shot * form_factor(q, k);
    }
    if (el.is_leaf()) {  // the split was refused (minimum area): the shot stops here
      walk.terminals.push_back(q);
      walk.reach.push_back(element_reach(q));
      ++report_.energy_transfers;
      if (el.generation > 0) ++report_.patch_element_transfers;
    } else {
      walk.next.insert(walk.next.end(), el.children.begin(), el.children.end());
    }
  }
  // (no sort: `next` is built in level order, the same for any number of threads)
  walk.level.swap(walk.next);
  std::sort(walk.complete_split_next.begin(), walk.complete_split_next.end());
  walk.complete_split.swap(walk.complete_split_next);
}

void Solver::update(std::uint32_t i, const Rgb& shot) {
  // The patches that shot now hold it as shot (a patch's unshot radiosity fell when it
  // was picked: pick_sender()).
  if (!sender_members_.empty()) {
    const PlaneGroups::Group& g = group_of(i);
    for (std::uint32_t n = 0; n < g.count; ++n) {
      index_shot_patch(groups_.members[g.first + n]);
      patches_[groups_.members[g.first + n]].shot += sender_member_unshot_[n] * options_.overshoot;
    }
    sender_members_.clear();
  } else if (!is_luminaire(i) && !is_cluster(i)) {
    index_shot_patch(i);
    patches_[i].shot += shot;
  }
  // Who lit each patch is known once the last luminaire has shot (exact_direct.cpp).
  if (is_luminaire(i) && next_luminaire_ == luminaires_.size()) {
    build_direct_lists();
    direct_for_new_elements(0);  // every receiver so far: the oracle sees the direct light
  }
  ++report_.iterations;
  report_.unshot_history.push_back(unshot_fraction());
  report_.transfers_history.push_back(report_.energy_transfers);
}

}  // namespace dynrad::rad
