// What the refinement oracle is given beyond the corner values: the push-down
// error of one shot at an element, and whether a shadow's edge crosses it (the
// decisions themselves are oracle.h's; the gates around them, shoot_element()).
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/form_factor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynrad::rad {

namespace {

constexpr double kShadowResolution = 0.02;

}  // namespace

double Solver::estimate_pushdown_error(ElementId q, const Rgb& reflectance, OracleInputs& in,
                                       std::array<double, 3>& mid) const {
  const double shot = (reflectance * current_shot_).luminance();
  in.pushdown_error = in.current_peak = 0;
  if (!(shot > 0)) return -1;
  midpoint_form_factors(q, mid);
  const bool resolved = shadow_resolved(q);
  double mid_sum = 0;
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    const CornerFormFactor& fa = corner_form_factor(q, k);
    const CornerFormFactor& fb = corner_form_factor(q, l);
    const double a = in.current[k].luminance(), b = in.current[l].luminance();
    const double at_mid = shot * mid[k];
    const bool shadow_edge = !resolved && std::abs(fa.visible_fraction() - fb.visible_fraction()) > 1e-9;
    const double error = std::abs(at_mid - 0.5 * (a + b)) + (shadow_edge ? 0.5 * std::abs(a - b) : 0.0);
    in.pushdown_error = std::max(in.pushdown_error, error);
    in.current_peak = std::max({in.current_peak, a, at_mid});
    mid_sum += mid[k];
  }
  if (is_luminaire(sender_)) {
    // A luminaire's pool of light peaks inside elements, where no edge midpoint sees
    // it (a point source straight above q): the centroid is checked too, against the
    // corners' mean, which is what q shows there if the shot stops at it (its exact
    // illuminance costs no more than a midpoint's).
    double corners = 0, unoccluded = 0, visible = 0;
    for (int k = 0; k < 3; ++k) {
      const CornerFormFactor& f = corner_form_factor(q, k);
      visible += f.visible;
      unoccluded += f.unoccluded;
      corners += in.current[k].luminance();
    }
    const double fraction = unoccluded > 0 ? visible / unoccluded : 1.0;
    const double at_centroid = shot * fraction * sender_closed_form(hierarchy_.centroid(q), hierarchy_.normal(q));
    in.pushdown_error = std::max(in.pushdown_error, std::abs(at_centroid - corners / 3));
    in.current_peak = std::max(in.current_peak, at_centroid);
  }
  return mid_sum / 3;
}

bool Solver::shadow_resolved(ElementId q) const {
  if (!is_luminaire(sender_) || luminaire(sender_).directional()) return false;
  const Element& el = hierarchy_.element(q);
  double longest = 0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (hierarchy_.position(el.corners[k]) - hierarchy_.position(el.corners[(k + 1) % 3])).sqrnorm());
  const double distance = (hierarchy_.centroid(q) - luminaire(sender_).position).norm();
  return std::sqrt(longest) < kShadowResolution * distance;
}

bool Solver::shadow_crosses(ElementId q) const {
  double lo = 2, hi = -1;
  for (int k = 0; k < 3; ++k) {
    const double fraction = corner_form_factor(q, k).visible_fraction();
    lo = std::min(lo, fraction);
    hi = std::max(hi, fraction);
  }
  return hi - lo > 0.25;
}

}  // namespace dynrad::rad
