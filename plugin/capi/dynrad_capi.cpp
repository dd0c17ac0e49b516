// The C ABI (include/dynrad/dynrad.h) over the same pipeline as `dynrad solve`:
// polygon soup -> cleanup -> scene mesh -> patches -> element hierarchy -> solver ->
// per-vertex output and display encoding. Every entry point catches everything and
// turns it into a status and a thread-local message: no exception crosses into C.
#include "dynrad/dynrad.h"

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

// The opaque handles.
struct dynrad_scene {
  // A scene file (dynrad_scene_load), or arrays (dynrad_scene_create) as a soup.
  std::string path;
  dynrad::PolygonSoup soup;
  // Read (or built) and checked when the scene was made, with the default cleanup; the
  // first solve with that cleanup takes it (a solve refines its mesh in place), later
  // solves read the file or build from `soup` again.
  mutable std::mutex mutex;
  mutable std::unique_ptr<dynrad::LoadedScene> unused;
};

struct dynrad_options {
  dynrad_options() {
    refine.method = dynrad::rad::Method::dynamic;  // as `dynrad solve`
    solve.ambient_display = true;
  }
  dynrad::rad::SolveOptions solve;
  dynrad::rad::RefineSettings refine;
  // What the caller set of the settings `dynrad solve` chooses from the model
  // (radiosity/solver/settings.h); the rest is chosen at the solve.
  dynrad::rad::SettingsRequest request;
  double exposure = 0;    // 0: automatic
  bool simplify = true;   // merge flat regions before patching, as `dynrad solve`
  bool imprint = true;    // imprint where surfaces meet, as `dynrad solve`
};

struct dynrad_result {
  std::string report_json;  // the solve's report (radiosity/pipeline/report_json.h), with "grids"
  std::vector<std::string> grid_names;
  std::vector<std::vector<double>> grid_points;  // per grid, x y z E per point (E NaN inside solids)
  std::vector<double> positions;
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint32_t> triangle_materials;
  std::vector<float> radiosity;
  std::vector<std::uint8_t> display;
  std::vector<float> illuminance;  // per vertex: lx (photometric), else W/m^2 weighted as luminance
  dynrad_report report{};
  // The solve itself, for dynrad_result_write_report (the solver's luminaires, the lit
  // scene's views and checks). The solved scene refers to the prepared one: it goes first.
  std::unique_ptr<dynrad::rad::PreparedScene> prepared;
  std::unique_ptr<dynrad::rad::SolvedScene> solved;
  std::string input;
};

namespace {

using namespace dynrad;

// What users read after a failure. thread_local: each thread sees its own last call.
thread_local std::string t_last_error;

// A failure with its status, thrown inside the library only.
struct Failure {
  dynrad_status status;
  std::string message;
};

[[noreturn]] void fail(dynrad_status status, std::string message) { throw Failure{status, std::move(message)}; }

void require(bool condition, const char* what) {
  if (!condition) fail(DYNRAD_INVALID_ARGUMENT, what);
}

// Runs `body` with every exception mapped to a status and message.
template <typename Body>
dynrad_status guarded(Body&& body) noexcept {
  t_last_error.clear();
  try {
    return body();
  } catch (const Failure& f) {
    t_last_error = f.message;
    return f.status;
  } catch (const rad::NoLightError& e) {
    t_last_error = e.what();
    return DYNRAD_NO_EMITTER;
  } catch (const InputError& e) {
    t_last_error = e.what();
    return DYNRAD_INVALID_INPUT;
  } catch (const OutputError& e) {
    t_last_error = e.what();
    return DYNRAD_OUTPUT_ERROR;
  } catch (const std::bad_alloc&) {
    t_last_error = "out of memory. Try a larger patch size or a smaller model.";
    return DYNRAD_OUT_OF_MEMORY;
  } catch (const std::exception& e) {
    try {
      t_last_error = std::string("internal error: ") + e.what() + ". Please report this with the input.";
    } catch (...) {
    }
    return DYNRAD_INTERNAL_ERROR;
  } catch (...) {
    t_last_error = "internal error: unknown exception. Please report this with the input.";
    return DYNRAD_INTERNAL_ERROR;
  }
}

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

template <typename T>
dynrad_status copy_out(const dynrad_result* result, const std::vector<T> dynrad_result::*member, std::size_t per_item,
                       std::size_t items, T* out, size_t capacity, const char* function) {
  return guarded([&] {
    require(result && out, "a result or buffer pointer is NULL.");
    const std::vector<T>& data = result->*member;
    if (capacity < items)
      fail(DYNRAD_BUFFER_TOO_SMALL, std::string(function) + ": the buffer holds " + std::to_string(capacity) +
                                        " items but " + std::to_string(items) +
                                        " are needed; size it from dynrad_result_vertex_count or _triangle_count.");
    if (items) std::memcpy(out, data.data(), items * per_item * sizeof(T));
    return DYNRAD_OK;
  });
}

dynrad_status set_option(dynrad_options* options, bool valid, const char* message) {
  return guarded([&] {
    require(options, "the options handle is NULL.");
    require(valid, message);
    return DYNRAD_OK;
  });
}

}  // namespace

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

