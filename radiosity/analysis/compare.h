// Comparing two solutions of the same scene that may be refined differently: B is
// interpolated, inside its face, under each output vertex of A (found with a short ray
// from just above A's surface, so each vertex reads the surface it belongs to).
#pragma once

#include "radiosity/solver/solver.h"

namespace dynrad::rad {

struct Comparison {
  std::size_t compared = 0, missed = 0;
  double rms_difference = 0;  // luminance
  double rms_a = 0;
  double relative() const { return rms_a > 0 ? rms_difference / rms_a : 0; }
};

// `b_visibility` must be built on `b_scene`.
Comparison compare(const SceneMesh& a_scene, const Solver::Output& a, const SceneMesh& b_scene,
                   const Solver::Output& b, const Visibility& b_visibility);

}  // namespace dynrad::rad
