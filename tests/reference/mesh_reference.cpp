// Writes the path-traced reference illuminance (tests/reference/mesh_tracer.h) at the
// points of a `dynrad solve` grid, for a mesh lit by point luminaires.
//
//   mesh_reference MESH.ply --lights SCENE.json --points GRID.csv -o OUT.txt
//                  [--target 0.003] [--seed 1] [--threads N] [--max-paths N] [--ray-offset 1e-4]
//                  [--note TEXT]...
//
// MESH.ply   as `dynrad clean MODEL -o MESH.ply` writes it (reflectance per vertex)
// SCENE.json the dynrad scene file: its "luminaires" array, point luminaires only
// GRID.csv   a grid CSV of `dynrad solve` (x,y,z,...,masked): the rows with masked 0
//
// OUT.txt gets '#' header lines (command, date, each --note, the inputs with their size
// and hash, seed, paths, time, the mean illuminance) and one line per point: x y z E std_error E_direct E_indirect
// paths (lx; E = E_direct + E_indirect, E_direct exact, std_error that of E_indirect, facing +z). It is written to
// OUT.txt.tmp and renamed when complete. Progress goes to stderr.
#include "reference/mesh_tracer.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace mt = dynrad_test::mesh_tracer;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Args {
  std::string mesh, lights, points, output, command = "mesh_reference";
  std::vector<std::string> notes;  // --note: lines for the header (how the inputs were made)
  mt::TraceOptions options;
};

struct NamedLight {
  std::string name;
  mt::PointLight light;
};

[[noreturn]] void input_error(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what);
}

// printf into a std::string.
__attribute__((format(printf, 1, 2))) std::string format(const char* pattern, ...) {
  char buffer[256];
  va_list args;
  va_start(args, pattern);
  std::vsnprintf(buffer, sizeof buffer, pattern, args);
  va_end(args);
  return buffer;
}

// The point luminaires of a dynrad scene file. Anything that would light the scene in
// a way this tool does not model is refused.
std::vector<NamedLight> read_lights(const std::string& path) {
  std::ifstream in(path);
  if (!in) input_error(path, "cannot open it");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    input_error(path, std::string("invalid JSON: ") + e.what());
  }
  if (!doc.is_object()) input_error(path, "not a dynrad scene (the top level is not an object)");
  if (doc.contains("sky")) input_error(path, "it has a \"sky\": mesh_reference models point luminaires only");
  if (!doc.contains("luminaires") || !doc["luminaires"].is_array() || doc["luminaires"].empty())
    input_error(path, "no \"luminaires\" array (or it is empty)");
  static const std::set<std::string> known = {"type", "name", "position", "lumens", "intensity", "maintenance_factor"};
  std::vector<NamedLight> out;
  for (std::size_t i = 0; i < doc["luminaires"].size(); ++i) {
    const nlohmann::json& e = doc["luminaires"][i];
    std::string where = "luminaires[" + std::to_string(i) + "]";
    if (!e.is_object()) input_error(path, where + " is not an object");
    NamedLight l;
    l.name = e.contains("name") && e["name"].is_string() ? e["name"].get<std::string>() : where;
    if (e.contains("name")) where += " (\"" + l.name + "\")";
    const std::string type = e.contains("type") && e["type"].is_string() ? e["type"].get<std::string>() : "";
    if (type != "point")
      input_error(path,
                  where + " is of type \"" + type + "\": mesh_reference handles only isotropic \"point\" luminaires");
    for (const auto& item : e.items())
      if (!known.count(item.key()))
        input_error(path, where + " has \"" + item.key() +
                              "\", which mesh_reference does not model (it knows type, name, position, lumens, "
                              "intensity, maintenance_factor)");
    auto number = [&](const nlohmann::json& v, const std::string& what) {
      if (!v.is_number() || !std::isfinite(v.get<double>())) input_error(path, where + "." + what + " is not a number");
      return v.get<double>();
    };
    if (!e.contains("position") || !e["position"].is_array() || e["position"].size() != 3)
      input_error(path, where + " needs a \"position\" [x, y, z]");
    l.light.position = {number(e["position"][0], "position"), number(e["position"][1], "position"),
                        number(e["position"][2], "position")};
    if (e.contains("lumens") == e.contains("intensity"))
      input_error(path, where + " needs exactly one of \"lumens\" and \"intensity\" (cd)");
    l.light.flux = e.contains("lumens") ? number(e["lumens"], "lumens") : 4 * kPi * number(e["intensity"], "intensity");
    if (e.contains("maintenance_factor")) l.light.flux *= number(e["maintenance_factor"], "maintenance_factor");
    if (!(l.light.flux >= 0)) input_error(path, where + " has a negative flux");
    out.push_back(l);
  }
  if (doc.contains("materials") || doc.contains("meshes")) {
    bool changes = doc.contains("materials");
    if (doc.contains("meshes") && doc["meshes"].is_array())
      for (const nlohmann::json& m : doc["meshes"])
        if (m.is_object())
          for (const char* key : {"transform", "material", "materials", "groups"}) changes = changes || m.contains(key);
    if (changes)
      std::fprintf(stderr,
                   "mesh_reference: warning: %s changes materials or transforms; the mesh must then come from "
                   "`dynrad clean %s`, not from the model file alone\n",
                   path.c_str(), path.c_str());
  }
  return out;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

