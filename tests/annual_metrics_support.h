// Hand-built hours and planes for the annual-metrics tests (annual_metrics_test.cpp:
// LM-83's hours, DA, cDA, UDI, sDA, ASE and blinds; en17037_test.cpp: EN 17037's levels).
#pragma once

#include "radiosity/climate/annual_metrics.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace dynrad::rad::annual_test {

// Every hour counted.
inline AnalysisHours all_hours(std::size_t n) {
  AnalysisHours h;
  h.in.assign(n, 1);
  return h;
}

// One point's hours as a grid of one point.
inline HourlyIlluminance one_point(const std::vector<float>& lux) {
  HourlyIlluminance e(1, lux.size());
  e.lux = lux;
  return e;
}

// The same plane of `values` (one per point) for `hours` hours.
inline HourlyIlluminance repeated_plane(const std::vector<float>& values, std::size_t hours) {
  HourlyIlluminance e(values.size(), hours);
  for (std::size_t h = 0; h < hours; ++h)
    for (std::size_t p = 0; p < values.size(); ++p) e.at(h, p) = values[p];
  return e;
}

// A plane of `count` points at each value, in order.
inline std::vector<float> plane(std::initializer_list<std::pair<std::size_t, float>> runs) {
  std::vector<float> v;
  for (const auto& [count, value] : runs) v.insert(v.end(), count, value);
  return v;
}

// A fixed-seed generator (64-bit LCG) so the randomised cases are the same everywhere.
struct Lcg {
  std::uint64_t state;
  explicit Lcg(std::uint64_t seed) : state(seed) {}
  double uniform() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  }
};

inline bool has_note(const GridMetrics& g, const std::string& part) {
  return std::any_of(g.notes.begin(), g.notes.end(), [&](const std::string& n) { return n.find(part) != n.npos; });
}

// --- occupied hours -------------------------------------------------------------------

inline HourlyIlluminance planes(const std::vector<std::vector<float>>& per_hour) {
  HourlyIlluminance e(per_hour.front().size(), per_hour.size());
  for (std::size_t h = 0; h < per_hour.size(); ++h)
    for (std::size_t p = 0; p < e.points; ++p) e.at(h, p) = per_hour[h][p];
  return e;
}

// 20 points. The bright plane: 10 at 750, 9 at 500, 1 at 99; the ceil(0.5 x 20) = 10th
// largest is 750 and the 19th is 500, so every level is met, high at its edges. The dim
// plane: 10 at 300, 9 at 100, 1 at 0: the minimum level only.
inline const std::vector<float> kBright = plane({{10, 750.0f}, {9, 500.0f}, {1, 99.0f}});
inline const std::vector<float> kDim = plane({{10, 300.0f}, {9, 100.0f}, {1, 0.0f}});

}  // namespace dynrad::rad::annual_test
