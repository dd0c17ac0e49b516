// Refinement oracles: the paper's Figure 3 (Adaptive Subdivision, Cohen et al. 1986)
// and Figure 6 (Dynamic Subdivision, Dubuis & Bieri), and our push-down oracle.
//
// All quantities are scale-free (independent of units and of how bright the scene is)
// and measured on luminance at an element's three corners:
//
//   cumulated gradient   (max - min) / max of the cumulated radiosity B, which
//                        includes the current transfer (without it the first shot
//                        from a light could never refine anything: before it,
//                        every surface is black);
//   current gradient     (max - min) / max of the radiosity dB that the current
//                        sender alone brings to the corners;
//   current/cumulated    mean dB / mean B: how much this transfer matters to the
//                        element's brightness;
//   push-down error      the largest error, relative to this transfer's own peak,
//                        that stopping here would leave at q's edge midpoints (the
//                        corners its children add), where push-down interpolates dB
//                        linearly: see OracleInputs::pushdown_error.
//
// A value of 0.3 for a gradient means the corners differ by 30% of the brightest.
#pragma once

#include "mesh/core/types.h"

#include <array>

namespace dynrad::rad {

struct OracleThresholds {
  // "paper": Figure 6 as published, all three conditions. "pushdown": the cumulated
  // gradient condition, then refine where the push-down error passes `pushdown`.
  //
  // Why a second oracle: the paper's share condition (current/cumulated) stops a
  // sender that is a small part of an element's light, whatever the error it leaves.
  // When many senders are each a small share (a whole emitting wall), those errors
  // have the same sign (dB is convex near a sender, and linear interpolation of a
  // convex function overshoots) and add up: on the paper's 128-emitter room the
  // paper's oracle ends 3.3x further from the reference than adaptive subdivision.
  // Bounding each transfer's error by a fraction of that transfer bounds the sum by
  // the same fraction of B, however many senders there are (bench/results/bench_paper_tables.md).
  enum class Variant { paper, pushdown } variant = Variant::pushdown;
  // Paper: Figure 6's three thresholds (the paper uses one value for all).
  double cumulated_gradient = 0.25;
  double current_gradient = 0.25;
  double current_ratio = 0.25;
  // Push-down: its own cumulated gradient threshold, the largest push-down error
  // allowed (a fraction of the transfer), and the floor: errors are measured against
  // max(the transfer's peak, pushdown_floor * max B), so a transfer that is a
  // negligible share of the element's light does not refine for its own sake.
  // Defaults from the sweep in bench/results/bench_paper_tables.md.
  double pushdown_cumulated_gradient = 0.05;
  double pushdown = 0.04;
  double pushdown_floor = 0.02;
  // Measure the floor against the element's expected final brightness, B plus its
  // share of the light not yet shot (Cohen et al. 1988's ambient term), instead of
  // B so far: early in a solve B is small and every sender looks important.
  bool pushdown_ambient = true;
};

struct OracleInputs {
  std::array<Rgb, 3> cumulated;  // B at the corners, current transfer included
  std::array<Rgb, 3> current;    // dB at the corners from the current sender alone
  // Push-down oracle only (0 otherwise). At each of q's edge midpoints, the gap between
  // dB estimated there (Lambert's closed form at the midpoint times the mean visible
  // fraction of the edge's ends: no rays) and the mean of dB at the edge's ends, plus
  // half the ends' difference when their visibility differs (a shadow edge may cross
  // anywhere between them); the largest over the three edges, as luminance.
  double pushdown_error = 0;
  // Largest dB (luminance) at the corners and the midpoint estimates.
  double current_peak = 0;
  // The element's reflectance times the ambient radiosity (luminance), when the floor
  // uses it; 0 otherwise.
  double ambient = 0;
  // Light at the corners that B leaves out, as luminance: the direct light evaluated
  // outside the hierarchy (RefineSettings::exact_direct). It counts in the element's
  // shading and brightness: the cumulated gradient, current/cumulated and the push-down
  // floor see B plus it.
  std::array<double, 3> direct{0, 0, 0};
  // The element has children already: the push-down oracle then asks only whether
  // pushing this transfer down to them would be wrong (going on costs transfers, no
  // new elements), not whether the element's shading is uneven.
  bool refined = false;
};

double cumulated_gradient(const OracleInputs& in);
double current_gradient(const OracleInputs& in);
double current_ratio(const OracleInputs& in);
// pushdown_error / max(current_peak, floor * max B) (0 when this sender does not reach q).
double pushdown_gradient(const OracleInputs& in, double floor = 0);

// Figure 3: refine where the cumulated gradient passes the threshold.
bool adaptive_oracle(const OracleInputs& in, double threshold);

// Figure 6 (paper variant): refine only where all three conditions hold. Push-down
// variant: where the cumulated gradient and the push-down error pass their thresholds.
bool dynamic_oracle(const OracleInputs& in, const OracleThresholds& thresholds);

}  // namespace dynrad::rad
