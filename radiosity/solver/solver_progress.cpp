// A sign of life during a long shot (SolveOptions::on_busy): a shot starts the clock,
// the threads computing its points beat. And the progress of the passes after the
// shots (SolveOptions::on_pass).
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

namespace {
std::int64_t nanoseconds(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}
}  // namespace

Solver::PassProgress::PassProgress(const SolveOptions& options, const char* name, std::size_t total)
    : options_(options), name_(name), total_(total), start_(std::chrono::steady_clock::now()) {
  next_ = nanoseconds(start_) + 2'000'000'000;
}

Solver::PassProgress::~PassProgress() {
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // Said at its end only when it took long enough to have been said before.
  if (options_.on_pass && seconds >= 2) options_.on_pass(name_, done_.load(), total_.load(), seconds);
}

void Solver::PassProgress::add(std::size_t done) {
  done_.fetch_add(done, std::memory_order_relaxed);
  if (!options_.on_pass) return;
  const auto now = std::chrono::steady_clock::now();
  std::int64_t due = next_.load(std::memory_order_relaxed);
  if (nanoseconds(now) < due) return;
  if (!next_.compare_exchange_strong(due, nanoseconds(now) + 2'000'000'000, std::memory_order_relaxed)) return;
  options_.on_pass(name_, done_.load(), total_.load(), std::chrono::duration<double>(now - start_).count());
}

bool Solver::PassProgress::stop() {
  if (stopped_.load(std::memory_order_relaxed)) return true;
  if (!options_.should_stop) return false;
  const std::int64_t now = nanoseconds(std::chrono::steady_clock::now());
  std::int64_t due = next_stop_check_.load(std::memory_order_relaxed);
  if (now < due || !next_stop_check_.compare_exchange_strong(due, now + 50'000'000, std::memory_order_relaxed))
    return false;
  if (options_.should_stop()) stopped_ = true;
  return stopped_.load();
}

}  // namespace dynrad::rad
