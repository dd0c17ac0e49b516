// bench_light_scenes: what light scenes cost. The storey sample (two control groups,
// three scenes) is solved by the built `dynrad` as a user solves it, once as it is
// (every group in a channel of its own: one solve for every scene) and once with its
// "scenes" taken out (one plain solve, the reference), alternately, each in a child
// process. Solving each group apart instead would cost about (groups) x the reference.
//
// Figures per configuration: the solve's seconds (the report's "seconds") and the whole
// command's, medians of the repeats, shots, peak resident memory; last lines: ratios with
// scenes over without. Both are stopped by the same rule (the quality's error target).
//
// Usage: bench_light_scenes [repeats (3)]
#include "bench/child.h"
#include "bench/median.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace dynrad;

struct Figures {
  std::vector<double> solve_seconds, wall_seconds, peak_mib;
  double shots = 0;
  std::size_t scenes = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dynrad-bench-scenes-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string samples = DYNRAD_SAMPLES_DIR;
  // The reference: the same scene file without "scenes", its paths made absolute.
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(samples + "/storey_luminaires.json"));
  scene["meshes"][0]["file"] = samples + "/" + scene["meshes"][0]["file"].get<std::string>();
  for (auto& l : scene["luminaires"]) l["photometry"] = samples + "/" + l["photometry"].get<std::string>();
  const std::size_t scene_count = scene["scenes"].size();
  const std::string with = (dir / "with.json").string(), without = (dir / "without.json").string();
  std::ofstream(with) << scene.dump();
  scene.erase("scenes");
  std::ofstream(without) << scene.dump();

  Figures figures[2];
  for (int r = 0; r < repeats; ++r)
    for (int k = 0; k < 2; ++k) {
      const std::string report = (dir / "report.json").string();
      const bench::ChildRun run = bench::run_child(
          {DYNRAD_CLI, "solve", "-q", k == 0 ? with : without, "-o", (dir / "lit.ply").string(), "--report", report},
          (dir / "log.txt").string());
      if (run.exit_code != 0) {
        std::fprintf(stderr, "dynrad failed (%d):\n%s\n", run.exit_code, run.output.c_str());
        return 1;
      }
      const nlohmann::json j = nlohmann::json::parse(std::ifstream(report));
      figures[k].solve_seconds.push_back(j["seconds"].get<double>());
      figures[k].wall_seconds.push_back(run.seconds);
      figures[k].peak_mib.push_back(run.peak_mib);
      figures[k].shots = j["iterations"].get<double>();
      figures[k].scenes = j.contains("scenes") ? j["scenes"].size() : 0;
    }
  fs::remove_all(dir);
  const char* names[2] = {"with scenes (2 groups in channels)", "without scenes (reference)"};
  std::printf("%-36s %8s %10s %10s %8s %8s\n", "storey sample", "scenes", "solve s", "command s", "shots", "MiB");
  for (int k = 0; k < 2; ++k)
    std::printf("%-36s %8zu %10.2f %10.2f %8.0f %8.0f\n", names[k], figures[k].scenes,
                bench::median(figures[k].solve_seconds), bench::median(figures[k].wall_seconds), figures[k].shots,
                bench::median(figures[k].peak_mib));
  std::printf("ratio solve seconds (with / without): %.3f (medians of %d; %zu scenes from one solve)\n",
              bench::median(figures[0].solve_seconds) / bench::median(figures[1].solve_seconds), repeats, scene_count);
  std::printf("ratio command seconds (with / without): %.3f\n",
              bench::median(figures[0].wall_seconds) / bench::median(figures[1].wall_seconds));
  return 0;
}
