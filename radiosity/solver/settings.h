// Settings chosen from the model: what `dynrad solve MODEL -o OUT.ply` uses when no
// expert option is given. One knob, the quality, picks an error target and the
// discretisation that reaches it; the model gives the scale (its mean free path, see
// mesh/core/mean_free_path.h) and the machine the memory. Every expert option overrides
// what is chosen here, and the report lists what was used.
#pragma once

#include "mesh/core/scene_mesh.h"
#include "radiosity/solver/oracle.h"
#include "radiosity/solver/solve_types.h"

#include <cstddef>
#include <string>

namespace dynrad::rad {

enum class Quality { draft, normal, high };
// "draft", "normal", "high"; throws std::invalid_argument otherwise.
Quality parse_quality(const std::string& name);
const char* quality_name(Quality quality);

// What a quality level asks for: draft 3%, normal 1%, high 0.3% estimated error, each
// with the discretisation that reaches it. The estimate runs at 3-5 times the error it
// estimates on the 1990 room and about the error on the obstructed room, mostly through
// its unshot part (bench/results/error_estimate.md): the targets
// are set for that estimate and must move if it does.
struct QualityPreset {
  // Stop when the estimated mean relative error of the written values (Solver::
  // estimate_error) is below this.
  double error_target = 0.01;
  // Patch size as a fraction of the model's mean free path.
  double patch_per_free_path = 0.75;
  int max_level = 2;
  double pushdown = 0.015, pushdown_floor = 0.015;  // the push-down oracle's (oracle.h)
};
QualityPreset quality_preset(Quality quality);

struct ChosenSettings {
  Quality quality = Quality::normal;
  QualityPreset preset;
  double mean_free_path = 0;  // model units; 0 when no ray met a surface
  double rays_met = 0;        // the fraction of its rays that met another surface
  double diagonal = 0;        // of the bounding box
  double patch_size = 0;
  std::string patch_size_rule;  // how patch_size was found, for the report
  std::size_t memory_budget = 0;  // bytes; 0: unknown (no limit)
};

// The patch size is patch_per_free_path times the mean free path, kept between a
// 500th and a quarter of the bounding-box diagonal (and rounded to three digits as a
// fraction of it) (a tenth of it when no ray met a
// surface: a single sheet). The memory budget for refinement is half of the memory
// available when the solve starts.
ChosenSettings choose_settings(const SceneMesh& scene, Quality quality);

// What a user asked for (the command line, the C ABI): 0 or negative means "choose".
struct SettingsRequest {
  Quality quality = Quality::normal;
  double patch_size = 0;
  double patch_scale = 1;  // a chosen patch size times this (annual daylight: CoefficientOptions::patch_factor)
  int max_level = -1;
  double converge = -1;  // given: stop by unshot power instead of by the error target
  double pushdown = -1, pushdown_floor = -1;
  double memory_budget_mib = -1;
  bool clusters = true;  // false: every patch on its own (SolveOptions::cluster_area 0)
  double overshoot = -1;  // given: SolveOptions::overshoot; otherwise 1 (none)
};

struct AppliedSettings {
  ChosenSettings chosen;
  double patch_size = 0;
  std::string patch_size_rule;
  bool from_model = false;  // patch_size is chosen.patch_size (times the request's scale)
};

struct RefineSettings;  // radiosity/solver/solver.h

// Everything `request` leaves open, chosen for `scene` and refine.method. Dynamic
// subdivision takes the quality's patches, levels, push-down thresholds and error
// target (SolveOptions::error_target, with converge 1e-4 as a floor); progressive
// and adaptive keep their classic rules (a tenth of the diagonal, three levels, 1%
// unshot). Writes refine.max_level, the push-down thresholds, refine.memory_budget,
// solve.error_target, solve.converge, solve.overshoot (1 unless asked: over-relaxation
// reaches the error target in fewer shots only by the signed unshot light, which an
// honest estimate does not count; see estimate_error), the face clusters
// (solve.cluster_area, an eighth of the patch size squared: the smallest a whole patch
// can be, for the area of a facet; solve.cluster_radius, half the patch size) and the
// sender groups (solve.group_radius, three quarters of the patch size); neither for
// adaptive.
AppliedSettings apply_settings(const SceneMesh& scene, const SettingsRequest& request, RefineSettings& refine,
                               SolveOptions& solve);

// MemAvailable from /proc/meminfo, in bytes (0 where unknown).
std::size_t available_memory();

}  // namespace dynrad::rad
