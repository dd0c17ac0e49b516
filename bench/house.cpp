// bench_house: an architect's real model lit as a user lights it. The IFC house of
// Debian's assimp-testmodels (AC14-FZK-Haus.ifc) with three 1500 lm point luminaires under
// the ground floor's ceilings and a work plane 0.8 m over the ground floor
// (samples/fzk_house_lamps.json), solved by the built `dynrad` with no options:
//
//   dynrad solve samples/fzk_house_lamps.json -o OUT.glb --report R.json
//
// (--report only writes what the solve did). Each run is a child process of its own, for
// its wall time and peak resident memory. Printed: the median of the runs' seconds and
// peak memory, and the last run's shots, elements, estimated error, written triangles and
// the work plane's average illuminance; the same scene at --quality high (one run) and
// the path-traced reference (tests/data/fzk_house_reference.txt, made by
// tests/reference/mesh_reference, which shares no code with the solver): the work
// plane's Eavg against both, and the grid points' relative differences from the
// reference (over the points that get at least a tenth of Eavg: the others, in rooms
// without a lamp, hold a few hundredths of a lux).
//
// The issue's goals (26): at most 30 s and 500 MB, estimated error at most 1%, Eavg
// within 2% of --quality high and within 3% of the reference.
//
// Last line: "ratio: X", the defaults' wall seconds over --quality high's, in this run.
//
// Usage: bench_house [runs (3)] [scene]
#include "bench/child.h"
#include "bench/median.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using dynrad::bench::ChildRun;
using dynrad::bench::median;
using dynrad::bench::run_or_exit;

const fs::path kWork = fs::temp_directory_path() / "dynrad_bench_house";

struct GridPoint {
  double x, y, z, e;
};

std::vector<GridPoint> read_grid_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<GridPoint> points;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    GridPoint p{};
    double direct = 0, indirect = 0;
    int masked = 0;
    if (fields >> p.x >> p.y >> p.z >> p.e >> direct >> indirect >> masked && masked == 0) points.push_back(p);
  }
  return points;
}

std::vector<GridPoint> read_reference(const fs::path& path) {
  std::ifstream in(path);
  std::vector<GridPoint> points;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    GridPoint p{};
    if (fields >> p.x >> p.y >> p.z >> p.e) points.push_back(p);
  }
  return points;
}

struct Solve {
  std::vector<double> seconds, peak_mib;
  nlohmann::json report;
  std::vector<GridPoint> grid;
  long triangles = 0;
};

