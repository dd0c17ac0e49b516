// bench_defaults: what `dynrad solve MODEL -o OUT.ply` gives with no options at all,
// beside what the old defaults gave (progressive refinement, patches a tenth of the
// diagonal, stop at 1% unshot, no ambient term). Every run is the command line itself,
// in a child process, as a user runs it; accuracy is read back with `dynrad probe`.
//
//   1990 room: mean and largest relative error over the comparison grid on floor and
//     ceiling (476 points: the 4 ceiling points on the source's corners are left out)
//     against the path-traced reference tests/data/globillum_room_reference.txt
//     (tests/reference/box_tracer.h: 0.1% standard error per point); solve seconds
//     from the report, median of the runs.
//   furnace: a unit cube whose faces all emit 1 and reflect 0.5; B = 2 everywhere:
//     largest and mean relative error over the written vertices.
//   storey: samples/storey.obj (or the model given), seconds and elements.
//
// Usage: bench_defaults [runs (5)] [storey model]
#include "bench/median.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using dynrad::bench::median;

const std::string kDynrad = DYNRAD_CLI;
const fs::path kWork = fs::temp_directory_path() / "dynrad_bench_defaults";

void run(const std::string& command) {
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "failed: %s\n", command.c_str());
    std::exit(1);
  }
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

struct ReferencePoint {
  bool floor;
  double x, y, z, b;
};

std::vector<ReferencePoint> read_reference() {
  std::ifstream in(DYNRAD_TEST_DATA_DIR "/globillum_room_reference.txt");
  if (!in) {
    std::fprintf(stderr, "cannot read %s\n", DYNRAD_TEST_DATA_DIR "/globillum_room_reference.txt");
    std::exit(1);
  }
  std::vector<ReferencePoint> points;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string surface;
    ReferencePoint p{};
    fields >> surface >> p.x >> p.y >> p.z >> p.b;
    p.floor = surface == "floor";
    const bool source_corner = !p.floor && (p.x == 4.75 || p.x == 5.25) && (p.y == 2.75 || p.y == 3.25);
    if (!source_corner) points.push_back(p);
  }
  return points;
}

struct Accuracy {
  double mean = 0, max = 0, floor_signed = 0, ceiling_signed = 0;
};

Accuracy compare(const fs::path& lit, const std::vector<ReferencePoint>& reference) {
  const fs::path points = kWork / "points.txt", probed = kWork / "probe.json";
  {
    std::ofstream out(points);
    out.precision(17);
    for (const auto& p : reference) out << p.x << ' ' << p.y << ' ' << p.z << " 0 0 " << (p.floor ? 1 : -1) << '\n';
  }
  run(kDynrad + " probe '" + lit.string() + "' --points '" + points.string() + "' --json -o '" + probed.string() + "'");
  const nlohmann::json j = read_json(probed);
  Accuracy a;
  std::size_t floors = 0, ceilings = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double b = j["points"][i]["radiosity"][1].get<double>();
    const double e = (b - reference[i].b) / reference[i].b;
    a.mean += std::abs(e) / static_cast<double>(reference.size());
    a.max = std::max(a.max, std::abs(e));
    (reference[i].floor ? a.floor_signed : a.ceiling_signed) += e;
    ++(reference[i].floor ? floors : ceilings);
  }
  a.floor_signed /= static_cast<double>(floors);
  a.ceiling_signed /= static_cast<double>(ceilings);
  return a;
}

// The written vertices' green radiosity, from an ASCII PLY.
std::vector<double> read_green(const fs::path& ply) {
  std::ifstream in(ply);
  std::string line;
  std::size_t vertices = 0;
  int property = 0, green = -1;
  bool in_vertex = false;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream f(line);
    std::string word, type, name;
    f >> word;
    if (word == "element") {
      std::size_t count = 0;
      f >> name >> count;
      in_vertex = name == "vertex";
      if (in_vertex) vertices = count;
    } else if (word == "property" && in_vertex) {
      f >> type >> name;
      if (name == "radiosity_g") green = property;
      ++property;
    }
  }
  std::vector<double> out;
  while (out.size() < vertices && std::getline(in, line)) {
    std::istringstream f(line);
    double v = 0;
    for (int k = 0; k <= green; ++k) f >> v;
    out.push_back(v);
  }
  return out;
}