dynrad_status dynrad_options_create(dynrad_options** out_options) {
  return guarded([&] {
    require(out_options, "dynrad_options_create: out_options is NULL.");
    *out_options = new dynrad_options();
    return DYNRAD_OK;
  });
}

void dynrad_options_destroy(dynrad_options* options) { delete options; }

dynrad_status dynrad_options_set_method(dynrad_options* options, const char* method) {
  return guarded([&] {
    require(options && method, "dynrad_options_set_method: options or method is NULL.");
    try {
      options->refine.method = rad::parse_method(method);
    } catch (const std::invalid_argument& e) {
      fail(DYNRAD_INVALID_ARGUMENT, std::string("dynrad_options_set_method: ") + e.what() + ".");
    }
    return DYNRAD_OK;
  });
}

dynrad_status dynrad_options_set_max_level(dynrad_options* options, int max_level) {
  const dynrad_status s =
      set_option(options, max_level >= 0 && max_level <= 12, "dynrad_options_set_max_level: must be in 0..12.");
  if (s == DYNRAD_OK) options->request.max_level = max_level;
  return s;
}

dynrad_status dynrad_options_set_patch_size(dynrad_options* options, double patch_size) {
  const dynrad_status s = set_option(options, std::isfinite(patch_size) && patch_size >= 0,
                                     "dynrad_options_set_patch_size: must be a finite number >= 0 (0: default).");
  if (s == DYNRAD_OK) options->request.patch_size = patch_size;
  return s;
}

dynrad_status dynrad_options_set_converge(dynrad_options* options, double converge) {
  const dynrad_status s =
      set_option(options, converge >= 0 && converge < 1, "dynrad_options_set_converge: must be in [0, 1).");
  if (s == DYNRAD_OK) options->request.converge = converge;
  return s;
}

dynrad_status dynrad_options_set_iterations(dynrad_options* options, uint64_t iterations) {
  const dynrad_status s = set_option(options, true, "");
  if (s == DYNRAD_OK) options->solve.max_iterations = static_cast<std::size_t>(iterations);
  return s;
}

dynrad_status dynrad_options_set_time_limit(dynrad_options* options, double seconds) {
  const dynrad_status s = set_option(options, std::isfinite(seconds) && seconds >= 0,
                                     "dynrad_options_set_time_limit: must be a finite number >= 0 (0: no limit).");
  if (s == DYNRAD_OK) options->solve.time_limit = seconds;
  return s;
}

dynrad_status dynrad_options_set_threads(dynrad_options* options, int threads) {
  const dynrad_status s =
      set_option(options, threads >= 0 && threads <= 1024, "dynrad_options_set_threads: must be in 0..1024.");
  if (s == DYNRAD_OK) options->solve.threads = threads;
  return s;
}

dynrad_status dynrad_options_set_seed(dynrad_options* options, uint64_t seed) {
  const dynrad_status s = set_option(options, true, "");
  if (s == DYNRAD_OK) options->solve.seed = seed;
  return s;
}

dynrad_status dynrad_options_set_threshold(dynrad_options* options, double threshold) {
  const dynrad_status s = set_option(options, std::isfinite(threshold) && threshold > 0,
                                     "dynrad_options_set_threshold: must be a finite number > 0.");
  if (s == DYNRAD_OK) {
    options->refine.adaptive_threshold = threshold;
    options->refine.dynamic.cumulated_gradient = options->refine.dynamic.current_gradient =
        options->refine.dynamic.current_ratio = threshold;
  }
  return s;
}

dynrad_status dynrad_options_set_oracle(dynrad_options* options, const char* oracle) {
  const bool known = oracle && (std::string(oracle) == "pushdown" || std::string(oracle) == "paper");
  const dynrad_status s =
      set_option(options, known, "dynrad_options_set_oracle: unknown oracle; available: pushdown, paper.");
  if (s == DYNRAD_OK)
    options->refine.dynamic.variant = std::string(oracle) == "paper" ? rad::OracleThresholds::Variant::paper
                                                                     : rad::OracleThresholds::Variant::pushdown;
  return s;
}

