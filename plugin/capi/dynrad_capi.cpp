// The C ABI (include/dynrad/dynrad.h) over the same pipeline as `dynrad solve`:
// polygon soup -> cleanup -> scene mesh -> patches -> element hierarchy -> solver ->
// per-vertex output and display encoding. Every entry point catches everything and
// turns it into a status and a thread-local message: no exception crosses into C.
#include "plugin/capi/capi_internal.h"

#include "plugin/capi/capi_report.h"
#include "plugin/report/grid_picture.h"

#include "mesh/core/error.h"
#include "mesh/io/import.h"
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "radiosity/pipeline/pipeline.h"
#include "radiosity/pipeline/report_json.h"
#include "radiosity/solver/settings.h"
#include "radiosity/solver/solver.h"
#include "radiosity/analysis/tonemap.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace dynrad;
using namespace dynrad::capi;

constexpr const char* kInputLabel = "scene arrays";

PolygonSoup soup_from_arrays(const double* positions, size_t vertex_count, const uint32_t* polygon_indices,
                             const uint32_t* polygon_sizes, size_t polygon_count, const uint32_t* polygon_materials,
                             const dynrad_material* materials, size_t material_count) {
  require(vertex_count == 0 || positions, "dynrad_scene_create: positions is NULL.");
  require(polygon_count == 0 || (polygon_indices && polygon_sizes && polygon_materials),
          "dynrad_scene_create: polygon_indices, polygon_sizes or polygon_materials is NULL.");
  require(material_count == 0 || materials, "dynrad_scene_create: materials is NULL.");
  if (polygon_count == 0) fail(DYNRAD_INVALID_INPUT, "dynrad_scene_create: no polygons, so there is nothing to light.");

  PolygonSoup soup;
  soup.files = {kInputLabel};
  soup.group_names = {"scene"};
  for (size_t i = 0; i < material_count; ++i) {
    const dynrad_material& m = materials[i];
    Material material;
    material.name = m.name && *m.name ? m.name : "material " + std::to_string(i);
    material.reflectance = Rgb(m.reflectance[0], m.reflectance[1], m.reflectance[2]);
    material.emission = Rgb(m.emission[0], m.emission[1], m.emission[2]);
    material.origin = "materials[" + std::to_string(i) + "]";
    soup.materials.push_back(std::move(material));
  }
  soup.points.reserve(vertex_count);
  for (size_t v = 0; v < vertex_count; ++v) {
    const Vec3d p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    if (!is_finite(p))
      fail(DYNRAD_INVALID_INPUT, "dynrad_scene_create: vertex " + std::to_string(v) +
                                     " has a coordinate that is not a finite number. Check the positions array.");
    soup.points.push_back(p);
  }
  std::vector<char> used(material_count, 0);
  size_t next = 0;
  for (size_t i = 0; i < polygon_count; ++i) {
    const std::string polygon = "dynrad_scene_create: polygon " + std::to_string(i);
    const uint32_t size = polygon_sizes[i];
    if (size < 3)
      fail(DYNRAD_INVALID_INPUT,
           polygon + " has " + std::to_string(size) + " corners; a polygon needs at least 3. Check polygon_sizes.");
    std::vector<std::uint32_t> loop(polygon_indices + next, polygon_indices + next + size);
    next += size;
    for (uint32_t k = 0; k < size; ++k)
      if (loop[k] >= vertex_count)
        fail(DYNRAD_INVALID_INPUT, polygon + ", corner " + std::to_string(k) + ": vertex index " +
                                       std::to_string(loop[k]) + " is out of range (there are " +
                                       std::to_string(vertex_count) + " vertices).");
    if (polygon_materials[i] >= material_count)
      fail(DYNRAD_INVALID_INPUT, polygon + ": material index " + std::to_string(polygon_materials[i]) +
                                     " is out of range (there are " + std::to_string(material_count) + " materials).");
    used[polygon_materials[i]] = 1;
    soup.polygons.push_back(std::move(loop));
    soup.material.push_back(polygon_materials[i]);
    soup.group.push_back(0);
    soup.origin.push_back(SourceRef{0, 0, static_cast<std::uint32_t>(i)});
  }
  bool emits = false;
  for (size_t i = 0; i < material_count; ++i) {
    if (!used[i]) continue;
    check_material(soup.materials[i], "dynrad_scene_create");
    emits = emits || soup.materials[i].emits();
  }
  if (!emits)
    fail(DYNRAD_NO_EMITTER,
         "dynrad_scene_create: no polygon's material emits light, so everything would be black. Give at least one "
         "material an emission above 0.");
  return soup;
}

