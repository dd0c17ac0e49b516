// Sender groups in the solver (see solver.h, "Sender groups", and mesh/core/plane_groups.h):
// building them and shooting from one.
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/random.h"

#include <boost/container/small_vector.hpp>

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

namespace {

// Solver::group_closed_form: from this many of its radii a member counts by the point-to-area form.
constexpr double kMemberFar = 12.0;

}  // namespace

void Solver::build_groups() {
  PlaneGroupOptions o;
  o.max_radius = refine_.method == Method::adaptive ? 0.0 : options_.group_radius;
  // Small: less than half the smallest whole patch (RefineSettings::patch_area, or the
  // largest patch where that is smaller), so that patches cut to the patch size stay
  // senders of their own and only slivers and pieces join them. Solved to convergence,
  // grouping changes nothing (the 1990 room: 0.0035% rms between the two); stopped by
  // the error target, a group sends sooner what its pieces hold, and the light left
  // unshot sits less evenly than the ambient term assumes: with the whole smallest
  // patch as the bound, the 1990 room stopped 0.54% from the path tracer instead of
  // 0.47% (half: 0.47%, and the IFC house's shots fall from 4,475 to 3,469).
  o.small_area = patch_area_ / 4;
  // Patches in face clusters send with their cluster. (An emitter's neighbours in a
  // group share its material, so they emit alike.)
  groups_ = build_plane_groups(hierarchy_, o, [this](std::uint32_t p) { return !patches_[p].clustered; });
  report_.sender_groups = report_.grouped_patches = 0;
  for (const PlaneGroups::Group& g : groups_.groups)
    if (g.count > 1) {
      ++report_.sender_groups;
      report_.grouped_patches += g.count;
    }
}

Rgb Solver::start_group_shot(std::uint32_t leader) {
  const PlaneGroups::Group& g = group_of(leader);
  Rgb power;
  for (std::uint32_t n = g.first; n < g.first + g.count; ++n) {
    const Patch& p = patches_[groups_.members[n]];
    power += p.unshot * p.area;
  }
  const Rgb mean = power * (1.0 / g.area);
  const double luminance = mean.luminance();
  const double total_magnitude = std::abs(mean.r) + std::abs(mean.g) + std::abs(mean.b);
  sender_members_.clear();
  sender_member_unshot_.clear();
  std::fill(coefficient_shot_.begin(), coefficient_shot_.end(), 0.0f);
  shape_.on = false;
  shape_.max_weight = 1;
  double cumulated = 0;
  for (std::uint32_t n = g.first; n < g.first + g.count; ++n) {
    Patch& p = patches_[groups_.members[n]];
    SenderMember m;
    m.corners = p.corners;
    m.centroid = p.centre;
    m.radius = p.radius;
    m.area = p.area;
    // The patch's share of the light per unit of area, by luminance (by the sum of the
    // channels for light no eye sees), so that the weights' area-weighted mean is 1.
    m.weight = std::abs(luminance) > 1e-12 * total_magnitude
                   ? p.unshot.luminance() / luminance
                   : (total_magnitude > 0 ? (p.unshot.r + p.unshot.g + p.unshot.b) / (mean.r + mean.g + mean.b) : 1.0);
    if (!std::isfinite(m.weight)) m.weight = 1;
    if (options_.shaped_senders) m.shape = shape_of(groups_.members[n], p.unshot.luminance());
    shape_.max_weight = std::max(shape_.max_weight, std::abs(m.weight) * m.shape.max_weight);
    cumulated += std::abs(m.weight) * m.area;
    m.cumulated = cumulated;
    sender_members_.push_back(m);
    sender_member_unshot_.push_back(p.unshot);
    p.unshot = p.unshot * (1 - options_.overshoot);  // update(i), as for one patch
    if (coefficients_.count > 0) shoot_coefficients(groups_.members[n], options_.overshoot, p.area / g.area);
  }
  for (SenderMember& m : sender_members_) m.cumulated = cumulated > 0 ? m.cumulated / cumulated : 1.0;
  sender_members_.back().cumulated = 1.0;
  sender_centre_ = g.centre;
  sender_radius_ = g.radius;
  return mean;
}

Vec3d Solver::group_sender_point(double u, double v, double w) const {
  std::size_t k = 0;
  while (k + 1 < sender_members_.size() && sender_members_[k].cumulated <= u) ++k;
  return point_on_triangle(sender_members_[k].corners, v, w);
}

