// Time to accuracy on the 1990 comparison room: error against a converged fine
// solution, at the published 0.5 m grid on floor and ceiling, against wall time.
//
// Reference: progressive refinement on 0.5 m patches to 0.01% unshot (bench_accuracy
// shows values there within 0.2% of 0.25 m patches). Each configuration is solved to a
// series of unshot targets; error is the mean over the grid points of |B - B_ref| /
// B_ref (green channel), wall time is the solve's own (loading and patching excluded,
// they are printed once).
//
// Usage: bench_time_to_accuracy [threads [configuration name contains]]   (default: all
// cores, every configuration). "k" is dynamic's push-down error (with a floor of half
// of it unless "f" gives the floor), "w" the overshoot, "flat:" rows shoot evenly from each patch (--flat-senders).
// Run it from build/bench (the reference cache goes there).
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "radiosity/analysis/probe.h"
#include "radiosity/solver/solver.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using namespace dynrad;

struct Point {
  Vec3d p, n;
};

std::vector<Point> grid() {
  std::vector<Point> points;
  for (double x = 0.25; x < 10; x += 0.5)
    for (double y = 0.25; y < 6; y += 0.5) {
      points.push_back({{x, y, 0}, {0, 0, 1}});
      points.push_back({{x, y, 3}, {0, 0, -1}});
    }
  return points;
}

struct Result {
  rad::SolveReport report;
  std::vector<double> values;          // per grid point
  std::vector<double> values_ambient;  // the same with the ambient display term
};

struct Config {
  const char* name;
  double patch;
  rad::Method method;
  int level = 0;  // --max-level
  double overshoot = 1.0;
  // Receivers split uniformly to `level` at the first shot (adaptive with a zero
  // threshold): what the patches as senders allow when receivers are fine everywhere.
  bool uniform = false;
  double pushdown = -1, floor = -1;  // dynamic oracle; negative: the defaults
  bool shaped = true;                // SolveOptions::shaped_senders
};

Result solve(const Config& c, double converge, int threads) {
  const std::string path = std::string(DYNRAD_SAMPLES_DIR) + "/globillum_room.obj";
  LoadedScene loaded = load_scene(path);
  make_patches(*loaded.mesh, c.patch);
  ElementHierarchy hierarchy(*loaded.mesh);
  rad::SolveOptions options;
  options.converge = converge;
  options.threads = threads;
  options.overshoot = c.overshoot;
  options.shaped_senders = c.shaped;
  rad::RefineSettings refine;
  refine.method = c.uniform ? rad::Method::adaptive : c.method;
  refine.max_level = c.level;
  if (c.uniform) refine.adaptive_threshold = 0;
  if (c.pushdown >= 0) refine.dynamic.pushdown = c.pushdown;
  if (c.floor >= 0) refine.dynamic.pushdown_floor = c.floor;
  rad::Solver solver(*loaded.mesh, hierarchy, options, refine);
  Result r;
  r.report = solver.run();
  const rad::Solver::Output out = solver.output(false), with_ambient = solver.output(true);
  for (const Point& p : grid()) {
    const auto value = rad::probe(*loaded.mesh, out.split, out.radiosity, p.p, p.n);
    r.values.push_back(value ? value->g : std::nan(""));
    const auto ambient = rad::probe(*loaded.mesh, with_ambient.split, with_ambient.radiosity, p.p, p.n);
    r.values_ambient.push_back(ambient ? ambient->g : std::nan(""));
  }
  return r;
}

