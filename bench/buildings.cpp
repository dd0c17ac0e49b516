// bench_buildings: how the cost of a solve grows with the size of a building. A furnished
// office building of 1, 2, 4 and 8 storeys (samples/make_office.py: every element closed
// triangulated solids as IFC exports give them, 87,500 triangles a storey, two 3000 lm
// point luminaires and a work plane per office), and the storey sample
// (samples/storey_luminaires.json), each solved by the built `dynrad` as a user runs it:
//
//   dynrad solve office_N.json -o office_N.ply --report R.json [options]
//
// in a child process of its own (wall seconds, peak resident memory). Printed per model:
// input triangles, patches, sender groups and clusters, shots, elements, estimated
// error, why it stopped, wall seconds and peak memory; then the exponents b of
// seconds = a * triangles^b and of memory, fitted by least squares over the office
// buildings (goal: at most 1.2, nearly linear).
//
// Last line: "ratio: X", the largest building's wall seconds over the smallest's.
//
// Usage: bench_buildings [storeys (1,2,4,8)] [dynrad solve options...]
#include "bench/child.h"

#include <nlohmann/json.hpp>

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
using dynrad::bench::run_or_exit;

const fs::path kWork = fs::temp_directory_path() / "dynrad_bench_buildings";

struct Result {
  std::string name;
  double triangles = 0, seconds = 0, peak_mib = 0;
  nlohmann::json report;
};

Result solve(const std::string& name, const std::string& scene, double triangles, const std::vector<std::string>& extra) {
  Result r;
  r.name = name;
  r.triangles = triangles;
  const fs::path report = kWork / (name + "_report.json");  // not name.json: the scene
  std::vector<std::string> argv = {DYNRAD_CLI, "solve", scene, "-o", (kWork / (name + ".ply")).string(), "--report",
                                   report.string()};
  argv.insert(argv.end(), extra.begin(), extra.end());
  const ChildRun run = run_or_exit(argv, (kWork / (name + ".log")).string());
  r.seconds = run.seconds;
  r.peak_mib = run.peak_mib;
  std::ifstream in(report);
  r.report = nlohmann::json::parse(in);
  std::fprintf(stderr, "  %s: %.1f s, %.0f MiB\n", name.c_str(), r.seconds, r.peak_mib);
  return r;
}

// Least-squares slope of log y against log x.
double exponent(const std::vector<Result>& results, double Result::*y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(results.size());
  for (const Result& r : results) {
    const double lx = std::log(r.triangles), ly = std::log(r.*y);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> storeys = {1, 2, 4, 8};
  std::vector<std::string> extra;
  if (argc > 1) {
    storeys.clear();
    std::stringstream list(argv[1]);
    std::string item;
    while (std::getline(list, item, ',')) storeys.push_back(std::stoi(item));
    for (int i = 2; i < argc; ++i) extra.push_back(argv[i]);
  }
  fs::create_directories(kWork);
  std::printf("bench_buildings: office buildings of");
  for (int n : storeys) std::printf(" %d", n);
  std::printf(" storeys and the storey sample; dynrad solve options:");
  for (const std::string& e : extra) std::printf(" %s", e.c_str());
  std::printf("%s\n", extra.empty() ? " none" : "");

  std::vector<Result> offices;
  for (int n : storeys) {
    const std::string name = "office_" + std::to_string(n);
    const fs::path prefix = kWork / name;
    const ChildRun made = run_or_exit({"python3", DYNRAD_SAMPLES_DIR "/make_office.py", prefix.string(), "--storeys",
                                       std::to_string(n)},
                                      (kWork / (name + "_make.log")).string());
    std::smatch m;
    static const std::regex count(R"((\d+) triangles)");
    const double triangles = std::regex_search(made.output, m, count) ? std::stod(m[1]) : 0;
    offices.push_back(solve(name, prefix.string() + ".json", triangles, extra));
  }
  const Result storey = solve("storey", DYNRAD_SAMPLES_DIR "/storey_luminaires.json", 848, extra);

  std::printf("\n| model | input triangles | patches | groups, clusters | shots | elements | estimated error "
              "(stopped by) | wall s | peak MiB |\n|---|---|---|---|---|---|---|---|---|\n");
  auto row = [](const Result& r) {
    const nlohmann::json& j = r.report;
    std::printf("| %s | %.0f | %zu | %zu, %zu | %zu | %zu | %.2f%% (%s) | %.1f | %.0f |\n", r.name.c_str(), r.triangles,
                j["patches"].get<std::size_t>(), j["sender_groups"]["groups"].get<std::size_t>(),
                j["clusters"]["clusters"].get<std::size_t>(), j["iterations"].get<std::size_t>(),
                j["elements"].get<std::size_t>(), 100 * j["estimated_error"]["total"].get<double>(),
                j["stopped_by"].get<std::string>().c_str(), r.seconds, r.peak_mib);
  };
  for (const Result& r : offices) row(r);
  row(storey);
  if (offices.size() >= 2) {
    std::printf("\nexponent of wall seconds against input triangles: %.2f (goal: at most 1.2)\n",
                exponent(offices, &Result::seconds));
    std::printf("exponent of peak memory against input triangles: %.2f\n", exponent(offices, &Result::peak_mib));
  }
  std::printf("\nratio: %.3f\n", offices.empty() ? 0.0 : offices.back().seconds / offices.front().seconds);
  return 0;
}
