// A map from (vertex, facing) to a value, for the solver's per-shot form factors and
// per-solve evaluation points. Nearly every vertex has one facing, so the first one
// lives in a flat array indexed by vertex; other facings (vertices on creases and
// junctions) go to a hash map. clear() costs what was inserted, not the vertex count.
#pragma once

#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace dynrad::rad {

template <class T>
class VertexPlaneMap {
 public:
  const T* find(std::uint32_t vertex, std::uint32_t plane) const {
    if (vertex < first_.size() && first_[vertex].plane == plane) return &first_[vertex].value;
    if (rest_.empty()) return nullptr;
    const auto it = rest_.find(key(vertex, plane));
    return it == rest_.end() ? nullptr : &it->second;
  }
  T* find(std::uint32_t vertex, std::uint32_t plane) {
    return const_cast<T*>(static_cast<const VertexPlaneMap&>(*this).find(vertex, plane));
  }
  // The value for (vertex, plane), default-constructed if new; true when new. The
  // pointer stays valid until the next emplace (the flat array may grow).
  std::pair<T*, bool> emplace(std::uint32_t vertex, std::uint32_t plane) {
    if (vertex >= first_.size()) first_.resize(std::max<std::size_t>(vertex + 1, first_.size() * 3 / 2));
    Slot& slot = first_[vertex];
    if (slot.plane == plane) return {&slot.value, false};
    if (slot.plane == kNone) {
      slot.plane = plane;
      slot.value = T{};
      touched_.push_back(vertex);
      return {&slot.value, true};
    }
    const auto [it, inserted] = rest_.try_emplace(key(vertex, plane));
    return {&it->second, inserted};
  }
  void clear() {
    for (std::uint32_t v : touched_) first_[v].plane = kNone;
    touched_.clear();
    rest_.clear();
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
  std::vector<std::uint32_t> touched_;
  std::unordered_map<std::uint64_t, T> rest_;
};

}  // namespace dynrad::rad
