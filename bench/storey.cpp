// bench_storey: the generated storey (samples/storey.obj, built as an IFC export gives a
// building: slabs under the walls, walls through slabs, furniture standing on floors),
// lit by the pipeline `dynrad solve --converge 0.01` calls (radiosity/pipeline/
// pipeline.h: cleanup, flat regions simplified, the patch size and oracle chosen from
// the model, to 1% unshot), with and without imprinting.
//
// Figures per configuration (each solve in a child process, so that its peak resident
// memory is its own):
//   elements, patches, shots, seconds to 1% unshot (median of the repeats), peak
//   resident memory, and the fringe: along lines 5 cm from every wall of every room
//   (30 cm clear of the corners, 1 m of doors, 0.5 m of windows and furniture: light
//   wedges through doors, dips under windows and shadows are real), floor irradiance
//   sampled every centimetre, fitted per run of at least 0.5 m by a polynomial of degree
//   6 in the position (least squares); the fringe is the largest |E - fit| / fit, the
//   runs' last 10 cm at each end left out (a fit follows its ends less closely).
//   A dark sawtooth along a wall's foot (vertices under the wall interpolated into the
//   floor) shows as a large fringe; a smoothly lit floor as a small one.
// Last lines: ratios with imprinting over without.
//
// Usage: bench_storey [repeats (3)] [model (samples/storey.obj)] [layout (…_layout.json)]
#include "bench/median.h"
#include "radiosity/pipeline/pipeline.h"
#include "radiosity/transfer/visibility.h"

#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace dynrad;

struct Layout {
  std::vector<std::array<double, 4>> rooms, furniture, doors, windows;  // rectangles x0, y0, x1, y1
};

Layout read_layout(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "cannot read %s\n", path.c_str());
    std::exit(2);
  }
  const nlohmann::json j = nlohmann::json::parse(in);
  Layout layout;
  auto rectangle = [](const nlohmann::json& r) {
    return std::array<double, 4>{r[0].get<double>(), r[1].get<double>(), r[2].get<double>(), r[3].get<double>()};
  };
  for (const auto& room : j.at("rooms")) layout.rooms.push_back(rectangle(room.at("rectangle")));
  for (const auto& piece : j.at("furniture")) layout.furniture.push_back(rectangle(piece.at("rectangle")));
  for (const auto& door : j.at("doors")) layout.doors.push_back(rectangle(door));
  for (const auto& window : j.at("windows")) layout.windows.push_back(rectangle(window));
  return layout;
}

// Clear of what lights the floor unevenly by nature: the wedge of light through a door
// (1 m), the dip below a window, a piece of furniture's shadow (0.5 m each).
constexpr double kDoorMargin = 1.0, kWindowMargin = 0.5, kFurnitureMargin = 0.5;
bool near(const std::array<double, 4>& r, double x, double y, double margin) {
  return x > r[0] - margin && x < r[2] + margin && y > r[1] - margin && y < r[3] + margin;
}

// Least squares polynomial of degree `degree` through (t, e), t in [-1, 1]; returns the
// fitted values (normal equations in Legendre polynomials, solved by Gaussian elimination).
std::vector<double> polynomial_fit(const std::vector<double>& t, const std::vector<double>& e, int degree) {
  const int n = degree + 1;
  auto basis = [&](double x, std::vector<double>& p) {
    p.assign(n, 1.0);
    if (n > 1) p[1] = x;
    for (int k = 2; k < n; ++k) p[k] = ((2 * k - 1) * x * p[k - 1] - (k - 1) * p[k - 2]) / k;
  };
  std::vector<std::vector<double>> a(n, std::vector<double>(n + 1, 0.0));
  std::vector<double> p;
  for (std::size_t i = 0; i < t.size(); ++i) {
    basis(t[i], p);
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) a[r][c] += p[r] * p[c];
      a[r][n] += p[r] * e[i];
    }
  }
  for (int c = 0; c < n; ++c) {
    int pivot = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    std::swap(a[c], a[pivot]);
    for (int r = 0; r < n; ++r) {
      if (r == c || a[c][c] == 0) continue;
      const double f = a[r][c] / a[c][c];
      for (int k = c; k <= n; ++k) a[r][k] -= f * a[c][k];
    }
  }
  std::vector<double> fit(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    basis(t[i], p);
    double v = 0;
    for (int k = 0; k < n; ++k) v += p[k] * (a[k][k] != 0 ? a[k][n] / a[k][k] : 0.0);
    fit[i] = v;
  }
  return fit;
}