std::unique_ptr<LoadedScene> build_loaded(const PolygonSoup& soup, bool merge_flat_regions = true,
                                          bool imprint = true) {
  // Flat regions merged before patching, as `dynrad solve` does by default, so that
  // both give one answer (mesh/repair/simplify.h; the result is a new mesh either way).
  SimplifyOptions simplify;
  simplify.enabled = merge_flat_regions;
  CleanupOptions cleanup;
  cleanup.imprint = imprint;
  auto loaded = std::make_unique<LoadedScene>(load_soup(soup, kInputLabel, cleanup, simplify));
  if (!(loaded->mesh->emitting_area() > 0))
    fail(DYNRAD_NO_EMITTER,
         "dynrad_scene_create: every emitting polygon is degenerate (no area), so nothing emits light.");
  return loaded;
}

// The request to the pipeline (radiosity/pipeline/pipeline.h) that `options` make.
rad::SceneRequest scene_request(const dynrad_scene& scene, const dynrad_options& options) {
  rad::SceneRequest request;
  request.path = scene.path.empty() ? kInputLabel : scene.path;
  request.simplify.enabled = options.simplify;
  request.cleanup.imprint = options.imprint;
  request.refine = options.refine;
  request.settings = options.request;
  request.solve = options.solve;
  return request;
}

dynrad_stop_reason stop_reason(rad::StopReason reason) {
  switch (reason) {
    case rad::StopReason::converged: return DYNRAD_STOP_CONVERGED;
    case rad::StopReason::error_target: return DYNRAD_STOP_ERROR_TARGET;
    case rad::StopReason::error_floor: return DYNRAD_STOP_ERROR_FLOOR;
    case rad::StopReason::iterations: return DYNRAD_STOP_ITERATIONS;
    case rad::StopReason::time_limit: return DYNRAD_STOP_TIME_LIMIT;
    case rad::StopReason::interrupted: return DYNRAD_STOP_CANCELLED;
  }
  return DYNRAD_STOP_CONVERGED;
}

