// Form factors of the walk: at element corners (receivers), at points, from
// luminaires and the sky, and their means over elements.
#include "radiosity/solver/solver.h"

#include "radiosity/sources/daylight.h"

#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/parallel.h"
#include "radiosity/transfer/random.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <thread>

namespace dynrad::rad {

namespace {

// Solver::settle_visibility: a corner is cast again when the sender's unoccluded light
// there is at least this share of what it holds (kSettleShareReflected for reflected light).
constexpr double kSettleShare = 0.05;
constexpr double kSettleShareReflected = 0.2;
// 3/4 at the centroid and 1/12 at each corner integrates quadratics exactly.
constexpr double kCentroidWeight = 0.75;
// estimate_pushdown_error(): distance, in sender radii, from which the midpoint
// estimate uses the point-to-area form (its error relative to the estimate is about
// (1 / kFarField)^2).
constexpr double kFarField = 5.0;

}  // namespace

void Solver::compute_form_factors(const std::vector<ElementId>& elements) {
  parallel_for_index(elements.size(), 8, [&](std::size_t n) { compute_corner_form_factors(elements[n]); });
}

// A receiver is shared by the elements around its vertex, and elements are handled in
// parallel. Its stamp says, for this shot s, claimed (2s) or done (2s + 1): the first
// task to claim it computes it, and a task that finds it claimed by another waits for
// it (the other task is computing it and waits for nothing, so this always ends). The
// value does not depend on which task computes it. The stamps use GCC and Clang atomic
// built-ins: std::atomic_ref needs C++20.
void Solver::compute_corner_form_factors(ElementId e) {
  const std::uint64_t claimed = 2 * (report_.iterations + 1), done = claimed + 1;
  bool wait = false;
  for (std::uint32_t id : corner_receiver_[e]) {
    std::uint64_t* stamp = &form_factor_shot_[id];
    std::uint64_t seen = __atomic_load_n(stamp, __ATOMIC_ACQUIRE);
    if (seen >= claimed) {
      wait = wait || seen != done;
      continue;
    }
    if (!__atomic_compare_exchange_n(stamp, &seen, claimed, false, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
      wait = wait || seen != done;  // another task claimed it just now
      continue;
    }
    const Receiver& r = receivers_[id];
    CornerFormFactor& f = form_factor_[id];
    f.visible = point_form_factor(r.vertex, r.point, patches_[r.patch].normal, sender_, &f.unoccluded, {false, &f.verdict});
    __atomic_store_n(stamp, done, __ATOMIC_RELEASE);
    beat();
  }
  if (!wait) return;
  for (std::uint32_t id : corner_receiver_[e])
    while (__atomic_load_n(&form_factor_shot_[id], __ATOMIC_ACQUIRE) != done) std::this_thread::yield();
}

void Solver::settle_visibility(const std::vector<ElementId>& elements) {
  // Marked receivers are listed per chunk of elements and joined in order, so that the
  // list (sorted, without repeats) is the same for any number of threads.
  const std::size_t chunk = std::max<std::size_t>(64, (elements.size() + kChunks - 1) / kChunks);
  const std::size_t chunks = (elements.size() + chunk - 1) / chunk;
  std::vector<std::vector<std::uint32_t>> marked(chunks);
  parallel_for_index(chunks, 2, [&](std::size_t c) {
    for (std::size_t n = c * chunk; n < std::min(elements.size(), (c + 1) * chunk); ++n) {
      const auto& ids = corner_receiver_[elements[n]];
      bool seen = false, hidden = false, mixed = false;
      for (std::uint32_t id : ids) {
        const RayVerdict v = form_factor_[id].verdict;
        seen = seen || v == RayVerdict::seen;
        hidden = hidden || v == RayVerdict::hidden;
        mixed = mixed || v == RayVerdict::mixed;
      }
      if (!mixed && !(seen && hidden)) continue;
      // Only where a wrong verdict would show: the sender's light there, unoccluded, is at
      // least kSettleShare of what the corner holds (on the IFC house, casting again
      // wherever corners disagreed cost a fifth of the solve; with the share, a tenth).
      const ElementId e = elements[n];
      const double light = (patches_[hierarchy_.element(e).patch].reflectance * current_shot_).luminance();
      const double share = patches_[sender_].emission.is_zero() ? kSettleShareReflected : kSettleShare;
      for (int k = 0; k < 3; ++k) {
        const CornerFormFactor& f = form_factor_[ids[k]];
        if ((f.verdict == RayVerdict::seen || f.verdict == RayVerdict::hidden) &&
            light * f.unoccluded >= share * value_[e][k].luminance())
          marked[c].push_back(ids[k]);
      }
    }
  });
  std::vector<std::uint32_t> again;
  for (const auto& m : marked) again.insert(again.end(), m.begin(), m.end());
  std::sort(again.begin(), again.end());
  again.erase(std::unique(again.begin(), again.end()), again.end());
  parallel_for_index(again.size(), 8, [&](std::size_t n) {
    const Receiver& r = receivers_[again[n]];
    CornerFormFactor& f = form_factor_[again[n]];
    f.visible = point_form_factor(r.vertex, r.point, patches_[r.patch].normal, sender_, &f.unoccluded, {true, &f.verdict});
  });
}

void Solver::register_receivers(ElementId first) {
  corner_receiver_.resize(hierarchy_.element_count());
  for (ElementId e = first; e < hierarchy_.element_count(); ++e) {
    const Element& el = hierarchy_.element(e);
    for (int k = 0; k < 3; ++k) {
      const VertexHandle v = el.corners[k];
      const auto [id, added] = receiver_id_.emplace(static_cast<std::uint32_t>(v.idx()), patches_[el.patch].plane);
      if (added) {
        *id = static_cast<std::uint32_t>(receivers_.size());
        // A step into the element: at a junction, the limit from inside the surface,
        // and no ray starting in a neighbouring wall's plane.
        const Vec3d position = hierarchy_.position(v);
        receivers_.push_back({v, el.patch, position + (hierarchy_.centroid(e) - position) * 1e-2});
      }
      corner_receiver_[e][k] = *id;
    }
  }
  form_factor_.resize(receivers_.size());
  form_factor_shot_.resize(receivers_.size(), 0);
}

// What the sky or the sun sends onto the model's surfaces (lm): per patch, its area
// times the illuminance at its centroid (the sun: the mean over the centroid and the
// three points halfway to its corners, for shadow edges), summed in patch order.
double Solver::daylight_flux(const Luminaire& l) const {
  std::vector<double> power(patches_.size(), 0.0);
  tbb::parallel_for(std::size_t(0), patches_.size(), [&](std::size_t p) {
    const Patch& patch = patches_[p];
    std::vector<Vec3d> points;
    if (l.kind != Luminaire::Kind::sun) {
      points.push_back(patch.centre);
    } else {
      // A shadow ray each: 6 x 6 stratified points. (With the centre and the points
      // halfway to the corners, a south room's sun, half its window in an overhang's
      // shadow, brought 3% less than the geometry lets in, and the solve scales every
      // shot's power to this: tests/daylight_coefficients_test.cpp.)
      const int m = 6;
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) points.push_back(point_on_triangle(patch.corners, (i + 0.5) / m, (j + 0.5) / m));
    }
    double e = 0;
    for (const Vec3d& x : points) e += daylight_illuminance(visibility_.get(), l, x, patch.normal, nullptr);
    power[p] = patch.area * e / static_cast<double>(points.size());
  });
  double total = 0;
  for (double w : power) total += w;
  return total;
}

double Solver::luminaire_illuminance(const Vec3d& x, const Vec3d& n, std::uint32_t id, std::uint64_t seed,
                                     bool rays, double* unoccluded) const {
  return rad::luminaire_illuminance(rays ? visibility_.get() : nullptr, luminaire(id), x, n, seed, unoccluded);
}

double Solver::point_form_factor(VertexHandle v, const Vec3d& x, const Vec3d& normal, std::uint32_t sender_id,
                                 double* unoccluded, const RayPlan& plan) const {
  return point_form_factor_keyed(static_cast<std::uint64_t>(v.idx()), x, normal, sender_id, unoccluded, plan);
}

// Targets behind (or on) the receiver's plane are left out: the closed form has already
// clipped that part of the sender away, and counting those targets as hidden would take
// it away twice. (A floor patch that the plane of a block's side cuts was seen as much as
// a quarter darker from points near the block's foot: the spikes of the Cornell demo,
// tests/pictures_test.cpp.)
void Solver::cast_to_patch(const Patch& sender, const Vec3d& x, const Vec3d& normal, int rays, std::uint64_t& state,
                           int& visible, int& cast) const {
  Rng rng{state};
  Vec3d targets[256];
  int side = 1, columns = 1;
  strata(rays, side, columns);
  int n = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < columns; ++j) {
      const Vec3d t = point_on_triangle(sender.corners, (i + rng.uniform()) / side, (j + rng.uniform()) / columns);
      if (OpenMesh::dot(normal, t - x) > 0) targets[n++] = t;
    }
  visible += visibility_->visible_count(x, normal, targets, n, sender.normal);
  cast += n;
  state = rng.state;
}