struct Fringe {
  double fit = 0;     // the largest |E - fit| / fit
  double metres = 0;  // of lines judged
};

// Floor irradiance along lines 5 cm from the rooms' walls: its largest relative
// deviation from a smooth fit.
Fringe fringe(const SceneMesh& mesh, const rad::Solver::Output& out, const Layout& layout) {
  const rad::Visibility index(mesh);
  auto irradiance = [&](double x, double y) -> double {
    const auto hit = index.intersect({x, y, 0.05}, {0, 0, -1});
    if (!hit.hit || !hit.front || std::abs(hit.distance - 0.05) > 1e-4) return -1;
    const FaceHandle f(hit.face);
    const double w[3] = {1 - hit.u - hit.v, hit.u, hit.v};
    double b = 0;
    for (int k = 0; k < 3; ++k) b += w[k] * out.radiosity[out.split.corner[3 * hit.face + k]].luminance();
    return b / mesh.material(f).reflectance.luminance();
  };
  double worst = 0, measured = 0;
  for (const auto& room : layout.rooms) {
    // Each wall: a line 5 cm in from it, from 30 cm after one corner to 30 cm before the other.
    const std::array<std::array<double, 4>, 4> lines = {
        {{room[0] + 0.3, room[1] + 0.05, room[2] - 0.3, room[1] + 0.05},
         {room[0] + 0.3, room[3] - 0.05, room[2] - 0.3, room[3] - 0.05},
         {room[0] + 0.05, room[1] + 0.3, room[0] + 0.05, room[3] - 0.3},
         {room[2] - 0.05, room[1] + 0.3, room[2] - 0.05, room[3] - 0.3}}};
    for (const auto& line : lines) {
      const double length = std::hypot(line[2] - line[0], line[3] - line[1]);
      const int samples = static_cast<int>(length / 0.01);
      std::vector<double> run_s, run_e;
      auto close_run = [&] {
        if (run_s.size() * 0.01 >= 0.5) {
          measured += run_s.size() * 0.01;
          std::vector<double> t(run_s.size());
          for (std::size_t i = 0; i < t.size(); ++i)
            t[i] = 2 * (run_s[i] - run_s.front()) / (run_s.back() - run_s.front()) - 1;
          const auto fit = polynomial_fit(t, run_e, 6);
          // The fit's ends follow the data less closely: 10 cm at each end are not judged.
          for (std::size_t i = 10; i + 10 < t.size(); ++i) {
            const double d = std::abs(run_e[i] - fit[i]) / fit[i];
            worst = std::max(worst, d);
          }
        }
        run_s.clear();
        run_e.clear();
      };
      for (int i = 0; i <= samples; ++i) {
        const double s = i * 0.01, x = line[0] + (line[2] - line[0]) * s / length,
                     y = line[1] + (line[3] - line[1]) * s / length;
        bool excluded = false;
        for (const auto& r : layout.furniture) excluded = excluded || near(r, x, y, kFurnitureMargin);
        for (const auto& r : layout.doors) excluded = excluded || near(r, x, y, kDoorMargin);
        for (const auto& r : layout.windows) excluded = excluded || near(r, x, y, kWindowMargin);
        const double e = excluded ? -1 : irradiance(x, y);
        if (e <= 0) {
          close_run();
          continue;
        }
        run_s.push_back(s);
        run_e.push_back(e);
      }
      close_run();
    }
  }
  return {worst, measured};
}