double mean_error(const std::vector<double>& values, const std::vector<double>& reference) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (std::isfinite(values[i]) && std::isfinite(reference[i]) && reference[i] > 0) {
      sum += std::abs(values[i] - reference[i]) / reference[i];
      ++n;
    }
  return n ? sum / n : std::nan("");
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 0;
  // The reference takes a minute or two; it is kept beside the program and reused
  // (delete the file to recompute it, e.g. after a change to the solver's physics).
  const std::string cache = "time_to_accuracy_reference.txt";
  Result reference;
  if (std::FILE* f = std::fopen(cache.c_str(), "r")) {
    for (double v; std::fscanf(f, "%lf", &v) == 1;) reference.values.push_back(v);
    std::fclose(f);
  }
  if (reference.values.size() != grid().size()) {
    // Even senders, as the reference always was. Shaped ones move it by 0.07% on
    // average and by up to 1.7% on the ceiling beside the middle of the long walls,
    // whose light changes fastest there (bench/results/bench_time_to_accuracy.md).
    reference = solve({"reference", 0.5, rad::Method::progressive, 0, 1.0, false, -1, -1, false}, 1e-4, threads);
    std::printf("reference: 0.5 m patches, progressive to 0.01%% unshot: %zu shots, %.1f s, %zu grid points\n",
                reference.report.iterations, reference.report.seconds, reference.values.size());
    if (std::FILE* f = std::fopen(cache.c_str(), "w")) {
      for (double v : reference.values) std::fprintf(f, "%.17g\n", v);
      std::fclose(f);
    }
  } else {
    std::printf("reference: %zu grid points from %s\n", reference.values.size(), cache.c_str());
  }
  using M = rad::Method;
  const Config configs[] = {
      {"progressive 2.0 m", 2.0, M::progressive},
      {"progressive 1.4 m", 1.4, M::progressive},
      {"progressive 1.2 m", 1.2, M::progressive},
      {"progressive 1.0 m", 1.0, M::progressive},
      {"progressive 1.0 m, w 1.3", 1.0, M::progressive, 0, 1.3},
      {"progressive 1.0 m, w 1.6", 1.0, M::progressive, 0, 1.6},
      {"dynamic 3.0 m, level 4, k 0.02", 3.0, M::dynamic, 3, 1.0, false, 0.02, 0.01},
      {"dynamic 2.5 m, level 3, k 0.02", 2.5, M::dynamic, 2, 1.0, false, 0.02, 0.01},
      {"dynamic 2.5 m, level 3, k 0.01", 2.5, M::dynamic, 2, 1.0, false, 0.01, 0.005},
      {"dynamic 2.5 m, level 3, k 0.015 f 0.015", 2.5, M::dynamic, 2, 1.0, false, 0.015, 0.015},
      {"dynamic 2.2 m, level 3, k 0.02", 2.2, M::dynamic, 2, 1.0, false, 0.02, 0.01},
      {"dynamic 2.0 m, level 2", 2.0, M::dynamic, 1},
      {"dynamic 2.0 m, level 2, w 1.3", 2.0, M::dynamic, 1, 1.3},
      {"dynamic 2.0 m, level 3", 2.0, M::dynamic, 2},
      {"dynamic 2.0 m, level 3, k 0.02", 2.0, M::dynamic, 2, 1.0, false, 0.02, 0.01},
      {"dynamic 2.0 m, level 3, k 0.01", 2.0, M::dynamic, 2, 1.0, false, 0.01, 0.005},
      {"dynamic 1.4 m, level 3", 1.4, M::dynamic, 2},
      {"dynamic 1.4 m, level 3, k 0.01", 1.4, M::dynamic, 2, 1.0, false, 0.01, 0.005},
      {"dynamic 1.0 m, level 2", 1.0, M::dynamic, 1},
      {"dynamic 1.0 m, level 2, w 1.3", 1.0, M::dynamic, 1, 1.3},
      // Where the error comes from: fine receivers everywhere leave only the senders'.
      {"uniform 3.0 m, level 4", 3.0, M::adaptive, 3, 1.0, true},
      {"uniform 2.5 m, level 3", 2.5, M::adaptive, 2, 1.0, true},
      {"uniform 2.0 m, level 3", 2.0, M::adaptive, 2, 1.0, true},
      {"uniform 1.4 m, level 3", 1.4, M::adaptive, 2, 1.0, true},
      // The same and the best rows with senders that shoot evenly (--flat-senders).
      {"flat: uniform 2.0 m, level 3", 2.0, M::adaptive, 2, 1.0, true, -1, -1, false},
      {"flat: uniform 1.4 m, level 3", 1.4, M::adaptive, 2, 1.0, true, -1, -1, false},
      {"flat: progressive 1.0 m", 1.0, M::progressive, 0, 1.0, false, -1, -1, false},
      {"flat: dynamic 2.5 m, level 3, k 0.01", 2.5, M::dynamic, 2, 1.0, false, 0.01, 0.005, false},
      {"flat: dynamic 2.5 m, level 3, k 0.015 f 0.015", 2.5, M::dynamic, 2, 1.0, false, 0.015, 0.015, false},
      {"flat: dynamic 2.0 m, level 3, k 0.02", 2.0, M::dynamic, 2, 1.0, false, 0.02, 0.01, false},
  };
  std::printf("%-36s %8s %7s %9s %10s %9s %9s\n", "configuration", "unshot", "shots", "elements", "seconds", "error",
              "+ambient");
  const std::string only = argc > 2 ? argv[2] : "";
  for (const Config& c : configs) {
    if (!only.empty() && std::string(c.name).find(only) == std::string::npos) continue;
    for (double converge : {0.3, 0.1, 0.05, 0.02, 0.01, 0.005}) {
      const Result r = solve(c, converge, threads);
      std::printf("%-36s %7.1f%% %7zu %9zu %10.3f %8.2f%% %8.2f%%\n", c.name, 100 * converge, r.report.iterations,
                  r.report.elements, r.report.seconds, 100 * mean_error(r.values, reference.values),
                  100 * mean_error(r.values_ambient, reference.values));
      std::fflush(stdout);
    }
  }
  return 0;
}