dynrad_status dynrad_options_set_oracle_threshold(dynrad_options* options, const char* name, double value) {
  dynrad_status s = set_option(options, name && std::isfinite(value) && value >= 0,
                               "dynrad_options_set_oracle_threshold: name is NULL or value is not a finite number >= 0.");
  if (s != DYNRAD_OK) return s;
  rad::OracleThresholds& t = options->refine.dynamic;
  const std::string n = name;
  if (n == "pushdown_ambient") {
    t.pushdown_ambient = value != 0;
    return DYNRAD_OK;
  }
  double* target = n == "cumulated_gradient" ? (t.variant == rad::OracleThresholds::Variant::paper
                                                    ? &t.cumulated_gradient
                                                    : &t.pushdown_cumulated_gradient)
                   : n == "current_gradient" ? &t.current_gradient
                   : n == "current_ratio"    ? &t.current_ratio
                   : n == "pushdown_error"   ? &t.pushdown
                   : n == "pushdown_floor"   ? &t.pushdown_floor
                                             : nullptr;
  s = set_option(options, target != nullptr,
                 "dynrad_options_set_oracle_threshold: unknown name; available: cumulated_gradient, current_gradient, "
                 "current_ratio, pushdown_error, pushdown_floor, pushdown_ambient.");
  if (s == DYNRAD_OK) {
    *target = value;
    if (n == "pushdown_error") options->request.pushdown = value;
    if (n == "pushdown_floor") options->request.pushdown_floor = value;
  }
  return s;
}

dynrad_status dynrad_options_set_quality(dynrad_options* options, const char* quality) {
  return guarded([&] {
    require(options && quality, "dynrad_options_set_quality: options or quality is NULL.");
    try {
      options->request.quality = rad::parse_quality(quality);
    } catch (const std::invalid_argument& e) {
      fail(DYNRAD_INVALID_ARGUMENT, std::string("dynrad_options_set_quality: ") + e.what());
    }
    return DYNRAD_OK;
  });
}

dynrad_status dynrad_options_set_max_elements(dynrad_options* options, uint64_t max_elements) {
  const dynrad_status s = set_option(options, true, "");
  if (s == DYNRAD_OK) options->refine.max_elements = static_cast<std::size_t>(max_elements);
  return s;
}

dynrad_status dynrad_options_set_ambient(dynrad_options* options, int on) {
  const dynrad_status s = set_option(options, true, "");
  if (s == DYNRAD_OK) options->solve.ambient_display = on != 0;
  return s;
}

dynrad_status dynrad_options_set_overshoot(dynrad_options* options, double overshoot) {
  const dynrad_status s = set_option(options, std::isfinite(overshoot) && overshoot > 0 && overshoot < 2,
                                     "dynrad_options_set_overshoot: must lie strictly between 0 and 2 (1: none).");
  if (s == DYNRAD_OK) options->request.overshoot = overshoot;
  return s;
}

dynrad_status dynrad_options_set_negligible_share(dynrad_options* options, double share) {
  const dynrad_status s = set_option(options, std::isfinite(share) && share >= 0 && share <= 0.1,
                                     "dynrad_options_set_negligible_share: must lie in [0, 0.1] (0: never skip).");
  if (s == DYNRAD_OK) options->solve.negligible_share = share;
  return s;
}

dynrad_status dynrad_options_set_simplify(dynrad_options* options, int on) {
  const dynrad_status s = set_option(options, true, "");
  if (s == DYNRAD_OK) options->simplify = on != 0;
  return s;
}

dynrad_status dynrad_options_set_imprint(dynrad_options* options, int on) {
  const dynrad_status s = set_option(options, true, "");
  if (s == DYNRAD_OK) options->imprint = on != 0;
  return s;
}

dynrad_status dynrad_options_set_shaped_senders(dynrad_options* options, int on) {
  const dynrad_status s = set_option(options, true, "");
  if (s == DYNRAD_OK) options->solve.shaped_senders = on != 0;
  return s;
}

dynrad_status dynrad_options_set_exposure(dynrad_options* options, double exposure) {
  const dynrad_status s = set_option(options, std::isfinite(exposure) && exposure >= 0,
                                     "dynrad_options_set_exposure: must be a finite number >= 0 (0: automatic).");
  if (s == DYNRAD_OK) options->exposure = exposure;
  return s;
}

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

void dynrad_result_destroy(dynrad_result* result) { delete result; }

size_t dynrad_result_vertex_count(const dynrad_result* result) { return result ? result->positions.size() / 3 : 0; }

