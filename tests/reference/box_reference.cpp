// Writes the path-traced reference for the 1990 globillum comparison room: radiosity
// and its standard error at the 480 comparison points (globillum_room.h), or with
// --walls at the 384 points of its walls' grid.
//
//   box_reference OUTPUT [--obstructed] [--walls] [--target REL] [--seed N] [--threads N]
//
// Every point is traced on its own (no use of the room's symmetries), so mirrored
// points are independent estimates and can check each other. The file is written
// to OUTPUT.tmp and renamed when complete.
#include "reference/box_tracer.h"
#include "reference/globillum_room.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <thread>

namespace ref = dynrad_test::reference;

namespace {

int usage(const char* message) {
  std::fprintf(stderr,
               "box_reference: %s\nusage: box_reference OUTPUT [--obstructed] [--walls] [--target REL] [--seed N] "
               "[--threads N]\n",
               message);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string output, command = "box_reference";
  bool obstructed = false, walls = false;
  ref::TraceOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    command += " " + arg;
    const bool has_value = i + 1 < argc;
    try {
      if (arg == "--obstructed") {
        obstructed = true;
      } else if (arg == "--walls") {
        walls = true;
      } else if (arg == "--target" && has_value) {
        options.target_relative_error = std::stod(argv[++i]);
        command += std::string(" ") + argv[i];
      } else if (arg == "--seed" && has_value) {
        options.seed = std::stoull(argv[++i]);
        command += std::string(" ") + argv[i];
      } else if (arg == "--threads" && has_value) {
        options.threads = std::stoi(argv[++i]);
        command += std::string(" ") + argv[i];
      } else if (arg.rfind("--", 0) != 0 && output.empty()) {
        output = arg;
      } else {
        return usage(("unknown or incomplete argument '" + arg + "'").c_str());
      }
    } catch (const std::exception&) {
      return usage(("'" + std::string(argv[i]) + "' is not a number").c_str());
    }
  }
  if (output.empty()) return usage("no output file");
  if (!(options.target_relative_error > 0)) return usage("--target must be positive");

  const ref::BoxScene scene = ref::globillum_room(obstructed);
  const std::vector<ref::ReferencePoint> points = walls ? ref::globillum_wall_points() : ref::globillum_points();
  std::vector<ref::SurfacePoint> at;
  for (const ref::ReferencePoint& p : points) at.push_back(p.at);

  const auto start = std::chrono::steady_clock::now();
  std::vector<ref::Estimate> b;
  try {
    b = ref::radiosity(scene, at, options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "box_reference: %s\n", e.what());
    return 1;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::int64_t paths = 0, fewest = b.front().samples, most = 0;
  double worst = 0;
  for (const ref::Estimate& e : b) {
    paths += e.samples;
    fewest = std::min(fewest, e.samples);
    most = std::max(most, e.samples);
    worst = std::max(worst, e.std_error / e.value);
  }
  const int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());

  const std::string temporary = output + ".tmp";
  std::FILE* file = std::fopen(temporary.c_str(), "w");
  if (!file) {
    std::fprintf(stderr, "box_reference: cannot write %s\n", temporary.c_str());
    return 1;
  }
  std::fprintf(file,
               "# Path-traced reference (tests/reference/box_tracer.h): the 1990 globillum comparison room%s.\n"
               "# Room 10 x 6 x 3 m, source 0.5 x 0.5 m centred in the ceiling, 31.416 W/m^2; reflectance ceiling "
               "0.70, walls 0.50, floor 0.30%s.\n"
               "# command: %s\n"
               "# seed %llu, target relative standard error %g, %d paths per replicate\n"
               "# %zu points, %lld paths (%lld to %lld per point), %.1f s on %d threads; worst relative standard "
               "error %.5f\n"
               "%s"
               "# surface x y z B(W/m^2) std_error(W/m^2)\n",
               obstructed ? ", obstructed" : "",
               obstructed ? "; partitions 0.1 m thick, full height, centred on x = 3 (y 3..6) and x = 7 (y 0..3), "
                            "reflectance 0.50"
                          : "",
               command.c_str(), static_cast<unsigned long long>(options.seed), options.target_relative_error,
               options.paths_per_replicate, points.size(), static_cast<long long>(paths),
               static_cast<long long>(fewest), static_cast<long long>(most), seconds, threads, worst,
               walls ? "# The walls' 0.5 m grid, 0.25 m in from their edges (globillum_wall_points()).\n"
                     : "# Ceiling points (4.75 or 5.25, 2.75 or 3.25) are the source's corners; B there is the "
                       "ceiling's.\n");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ref::Vec3& p = points[i].at.point;
    std::fprintf(file, "%s %.2f %.2f %.2f %.7g %.3g\n", points[i].surface.c_str(), p.x, p.y, p.z, b[i].value,
                 b[i].std_error);
  }
  if (std::fclose(file) != 0 || std::rename(temporary.c_str(), output.c_str()) != 0) {
    std::fprintf(stderr, "box_reference: cannot write %s\n", output.c_str());
    std::remove(temporary.c_str());
    return 1;
  }
  std::printf("%s: %zu points, %.1f s, worst relative standard error %.5f\n", output.c_str(), points.size(), seconds,
              worst);
  return 0;
}
