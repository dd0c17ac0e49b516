// A sign of life during a long shot (SolveOptions::on_busy): a shot starts the clock,
// the threads computing its points beat.
#include "radiosity/solver/solver.h"

#include <chrono>

namespace dynrad::rad {

void Solver::start_heartbeat() {
  shot_start_ = std::chrono::steady_clock::now();
  shot_points_ = 0;
  next_beat_ = std::chrono::duration_cast<std::chrono::nanoseconds>(
                   (shot_start_ + std::chrono::seconds(2)).time_since_epoch()).count();
}

void Solver::beat() {
  if (!options_.on_busy) return;
  // Counted on each thread and added to the shared count 64 at a time: a shared counter
  // touched at every point cost the IFC house 2.3% of its solve (the cores fought over
  // its cache line). The count is then a multiple of 64, which is enough for a sign of
  // life.
  thread_local std::size_t local = 0;
  if (++local % 64) return;
  const std::size_t points = shot_points_.fetch_add(64, std::memory_order_relaxed) + 64;
  const auto now = std::chrono::steady_clock::now();
  const std::int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count();
  std::int64_t due = next_beat_.load(std::memory_order_relaxed);
  if (now_ns < due) return;
  // One thread takes the beat; the others see the new due time.
  if (!next_beat_.compare_exchange_strong(due, now_ns + 2'000'000'000, std::memory_order_relaxed)) return;
  options_.on_busy(points, std::chrono::duration<double>(now - shot_start_).count());
}

}  // namespace dynrad::rad
