#include "radiosity/pipeline/phase_log.h"

#include "radiosity/transfer/process_memory.h"

#include <algorithm>

namespace dynrad::rad {

void PhaseLog::done(std::string name) {
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - last_).count();
  phases_.push_back({std::move(name), std::max(0.0, seconds - taken_), resident_memory(), peak_resident_memory()});
  last_ = now;
  taken_ = 0;
}

void PhaseLog::add(std::string name, double seconds) {
  add(std::move(name), seconds, resident_memory(), peak_resident_memory());
}

void PhaseLog::add(std::string name, double seconds, std::size_t resident, std::size_t peak) {
  phases_.push_back({std::move(name), seconds, resident, peak});
  taken_ += seconds;
}

}  // namespace dynrad::rad
