// One pipeline from a scene to a solved result, for every host: the command line
// (plugin/cli/cmd_solve.cpp), the C ABI (plugin/capi), tests and benchmarks. A feature
// added here reaches all of them.
//
//   1. prepare_scene(): read the model or scene file and repair it (mesh/load.h); its
//      light sources (daylight first, then luminaires; light scenes' channels); the
//      settings chosen from the model and the request (radiosity/solver/settings.h);
//      patches, shadow outlines, the element hierarchy.
//   2. solve_scene(): the solve (radiosity/solver/solver.h), its output per vertex,
//      and, when asked for, the lit scene and the scene file's grids gathered from it.
//
// Annual daylight (`dynrad annual`) asks for the same with SceneRequest::coefficients:
// one solve under the steering sky whose light carries a channel per sky patch, the
// ground and each sun position (radiosity/climate/coefficient_solve.h).
//
// What each host does around it (its options, checking its outputs can be written,
// writing files or returning arrays) stays with the host.
#pragma once

#include "mesh/repair/cleanup.h"
#include "mesh/core/error.h"
#include "mesh/io/import.h"
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "mesh/repair/simplify.h"
#include "radiosity/analysis/grid.h"
#include "radiosity/analysis/lit_scene.h"
#include "radiosity/climate/coefficient_solve.h"
#include "radiosity/design/light_scenes.h"
#include "radiosity/pipeline/phase_log.h"
#include "radiosity/pipeline/scene_sections.h"
#include "radiosity/solver/settings.h"
#include "radiosity/solver/solver.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/sources/shadow_outlines.h"
#include "radiosity/transfer/visibility.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dynrad::rad {

enum class Units { automatic, photometric, radiometric };

// Annual daylight's one solve (radiosity/climate/coefficient_solve.h). Instead of the
// scene's light (its emission, luminaires and sky), the steering sky through the
// model's windows and openings shoots, and its light carries one channel per patch of
// `indirect`, the ground and each of `suns`; materials are grey of the same luminance
// reflectance; no shadow outlines, no light scenes. The solve is progressive refinement
// (whatever request.refine.method says) on patches options.patch_factor times its size,
// a tenth of the model's diagonal, to 1% unshot unless the settings say otherwise: the
// configuration whose coefficients tests/daylight_coefficients_test.cpp measures
// against direct solves. A model without windows is refused.
struct CoefficientRequest {
  Vec3d up{0.0, 0.0, 1.0};
  CoefficientOptions options;
  const SkyPatches* indirect = nullptr;      // must outlive the solve
  const std::vector<Vec3d>* suns = nullptr;  // the sun positions; must outlive the solve
};

// RefineSettings with the dynamic method, `dynrad solve`'s default.
inline RefineSettings dynamic_refine() {
  RefineSettings r;
  r.method = Method::dynamic;
  return r;
}

// What a host asks for. Defaults are `dynrad solve`'s with no options.
struct SceneRequest {
  std::string path;  // a model file, or a JSON scene file
  CleanupOptions cleanup;
  SimplifyOptions simplify;  // flat regions merged before patching: `dynrad solve` and the C ABI enable it
  ReadOptions read;          // its other_scene_keys are set to scene_file_sections()
  // The method, the oracle and its thresholds, the element limits; the settings below
  // set the quality's levels and push-down thresholds on it (settings.h).
  RefineSettings refine = dynamic_refine();
  SettingsRequest settings;  // the quality, and what the host sets of what is chosen from the model
  // Hard shadows' outlines as mesh edges (shadow_outlines.h): with exact direct light
  // (RefineSettings::exact_direct, the default) drawn after the shots, before them
  // otherwise. Off by default: the display's refinement draws a shadow's edge to 2% of
  // its distance from the light, and on one storey of the generated office the outlines
  // doubled the written mesh for pictures we could not tell apart
  // (bench/results/whole_buildings.md).
  bool shadow_outlines = false;
  Units units = Units::automatic;
  // Stop rules, threads, seed, display options; on_shot and should_stop are the host's
  // (on_shot is wired to `on_shot` below when that is set).
  SolveOptions solve;
  // Called after each shot with the running solver (for progress that shows its report).
  std::function<void(const Solver&, std::size_t shot, double unshot)> on_shot;
  std::optional<CoefficientRequest> coefficients;  // annual daylight's solve (above)
};

// Everything up to the solve.
struct PreparedScene {
  SceneRequest request;
  LoadedScene scene;  // scene.mesh is refined in place by the solve
  std::vector<Luminaire> luminaires;  // daylight (the sun, then the sky), then luminaires
  bool daylight = false;
  bool photometric = false;
  std::vector<LightScene> light_scenes;  // with `channels`: materials grey for the solve
  ChannelPlan channels;
  std::vector<Material> materials;  // as read (restored after a light-scene solve)
  std::vector<GridSpec> grids;
  RefineSettings refine;
  SolveOptions solve;
  AppliedSettings applied;
  PatchingReport patching;
  ShadowOutlineReport outlines;
  std::unique_ptr<ElementHierarchy> hierarchy;
  // Each phase's time and memory: prepare_scene() and solve_scene() log theirs, a host
  // adds what it does after (views, decimation, writing).
  PhaseLog phases;
  std::shared_ptr<const Glazing> glazing;  // with coefficients: the windows the steering sky comes through
};

// Nothing would be lit: no emitting face, no luminaire, no sky.
class NoLightError : public InputError {
 public:
  using InputError::InputError;
};

// Throws InputError (naming the file, and the line or entry) for what cannot be read or
// lit: NoLightError for no light at all (with coefficients: for no window), radiometric units with luminaires, bad
// settings. `loaded`, when given, is the model already read and repaired (a host that
// builds it from arrays, or read it to check it): it is taken instead of reading
// request.path, whose scene-file sections are still read when it is a scene file.
PreparedScene prepare_scene(const SceneRequest& request, LoadedScene* loaded = nullptr);

// Reads every section of a scene file that the pipeline and the designer's checks read
// (sky, luminaires, grids, cameras, observers, routes, open areas, light scenes), so
// that an error in any of them is reported before any work. `loaded` is the model
// (its glazing and openings, which the sky needs).
void check_scene_sections(const std::string& path, const LoadedScene& loaded);

struct SolvedScene {
  std::unique_ptr<Visibility> channel_visibility;  // with coefficients: what the channels see by
  std::unique_ptr<Solver> solver;
  SolveReport report;
  Solver::Output output;
  std::unique_ptr<LitScene> lit;  // when asked for (or needed by grids and light scenes)
  std::vector<GridResult> grids;  // the scene file's grids, gathered from `lit`
};

// `lit`: also build the lit scene (views, renders, the designer's checks need it); it
// is built anyway when the scene has grids or light scenes.
SolvedScene solve_scene(PreparedScene& prepared, bool lit = false);

}  // namespace dynrad::rad
