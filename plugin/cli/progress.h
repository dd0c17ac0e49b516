// Progress of a long solve on stderr, and the stop that SIGINT and SIGTERM ask for:
// shared by the commands that solve (solve, annual).
#pragma once

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <string>

namespace dynrad::cli {

// First SIGINT/SIGTERM asks the solve to stop at the next shot boundary; the handler
// then restores the default action, so a second one ends the program at once.
inline std::atomic<bool> g_stop_requested{false};
extern "C" inline void on_stop_signal(int signal_number) {
  g_stop_requested.store(true);
  std::signal(signal_number, SIG_DFL);
}

// Progress on stderr. On a terminal, a bar redrawn in place (at most 10 times a
// second); otherwise (a log file, a pipe, a build system) a line every 5 seconds, so a
// long solve is never silent. Neither with --quiet.
class Progress {
 public:
  explicit Progress(double converge)
      : terminal_(::isatty(STDERR_FILENO)), quiet_(!spdlog::should_log(spdlog::level::info)), converge_(converge),
        start_(std::chrono::steady_clock::now()), last_(start_) {}
  // `error` is the estimated error of the values so far (negative: not estimated yet).
  void update(std::size_t shot, double unshot, double error, std::size_t elements) {
    shots_ = shot;
    if (quiet_) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const std::string error_text = error >= 0 ? fmt::format("estimated error {:.2f}%, ", 100 * error) : "";
    if (!terminal_) {
      if (now - last_ < std::chrono::seconds(5)) return;
      last_ = now;
      std::fprintf(stderr, "progress: shot %zu, %sunshot %.2f%%, %zu elements, %.0f s\n", shot, error_text.c_str(),
                   100 * unshot, elements, elapsed);
      std::fflush(stderr);
      return;
    }
    if (shot > 1 && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    // Unshot power falls roughly geometrically: progress on a log scale.
    const double done = std::clamp(std::log(std::max(unshot, 1e-12)) / std::log(converge_), 0.0, 1.0);
    const int width = 30, filled = static_cast<int>(done * width);
    std::fprintf(stderr, "\r  [%s%s] shot %zu, %sunshot %.2f%%, %zu elements, %.0f s   ",
                 std::string(filled, '#').c_str(), std::string(width - filled, '-').c_str(), shot, error_text.c_str(),
                 100 * unshot, elements, elapsed);
    std::fflush(stderr);
    drawn_ = true;
  }
  // During a long shot (SolveOptions::on_busy; from a worker thread, never at the same
  // time as update): a line that says the shot goes on, and that a stop waits for it.
  void busy(std::size_t points, double seconds, bool stop_requested) {
    if (quiet_) return;
    const std::string stop = stop_requested ? "; stopping when it ends, then writing the solution" : "";
    std::fprintf(stderr, "%sprogress: shot %zu running, %zu points lit in %.0f s%s%s", terminal_ ? "\r  " : "",
                 shots_ + 1, points, seconds, stop.c_str(), terminal_ ? "   " : "\n");
    std::fflush(stderr);
    drawn_ = drawn_ || terminal_;
  }
  // During a pass after the shots (SolveOptions::on_pass; from a worker thread, never
  // at the same time as update or busy): what it is and how far, so that no phase is
  // silent (also when not on a terminal).
  void pass(const char* name, std::size_t done, std::size_t total, double seconds, bool stop_requested) {
    if (quiet_) return;
    const std::string stop = stop_requested ? "; stopping: cutting it short, then writing the solution" : "";
    const double percent = total > 0 ? 100.0 * std::min(done, total) / total : 100.0;
    std::fprintf(stderr, "%sprogress: %s: %zu of %zu (%.0f%%), %.0f s%s%s", terminal_ ? "\r  " : "", name, done, total,
                 percent, seconds, stop.c_str(), terminal_ ? "   " : "\n");
    std::fflush(stderr);
    drawn_ = drawn_ || terminal_;
  }
  void finish() {
    if (drawn_) std::fprintf(stderr, "\n");
  }

 private:
  bool terminal_, quiet_;
  double converge_;
  bool drawn_ = false;
  std::size_t shots_ = 0;  // shots done
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace dynrad::cli
