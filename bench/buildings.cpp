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
// With --lamps L1,L2,...: one storey only, with L point luminaires per office of 6000/L
// lm each (make_office.py --lamps; 2 is the usual storey), the same light in every run:
// how a solve grows with the number of luminaires alone (goal: twice the luminaires, at
// most 1.3 times the time). Last line: "ratio: X", the most luminaires' wall seconds
// over the fewest's.
//
// Usage: bench_buildings [storeys (1,2,4,8)] [dynrad solve options...]
//        bench_buildings --lamps L1,L2,... [dynrad solve options...]
#include "bench/child.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
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

// Each office's Eavg on one storey against the path-traced reference (mesh_reference
// on the cleaned storey; tests/data/office_storey_reference.txt says how it was made):
// the goal is every office within 3%.
void compare_offices(const std::string& name) {
  std::ifstream in(DYNRAD_TEST_DATA_DIR "/office_storey_reference.txt");
  std::vector<std::array<double, 3>> reference;  // x, y, E
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::array<double, 3> p{};
    double z = 0;
    if (fields >> p[0] >> p[1] >> z >> p[2]) reference.push_back(p);
  }
  std::size_t next = 0;
  double worst = 0, sum = 0;
  int rooms = 0;
  std::printf("\n%s against the path-traced reference, each office's Eavg:", name.c_str());
  for (int room = 1;; ++room) {
    std::ifstream csv(kWork / (name + "_grid_s1_r" + std::to_string(room) + ".csv"));
    if (!csv) break;
    std::getline(csv, line);  // header
    double solved = 0, traced = 0;
    while (std::getline(csv, line)) {
      std::replace(line.begin(), line.end(), ',', ' ');
      std::istringstream fields(line);
      double x = 0, y = 0, z = 0, e = 0;
      if (!(fields >> x >> y >> z >> e)) continue;
      if (next >= reference.size() || std::abs(reference[next][0] - x) > 1e-3 || std::abs(reference[next][1] - y) > 1e-3) {
        std::printf(" the grids are not the reference's points: not compared\n");
        return;
      }
      solved += e;
      traced += reference[next++][2];
    }
    const double d = solved / traced - 1;
    std::printf(" %+.2f%%", 100 * d);
    worst = std::max(worst, std::abs(d));
    sum += std::abs(d);
    ++rooms;
  }
  if (rooms > 0) std::printf("\nworst office %.2f%%, mean %.2f%% (goal: every office within 3%%)\n", 100 * worst, 100 * sum / rooms);
}

}  // namespace

std::vector<int> numbers(const std::string& list) {
  std::vector<int> out;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::stoi(item));
  return out;
}

// The generated office (make_office.py OUT --storeys N [--lamps L]), solved; returns
// its run with the input triangles the script reported.
Result office(const std::string& name, int storeys, int lamps, const std::vector<std::string>& extra) {
  const fs::path prefix = kWork / name;
  const ChildRun made =
      run_or_exit({"python3", DYNRAD_SAMPLES_DIR "/make_office.py", prefix.string(), "--storeys",
                   std::to_string(storeys), "--lamps", std::to_string(lamps)},
                  (kWork / (name + "_make.log")).string());
  std::smatch m;
  static const std::regex count(R"((\d+) triangles)");
  const double triangles = std::regex_search(made.output, m, count) ? std::stod(m[1]) : 0;
  return solve(name, prefix.string() + ".json", triangles, extra);
}

void print_phases(const Result& r) {
  if (!r.report.contains("phases")) return;
  std::printf("\n%s, by phase:\n\n| phase | seconds | resident MiB at its end | peak MiB so far |\n|---|---|---|---|\n",
              r.name.c_str());
  for (const nlohmann::json& p : r.report["phases"])
    std::printf("| %s | %.1f | %.0f | %.0f |\n", p["name"].get<std::string>().c_str(), p["seconds"].get<double>(),
                p["resident_mib"].get<double>(), p["peak_mib"].get<double>());
}

// One storey with L luminaires per office for each L given, the same light in all.
int luminaires(const std::vector<int>& lamps, const std::vector<std::string>& extra) {
  std::printf("bench_buildings: one office storey with");
  for (int l : lamps) std::printf(" %d", 18 * l);
  std::printf(" point luminaires (324,000 lm in all); dynrad solve options:");
  for (const std::string& e : extra) std::printf(" %s", e.c_str());
  std::printf("%s\n", extra.empty() ? " none" : "");
  std::vector<Result> runs;
  for (int l : lamps) runs.push_back(office("office_1_lamps_" + std::to_string(l), 1, l, extra));
  std::printf("\n| luminaires | shots | elements | estimated error (stopped by) | wall s | peak MiB | wall s over "
              "the fewest's |\n|---|---|---|---|---|---|---|\n");
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const nlohmann::json& j = runs[k].report;
    std::printf("| %d | %zu | %zu | %.2f%% (%s) | %.1f | %.0f | %.2f |\n", 18 * lamps[k],
                j["iterations"].get<std::size_t>(), j["elements"].get<std::size_t>(),
                100 * j["estimated_error"]["total"].get<double>(), j["stopped_by"].get<std::string>().c_str(),
                runs[k].seconds, runs[k].peak_mib, runs[k].seconds / runs.front().seconds);
  }
  for (const Result& r : runs) print_phases(r);
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (lamps[k] == 2) compare_offices(runs[k].name);
  std::printf("\nratio: %.3f\n", runs.back().seconds / runs.front().seconds);
  return 0;
}

int main(int argc, char** argv) {
  std::vector<int> storeys = {1, 2, 4, 8};
  std::vector<std::string> extra;
  fs::create_directories(kWork);
  if (argc > 2 && std::string(argv[1]) == "--lamps") {
    for (int i = 3; i < argc; ++i) extra.push_back(argv[i]);
    return luminaires(numbers(argv[2]), extra);
  }
  if (argc > 1) {
    storeys = numbers(argv[1]);
    for (int i = 2; i < argc; ++i) extra.push_back(argv[i]);
  }
  std::printf("bench_buildings: office buildings of");
  for (int n : storeys) std::printf(" %d", n);
  std::printf(" storeys and the storey sample; dynrad solve options:");
  for (const std::string& e : extra) std::printf(" %s", e.c_str());
  std::printf("%s\n", extra.empty() ? " none" : "");

  std::vector<Result> offices;
  for (int n : storeys) offices.push_back(office("office_" + std::to_string(n), n, 2, extra));
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
  // Where each run's time and memory went (the report's phases).
  if (!offices.empty()) print_phases(offices.front());
  print_phases(storey);
  // One storey against its path-traced reference (tests/data/office_storey_reference.txt):
  // each office's Eavg.
  for (std::size_t k = 0; k < storeys.size(); ++k)
    if (storeys[k] == 1) compare_offices(offices[k].name);
  if (offices.size() >= 2) {
    std::printf("\nexponent of wall seconds against input triangles: %.2f (goal: at most 1.2)\n",
                exponent(offices, &Result::seconds));
    std::printf("exponent of peak memory against input triangles: %.2f\n", exponent(offices, &Result::peak_mib));
  }
  std::printf("\nratio: %.3f\n", offices.empty() ? 0.0 : offices.back().seconds / offices.front().seconds);
  return 0;
}