struct Figures {
  double seconds = 0, fringe = 0, metres = 0, peak_mib = 0;
  std::size_t elements = 0, patches = 0, shots = 0;
};

Figures solve_once(const std::string& model, const Layout& layout, bool imprint) {
  rad::SceneRequest request;
  request.path = model;
  request.cleanup.imprint = imprint;
  request.simplify.enabled = true;
  request.settings.converge = 0.01;
  rad::PreparedScene prepared = rad::prepare_scene(request);
  const rad::SolvedScene solved = rad::solve_scene(prepared);
  const rad::SolveReport& report = solved.report;
  Figures f;
  f.seconds = report.seconds;
  f.elements = report.elements;
  f.patches = report.patches;
  f.shots = report.iterations;
  f.peak_mib = static_cast<double>(rad::peak_resident_memory()) / (1024 * 1024);
  const Fringe fr = fringe(*prepared.scene.mesh, solved.output, layout);
  f.fringe = fr.fit;
  f.metres = fr.metres;
  return f;
}

// Runs solve_once in a child process and reads its figures back through a pipe.
Figures solve_in_child(const std::string& model, const Layout& layout, bool imprint) {
  int fd[2];
  if (pipe(fd) != 0) std::exit(1);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    const Figures f = solve_once(model, layout, imprint);
    const std::string text = std::to_string(f.seconds) + " " + std::to_string(f.fringe) + " " +
                             std::to_string(f.metres) + " " + std::to_string(f.peak_mib) + " " +
                             std::to_string(f.elements) + " " + std::to_string(f.patches) + " " +
                             std::to_string(f.shots);
    if (write(fd[1], text.data(), text.size()) < 0) _exit(1);
    _exit(0);
  }
  close(fd[1]);
  std::string text;
  char buffer[256];
  for (ssize_t n; (n = read(fd[0], buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  Figures f;
  if (std::sscanf(text.c_str(), "%lf %lf %lf %lf %zu %zu %zu", &f.seconds, &f.fringe, &f.metres, &f.peak_mib,
                  &f.elements, &f.patches, &f.shots) != 7) {
    std::fprintf(stderr, "a solve failed (status %d)\n", status);
    std::exit(1);
  }
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 3;
  const std::string model = argc > 2 ? argv[2] : DYNRAD_SAMPLES_DIR "/storey.obj";
  const std::string layout_path =
      argc > 3 ? argv[3] : model.substr(0, model.size() - std::string(".obj").size()) + "_layout.json";
  const Layout layout = read_layout(layout_path);
  std::printf("%s, dynamic subdivision with the defaults, to 1%% unshot; %d runs each\n", model.c_str(), repeats);
  std::printf("%-18s %9s %8s %6s %13s %9s %8s\n", "imprinting", "elements", "patches", "shots", "seconds (med)",
              "peak MiB", "fringe");
  Figures result[2];
  for (int imprint = 0; imprint < 2; ++imprint) {
    std::vector<double> seconds;
    for (int r = 0; r < repeats; ++r) {
      result[imprint] = solve_in_child(model, layout, imprint == 1);
      seconds.push_back(result[imprint].seconds);
    }
    result[imprint].seconds = bench::median(seconds);
    const Figures& f = result[imprint];
    std::printf("%-18s %9zu %8zu %6zu %13.2f %9.0f %7.2f%%\n", imprint ? "on" : "off (--no-imprint)", f.elements,
                f.patches, f.shots, f.seconds, f.peak_mib, 100 * f.fringe);
  }
  std::printf("fringe judged along %.1f m of lines 5 cm from the walls\n", result[1].metres);
  std::printf("elements ratio: %.3f\n", double(result[1].elements) / double(result[0].elements));
  std::printf("memory ratio: %.3f\n", result[1].peak_mib / result[0].peak_mib);
  std::printf("ratio: %.3f\n", result[1].seconds / result[0].seconds);
  return 0;
}
