// Stop reasons by name (see solve_types.h).
#include "radiosity/solver/solve_types.h"

#include <array>
#include <utility>

namespace dynrad::rad {

namespace {
constexpr std::array<std::pair<StopReason, const char*>, 6> kStopNames{{
    {StopReason::converged, "converged"},
    {StopReason::error_target, "error target"},
    {StopReason::error_floor, "error floor"},
    {StopReason::iterations, "iterations"},
    {StopReason::time_limit, "time limit"},
    {StopReason::interrupted, "interrupted"},
}};
}  // namespace

const char* to_string(StopReason reason) {
  for (const auto& [r, name] : kStopNames)
    if (r == reason) return name;
  return "?";
}

bool parse_stop_reason(std::string_view name, StopReason* reason) {
  for (const auto& [r, n] : kStopNames)
    if (name == n) {
      *reason = r;
      return true;
    }
  return false;
}

}  // namespace dynrad::rad