double Solver::point_form_factor_keyed(std::uint64_t key, const Vec3d& x, const Vec3d& normal, std::uint32_t sender_id,
                                       double* unoccluded, const RayPlan& plan) const {
  if (plan.verdict) *plan.verdict = RayVerdict::none;
  if (is_luminaire(sender_id)) {
    double open = 0;
    const double seen =
        luminaire_illuminance(x, normal, sender_id, mix(options_.seed ^ mix((key << 32) ^ sender_id)), true, &open);
    if (unoccluded) *unoccluded = open;
    return seen;
  }
  if (is_cluster(sender_id)) return cluster_form_factor(x, normal, key, true, unoccluded);
  const Patch& sender = patches_[sender_id];
  // A patch sends nothing to a point that faces the way it does (in its own plane or a
  // parallel one). The closed form is undefined at a point in the sender's plane: a
  // receiver that a coplanar neighbour shares with the sender, evaluated inside the
  // sender, took F = 1.71 from it (the Cornell demo's right wall: a vertex 8-20% above
  // its ring, tests/pictures_test.cpp).
  if (OpenMesh::dot(normal, sender.normal) > 1 - 1e-9) {
    if (unoccluded) *unoccluded = 0;
    return 0.0;
  }
  if (sender_id == sender_ && !sender_members_.empty()) return group_form_factor(key, x, normal, unoccluded, plan);
  double f = sender_id == sender_ ? sender_closed_form(x, normal)
                                  : point_to_triangle(x, normal, sender.corners[0], sender.corners[1],
                                                      sender.corners[2], sender.normal);
  if (unoccluded) *unoccluded = f;
  if (f <= 0) return 0.0;
  // Visible fraction: a few rays first; more only where those disagree.
  std::uint64_t state = mix(options_.seed ^ mix((key << 32) ^ sender_id));
  int visible = 0, cast = 0;
  cast_to_patch(sender, x, normal, options_.min_rays, state, visible, cast);
  const bool agreed = visible == 0 || visible == cast;
  if (!agreed || plan.full) cast_to_patch(sender, x, normal, shot_max_rays_, state, visible, cast);
  if (cast == 0) return f;  // the sender lies (all but) behind the plane: f is about 0 anyway
  if (plan.verdict) *plan.verdict = !agreed || plan.full ? RayVerdict::mixed : visible == 0 ? RayVerdict::hidden : RayVerdict::seen;
  return f * visible / cast;
}