// The unmasked points of a grid CSV; `rows` gets the number of data rows.
std::vector<mt::Vec3> read_points(const std::string& path, std::size_t& rows) {
  std::ifstream in(path);
  if (!in) input_error(path, "cannot open it");
  std::string line;
  if (!std::getline(in, line)) input_error(path, "it is empty");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string> header = split(line);
  int column[4] = {-1, -1, -1, -1};
  const char* names[4] = {"x", "y", "z", "masked"};
  for (std::size_t k = 0; k < header.size(); ++k)
    for (int c = 0; c < 4; ++c)
      if (header[k] == names[c]) column[c] = static_cast<int>(k);
  for (int c = 0; c < 4; ++c)
    if (column[c] < 0)
      input_error(path, std::string("the header has no \"") + names[c] +
                            "\" column (expected the grid CSV of `dynrad solve`: x,y,z,...,masked)");
  std::vector<mt::Vec3> out;
  rows = 0;
  for (int number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    ++rows;
    const std::vector<std::string> fields = split(line);
    double value[4];
    for (int c = 0; c < 4; ++c) {
      const std::size_t k = static_cast<std::size_t>(column[c]);
      char* end = nullptr;
      if (k < fields.size()) value[c] = std::strtod(fields[k].c_str(), &end);
      if (k >= fields.size() || end == fields[k].c_str() || *end != '\0' || !std::isfinite(value[c]))
        input_error(path, "line " + std::to_string(number) + ": \"" + names[c] + "\" is not a number");
    }
    if (value[3] == 0) out.push_back({value[0], value[1], value[2]});
  }
  if (out.empty()) input_error(path, rows == 0 ? "no points (no data rows)" : "no points (every row is masked)");
  return out;
}

// An argument as a shell would need it to be typed.
std::string quoted(const std::string& arg) {
  if (!arg.empty() && arg.find_first_of(" \t\"'\\$`*?;&|<>()") == std::string::npos) return arg;
  std::string out = "'";
  for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

int usage(const std::string& message) {
  std::fprintf(stderr,
               "mesh_reference: %s\nusage: mesh_reference MESH.ply --lights SCENE.json --points GRID.csv -o OUT.txt "
               "[--target REL] [--seed N] [--threads N] [--max-paths N] [--ray-offset REL] [--note TEXT]...\n",
               message.c_str());
  return 2;
}

// "N bytes, FNV-1a 64 H" of a file, so that the header identifies its inputs.
std::string fingerprint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::uint64_t hash = 0xcbf29ce484222325ULL, bytes = 0;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    const std::streamsize n = in.gcount();
    for (std::streamsize i = 0; i < n; ++i) hash = (hash ^ static_cast<unsigned char>(buffer[i])) * 0x100000001b3ULL;
    bytes += static_cast<std::uint64_t>(n);
  }
  return format("%llu bytes, FNV-1a 64 %016llx", static_cast<unsigned long long>(bytes),
                static_cast<unsigned long long>(hash));
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

// What the workers report, for the progress lines.
class Progress {
 public:
  Progress(const std::vector<mt::Vec3>& points) : points_(points), latest_(points.size()) {}

  void report(std::size_t point, const mt::Estimate& e, bool finished) {
    const std::lock_guard<std::mutex> lock(mutex_);
    latest_[point] = e;
    if (!finished) return;
    ++done_;
    const mt::Vec3& p = points_[point];
    std::fprintf(
        stderr, "mesh_reference: point %zu (%.3f, %.3f, %.3f) done, %zu/%zu: %.5g lx +- %.3g (%.2f%%), %lld paths%s\n",
        point, p.x, p.y, p.z, done_, points_.size(), e.value, e.std_error,
        e.value > 0 ? 100 * e.std_error / e.value : 0.0, static_cast<long long>(e.paths),
        e.back_share > 0.1 ? format(", %.0f%% of first rays meet backs of faces", 100 * e.back_share).c_str() : "");
  }

