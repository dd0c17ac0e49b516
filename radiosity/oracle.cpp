#include "radiosity/oracle.h"

#include <algorithm>

namespace dynrad::rad {
namespace {

double relative_spread(const std::array<Rgb, 3>& v) {
  const double a = v[0].luminance(), b = v[1].luminance(), c = v[2].luminance();
  const double hi = std::max({a, b, c}), lo = std::min({a, b, c});
  return hi > 0 ? (hi - lo) / hi : 0.0;
}

double mean_luminance(const std::array<Rgb, 3>& v) {
  return (v[0].luminance() + v[1].luminance() + v[2].luminance()) / 3.0;
}

}  // namespace

double cumulated_gradient(const OracleInputs& in) { return relative_spread(in.cumulated); }
double current_gradient(const OracleInputs& in) { return relative_spread(in.current); }
double current_ratio(const OracleInputs& in) {
  const double cumulated = mean_luminance(in.cumulated);
  return cumulated > 0 ? mean_luminance(in.current) / cumulated : 0.0;
}

double contribution_gradient(const OracleInputs& in) {
  double hi_current = 0, lo_current = 0, hi_cumulated = 0;
  for (int k = 0; k < 3; ++k) {
    const double c = in.current[k].luminance();
    hi_current = k == 0 ? c : std::max(hi_current, c);
    lo_current = k == 0 ? c : std::min(lo_current, c);
    hi_cumulated = std::max(hi_cumulated, in.cumulated[k].luminance());
  }
  return hi_cumulated > 0 ? (hi_current - lo_current) / hi_cumulated : 0.0;
}

double curvature_gradient(const OracleInputs& in) {
  const double hi = std::max({in.cumulated[0].luminance(), in.cumulated[1].luminance(), in.cumulated[2].luminance()});
  return hi > 0 ? in.current_curvature / hi : 0.0;
}

bool adaptive_oracle(const OracleInputs& in, double threshold) { return cumulated_gradient(in) > threshold; }

bool dynamic_oracle(const OracleInputs& in, const OracleThresholds& t) {
  if (t.variant == OracleThresholds::Variant::contribution)
    return (cumulated_gradient(in) > t.cumulated_gradient &&       // the element's shading is uneven
            contribution_gradient(in) > t.contribution_gradient) ||  // and this sender's part of it is,
           curvature_gradient(in) > t.contribution_gradient;         // or dB bends where push-down is linear.
  return cumulated_gradient(in) > t.cumulated_gradient &&  // the element's shading is uneven,
         current_gradient(in) > t.current_gradient &&      // this sender is what makes it uneven,
         current_ratio(in) > t.current_ratio;              // and this sender matters to it.
}

}  // namespace dynrad::rad