double Solver::form_factor(ElementId e, int corner) const {
  return corner_form_factor(e, corner).visible;
}

// Mean form factor over element q, for the power it receives. The three corner values
// alone misjudge elements next to the sender's edge, where F changes fastest, the
// same way at every scale; Lambert's closed form at the centroid (no rays: scaled by
// the corners' visible fractions) gives the integral a second, interior sample.
double Solver::element_form_factor(ElementId q) const {
  double corners = 0, unoccluded = 0;
  for (int k = 0; k < 3; ++k) {
    const CornerFormFactor& f = corner_form_factor(q, k);
    corners += f.visible;
    unoccluded += f.unoccluded;
  }
  const double visible = unoccluded > 0 ? std::min(1.0, corners / unoccluded) : 0.0;
  const double centre = sender_closed_form(hierarchy_.centroid(q), hierarchy_.normal(q)) * visible;
  return (1 - kCentroidWeight) * corners / 3.0 + kCentroidWeight * centre;
}

double Solver::sender_closed_form(const Vec3d& x, const Vec3d& n) const {
  if (is_luminaire(sender_)) return luminaire_illuminance(x, n, sender_, 0, false, nullptr);
  if (is_cluster(sender_)) return cluster_form_factor(x, n, 0, false, nullptr);
  const Patch& sender = patches_[sender_];
  if (OpenMesh::dot(n, sender.normal) > 1 - 1e-9) return 0.0;  // facing the same way (see point_form_factor_keyed)
  if (!sender_members_.empty()) return group_closed_form(x, n);
  return shaped_closed_form(x, n, sender.corners, sender.centre, sender.radius, sender.area, sender.normal, shape_);
}

