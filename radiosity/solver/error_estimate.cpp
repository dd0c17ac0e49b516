// Solver::estimate_error (see solver.h).
#include "radiosity/solver/solver.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

namespace {

constexpr double kDirectGapWeight = 2.0 / 3;    // its weight in the estimate's mesh part

}  // namespace
namespace {
double sum_of(const Rgb& c) { return c.r + c.g + c.b; }
}  // namespace

ErrorEstimate Solver::estimate_error(bool shadows) {
  flush_all();  // every leaf holds what was pushed down above it
  if (shadows) update_direct_gaps();
  const Rgb ambient_now = ambient();
  const Rgb ambient_error = unshot_error_radiosity();
  struct Sums {
    double radiosity_area = 0, unshot_area = 0, surplus_area = 0, shadow_area = 0;
  };
  // A deterministic reduction: the same blocks, joined in the same order, for any
  // number of threads.
  const Sums sums = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<ElementId>(0, static_cast<ElementId>(hierarchy_.element_count()), 4096), Sums{},
      [&](const tbb::blocked_range<ElementId>& range, Sums s) {
        for (ElementId e = range.begin(); e < range.end(); ++e) {
          const Element& el = hierarchy_.element(e);
          if (!el.is_leaf()) continue;
          const Patch& patch = patches_[el.patch];
          if (!(patch.reflectance.luminance() > 0)) continue;  // its value is its emission, exact
          const double ambient_here = (patch.reflectance * ambient_now).luminance();
          const auto& v = value_[e];
          const double mean = (v[0].luminance() + v[1].luminance() + v[2].luminance()) / 3;
          s.radiosity_area +=
              el.area * (mean + patch.direct.luminance() + (options_.ambient_display ? ambient_here : 0.0));
          s.unshot_area += el.area * (patch.reflectance * ambient_error).luminance();
          const double bend = 0.5 * surplus(e);
          s.surplus_area += el.area * bend;
          if (shadows) s.shadow_area += el.area * (mesh_error(e) - bend);
        }
        return s;
      },
      [](Sums a, const Sums& b) {
        a.radiosity_area += b.radiosity_area;
        a.unshot_area += b.unshot_area;
        a.surplus_area += b.surplus_area;
        a.shadow_area += b.shadow_area;
        return a;
      });
  ErrorEstimate out;
  if (sums.radiosity_area > 0) {
    out.unshot = sums.unshot_area / sums.radiosity_area;
    out.discretisation = sums.surplus_area / sums.radiosity_area;
    out.shadows = sums.shadow_area / sums.radiosity_area;
  }
  return out;
}

Rgb Solver::unshot_error_radiosity() const {
  const Rgb ambient_now = ambient();
  const double unshot_weight = options_.ambient_display ? 0.25 : 1.0;
  // With over-relaxation the unshot light has both signs: the ambient term (its sum)
  // can be near 0 while much is yet to move. Its error is then that of its magnitude.
  Rgb ambient_error = ambient_now;
  const double signed_total = std::abs(sum_of(report_.energy.unshot));
  if (options_.overshoot != 1.0 && signed_total > 0) {
    const double scale = unshot_magnitude_ / signed_total;
    ambient_error = Rgb(std::abs(ambient_now.r), std::abs(ambient_now.g), std::abs(ambient_now.b)) * scale;
  }
  return ambient_error * unshot_weight;
}

double Solver::mesh_error(ElementId e) const {
  // (the display gap: direct light evaluated outside the hierarchy, exact_direct.cpp)
  return std::max(0.5 * surplus(e), kDirectGapWeight * direct_gap(e) + display_gap(e));
}

double Solver::surplus(ElementId e) const {
  const Element& el = hierarchy_.element(e);
  if (el.parent == kNoElement) return 0.0;
  const Element& parent = hierarchy_.element(el.parent);
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const VertexHandle c = el.corners[k];
    if (c == parent.corners[0] || c == parent.corners[1] || c == parent.corners[2]) continue;
    const Rgb interpolated = interpolate(el.parent, value_[el.parent], hierarchy_.position(c));
    sum += std::abs(value_[e][k].luminance() - interpolated.luminance());
  }
  return sum;
}

}  // namespace dynrad::rad