dynrad_result* solve(const dynrad_scene& scene, const dynrad_options& options, dynrad_progress_fn progress, void* user,
                     const volatile int* cancel) {
  // The library speaks through statuses and dynrad_last_error; the pipeline's notes
  // (what it read, the settings it chose) are for the command line.
  static const bool quiet = [] {
    spdlog::set_level(spdlog::level::warn);
    return true;
  }();
  (void)quiet;
  rad::SceneRequest request = scene_request(scene, options);
  std::unique_ptr<LoadedScene> loaded;
  if (options.simplify && options.imprint) {  // the scene was read or built with that cleanup
    std::lock_guard<std::mutex> lock(scene.mutex);
    loaded = std::move(scene.unused);
  }
  if (!loaded && scene.path.empty()) loaded = build_loaded(scene.soup, options.simplify, options.imprint);

  // The pipeline `dynrad solve` runs, so that both give one answer.
  bool callback_stop = false;
  request.solve.should_stop = [&] { return callback_stop || (cancel && *cancel != 0); };
  request.on_shot = [&](const rad::Solver&, std::size_t shot, double unshot) {
    if (progress && progress(shot, unshot, user) != 0) callback_stop = true;
  };
  // On the heap and kept by the result, for its report; the lit scene (views, the
  // designer's checks) only for scene files, whose reports have them.
  auto kept_prepared = std::make_unique<rad::PreparedScene>(rad::prepare_scene(request, loaded.get()));
  rad::PreparedScene& prepared = *kept_prepared;
  const double patch_size = prepared.applied.patch_size;
  const PatchingReport& patching = prepared.patching;
  auto kept_solved = std::make_unique<rad::SolvedScene>(rad::solve_scene(prepared, !scene.path.empty()));
  rad::SolvedScene& solved = *kept_solved;
  const rad::SolveReport& report = solved.report;
  const rad::Solver::Output& output = solved.output;
  const SceneMesh* mesh = prepared.scene.mesh.get();

  auto result = std::make_unique<dynrad_result>();
  const std::size_t vertices = output.split.size();
  result->positions.reserve(3 * vertices);
  for (auto v : output.split.source) {
    const Vec3d& p = mesh->mesh().point(v);
    result->positions.insert(result->positions.end(), {p[0], p[1], p[2]});
  }
  result->triangles.assign(output.split.corner.begin(), output.split.corner.end());
  for (auto f : mesh->mesh().faces()) result->triangle_materials.push_back(mesh->material_id(f));

  std::vector<char> lit(output.emitter.size());
  for (std::size_t x = 0; x < lit.size(); ++x) lit[x] = !output.emitter[x];
  const double exposure = options.exposure > 0 ? options.exposure : rad::auto_exposure(output.radiosity, lit, split_vertex_areas(*mesh, output.split));
  const VertexValues values = rad::tone_map(output.radiosity, exposure, "radiosity");
  result->radiosity.reserve(3 * vertices);
  result->display.reserve(3 * vertices);
  result->illuminance.reserve(vertices);
  for (const Rgb& e : output.irradiance) result->illuminance.push_back(static_cast<float>(e.luminance()));
  for (std::size_t x = 0; x < vertices; ++x) {
    const Rgb& b = output.radiosity[x];
    result->radiosity.insert(result->radiosity.end(),
                             {static_cast<float>(b.r), static_cast<float>(b.g), static_cast<float>(b.b)});
    result->display.insert(result->display.end(), values.display[x].begin(), values.display[x].end());
  }

  dynrad_report& r = result->report;
  r.shots = report.iterations;
  r.energy_transfers = report.energy_transfers;
  r.patch_element_transfers = report.patch_element_transfers;
  r.visibility_rays = report.visibility_rays;
  r.patches = patching.patches;
  r.elements = report.elements;
  r.seconds = report.seconds;
  r.unshot_fraction = report.unshot_fraction;
  r.exposure = exposure;
  r.patch_size = patch_size;
  for (int c = 0; c < 3; ++c) {
    r.emitted[c] = report.energy.emitted[c];
    r.absorbed[c] = report.energy.absorbed[c];
    r.escaped[c] = report.energy.escaped[c];
  }
  r.stopped_by = stop_reason(report.stopped_by);
  r.estimated_error = report.estimated_error.total();

  // The scene file's grids, and the report.
  for (const rad::GridResult& g : solved.grids) {
    result->grid_names.push_back(g.spec.name);
    std::vector<double>& points = result->grid_points.emplace_back();
    for (const rad::GridPointResult& q : g.points)
      points.insert(points.end(), {q.position[0], q.position[1], q.position[2],
                                   q.masked ? std::numeric_limits<double>::quiet_NaN() : q.illuminance});
  }
  nlohmann::json j = rad::solve_report_json(prepared, solved, exposure);
  j["dynrad_version"] = DYNRAD_VERSION;
  j["input"] = request.path;
  j["grids"] = rad::grid_summary_json(solved);
  result->report_json = j.dump(2);
  result->input = request.path;
  result->prepared = std::move(kept_prepared);
  result->solved = std::move(kept_solved);
  return result.release();
}

}  // namespace

namespace dynrad::capi {
thread_local std::string t_last_error;
}  // namespace dynrad::capi

