#include "radiosity/solver/settings.h"

#include "mesh/core/mean_free_path.h"
#include "mesh/core/refinement.h"
#include "radiosity/solver/solver.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace dynrad::rad {

Quality parse_quality(const std::string& name) {
  if (name == "draft") return Quality::draft;
  if (name == "normal") return Quality::normal;
  if (name == "high") return Quality::high;
  throw std::invalid_argument("'" + name + "' is not a quality; available: draft, normal, high.");
}

const char* quality_name(Quality quality) {
  switch (quality) {
    case Quality::draft: return "draft";
    case Quality::normal: return "normal";
    case Quality::high: return "high";
  }
  return "normal";
}

QualityPreset quality_preset(Quality quality) {
  //                                   target  patch  level  push-down  floor
  static const QualityPreset draft{0.03, 1.0, 2, 0.04, 0.02};
  static const QualityPreset normal{};  // the struct's defaults
  static const QualityPreset high{0.003, 0.5, 3, 0.01, 0.01};
  return quality == Quality::draft ? draft : quality == Quality::high ? high : normal;
}

std::size_t available_memory() {
  std::FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f) return 0;
  char line[256];
  std::size_t kib = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "MemAvailable: %zu kB", &kib) == 1) break;
  std::fclose(f);
  return kib * 1024;
}

ChosenSettings choose_settings(const SceneMesh& scene, Quality quality) {
  ChosenSettings s;
  s.quality = quality;
  s.preset = quality_preset(quality);
  s.diagonal = scene.bounds().diagonal();
  const MeanFreePath path = mean_free_path(scene);
  s.mean_free_path = path.length;
  s.rays_met = path.met;
  if (s.mean_free_path > 0) {
    // As a fraction of the diagonal rounded to three digits: the rays are traced in
    // single precision, and the same model scaled or moved must get the same patches.
    const double wanted = s.preset.patch_per_free_path * s.mean_free_path / s.diagonal;
    const double fraction = std::clamp(wanted, 1.0 / 500, 1.0 / 4);
    const double digits = std::pow(10.0, 2 - std::floor(std::log10(fraction)));
    s.patch_size = std::round(fraction * digits) / digits * s.diagonal;
    s.patch_size_rule = fraction == wanted ? "mean free path" : "mean free path, clamped to the diagonal";
  } else {
    s.patch_size = s.diagonal / 10;
    s.patch_size_rule = "diagonal (no ray met a surface)";
  }
  s.memory_budget = available_memory() / 2;
  return s;
}

AppliedSettings apply_settings(const SceneMesh& scene, const SettingsRequest& request, RefineSettings& refine,
                               SolveOptions& solve) {
  AppliedSettings out;
  const bool dynamic = refine.method == Method::dynamic;
  out.chosen = choose_settings(scene, request.quality);
  const ChosenSettings& c = out.chosen;
  if (request.patch_size > 0) {
    out.patch_size = request.patch_size;
    out.patch_size_rule = "given";
  } else if (dynamic) {
    out.patch_size = c.patch_size * request.patch_scale;
    out.patch_size_rule = c.patch_size_rule;
    out.from_model = true;
  } else {
    out.patch_size = default_patch_size(scene) * request.patch_scale;
    out.patch_size_rule = "a tenth of the diagonal";
  }
  if (request.patch_size <= 0 && request.patch_scale != 1)
    out.patch_size_rule += fmt::format(", times {:.3g}", request.patch_scale);
  refine.max_level = request.max_level >= 0 ? request.max_level : dynamic ? c.preset.max_level : 3;
  // A level given is the level every patch's shot refines to, as in the paper's
  // comparisons of adaptive and dynamic subdivision at one level (luminaires, which the
  // paper has not, still add theirs).
  refine.sharp_primary_patches = request.max_level < 0;
  if (dynamic && refine.dynamic.variant == OracleThresholds::Variant::pushdown) {
    refine.dynamic.pushdown = c.preset.pushdown;
    refine.dynamic.pushdown_floor = c.preset.pushdown_floor;
  }
  if (request.pushdown >= 0) refine.dynamic.pushdown = request.pushdown;
  if (request.pushdown_floor >= 0) refine.dynamic.pushdown_floor = request.pushdown_floor;
  refine.memory_budget = request.memory_budget_mib >= 0
                             ? static_cast<std::size_t>(request.memory_budget_mib * 1024 * 1024)
                             : c.memory_budget;
  refine.patch_area = out.patch_size * out.patch_size / 8;
  if (request.clusters && refine.method != Method::adaptive) {
    solve.cluster_area = out.patch_size * out.patch_size / 8;
    solve.cluster_radius = 0.5 * out.patch_size;
    solve.group_radius = 0.75 * out.patch_size;
  } else {
    solve.cluster_area = solve.cluster_radius = solve.group_radius = 0;
  }
  solve.overshoot = request.overshoot > 0 ? request.overshoot : 1.0;
  solve.error_target = 0;
  if (request.converge >= 0) {
    solve.converge = request.converge;
  } else if (dynamic) {
    solve.error_target = c.preset.error_target;
    solve.converge = 1e-4;  // a floor: the error target stops the solve first
  } else {
    solve.converge = 0.01;
  }
  return out;
}

}  // namespace dynrad::rad