double Solver::group_closed_form(const Vec3d& x, const Vec3d& n, double* terms) const {
  const Vec3d& normal = patches_[sender_].normal;
  double f = 0;
  for (std::size_t k = 0; k < sender_members_.size(); ++k) {
    const SenderMember& m = sender_members_[k];
    double term = 0;
    if (m.weight != 0) {
      const Vec3d d = m.centroid - x;
      const double r2 = d.sqrnorm();
      const double above = OpenMesh::dot(n, d), facing = -OpenMesh::dot(normal, d);
      if (r2 > kMemberFar * kMemberFar * m.radius * m.radius && above > m.radius)
        term = facing > 0 ? m.weight * m.area * above * facing / (M_PI * r2 * r2) : 0.0;
      else
        term = m.weight * shaped_closed_form(x, n, m.corners, m.centroid, m.radius, m.area, normal, m.shape);
    }
    if (terms) terms[k] = term;
    f += term;
  }
  return std::max(0.0, f);
}

double Solver::group_form_factor(std::uint64_t key, const Vec3d& x, const Vec3d& n, double* unoccluded,
                                 const RayPlan& plan) const {
  boost::container::small_vector<double, 32> term(sender_members_.size());
  const double f = group_closed_form(x, n, term.data());
  if (unoccluded) *unoccluded = f;
  if (!(f > 0)) return 0.0;
  // Rays go to patches drawn by |term| (T their sum); each counts with its term's sign,
  // so that T times the mean is the sum of the terms' visible parts.
  boost::container::small_vector<double, 32> before(sender_members_.size());  // |term| of the members before k
  double total = 0;
  for (std::size_t k = 0; k < sender_members_.size(); ++k) {
    before[k] = total;
    total += std::abs(term[k]);
  }
  Rng rng{mix(options_.seed ^ mix((key << 32) ^ sender_))};
  int hits = 0, cast = 0;
  double signed_hits = 0;
  Vec3d plus[256], minus[256];  // targets on patches whose term is positive, negative
  const Vec3d& front = patches_[sender_].normal;
  auto pass = [&](int count) {
    int rows = 1, columns = 1;
    strata(count, rows, columns);
    int n_plus = 0, n_minus = 0;
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < columns; ++j) {
        // A jittered cell of the (share, v) square: where `at` falls in the member's
        // share is the first coordinate on it, so that the rays are stratified over
        // each member in both directions. (With that coordinate drawn afresh, a
        // penumbra's thin strip of a small area light could be hit by 1 ray of 66
        // where 6 were due.)
        const double at = (i + rng.uniform()) / rows * total;
        // The member whose share holds `at`: the last whose share begins at or before it
        // (one with no share has none to hold it).
        std::size_t k = static_cast<std::size_t>(std::upper_bound(before.begin(), before.end(), at) - before.begin());
        k = k > 0 ? k - 1 : 0;
        while (k > 0 && !(std::abs(term[k]) > 0)) --k;
        const double u = term[k] != 0 ? std::clamp((at - before[k]) / std::abs(term[k]), 0.0, 1.0) : 0.5;
        const Vec3d t = point_on_triangle(sender_members_[k].corners, u, (j + rng.uniform()) / columns);
        if (OpenMesh::dot(n, t - x) > 0) {
          if (term[k] < 0)
            minus[n_minus++] = t;
          else
            plus[n_plus++] = t;
        }
      }
    const int seen_plus = n_plus > 0 ? visibility_->visible_count(x, n, plus, n_plus, front) : 0;
    const int seen_minus = n_minus > 0 ? visibility_->visible_count(x, n, minus, n_minus, front) : 0;
    hits += seen_plus + seen_minus;
    signed_hits += seen_plus - seen_minus;
    cast += n_plus + n_minus;
  };
  pass(options_.min_rays);
  const bool agreed = hits == 0 || hits == cast;
  if (!agreed || plan.full) pass(shot_max_rays_);
  if (cast == 0) return f;  // the group lies (all but) behind x's plane
  if (plan.verdict) *plan.verdict = !agreed || plan.full ? RayVerdict::mixed : hits == 0 ? RayVerdict::hidden : RayVerdict::seen;
  return std::max(0.0, total * signed_hits / cast);
}

}  // namespace dynrad::rad
