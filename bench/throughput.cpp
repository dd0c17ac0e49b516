// Ray throughput: visibility rays per second inside a solve against Embree's own rate
// on the very same rays, in one process.
//
// 1. A short single-threaded solve records every occlusion ray it casts.
// 2. Those rays are replayed straight into Embree on all threads, one at a time
//    (rtcOccluded1) and in streams of 64 (rtcOccluded1M); the faster is the reference.
// 3. A full solve (fresh, all threads, no recording) gives rays per second achieved:
//    all its visibility rays over its wall time, so everything else the solve does
//    counts against it.
// 4. One more solve times Embree's own calls (a few percent slower, so it is not one of
//    the three): how fast Embree runs the rays inside the solve against the replay
//    (per thread), and its share of the solve's thread time. The ratio can be at most
//    that efficiency, even if everything else took no time.
// The last line is `ratio: achieved / reference`.
//
// Usage: bench_throughput [model] [patch size] [method]
//   (default: samples/globillum_room_obstructed.obj, 0.5, dynamic; to 1% unshot)
#include "bench/median.h"
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "radiosity/solver/solver.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using namespace dynrad;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

using bench::median;

struct Setup {
  LoadedScene loaded;
  std::unique_ptr<ElementHierarchy> hierarchy;
};

Setup prepare(const std::string& path, double patch_size) {
  Setup s{load_scene(path), nullptr};
  make_patches(*s.loaded.mesh, patch_size);
  s.hierarchy = std::make_unique<ElementHierarchy>(*s.loaded.mesh);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // figures as they come
  const std::string path = argc > 1 ? argv[1] : std::string(DYNRAD_SAMPLES_DIR) + "/globillum_room_obstructed.obj";
  const double patch_size = argc > 2 ? std::atof(argv[2]) : 0.5;
  rad::RefineSettings refine;
  refine.method = rad::parse_method(argc > 3 ? argv[3] : "dynamic");

  // 1. Record the solver's rays.
  std::vector<RTCRay> rays;
  {
    Setup s = prepare(path, patch_size);
    rad::SolveOptions options;
    options.threads = 1;
    options.max_iterations = 300;
    rad::Solver solver(*s.loaded.mesh, *s.hierarchy, options, refine);
    solver.record_rays(&rays);
    solver.run();
  }
  std::printf("scene: %s, patch size %g, %s\n", path.c_str(), patch_size, rad::method_name(refine.method));
  std::printf("recorded %zu rays from the first 300 shots\n", rays.size());

  // 2. Raw Embree on the same rays, all threads.
  Setup s = prepare(path, patch_size);
  std::printf("triangles: %zu\n", s.loaded.mesh->face_count());
  const rad::Visibility visibility(*s.loaded.mesh);
  auto raw = [&](int stream) {
    const auto start = Clock::now();
    const std::size_t chunk = 4096;
    tbb::parallel_for(std::size_t(0), (rays.size() + chunk - 1) / chunk, [&](std::size_t c) {
      const std::size_t begin = c * chunk, n = std::min(chunk, rays.size() - begin);
      visibility.replay(rays.data() + begin, n, stream);
    });
    return rays.size() / seconds_since(start);
  };
  std::vector<double> single, streamed;
  for (int rep = 0; rep < 5; ++rep) {
    single.push_back(raw(1));
    streamed.push_back(raw(64));
  }
  const double reference = std::max(median(single), median(streamed));
  std::printf("raw Embree, rtcOccluded1:        %.2f M rays/s (median of 5)\n", median(single) / 1e6);
  std::printf("raw Embree, rtcOccluded1M (64):  %.2f M rays/s (median of 5)\n", median(streamed) / 1e6);

  // 3. The full solve.
  std::vector<double> achieved;
  for (int rep = 0; rep < 3; ++rep) {
    Setup run = prepare(path, patch_size);
    rad::SolveOptions options;
    rad::Solver solver(*run.loaded.mesh, *run.hierarchy, options, refine);
    const rad::SolveReport report = solver.run();
    achieved.push_back(report.visibility_rays / report.seconds);
    std::printf("solve %d: %zu shots, %.2f s, %.1f M rays, %.2f M rays/s\n", rep + 1, report.iterations, report.seconds,
                report.visibility_rays / 1e6, achieved.back() / 1e6);
  }
  std::printf("in the solve: %.2f M rays/s (median of 3)\n", median(achieved) / 1e6);

  // 4. Where the time goes.
  {
    Setup run = prepare(path, patch_size);
    rad::SolveOptions options;
    rad::Solver solver(*run.loaded.mesh, *run.hierarchy, options, refine);
    solver.time_visibility(true);
    const rad::SolveReport report = solver.run();
    const int threads = tbb::this_task_arena::max_concurrency();
    const double in_embree = solver.seconds_in_embree();
    const double inside = report.visibility_rays / in_embree, raw_per_thread = reference / threads;
    std::printf("inside Embree (a timed solve, %.2f s): %.2f thread-s, %.1f%% of the solve's %d threads; "
                "%.2f M rays/s per thread against %.2f M raw: efficiency %.2f (the ratio's bound)\n",
                report.seconds, in_embree, 100 * in_embree / (report.seconds * threads), threads, inside / 1e6,
                raw_per_thread / 1e6, inside / raw_per_thread);
  }
  std::printf("ratio: %.3f\n", median(achieved) / reference);
  return 0;
}
