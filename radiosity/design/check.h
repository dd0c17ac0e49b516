// One requirement of a lighting standard checked against a computed value: what was
// measured where ("task area", "Em"), its value and unit, the target and the sense of
// the comparison, so that a report can show every figure beside the figure it had to
// reach, and by how much it passed or failed.
#pragma once

#include <cmath>
#include <string>
#include <vector>

namespace dynrad::rad {

struct Check {
  enum class Relation { at_least, at_most, within };
  std::string area;      // where: "task area", "surrounding", "walls", "escape route", ...
  std::string quantity;  // what: "Em", "U0", "Ez", "Ez/Eh", "UGR", "Emin", "Emax/Emin"
  double value = 0;
  bool defined = true;   // false: the value could not be computed (see note); not met
  std::string unit;      // "lx", or empty for ratios and UGR
  Relation relation = Relation::at_least;
  double target = 0, target_high = 0;  // within: [target, target_high]
  std::string note;      // the standard's clause or why the value is undefined

  bool met() const {
    if (!defined || !std::isfinite(value)) return false;
    switch (relation) {
      case Relation::at_least: return value >= target;
      case Relation::at_most: return value <= target;
      case Relation::within: return value >= target && value <= target_high;
    }
    return false;
  }
  // By how much, as a fraction of the target: positive when the requirement is passed
  // (above a minimum, below a maximum, inside a range by the nearer end), negative when
  // it is failed. 0 when undefined or the target is 0.
  double margin() const {
    if (!defined || !std::isfinite(value)) return 0;
    switch (relation) {
      case Relation::at_least: return target != 0 ? (value - target) / target : 0;
      case Relation::at_most: return target != 0 ? (target - value) / target : 0;
      case Relation::within: {
        const double below = target != 0 ? (value - target) / target : 0;
        const double above = target_high != 0 ? (target_high - value) / target_high : 0;
        return std::min(below, above);
      }
    }
    return 0;
  }
};

inline bool all_met(const std::vector<Check>& checks) {
  for (const Check& c : checks)
    if (!c.met()) return false;
  return true;
}

}  // namespace dynrad::rad
