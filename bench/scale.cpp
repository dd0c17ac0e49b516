// Scale: a big model (the generated building floor, samples/make_building.py) loaded
// and patched by the pipeline `dynrad solve` calls (radiosity/pipeline/pipeline.h:
// cleanup, flat regions simplified, the patch size chosen from the model), then
// 1. thread scaling: the same number of dynamic shots with 1 thread and with 2 (or
//    more), fresh solvers in one process, each repeated; medians and their ratio;
// 2. one solve to the target unshot fraction with all threads: time, shots, elements,
//    peak resident memory and resident bytes per element.
//
// Usage: bench_scale MODEL.obj [shots for scaling (200)] [converge (0.01)] [repeats (3)]
//   (converge 0 measures the thread scaling only)
//   e.g. python3 samples/make_building.py /tmp/b100k.obj --cell 0.25
//        build/bench/bench_scale /tmp/b100k.obj
#include "bench/median.h"
#include "radiosity/pipeline/pipeline.h"

#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace dynrad;
using Clock = std::chrono::steady_clock;

using bench::median;

// `dynrad solve`'s request, its stop rule replaced by `shots` and `converge`.
rad::SceneRequest request(const std::string& path, int threads, std::size_t shots, double converge) {
  rad::SceneRequest r;
  r.path = path;
  r.simplify.enabled = true;
  r.settings.converge = converge;
  r.solve.threads = threads;
  r.solve.max_iterations = shots;
  return r;
}

rad::SolveReport solve(const std::string& path, int threads, std::size_t shots, double converge) {
  rad::PreparedScene p = rad::prepare_scene(request(path, threads, shots, converge));
  return rad::solve_scene(p).report;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_scale MODEL.obj [shots] [converge] [repeats]\n");
    return 2;
  }
  const std::string path = argv[1];
  const std::size_t shots = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 200;
  const double converge = argc > 3 ? std::atof(argv[3]) : 0.01;
  const int repeats = argc > 4 ? std::atoi(argv[4]) : 3;
  const int cores = static_cast<int>(std::max(2u, std::thread::hardware_concurrency()));

  const auto load_start = Clock::now();
  {
    const rad::PreparedScene p = rad::prepare_scene(request(path, 0, 0, converge));
    std::printf("model: %s: %zu triangles after cleanup, %zu after simplification, %zu patches (load %.1f s)\n",
                path.c_str(), p.scene.simplify.faces_before, p.scene.simplify.faces_after, p.hierarchy->patch_count(),
                std::chrono::duration<double>(Clock::now() - load_start).count());
  }

  // 1. Thread scaling on the same shots (the solve's own wall time, loading excluded).
  std::vector<double> one, many;
  for (int r = 0; r < repeats; ++r) {
    one.push_back(solve(path, 1, shots, 0).seconds);
    many.push_back(solve(path, cores, shots, 0).seconds);
    std::printf("  run %d: %zu shots, 1 thread %.2f s, %d threads %.2f s\n", r + 1, shots, one.back(), cores,
                many.back());
  }
  std::printf("thread scaling: %zu dynamic shots, median 1 thread %.2f s, %d threads %.2f s, speedup %.2f\n", shots,
              median(one), cores, median(many), median(one) / median(many));

  // 2. To the target.
  if (!(converge > 0)) return 0;
  const rad::SolveReport report = solve(path, 0, 0, converge);
  std::printf("solve to %.1f%% unshot: %zu shots, %.1f s, %zu elements, unshot %.2f%%, peak resident %.0f MiB, "
              "%.0f bytes per element (resident / elements)\n",
              100 * converge, report.iterations, report.seconds, report.elements, 100 * report.unshot_fraction,
              report.peak_resident_memory / 1048576.0,
              static_cast<double>(report.peak_resident_memory) / static_cast<double>(report.elements));
  return 0;
}
