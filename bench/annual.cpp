// bench_annual: what a year of daylight costs (issue 30's goal: the daylit room sample's
// year in at most 60 s on 2 cores). The built `dynrad` runs as a user runs it, in a child
// process: `dynrad annual` on samples/daylight_overcast.json with a synthetic year
// (samples/make_weather.py), and, as the reference, one `dynrad solve` of the same scene
// under its overcast sky with its grid, alternately.
//
// Figures: the command's seconds and peak resident memory (medians of the repeats), and
// from the annual run's log its phases (skies, solve, points and hours) and the
// coefficient channels' memory: patches x channels x 8 bytes (each patch's unshot and
// received light per channel, floats). Last lines: ratios annual over one solve.
//
// With --house, also the IFC house's ground floor once (issue 30's goal: at most 10
// minutes and 2 GB): the model and grid "ground" of samples/fzk_house_lamps.json, its
// glazing as windows, without the lamps, the same synthetic year.
//
// Usage: bench_annual [repeats (3)] [--house]
#include "bench/child.h"
#include "bench/median.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace dynrad;
  int repeats = 3;
  bool house = false;
  for (int a = 1; a < argc; ++a) {
    if (std::string(argv[a]) == "--house")
      house = true;
    else
      repeats = std::max(1, std::atoi(argv[a]));
  }
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dynrad-bench-annual-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string samples = DYNRAD_SAMPLES_DIR;
  const std::string weather = (dir / "london.epw").string();
  const bench::ChildRun made =
      bench::run_child({"python3", samples + "/make_weather.py", weather}, (dir / "weather.txt").string());
  if (made.exit_code != 0) {
    std::fprintf(stderr, "make_weather.py failed:\n%s\n", made.output.c_str());
    return 1;
  }
  const std::string scene = samples + "/daylight_overcast.json";
  std::vector<double> seconds[2], mib[2];
  std::string annual_log;
  for (int r = 0; r < repeats; ++r)
    for (int k = 0; k < 2; ++k) {
      const std::vector<std::string> command =
          k == 0 ? std::vector<std::string>{DYNRAD_CLI, "annual", scene, "--weather", weather, "-o",
                                            (dir / "room").string()}
                 : std::vector<std::string>{DYNRAD_CLI, "solve", scene, "-o", (dir / "lit.ply").string()};
      const bench::ChildRun run = bench::run_child(command, (dir / "log.txt").string());
      if (run.exit_code != 0) {
        std::fprintf(stderr, "dynrad failed (%d):\n%s\n", run.exit_code, run.output.c_str());
        return 1;
      }
      seconds[k].push_back(run.seconds);
      mib[k].push_back(run.peak_mib);
      if (k == 0) annual_log = run.output;
    }
  bench::ChildRun house_run;
  std::string house_log;
  if (house) {
    nlohmann::json lamps = nlohmann::json::parse(std::ifstream(samples + "/fzk_house_lamps.json"));
    nlohmann::json scene_house = {{"meshes", lamps["meshes"]},
                                  {"grids", lamps["grids"]},
                                  {"sky", {{"type", "cie_overcast"}, {"ground_reflectance", 0.2}}}};
    const std::string path = (dir / "house.json").string();
    std::ofstream(path) << scene_house.dump();
    house_run = bench::run_child({DYNRAD_CLI, "annual", path, "--weather", weather, "-o", (dir / "house").string()},
                                 (dir / "house_log.txt").string());
    if (house_run.exit_code != 0) {
      std::fprintf(stderr, "dynrad annual (house) failed (%d):\n%s\n", house_run.exit_code, house_run.output.c_str());
      return 1;
    }
  }
  fs::remove_all(dir);
  // The last annual run's phases and channels, from its log.
  auto find = [&](const char* pattern) {
    std::smatch m;
    return std::regex_search(annual_log, m, std::regex(pattern)) ? m[1].str() : std::string("?");
  };
  const std::string skies = find(R"(skies in ([0-9.]+) s)"), solve = find(R"(solved in ([0-9.]+) s)");
  const std::string patches = find(R"(solve: ([0-9]+) patches)"), channels = find(R"(patches \(patch size [0-9.]+\), ([0-9]+) channels)");
  const std::string points = find(R"(coefficients of ([0-9]+) points)");
  std::printf("daylit room sample, synthetic year   %10s %10s\n", "command s", "peak MiB");
  std::printf("%-36s %10.2f %10.0f\n", "annual (8760 hours)", bench::median(seconds[0]), bench::median(mib[0]));
  std::printf("%-36s %10.2f %10.0f\n", "one overcast solve (reference)", bench::median(seconds[1]), bench::median(mib[1]));
  std::printf("annual phases (last run): skies %s s, solve %s s; %s patches x %s channels", skies.c_str(),
              solve.c_str(), patches.c_str(), channels.c_str());
  if (patches != "?" && channels != "?")
    std::printf(" = %.1f MiB of channels", std::stod(patches) * std::stod(channels) * 8 / 1048576.0);
  std::printf("; %s grid points\n", points.c_str());
  std::printf("ratio command seconds (annual / one solve): %.2f (medians of %d)\n",
              bench::median(seconds[0]) / bench::median(seconds[1]), repeats);
  std::printf("ratio peak memory (annual / one solve): %.2f\n", bench::median(mib[0]) / bench::median(mib[1]));
  if (house) {
    annual_log = house_run.output;
    std::printf("IFC house ground floor, one run: %.1f s (goal 600), peak %.0f MiB (goal 2048); solve %s s, %s patches "
                "x %s channels, %s grid points\n",
                house_run.seconds, house_run.peak_mib, find(R"(solved in ([0-9.]+) s)").c_str(),
                find(R"(solve: ([0-9]+) patches)").c_str(),
                find(R"(patches \(patch size [0-9.]+\), ([0-9]+) channels)").c_str(),
                find(R"(coefficients of ([0-9]+) points)").c_str());
  }
  return 0;
}