  // Every `period` until stop(): points done, paths so far, seconds.
  void run(std::chrono::seconds period) {
    const auto start = std::chrono::steady_clock::now();
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      if (wake_.wait_for(lock, period, [this] { return stop_; })) break;
      long long paths = 0;
      for (const mt::Estimate& e : latest_) paths += e.paths;
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "mesh_reference: progress: %zu/%zu points, %lld paths, %.0f s\n", done_, points_.size(),
                   paths, seconds);
    }
  }

  void stop() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
  }

 private:
  const std::vector<mt::Vec3>& points_;
  std::vector<mt::Estimate> latest_;
  std::size_t done_ = 0;
  bool stop_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
};

int run(const Args& args) {
  mt::Scene scene = mt::read_ply(args.mesh);
  const std::vector<NamedLight> lights = read_lights(args.lights);
  std::size_t rows = 0;
  const std::vector<mt::Vec3> points = read_points(args.points, rows);
  for (const NamedLight& l : lights) scene.lights.push_back(l.light);
  const std::size_t triangles_read = scene.triangles.size();

  // Fail on an unwritable output now, not after hours.
  const std::string temporary = args.output + ".tmp";
  if (std::FILE* probe = std::fopen(temporary.c_str(), "w")) {
    std::fclose(probe);
    std::remove(temporary.c_str());
  } else {
    throw std::runtime_error(args.output + ": cannot write " + temporary);
  }

  const int threads = args.options.threads > 0 ? args.options.threads
                                               : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const mt::Tracer tracer(std::move(scene), threads);
  std::fprintf(
      stderr, "mesh_reference: %s: %zu triangles (%zu of zero area left out), %zu lights, %zu points, %d threads\n",
      args.mesh.c_str(), tracer.triangle_count(), tracer.degenerate_triangles(), lights.size(), points.size(), threads);

  Progress progress(points);
  mt::TraceOptions options = args.options;
  options.threads = threads;
  options.progress = [&progress](std::size_t point, const mt::Estimate& e, bool finished) {
    progress.report(point, e, finished);
  };
  std::thread monitor([&progress] { progress.run(std::chrono::seconds(5)); });
  const auto start = std::chrono::steady_clock::now();
  std::vector<mt::Estimate> results;
  try {
    results = tracer.illuminance(points, {0, 0, 1}, options);
  } catch (...) {
    progress.stop();
    monitor.join();
    throw;
  }
  progress.stop();
  monitor.join();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Summary: paths, points that stopped at the cap, the mean and its standard error.
  long long total_paths = 0, fewest = results.front().paths, most = 0;
  std::size_t capped = 0, worst = 0;
  double sum = 0, variance = 0, worst_relative = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const mt::Estimate& e = results[i];
    total_paths += e.paths;
    fewest = std::min<long long>(fewest, e.paths);
    most = std::max<long long>(most, e.paths);
    const double relative = e.value > 0 ? e.std_error / e.value : 0;
    if (relative > options.target_relative_error) ++capped;
    if (relative > worst_relative) worst_relative = relative, worst = i;
    sum += e.value;
    variance += e.std_error * e.std_error;
  }
  const double n = static_cast<double>(results.size());
  const double mean = sum / n, mean_error = std::sqrt(variance) / n;

  std::FILE* file = std::fopen(temporary.c_str(), "w");
  if (!file) throw std::runtime_error(args.output + ": cannot write " + temporary);
  std::fprintf(file,
               "# Path-traced reference illuminance (tests/reference/mesh_tracer.h, independent of the solver): "
               "Lambertian front faces, backs absorb, Rec. 709 luminance of the RGB irradiance, facing +z.\n");
  std::fprintf(file, "# command: %s\n", args.command.c_str());
  std::fprintf(file, "# date: %s\n", utc_now().c_str());
  for (const std::string& note : args.notes) std::fprintf(file, "# %s\n", note.c_str());
  std::fprintf(file, "# mesh: %s (%s): %zu triangles read, %zu used (%zu of zero area left out), scene size %.4g\n",
               args.mesh.c_str(), fingerprint(args.mesh).c_str(), triangles_read, tracer.triangle_count(),
               tracer.degenerate_triangles(), tracer.scene_size());
  std::fprintf(file, "# lights: %s (%s):", args.lights.c_str(), fingerprint(args.lights).c_str());
  for (const NamedLight& l : lights)
    std::fprintf(file, " %s %.6g lm at %s;", l.name.c_str(), l.light.flux,
                 format("(%g, %g, %g)", l.light.position.x, l.light.position.y, l.light.position.z).c_str());
  std::fprintf(file, "\n# points: %s (%s): %zu of %zu rows (masked rows left out)\n", args.points.c_str(),
               fingerprint(args.points).c_str(), points.size(), rows);
  std::fprintf(file,
               "# seed %llu, target relative standard error %g, at most %lld paths per point, %d paths per replicate "
               "(at least %d replicates), roulette below %g, ray offset %g of the scene size\n",
               static_cast<unsigned long long>(options.seed), options.target_relative_error,
               static_cast<long long>(options.max_paths), options.paths_per_replicate, options.min_replicates,
               options.roulette_below, options.ray_offset);
  std::fprintf(file, "# paths: %lld in all, %lld to %lld per point; %.1f s wall on %d threads\n", total_paths, fewest,
               most, seconds, threads);
  std::fprintf(file,
               "# %zu points stopped at the path cap above the target error; worst relative standard error %.3g at "
               "(%g, %g, %g)\n",
               capped, worst_relative, points[worst].x, points[worst].y, points[worst].z);
  std::string backs;
  for (std::size_t i = 0; i < results.size(); ++i)
    if (results[i].back_share > 0.1)
      backs += format(" (%g, %g, %g) %.0f%%;", points[i].x, points[i].y, points[i].z, 100 * results[i].back_share);
  if (!backs.empty())
    std::fprintf(file,
                 "# points whose first rays meet the backs of faces more than 10%% of the time (inside or against a "
                 "solid, or under single-sided surfaces seen from behind; backs absorb):%s\n",
                 backs.c_str());
  std::fprintf(file, "# Eavg %.6g lx, standard error %.3g lx (%.3g%%), over %zu points\n", mean, mean_error,
               100 * mean_error / mean, points.size());
  std::fprintf(file,
               "# x y z E_lx std_error_lx E_direct_lx E_indirect_lx paths   (E = direct + indirect; direct exact; "
               "std_error is the indirect part's)\n");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const mt::Estimate& e = results[i];
    std::fprintf(file, "%.6g %.6g %.6g %.7g %.3g %.7g %.7g %lld\n", points[i].x, points[i].y, points[i].z, e.value,
                 e.std_error, e.direct, e.indirect, static_cast<long long>(e.paths));
  }
  if (std::fclose(file) != 0 || std::rename(temporary.c_str(), args.output.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw std::runtime_error(args.output + ": cannot write it");
  }
  std::printf(
      "%s: %zu points, Eavg %.5g lx +- %.3g, %.1f s, worst relative standard error %.3g (%zu above the target)\n",
      args.output.c_str(), points.size(), mean, mean_error, seconds, worst_relative, capped);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    args.command += " " + quoted(arg);
    const bool has_value = i + 1 < argc;
    auto value = [&]() -> std::string {
      args.command += " " + quoted(argv[i + 1]);
      return argv[++i];
    };
    try {
      if (arg == "--lights" && has_value) {
        args.lights = value();
      } else if (arg == "--points" && has_value) {
        args.points = value();
      } else if ((arg == "-o" || arg == "--output") && has_value) {
        args.output = value();
      } else if (arg == "--target" && has_value) {
        args.options.target_relative_error = std::stod(value());
      } else if (arg == "--seed" && has_value) {
        args.options.seed = std::stoull(value());
      } else if (arg == "--threads" && has_value) {
        args.options.threads = std::stoi(value());
      } else if (arg == "--max-paths" && has_value) {
        args.options.max_paths = static_cast<std::int64_t>(std::stod(value()));
      } else if (arg == "--note" && has_value) {
        args.notes.push_back(value());
      } else if (arg == "--ray-offset" && has_value) {
        args.options.ray_offset = std::stod(value());
      } else if (arg.rfind("-", 0) != 0 && args.mesh.empty()) {
        args.mesh = arg;
      } else {
        return usage("unknown or incomplete argument '" + arg + "'");
      }
    } catch (const std::exception&) {
      return usage("'" + std::string(argv[i]) + "' is not a number");
    }
  }
  if (args.mesh.empty()) return usage("no mesh (MESH.ply)");
  if (args.lights.empty()) return usage("no --lights SCENE.json");
  if (args.points.empty()) return usage("no --points GRID.csv");
  if (args.output.empty()) return usage("no output (-o OUT.txt)");
  if (!(args.options.target_relative_error > 0)) return usage("--target must be positive");
  if (args.options.max_paths < 1) return usage("--max-paths must be positive");
  if (args.options.threads < 0) return usage("--threads must be 0 (all cores) or more");
  try {
    return run(args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mesh_reference: %s\n", e.what());
    return 1;
  }
}