Solve solve(const std::string& scene, const std::string& name, int runs, const std::vector<std::string>& extra) {
  Solve s;
  const fs::path out = kWork / (name + ".glb"), report = kWork / (name + ".json");
  for (int r = 0; r < runs; ++r) {
    std::vector<std::string> argv = {DYNRAD_CLI, "solve", scene, "-o", out.string(), "--report", report.string()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    const ChildRun run = run_or_exit(argv, (kWork / (name + ".log")).string());
    s.seconds.push_back(run.seconds);
    s.peak_mib.push_back(run.peak_mib);
    std::smatch m;
    static const std::regex wrote(R"(wrote \S+\.glb \((\d+) vertices, (\d+) triangles)");
    if (std::regex_search(run.output, m, wrote)) s.triangles = std::stol(m[2]);
    std::fprintf(stderr, "  %s run %d: %.1f s, %.0f MiB\n", name.c_str(), r + 1, run.seconds, run.peak_mib);
  }
  std::ifstream in(report);
  s.report = nlohmann::json::parse(in);
  s.grid = read_grid_csv(kWork / (name + "_grid_ground.csv"));
  return s;
}

double eavg(const std::vector<GridPoint>& points) {
  double sum = 0;
  for (const GridPoint& p : points) sum += p.e;
  return points.empty() ? 0.0 : sum / static_cast<double>(points.size());
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::string scene = argc > 2 ? argv[2] : DYNRAD_SAMPLES_DIR "/fzk_house_lamps.json";
  fs::create_directories(kWork);
  std::printf("bench_house: %s, %d runs of the defaults, one of --quality high\n", scene.c_str(), runs);

  const Solve defaults = solve(scene, "defaults", runs, {});
  const Solve high = solve(scene, "high", 1, {"--quality", "high"});
  const double wall = median(defaults.seconds), memory = median(defaults.peak_mib);
  const nlohmann::json& r = defaults.report;
  const double estimated = r["estimated_error"]["total"].get<double>();
  const double e_default = eavg(defaults.grid), e_high = eavg(high.grid);

  std::printf("\n| figure | defaults | goal |\n|---|---|---|\n");
  std::printf("| wall seconds (median of %d) | %.1f | at most 30 |\n", runs, wall);
  std::printf("| peak resident memory, MiB (median) | %.0f | at most 500 |\n", memory);
  std::printf("| solve seconds (report) | %.1f | |\n", r["seconds"].get<double>());
  std::printf("| shots | %zu | |\n", r["iterations"].get<std::size_t>());
  std::printf("| patches, sender groups, clusters | %zu, %zu, %zu | |\n", r["patches"].get<std::size_t>(),
              r["sender_groups"]["groups"].get<std::size_t>(),
              r["clusters"]["clusters"].get<std::size_t>());
  std::printf("| elements | %zu | |\n", r["elements"].get<std::size_t>());
  std::printf("| visibility rays | %.0f M | |\n", r["visibility_rays"].get<double>() / 1e6);
  std::printf("| estimated error | %.2f%% | at most 1%% |\n", 100 * estimated);
  std::printf("| triangles written (.glb) | %ld | at most 500,000 |\n", defaults.triangles);
  std::printf("| work plane Eavg, lx (%zu points) | %.2f | |\n", defaults.grid.size(), e_default);
  std::printf("| --quality high: Eavg, lx; wall seconds | %.2f; %.1f | |\n", e_high, high.seconds.front());
  std::printf("| Eavg against --quality high | %+.2f%% | within 2%% |\n", 100 * (e_default / e_high - 1));

  const fs::path reference_path = DYNRAD_TEST_DATA_DIR "/fzk_house_reference.txt";
  const std::vector<GridPoint> reference = read_reference(reference_path);
  if (reference.size() != defaults.grid.size()) {
    std::printf("| path-traced reference | %s: %zu points, the grid has %zu: not compared | |\n",
                reference_path.c_str(), reference.size(), defaults.grid.size());
  } else {
    const double e_reference = eavg(reference);
    double sum = 0, worst = 0, high_sum = 0;
    int counted = 0;
    for (std::size_t k = 0; k < reference.size(); ++k) {
      const GridPoint& p = reference[k];
      if (std::abs(p.x - defaults.grid[k].x) > 1e-3 || std::abs(p.y - defaults.grid[k].y) > 1e-3) {
        std::printf("| path-traced reference | point %zu is not the grid's: not compared | |\n", k);
        counted = -1;
        break;
      }
      if (p.e < 0.1 * e_reference) continue;
      const double d = std::abs(defaults.grid[k].e / p.e - 1);
      sum += d;
      worst = std::max(worst, d);
      high_sum += std::abs(high.grid[k].e / p.e - 1);
      ++counted;
    }
    if (counted > 0) {
      std::printf("| path-traced reference: Eavg, lx | %.2f | |\n", e_reference);
      std::printf("| Eavg against the reference | %+.2f%% (high: %+.2f%%) | within 3%% |\n",
                  100 * (e_default / e_reference - 1), 100 * (e_high / e_reference - 1));
      std::printf("| points at 0.1 Eavg or more (%d): mean, largest difference | %.2f%%, %.2f%% (high: mean %.2f%%) | |\n",
                  counted, 100 * sum / counted, 100 * worst, 100 * high_sum / counted);
    }
  }
  std::printf("\nratio: %.3f\n", wall / high.seconds.front());
  return 0;
}
