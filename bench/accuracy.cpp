// Convergence with patch size on the 1990 comparison room (Ward, Rushmeier et al.):
// radiosity at points of the published 0.5 grid on floor and ceiling, solved with
// the progressive method for shrinking patch sizes. Values should settle as patches
// shrink; the last column is the relative change from the previous size.
//
// Usage: bench_accuracy [converge] (default 0.001)
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "radiosity/analysis/probe.h"
#include "radiosity/solver/solver.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace dynrad;
  const double converge = argc > 1 ? std::atof(argv[1]) : 1e-3;
  const std::string path = std::string(DYNRAD_SAMPLES_DIR) + "/globillum_room.obj";
  struct Point {
    const char* name;
    Vec3d p, n;
  };
  const std::vector<Point> points = {
      {"floor (0.25, 0.25)", {0.25, 0.25, 0}, {0, 0, 1}},  {"floor (2.25, 1.75)", {2.25, 1.75, 0}, {0, 0, 1}},
      {"floor (4.75, 2.75)", {4.75, 2.75, 0}, {0, 0, 1}},  {"floor (9.75, 5.75)", {9.75, 5.75, 0}, {0, 0, 1}},
      {"ceiling (0.25, 0.25)", {0.25, 0.25, 3}, {0, 0, -1}}, {"ceiling (2.25, 1.75)", {2.25, 1.75, 3}, {0, 0, -1}},
      {"ceiling (4.25, 2.75)", {4.25, 2.75, 3}, {0, 0, -1}}, {"ceiling (9.75, 5.75)", {9.75, 5.75, 3}, {0, 0, -1}},
  };
  const std::vector<double> sizes = {2.0, 1.0, 0.5, 0.25};
  std::vector<std::vector<double>> table(points.size());
  std::printf("globillum_room, progressive, converge %g\n", converge);
  std::printf("%-22s", "patch size");
  for (double s : sizes) std::printf("%10.3f", s);
  std::printf("%10s\n", "change");
  std::vector<std::string> timing;
  for (double size : sizes) {
    LoadedScene loaded = load_scene(path);
    make_patches(*loaded.mesh, size);
    ElementHierarchy hierarchy(*loaded.mesh);
    rad::SolveOptions options;
    options.converge = converge;
    rad::Solver solver(*loaded.mesh, hierarchy, options);
    const rad::SolveReport report = solver.run();
    const rad::Solver::Output out = solver.output();
    char line[160];
    std::snprintf(line, sizeof line, "patch size %.3f: %zu patches, %zu shots, %.2f s", size, report.patches,
                  report.iterations, report.seconds);
    timing.push_back(line);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto value = rad::probe(*loaded.mesh, out.split, out.radiosity, points[i].p, points[i].n);
      table[i].push_back(value ? value->g : -1);
    }
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::printf("%-22s", points[i].name);
    for (double v : table[i]) std::printf("%10.4f", v);
    const double last = table[i].back(), before = table[i][table[i].size() - 2];
    std::printf("%9.2f%%\n", 100 * (last - before) / before);
  }
  for (const auto& t : timing) std::printf("%s\n", t.c_str());
  return 0;
}