double Solver::element_reach(ElementId q) const {
  return element_form_factor(q) * hierarchy_.element(q).area;
}

void Solver::midpoint_form_factors(ElementId q, std::array<double, 3>& mid) const {
  const Element& el = hierarchy_.element(q);
  // (the exact form costs a luminaire or a cluster no more than a far-field one; a
  // group's far field would need its weights' moments)
  if (is_luminaire(sender_) || is_cluster(sender_) || !sender_members_.empty()) {
    const Vec3d& n = hierarchy_.normal(q);
    const Vec3d centroid = hierarchy_.centroid(q);
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      const CornerFormFactor& fa = corner_form_factor(q, k);
      const CornerFormFactor& fb = corner_form_factor(q, l);
      const double unoccluded = fa.unoccluded + fb.unoccluded;
      const double visible = unoccluded > 0 ? (fa.visible + fb.visible) / unoccluded : 1.0;
      Vec3d at = (hierarchy_.position(el.corners[k]) + hierarchy_.position(el.corners[l])) * 0.5;
      at += (centroid - at) * 1e-2;
      mid[k] = visible * sender_closed_form(at, n);
    }
    return;
  }
  const Patch& sender = patches_[sender_];
  const Vec3d& n = hierarchy_.normal(q);
  const Vec3d centroid = hierarchy_.centroid(q);
  // Far from the sender, what matters is the second difference of F along each edge,
  // F(mid) - (F(a) + F(b)) / 2, and the point-to-area form A cos cos / (pi r^2) gives it
  // within a fraction (R/r)^2 of itself (R: the sender's radius), at a fraction of the
  // closed form's cost. Used when q is at least kFarField sender radii away and no part
  // of the sender is below q's horizon (nor q behind the sender), where the closed form
  // would clip.
  Vec3d pos[3];
  for (int k = 0; k < 3; ++k) pos[k] = hierarchy_.position(el.corners[k]);
  double q_radius = 0;
  for (const Vec3d& p : pos) q_radius = std::max(q_radius, (p - centroid).norm());
  bool far = (centroid - sender.centre).norm() - q_radius >= kFarField * sender.radius;
  for (int k = 0; far && k < 3; ++k)
    far = OpenMesh::dot(n, sender.corners[k] - centroid) > 0 && OpenMesh::dot(sender.normal, pos[k] - sender.corners[0]) > 0;
  auto far_form = [&](const Vec3d& x) { return point_to_area(x, n, sender.centre, sender.normal, sender.area); };
  double far_at[3] = {0, 0, 0};
  if (far)
    for (int k = 0; k < 3; ++k) far_at[k] = far_form(receivers_[corner_receiver_[q][k]].point);
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    const CornerFormFactor& fa = corner_form_factor(q, k);
    const CornerFormFactor& fb = corner_form_factor(q, l);
    const double unoccluded = fa.unoccluded + fb.unoccluded;
    const double visible = unoccluded > 0 ? (fa.visible + fb.visible) / unoccluded : 1.0;
    Vec3d at = (pos[k] + pos[l]) * 0.5;
    at += (centroid - at) * 1e-2;  // inside q, as evaluation points are
    mid[k] = far ? 0.5 * (fa.visible + fb.visible) + visible * (far_form(at) - 0.5 * (far_at[k] + far_at[l]))
                 : visible * sender_closed_form(at, n);
  }
}

}  // namespace dynrad::rad
