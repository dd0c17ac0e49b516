// The pipeline from a scene to a solved result (see pipeline.h).
#include "radiosity/pipeline/pipeline.h"

#include "mesh/core/error.h"
#include "radiosity/analysis/grid_scene.h"
#include "radiosity/analysis/views.h"
#include "radiosity/design/emergency.h"
#include "radiosity/design/glare.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/transfer/visibility.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <stdexcept>

namespace dynrad::rad {

std::vector<std::string> scene_file_sections() {
  // read_luminaires, read_grids, read_cameras, read_daylight, read_observers,
  // read_emergency_areas, read_light_scenes; "project", the reports' title block.
  return {"luminaires", "grids", "cameras", "sky", "observers", "routes", "open_areas", "project", "scenes"};
}

namespace {

// Below this share of the mean free path's rays meeting a surface, its patch size is
// warned about: an open site keeps more (the Cornell box, open at the front, 70% and
// more), an inside-out room keeps its lamps' rays alone (0.7% in the glTF fuzz seed as
// first written).
constexpr double kFewRaysMet = 0.05;

// Every material grey of its luminance reflectance, emitting `emission_colour` times its
// emission's luminance (nothing when that is black); returns how many had a colour.
std::size_t grey_materials(SceneMesh& mesh, const std::vector<Material>& materials, const Rgb& emission_colour) {
  std::size_t coloured = 0;
  for (std::size_t m = 0; m < materials.size(); ++m) {
    Material grey_material = materials[m];
    coloured += grey_material.reflectance.max_channel() - grey_material.reflectance.min_channel() > 1e-9;
    grey_material.reflectance = grey(grey_material.reflectance);
    grey_material.emission = emission_colour * grey_material.emission.luminance();
    mesh.set_material(m, grey_material);
  }
  return coloured;
}

// Light scenes: each control group's light in a channel of its own (design/
// light_scenes.h); materials grey for the solve (PreparedScene::materials keeps them).
void plan_light_scenes(PreparedScene& p) {
  SceneMesh& mesh = *p.scene.mesh;
  p.light_scenes = read_light_scenes(p.request.path, p.luminaires);
  p.materials = mesh.materials();
  if (p.light_scenes.empty()) return;
  p.channels = plan_channels(p.request.path, p.luminaires, mesh.emitting_area() > 0);
  assign_channels(p.luminaires, p.channels);
  const int own = p.channels.channel("");
  const std::size_t coloured = grey_materials(mesh, p.materials, own >= 0 ? channel_colour(own) : Rgb());
  if (coloured > 0)
    spdlog::warn("light scenes: {} coloured materials are taken as grey of the same luminance reflectance (each "
                 "group's light travels in a colour channel of its own); the lit mesh is grey.",
                 coloured);
  std::string groups;
  for (const std::string& g : p.channels.channels) groups += (groups.empty() ? "" : ", ") + (g.empty() ? "(no group)" : g);
  spdlog::info("light scenes: {} scenes of {} channels ({}), from one solve", p.light_scenes.size(),
               p.channels.channels.size(), groups);
}

// The scene's own light: daylight (its "sky": the sun, then the sky) shoots first, then
// luminaires; faces' emission; light scenes' channels.
void scene_light(PreparedScene& p) {
  SceneMesh& mesh = *p.scene.mesh;
  p.luminaires = read_daylight(p.request.path, p.scene.glazing, p.scene.openings);
  p.daylight = !p.luminaires.empty();
  for (Luminaire& l : read_luminaires(p.request.path)) p.luminaires.push_back(std::move(l));
  if (!p.scene.glazing.empty())
    spdlog::info("{} glazing triangles (materials with a transmittance): windows, not lit{}", p.scene.glazing.size(),
                 p.daylight ? "; the sky and the sun come through them"
                            : "; without a \"sky\" nothing comes through them");
  if (!(mesh.emitting_area() > 0) && p.luminaires.empty())
    throw NoLightError(p.request.path, 0,
                     "no face emits light and there is no luminaire and no sky, so everything would be black. "
                     "Place luminaires (\"luminaires\" in a scene file), bring daylight in (\"sky\" in a scene "
                     "file), or give a material an emission: Ke in the .mtl file, or \"emission\" in a scene file's "
                     "materials.");
  p.photometric = !p.luminaires.empty();
  if (p.request.units == Units::photometric) {
    p.photometric = true;
  } else if (p.request.units == Units::radiometric) {
    if (!p.luminaires.empty())
      throw InputError("--units", 0,
                       "radiometric units cannot be used with luminaires or daylight, which are given in candela, "
                       "lumens and lux. Leave --units out (photometric) or remove them.");
    p.photometric = false;
  }
  if (p.photometric) {
    p.solve.emission_scale = kLumensPerWatt;
    p.solve.min_reflectance = 1e-4;
  }
  for (const Luminaire& l : p.luminaires) spdlog::info("luminaire {}", l.describe());
  plan_light_scenes(p);
  if (!p.luminaires.empty()) {
    const Visibility visibility(mesh);
    for (const std::string& w : luminaire_warnings(visibility, p.luminaires)) spdlog::warn("{}", w);
  }
}

// Annual daylight's: the steering sky alone, carrying channels (CoefficientRequest).
void steering_sky_light(PreparedScene& p) {
  const CoefficientRequest& c = *p.request.coefficients;
  if (p.scene.glazing.empty() && p.scene.openings.empty())
    throw NoLightError(p.request.path, 0,
                       "the model has no windows: no glazing (a material with a transmittance) and no opening, so "
                       "no daylight comes in. Give the windows' glass a transmittance (Tf or d in the .mtl file).");
  SceneMesh& mesh = *p.scene.mesh;
  p.materials = mesh.materials();
  const std::size_t coloured = grey_materials(mesh, p.materials, Rgb());  // daylight alone
  if (coloured > 0)
    spdlog::info("annual daylight: {} coloured materials taken as grey of the same luminance reflectance", coloured);
  p.glazing = std::make_shared<const Glazing>(p.scene.glazing, p.scene.openings);
  p.luminaires = {steering_sky(p.glazing, c.up, c.options.steering_ground)};
  p.daylight = p.photometric = true;
  p.solve.emission_scale = kLumensPerWatt;
  p.solve.min_reflectance = 1e-4;
}

}  // namespace

void check_scene_sections(const std::string& path, const LoadedScene& loaded) {
  std::vector<Luminaire> luminaires = read_daylight(path, loaded.glazing, loaded.openings);
  for (Luminaire& l : read_luminaires(path)) luminaires.push_back(std::move(l));
  read_grids(path);
  read_cameras(path);
  read_observers(path);
  read_emergency_areas(path);
  read_light_scenes(path, luminaires);
}

PreparedScene prepare_scene(const SceneRequest& request, LoadedScene* loaded) {
  PreparedScene p;
  p.request = request;
  p.solve = request.solve;
  p.refine = request.refine;
  if (request.coefficients) p.refine.method = Method::progressive;  // as measured (CoefficientRequest)
  p.grids = read_grids(request.path);

  // 1. Read and repair.
  ReadOptions read = request.read;
  read.other_scene_keys = scene_file_sections();  // whatever the host set: the sections this reads
  p.scene = loaded ? std::move(*loaded) : load_scene(request.path, request.cleanup, request.simplify, read);
  if (!loaded)
    for (const auto& w : p.scene.warnings) spdlog::warn("{}", w);
  if (request.cleanup.imprint && p.scene.cleanup.imprinted_edges > 0)
    spdlog::info("imprinted {} lines where surfaces meet; removed {:.4g} (model units squared) that no light reaches",
                 p.scene.cleanup.imprinted_edges, p.scene.cleanup.hidden_area);
  if (request.simplify.enabled)
    spdlog::info("simplified flat regions: {} -> {} triangles in {:.2f} s", p.scene.simplify.faces_before,
                 p.scene.simplify.faces_after, p.scene.simplify.seconds);
  SceneMesh& mesh = *p.scene.mesh;
  p.phases.done("read and repair");

  // 2. Light sources.
  if (request.coefficients)
    steering_sky_light(p);
  else
    scene_light(p);

  // 3. Settings from the model and the quality (radiosity/solver/settings.h); every
  // setting the request gives overrides.
  SettingsRequest settings = request.settings;
  if (request.coefficients) settings.patch_scale = request.coefficients->options.patch_factor;
  p.phases.done("light sources");
  p.applied = apply_settings(mesh, settings, p.refine, p.solve);
  p.phases.done("settings");
  const double patch_size = p.applied.patch_size;
  // A closed room whose faces point outward: of the rays leaving the fronts, almost all
  // escape, and the few that meet something (a lamp facing the ceiling it hangs under)
  // make the patches tiny: a 2 m room so exported got 790,000 patches.
  const ChosenSettings& chosen = p.applied.chosen;
  if (p.applied.from_model && chosen.mean_free_path > 0 && chosen.rays_met < kFewRaysMet)
    spdlog::warn("only {:.1f}% of the rays leaving the surfaces' fronts met another surface, so the patch size ({:.4g}) "
                 "rests on a few of them. If the model is a closed building, its faces may point outward: check the "
                 "normals (Blender: Face Orientation), or give --patch-size.",
                 100 * chosen.rays_met, patch_size);

  // 4. Patches, the outlines of hard shadows, the element hierarchy.
  p.patching = make_patches(mesh, patch_size);
  // With exact direct light, the outlines are drawn after the shots (the solver's
  // SolveOptions::outline_patch_size), not made into patches here.
  const bool outlines_after = p.refine.exact_direct && p.refine.method == Method::dynamic;
  if (request.shadow_outlines && !request.coefficients && !p.luminaires.empty() && outlines_after)
    p.solve.outline_patch_size = patch_size;
  if (request.shadow_outlines && !request.coefficients && !p.luminaires.empty() && !outlines_after) {
    p.outlines = insert_shadow_outlines(mesh, p.luminaires, shadow_outline_options(patch_size));
    if (p.outlines.outlines > 0)
      spdlog::info("shadow outlines: {} straight pieces from {} silhouette edges made into {} lines ({} vertices) in "
                   "{:.2f} s",
                   p.outlines.outlines, p.outlines.silhouette_edges, p.outlines.lines, p.outlines.vertices_added,
                   p.outlines.seconds);
  }
  p.hierarchy = std::make_unique<ElementHierarchy>(mesh, refinement_for_patch_size(patch_size));
  p.phases.done("patches");
  spdlog::info("{}: {} triangles, {} patches (patch size {:.4g}: {}), {}", request.path, p.patching.faces_before,
               p.hierarchy->patch_count(), patch_size, p.applied.patch_size_rule,
               p.solve.error_target > 0
                   ? fmt::format("quality {}: stop at {:.2g}% estimated error", quality_name(request.settings.quality),
                                 100 * p.solve.error_target)
                   : fmt::format("stop at {:.2g}% unshot", 100 * p.solve.converge));
  return p;
}

SolvedScene solve_scene(PreparedScene& p, bool lit) {
  SolvedScene s;
  SolveOptions options = p.solve;
  // The solver keeps its options: the callback holds what it needs itself.
  auto running = std::make_shared<const Solver*>(nullptr);
  if (p.request.on_shot)
    options.on_shot = [running, on_shot = p.request.on_shot](std::size_t shot, double unshot) {
      on_shot(**running, shot, unshot);
    };
  s.solver = std::make_unique<Solver>(*p.scene.mesh, *p.hierarchy, options, p.refine, p.luminaires);
  *running = s.solver.get();
  if (const auto& c = p.request.coefficients) {
    if (c->indirect == nullptr || c->suns == nullptr)
      throw std::invalid_argument("CoefficientRequest: indirect and suns must be given before the solve");
    s.channel_visibility = std::make_unique<Visibility>(*p.scene.mesh);
    s.solver->carry_coefficients(
        coefficient_channels(*s.channel_visibility, p.luminaires.front(), *c->indirect, *c->suns, c->options));
  }
  p.phases.done("solver set-up");
  s.report = s.solver->run();
  // (in the order they ran; the last one ends now and takes the remaining seconds)
  const SolveReport::Part& lum = s.report.luminaire_shots;
  if (lum.seconds > 0) p.phases.add("shots of luminaires and the sun", lum.seconds, lum.resident, lum.peak);
  p.phases.add("shots", s.report.later_shots.seconds, s.report.later_shots.resident, s.report.later_shots.peak);
  p.phases.done("refinement for direct light and the estimate");
  if (p.solve.outline_patch_size > 0) {
    p.outlines = s.solver->outline_report();
    if (p.outlines.outlines > 0)
      spdlog::info("shadow outlines: {} straight pieces from {} silhouette edges made into {} lines ({} vertices) in "
                   "{:.2f} s",
                   p.outlines.outlines, p.outlines.silhouette_edges, p.outlines.lines, p.outlines.vertices_added,
                   p.outlines.seconds);
  }
  s.output = s.solver->output();
  // (annual daylight reads the solver's channels and refines nothing more; a lit scene
  // and the written mesh need only the output from here)
  if (!p.request.coefficients) s.solver->release_elements();
  p.phases.done("values per vertex");
  if (lit || !p.grids.empty() || !p.light_scenes.empty()) {
    s.lit = std::make_unique<LitScene>(lit_scene(*p.scene.mesh, s.output.split, s.output.radiosity, p.luminaires,
                                                 p.solve.emission_scale, p.photometric));
    p.phases.done("lit scene");
  }
  // Grids: illuminance in mid-air, gathered from the solution (radiosity/analysis/
  // grid.h). With light scenes, from the channelled solve.
  // Annual daylight's grids are its own: each point's coefficients (climate/).
  if (s.lit && !p.request.coefficients) {
    s.grids = gather_grids(*s.lit, p.grids);
    if (!p.grids.empty()) p.phases.done("grids");
  }
  return s;
}

}  // namespace dynrad::rad
