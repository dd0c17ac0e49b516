// Refinement oracles: the paper's Figure 3 (Adaptive Subdivision, Cohen et al. 1986)
// and Figure 6 (Dynamic Subdivision, Dubuis & Bieri).
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
//                        element's brightness.
//
// A value of 0.3 for a gradient means the corners differ by 30% of the brightest.
#pragma once

#include "mesh/types.h"

#include <array>

namespace dynrad::rad {

struct OracleThresholds {
  double cumulated_gradient = 0.25;
  double current_gradient = 0.25;
  double current_ratio = 0.25;
  // "paper": Figure 6 as published. "contribution": the current transfer's spread
  // measured against the cumulated brightness, (max dB - min dB) / max B, above
  // `contribution_gradient`, with the cumulated gradient condition; no share condition.
  // Many weak senders (a whole emitting wall) each shape an element's shading without
  // any one of them being a large share of it, which the paper's third condition misses.
  // The same variant also refines, whatever the corners say, where dB bends between
  // them by more than `contribution_gradient` of max B (see current_curvature below):
  // a lamp above the middle of a floor element lights its corners evenly.
  enum class Variant { paper, contribution } variant = Variant::paper;
  double contribution_gradient = 0.05;
};

struct OracleInputs {
  std::array<Rgb, 3> cumulated;  // B at the corners, current transfer included
  std::array<Rgb, 3> current;    // dB at the corners from the current sender alone
  // Luminance of the largest gap, over q's three edge midpoints, between dB estimated
  // at the midpoint (Lambert's closed form there, times the mean visible fraction of
  // the edge's ends: no rays) and the mean of dB at the edge's ends. It is the error
  // push-down would make at the children's new corners. Filled only for the
  // contribution variant; 0 otherwise.
  double current_curvature = 0;
};

double cumulated_gradient(const OracleInputs& in);
double current_gradient(const OracleInputs& in);
double current_ratio(const OracleInputs& in);
// (max dB - min dB) / max B: how much this transfer alone reshapes the element's shading.
double contribution_gradient(const OracleInputs& in);
// current_curvature / max B.
double curvature_gradient(const OracleInputs& in);

// Figure 3: refine where the cumulated gradient passes the threshold.
bool adaptive_oracle(const OracleInputs& in, double threshold);

// Figure 6: refine only where all three conditions hold.
bool dynamic_oracle(const OracleInputs& in, const OracleThresholds& thresholds);

}  // namespace dynrad::rad