fs::path write_furnace() {
  const fs::path obj = kWork / "furnace.obj";
  std::ofstream(kWork / "furnace.mtl") << "newmtl glow\nKd 0.5 0.5 0.5\nKe 1 1 1\n";
  std::ofstream(obj) << "mtllib furnace.mtl\nusemtl glow\n"
                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                        "f 1 4 8 5\nf 2 6 7 3\nf 1 5 6 2\nf 4 3 7 8\nf 1 2 3 4\nf 5 8 7 6\n";
  return obj;
}

struct Config {
  std::string name, options;
};

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string storey = argc > 2 ? argv[2] : DYNRAD_SAMPLES_DIR "/storey.obj";
  fs::create_directories(kWork);
  const std::vector<Config> configs = {
      {"defaults (no options)", ""},
      {"old defaults", "--method progressive --no-ambient --converge 0.01"},
  };
  const std::vector<ReferencePoint> reference = read_reference();
  const fs::path lit = kWork / "lit.ply", report = kWork / "report.json";
  auto solve = [&](const std::string& model, const Config& c, const std::string& extra = "") {
    run(kDynrad + " solve '" + model + "' -o '" + lit.string() + "' --report '" + report.string() + "' -q " +
        c.options + extra);
    return read_json(report);
  };

  std::printf("1990 room (samples/globillum_room.obj) against the path-traced reference, %zu points; %d runs\n",
              reference.size(), runs);
  std::printf("%-24s %9s %9s %9s %9s %9s %7s %9s %10s\n", "configuration", "mean", "max", "floor", "ceiling",
              "estimate", "shots", "elements", "seconds");
  double seconds_of[2] = {0, 0};
  for (std::size_t c = 0; c < configs.size(); ++c) {
    std::vector<double> seconds;
    nlohmann::json last;
    for (int r = 0; r < runs; ++r) {
      last = solve(DYNRAD_SAMPLES_DIR "/globillum_room.obj", configs[c]);
      seconds.push_back(last["seconds"].get<double>());
    }
    const Accuracy a = compare(lit, reference);
    seconds_of[c] = median(seconds);
    std::printf("%-24s %8.3f%% %8.3f%% %+8.3f%% %+8.3f%% %8.3f%% %7d %9d %10.3f\n", configs[c].name.c_str(),
                100 * a.mean, 100 * a.max, 100 * a.floor_signed, 100 * a.ceiling_signed,
                100 * last["estimated_error"]["total"].get<double>(), last["iterations"].get<int>(),
                last["elements"].get<int>(), seconds_of[c]);
  }

  const fs::path furnace = write_furnace();
  std::printf("\nfurnace (unit cube, every face emits 1 and reflects 0.5: B = 2 everywhere)\n");
  std::printf("%-24s %9s %9s %9s %9s\n", "configuration", "worst", "mean", "vertices", "seconds");
  for (const Config& c : configs) {
    const nlohmann::json j = solve(furnace.string(), c, " --ascii");
    const std::vector<double> green = read_green(lit);
    double worst = 0, mean = 0;
    for (double b : green) {
      worst = std::max(worst, std::abs(b - 2) / 2);
      mean += std::abs(b - 2) / 2 / static_cast<double>(green.size());
    }
    std::printf("%-24s %8.3f%% %8.3f%% %9zu %9.3f\n", c.name.c_str(), 100 * worst, 100 * mean, green.size(),
                j["seconds"].get<double>());
  }

  std::printf("\nstorey (%s)\n", storey.c_str());
  std::printf("%-24s %9s %9s %9s %10s\n", "configuration", "estimate", "shots", "elements", "seconds");
  for (const Config& c : configs) {
    const nlohmann::json j = solve(storey, c);
    std::printf("%-24s %8.3f%% %9d %9d %10.2f\n", c.name.c_str(), 100 * j["estimated_error"]["total"].get<double>(),
                j["iterations"].get<int>(), j["elements"].get<int>(), j["seconds"].get<double>());
  }
  std::printf("ratio: %.3f (1990 room, defaults' seconds over the old defaults')\n", seconds_of[0] / seconds_of[1]);
  return 0;
}
