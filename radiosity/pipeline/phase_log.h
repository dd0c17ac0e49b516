// Where a run's time and memory go, phase by phase (the report's "phases"): each phase's
// wall seconds, and the process's resident and peak memory when it ended.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

namespace dynrad::rad {

struct PhaseTime {
  std::string name;
  double seconds = 0;
  std::size_t resident = 0, peak = 0;  // bytes, when the phase ended (0 where unknown)
};

class PhaseLog {
 public:
  PhaseLog() : last_(std::chrono::steady_clock::now()) {}
  // The phase that ends now: its time since the last one ended (or the log was made).
  void done(std::string name);
  // A phase whose time is known otherwise (a part of the one that ends next is then
  // counted once: it is taken off that one).
  void add(std::string name, double seconds);
  // The same, with the memory when it ended (bytes), measured by whoever timed it.
  void add(std::string name, double seconds, std::size_t resident, std::size_t peak);
  const std::vector<PhaseTime>& phases() const { return phases_; }

 private:
  std::chrono::steady_clock::time_point last_;
  double taken_ = 0;  // seconds add() gave since the last done()
  std::vector<PhaseTime> phases_;
};

}  // namespace dynrad::rad