size_t dynrad_result_triangle_count(const dynrad_result* result) { return result ? result->triangles.size() / 3 : 0; }

dynrad_status dynrad_result_positions(const dynrad_result* result, double* xyz, size_t capacity) {
  return copy_out(result, &dynrad_result::positions, 3, dynrad_result_vertex_count(result), xyz, capacity,
                  "dynrad_result_positions");
}

dynrad_status dynrad_result_triangles(const dynrad_result* result, uint32_t* indices, size_t capacity) {
  return copy_out(result, &dynrad_result::triangles, 3, dynrad_result_triangle_count(result), indices, capacity,
                  "dynrad_result_triangles");
}

dynrad_status dynrad_result_triangle_materials(const dynrad_result* result, uint32_t* materials, size_t capacity) {
  return copy_out(result, &dynrad_result::triangle_materials, 1, dynrad_result_triangle_count(result), materials,
                  capacity, "dynrad_result_triangle_materials");
}

dynrad_status dynrad_result_radiosity(const dynrad_result* result, float* rgb, size_t capacity) {
  return copy_out(result, &dynrad_result::radiosity, 3, dynrad_result_vertex_count(result), rgb, capacity,
                  "dynrad_result_radiosity");
}

dynrad_status dynrad_result_display(const dynrad_result* result, uint8_t* rgb, size_t capacity) {
  return copy_out(result, &dynrad_result::display, 3, dynrad_result_vertex_count(result), rgb, capacity,
                  "dynrad_result_display");
}

dynrad_status dynrad_result_report(const dynrad_result* result, dynrad_report* report) {
  return guarded([&] {
    require(result && report, "dynrad_result_report: result or report is NULL.");
    *report = result->report;
    return DYNRAD_OK;
  });
}

const char* dynrad_result_report_json(const dynrad_result* result) { return result ? result->report_json.c_str() : ""; }

size_t dynrad_result_grid_count(const dynrad_result* result) { return result ? result->grid_names.size() : 0; }

const char* dynrad_result_grid_name(const dynrad_result* result, size_t grid) {
  return result && grid < result->grid_names.size() ? result->grid_names[grid].c_str() : nullptr;
}

size_t dynrad_result_grid_point_count(const dynrad_result* result, size_t grid) {
  return result && grid < result->grid_points.size() ? result->grid_points[grid].size() / 4 : 0;
}

dynrad_status dynrad_result_grid_points(const dynrad_result* result, size_t grid, double* xyze, size_t capacity) {
  return guarded([&] {
    require(result && xyze, "dynrad_result_grid_points: result or xyze is NULL.");
    require(grid < result->grid_points.size(), "dynrad_result_grid_points: no grid of that index.");
    const std::vector<double>& points = result->grid_points[grid];
    if (capacity < points.size() / 4)
      fail(DYNRAD_BUFFER_TOO_SMALL, "dynrad_result_grid_points: the buffer holds " + std::to_string(capacity) +
                                        " points but " + std::to_string(points.size() / 4) +
                                        " are needed; size it from dynrad_result_grid_point_count.");
    if (!points.empty()) std::memcpy(xyze, points.data(), points.size() * sizeof(double));
    return DYNRAD_OK;
  });
}

dynrad_status dynrad_result_illuminance(const dynrad_result* result, float* lux, size_t capacity) {
  return copy_out(result, &dynrad_result::illuminance, 1, dynrad_result_vertex_count(result), lux, capacity,
                  "dynrad_result_illuminance");
}

dynrad_status dynrad_result_write_report(const dynrad_result* result, const char* path) {
  return guarded([&] {
    require(result && path && *path, "dynrad_result_write_report: result is NULL, or path is NULL or empty.");
    capi::ReportInputs inputs;
    inputs.prepared = result->prepared.get();
    inputs.solved = result->solved.get();
    inputs.exposure = result->report.exposure;
    inputs.input = result->input;
    inputs.version = DYNRAD_VERSION;
    capi::write_report(path, inputs);
    return DYNRAD_OK;
  });
}

dynrad_status dynrad_false_colour(double t, uint8_t rgb[3]) {
  return guarded([&] {
    require(rgb, "dynrad_false_colour: rgb is NULL.");
    require(std::isfinite(t), "dynrad_false_colour: t is not a finite number.");
    const std::array<std::uint8_t, 3> c = report::false_colour(std::clamp(t, 0.0, 1.0));
    std::copy(c.begin(), c.end(), rgb);
    return DYNRAD_OK;
  });
}

}  // extern "C"
