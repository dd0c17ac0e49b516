#include "radiosity/solver/oracle.h"

#include <algorithm>

namespace dynrad::rad {
namespace {

// (max - min) / max of the corners' luminance plus `extra` at each (OracleInputs::direct).
double relative_spread(const std::array<Rgb, 3>& v, const std::array<double, 3>& extra = {0, 0, 0}) {
  const double a = v[0].luminance() + extra[0], b = v[1].luminance() + extra[1], c = v[2].luminance() + extra[2];
  const double hi = std::max({a, b, c}), lo = std::min({a, b, c});
  return hi > 0 ? (hi - lo) / hi : 0.0;
}

double mean_luminance(const std::array<Rgb, 3>& v) {
  return (v[0].luminance() + v[1].luminance() + v[2].luminance()) / 3.0;
}

double direct_mean(const OracleInputs& in) { return (in.direct[0] + in.direct[1] + in.direct[2]) / 3.0; }

}  // namespace

double cumulated_gradient(const OracleInputs& in) { return relative_spread(in.cumulated, in.direct); }
double current_gradient(const OracleInputs& in) { return relative_spread(in.current); }
double current_ratio(const OracleInputs& in) {
  const double cumulated = mean_luminance(in.cumulated) + direct_mean(in);
  return cumulated > 0 ? mean_luminance(in.current) / cumulated : 0.0;
}
double pushdown_gradient(const OracleInputs& in, double floor) {
  const double hi = std::max({in.cumulated[0].luminance() + in.direct[0], in.cumulated[1].luminance() + in.direct[1],
                              in.cumulated[2].luminance() + in.direct[2]});
  const double scale = std::max(in.current_peak, floor * (hi + in.ambient));
  return scale > 0 ? in.pushdown_error / scale : 0.0;
}

bool adaptive_oracle(const OracleInputs& in, double threshold) { return cumulated_gradient(in) > threshold; }

bool dynamic_oracle(const OracleInputs& in, const OracleThresholds& t) {
  if (t.variant == OracleThresholds::Variant::pushdown)
    return (in.refined || cumulated_gradient(in) > t.pushdown_cumulated_gradient) &&  // the element's shading is uneven,
           pushdown_gradient(in, t.pushdown_floor) > t.pushdown;               // and interpolating this transfer would be wrong.
  return cumulated_gradient(in) > t.cumulated_gradient &&  // the element's shading is uneven,
         current_gradient(in) > t.current_gradient &&      // this sender is what makes it uneven,
         current_ratio(in) > t.current_ratio;              // and this sender matters to it.
}

}  // namespace dynrad::rad