using namespace dynrad;
using namespace dynrad::capi;

extern "C" {

const char* dynrad_version(void) { return DYNRAD_VERSION; }

int dynrad_abi_version(void) { return DYNRAD_ABI_VERSION; }

const char* dynrad_status_name(dynrad_status status) {
  switch (status) {
    case DYNRAD_OK:
      return "DYNRAD_OK";
    case DYNRAD_STOPPED:
      return "DYNRAD_STOPPED";
    case DYNRAD_INVALID_ARGUMENT:
      return "DYNRAD_INVALID_ARGUMENT";
    case DYNRAD_INVALID_INPUT:
      return "DYNRAD_INVALID_INPUT";
    case DYNRAD_NO_EMITTER:
      return "DYNRAD_NO_EMITTER";
    case DYNRAD_BUFFER_TOO_SMALL:
      return "DYNRAD_BUFFER_TOO_SMALL";
    case DYNRAD_OUT_OF_MEMORY:
      return "DYNRAD_OUT_OF_MEMORY";
    case DYNRAD_INTERNAL_ERROR:
      return "DYNRAD_INTERNAL_ERROR";
    case DYNRAD_OUTPUT_ERROR:
      return "DYNRAD_OUTPUT_ERROR";
  }
  return "unknown status";
}

const char* dynrad_last_error(void) { return t_last_error.c_str(); }

dynrad_status dynrad_scene_create(const double* positions, size_t vertex_count, const uint32_t* polygon_indices,
                                  const uint32_t* polygon_sizes, size_t polygon_count,
                                  const uint32_t* polygon_materials, const dynrad_material* materials,
                                  size_t material_count, dynrad_scene** out_scene) {
  return guarded([&] {
    require(out_scene, "dynrad_scene_create: out_scene is NULL.");
    *out_scene = nullptr;
    auto scene = std::make_unique<dynrad_scene>();
    scene->soup = soup_from_arrays(positions, vertex_count, polygon_indices, polygon_sizes, polygon_count,
                                   polygon_materials, materials, material_count);
    scene->unused = build_loaded(scene->soup);
    *out_scene = scene.release();
    return DYNRAD_OK;
  });
}

dynrad_status dynrad_scene_load(const char* path, dynrad_scene** out_scene) {
  return guarded([&] {
    require(out_scene, "dynrad_scene_load: out_scene is NULL.");
    *out_scene = nullptr;
    require(path && *path, "dynrad_scene_load: path is NULL or empty.");
    auto scene = std::make_unique<dynrad_scene>();
    scene->path = path;
    // Read and repaired now, as the first solve will take it, so that a file that
    // cannot be read fails here; its scene-file sections are checked too.
    ReadOptions read;
    read.other_scene_keys = rad::scene_file_sections();
    SimplifyOptions simplify;
    simplify.enabled = dynrad_options{}.simplify;  // the cleanup of the default options, which the first solve takes
    CleanupOptions cleanup;
    cleanup.imprint = dynrad_options{}.imprint;
    scene->unused = std::make_unique<LoadedScene>(load_scene(scene->path, cleanup, simplify, read));
    rad::check_scene_sections(scene->path, *scene->unused);
    *out_scene = scene.release();
    return DYNRAD_OK;
  });
}

void dynrad_scene_destroy(dynrad_scene* scene) { delete scene; }

dynrad_status dynrad_solve(const dynrad_scene* scene, const dynrad_options* options, dynrad_progress_fn progress,
                           void* user, const volatile int* cancel, dynrad_result** out_result) {
  if (out_result) *out_result = nullptr;
  return guarded([&] {
    require(scene && out_result, "dynrad_solve: scene or out_result is NULL.");
    const dynrad_options defaults;
    dynrad_result* result = solve(*scene, options ? *options : defaults, progress, user, cancel);
    *out_result = result;
    return result->report.stopped_by == DYNRAD_STOP_CANCELLED ? DYNRAD_STOPPED : DYNRAD_OK;
  });
}

}  // extern "C"
