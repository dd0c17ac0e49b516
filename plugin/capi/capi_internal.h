// What the C ABI's files share (dynrad_capi.cpp: scenes and the solve; capi_options.cpp:
// options; capi_results.cpp: results): the opaque handles' contents and the guard that
// turns every exception into a status and a thread-local message.
#pragma once

#include "dynrad/dynrad.h"

#include "mesh/io/import.h"
#include "mesh/load.h"
#include "radiosity/pipeline/pipeline.h"
#include "radiosity/solver/settings.h"
#include "radiosity/solver/solver.h"

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

namespace dynrad::capi {

// What users read after a failure. thread_local: each thread sees its own last call.
extern thread_local std::string t_last_error;

// A failure with its status, thrown inside the library only.
struct Failure {
  dynrad_status status;
  std::string message;
};

[[noreturn]] inline void fail(dynrad_status status, std::string message) { throw Failure{status, std::move(message)}; }

inline void require(bool condition, const char* what) {
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

inline dynrad_status set_option(dynrad_options* options, bool valid, const char* message) {
  return guarded([&] {
    require(options, "the options handle is NULL.");
    require(valid, message);
    return DYNRAD_OK;
  });
}

}  // namespace dynrad::capi
