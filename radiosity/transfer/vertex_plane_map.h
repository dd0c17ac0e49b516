// A map from (vertex, facing) to a value, for the solver's numbering of receivers
// (Solver::register_receivers). Nearly every vertex has one facing, so the first one
// lives in a flat array indexed by vertex; other facings (vertices on creases and
// junctions) go to a hash map.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace dynrad::rad {

template <class T>
class VertexPlaneMap {
 public:
  // The value for (vertex, plane), default-constructed if new; true when new. The
  // pointer stays valid until the next emplace (the flat array may grow).
  std::pair<T*, bool> emplace(std::uint32_t vertex, std::uint32_t plane) {
    if (vertex >= first_.size()) first_.resize(std::max<std::size_t>(vertex + 1, first_.size() * 3 / 2));
    Slot& slot = first_[vertex];
    if (slot.plane == plane) return {&slot.value, false};
    if (slot.plane == kNone) {
      slot.plane = plane;
      slot.value = T{};
      return {&slot.value, true};
    }
    const auto [it, inserted] = rest_.try_emplace(key(vertex, plane));
    return {&it->second, inserted};
  }

 private:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  struct Slot {
    std::uint32_t plane = kNone;
    T value{};
  };
  static std::uint64_t key(std::uint32_t vertex, std::uint32_t plane) {
    return (static_cast<std::uint64_t>(vertex) << 32) | plane;
  }
  std::vector<Slot> first_;
  std::unordered_map<std::uint64_t, T> rest_;
};

}  // namespace dynrad::rad
