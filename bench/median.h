// The median the benchmarks quote: the middle value (the upper one of an even count).
#pragma once

#include <algorithm>
#include <vector>

namespace dynrad::bench {

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace dynrad::bench
