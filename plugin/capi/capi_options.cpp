// The C ABI's solve options (dynrad_options_*): each setter checks its value and says
// what is allowed.
#include "plugin/capi/capi_internal.h"

#include <cmath>
#include <string>

using namespace dynrad;
using namespace dynrad::capi;

extern "C" {

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

}  // extern "C"
