// Progressive refinement radiosity (Cohen, Chen, Wallace & Greenberg 1988) on the
// initial patches. See progressive.cpp for the loop and its quantities.
#pragma once

#include "mesh/refinement.h"
#include "radiosity/receivers.h"
#include "radiosity/solve_types.h"
#include "radiosity/visibility.h"

#include <memory>

namespace dynrad::rad {

class ProgressiveSolver {
 public:
  // `scene` must not be refined while the solver lives. Throws InputError-free
  // std::invalid_argument when nothing emits (the CLI checks first and says so).
  ProgressiveSolver(const SceneMesh& scene, const ElementHierarchy& hierarchy, SolveOptions options);
  ~ProgressiveSolver();

  // Runs until a stopping rule in the options holds.
  SolveReport run();
  // One shot from the patch with the most unshot power; false when nothing is left.
  bool shoot_once();

  const std::vector<Rgb>& radiosity() const { return node_radiosity_; }  // per receiver node
  const Receivers& receivers() const { return receivers_; }
  const EnergyBalance& energy() const { return report_.energy; }
  double unshot_fraction() const;
  const SolveReport& report() const { return report_; }

 private:
  struct Patch;
  std::uint32_t brightest_patch() const;
  double lost_fraction(std::uint32_t patch);
  double visible_fraction(std::uint32_t node, const Patch& sender, std::uint32_t sender_id) const;

  const SceneMesh& scene_;
  const ElementHierarchy& hierarchy_;
  SolveOptions options_;
  Receivers receivers_;
  std::unique_ptr<Visibility> visibility_;
  std::vector<Patch> patches_;
  std::vector<Rgb> node_radiosity_;
  std::vector<double> node_form_factor_;  // scratch: F(node -> current sender)
  double emitted_total_ = 0;              // sum over channels, for the unshot fraction
  double form_factor_error_sum_ = 0;
  SolveReport report_;
};

}  // namespace dynrad::rad
