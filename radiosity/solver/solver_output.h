// What a solve writes per output vertex (Solver::output()).
#pragma once

#include "mesh/core/types.h"
#include "mesh/core/vertex_split.h"

#include <vector>

namespace dynrad::rad {

// Per output vertex (see mesh/core/vertex_split.h) of the current mesh: the mean of the
// leaf corner values that meet there, weighted by the leaves' areas. (Unweighted, a
// sliver that a shot culled as a negligible receiver, and so holds less at a corner
// it shares with large lit elements, pulled the vertex down as much as they did: the
// 1990 room's largest error fell from 3.34% to 2.77% with the weights.)
struct SolverOutput {
  VertexSplit split;
  std::vector<Rgb> radiosity;
  std::vector<char> emitter;  // the vertex belongs to an emitting surface
  // Light arriving (irradiance; illuminance in photometric units), (B - emission) /
  // reflectance per channel, averaged like `radiosity`. Where a channel's reflectance
  // is 0 it is 0: see SolveOptions::min_reflectance.
  std::vector<Rgb> irradiance;
  // The estimated relative error of `radiosity` at the vertex (luminance), the terms of
  // Solver::estimate_error() taken locally: the unshot light's share of the vertex's value, and
  // half the largest hierarchical surplus of the leaves that meet there. 0 where the
  // surface reflects nothing (its value is its emission, exact).
  std::vector<float> error;
};

}  // namespace dynrad::rad
