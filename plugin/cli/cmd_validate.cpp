// `dynrad validate`: the analytical cases of CIE 171:2006 (plugin/validate/cases.h),
// each written as a scene, lit by this program's own `solve` and read back with its
// own `probe` (child processes, as a user runs them), and compared with references
// that share no code with the solver (plugin/validate/reference.h). It prints, per
// case, the worst and mean error against this project's goal and CIE's tolerance, and
// exits with kExitValidation when any case misses its goal.
#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "mesh/io/io_util.h"
#include "plugin/cli/commands.h"
#include "plugin/cli/lit_mesh.h"
#include "plugin/cli/validate_report.h"
#include "plugin/validate/cases.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include <spawn.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

extern char** environ;

namespace dynrad::cli {
namespace {

// A first SIGINT/SIGTERM stops the run after the current case (whose solve, which gets
// the signal too, stops early and is left out); the default action is then restored,
// so a second one ends the program at once. What is done so far is reported and
// written, and the work folder removed unless kept.
std::atomic<bool> g_validate_stop{false};
extern "C" void on_validate_signal(int signal_number) {
  g_validate_stop.store(true);
  std::signal(signal_number, SIG_DFL);
}

namespace fs = std::filesystem;

struct ValidateOptions {
  std::vector<std::string> cases;  // ids ("5.11") or id/variant prefixes; all when empty
  std::vector<std::string> skip;   // the same, left out
  std::string json, html, keep;
  std::string quality;  // passed to every solve; the solve's default when empty
  // Passed to every solve as --converge when above 0: shoot until this fraction of the
  // light is unshot, so that what is measured is the mesh and the transfers alone, not
  // where the solve's error estimate stops it.
  double converge = 0;
  bool list = false;
};

// Runs this program with `arguments`, its output to `log`. Returns the exit code.
int run_self(const std::vector<std::string>& arguments, const fs::path& log) {
  std::vector<std::string> all = {"/proc/self/exe"};
  all.insert(all.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  char self[4096];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) throw std::runtime_error("cannot find this program (/proc/self/exe)");
  self[n] = 0;
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, self, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error(std::string("cannot run ") + self + ": " + std::strerror(spawned));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("waitpid failed");
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

struct Compared {
  std::string where;  // "mesh (1.25, 0.25, 0)", "grid work_plane (...)", "area floor"
  double value = 0, reference = 0;
  double error = 0;   // judged: relative, or against 1% of the case's largest reference (relative())
  double strict = 0;  // relative to the reference alone
};

struct Outcome {
  const validate::Case* c = nullptr;
  std::vector<Compared> points;
  double worst = 0, mean = 0, strict_worst = 0, seconds = 0;
  std::size_t floored = 0;  // points judged against 1% of the largest reference
  std::string worst_where, failure;
  std::string picture;  // the first grid's false-colour plan (a PNG the solve wrote), if any
  bool passed() const { return failure.empty() && worst <= c->goal; }
};

// The error a point is judged by: relative to its reference, or where the reference
// is below 1% of `scale` (the case's largest reference: a point in a shadow or in deep
// shade), relative to 1% of it. A lighting designer reads lux: 0.2 lx off at a point
// of 0.8 lx in a room of 700 lx is 25% of the point and 0.03% of the room.
constexpr double kShadeFloor = 0.01;
double relative(double value, double reference, double scale) {
  return std::abs(value - reference) / std::max(std::abs(reference), kShadeFloor * scale);
}

Outcome run_case(const validate::Case& c, const fs::path& dir, const ValidateOptions& options) {
  Outcome out;
  out.c = &c;
  const auto start = std::chrono::steady_clock::now();
  fs::create_directories(dir);
  for (const auto& [name, text] : c.files) std::ofstream(dir / name) << text;
  const fs::path scene = dir / c.files.front().first, lit = dir / "lit.ply";
  std::vector<std::string> solve = {"solve", scene.string(), "-o", lit.string(), "--report",
                                    (dir / "report.json").string(), "-q"};
  solve.insert(solve.end(), c.options.begin(), c.options.end());
  if (!options.quality.empty()) solve.insert(solve.end(), {"--quality", options.quality});
  if (options.converge > 0) solve.insert(solve.end(), {"--converge", fmt::format("{}", options.converge)});
  if (const int code = run_self(solve, dir / "solve.log"); code != 0) {
    out.failure = fmt::format("solve exited with {}: {}", code, detail::read_file((dir / "solve.log").string()));
    return out;
  }
  // The lit mesh at points.
  std::vector<Compared> compared;
  std::vector<std::pair<Vec3d, Vec3d>> where;
  if (!c.mesh_points.empty()) {
    std::string points;
    for (const auto& [p, n] : c.mesh_points) points += fmt::format("{} {} {} {} {} {}\n", p[0], p[1], p[2], n[0], n[1], n[2]);
    std::ofstream(dir / "points.txt") << points;
    const int code = run_self({"probe", "--json", lit.string(), "--points", (dir / "points.txt").string(), "-o",
                               (dir / "probe.json").string()},
                              dir / "probe.log");
    if (code != 0) {
      out.failure = fmt::format("probe exited with {}: {}", code, detail::read_file((dir / "probe.log").string()));
      return out;
    }
    const nlohmann::json probed = nlohmann::json::parse(detail::read_file((dir / "probe.json").string()));
    for (std::size_t i = 0; i < c.mesh_points.size(); ++i) {
      const Vec3d& p = c.mesh_points[i].first;
      compared.push_back({fmt::format("mesh ({:.3g}, {:.3g}, {:.3g})", p[0], p[1], p[2]),
                          probed["points"][i]["illuminance"].get<double>(), 0, 0});
      where.push_back(c.mesh_points[i]);
    }
  }
  // Every point of the scene's grids (solve writes lit_grid_NAME.csv).
  for (const std::string& grid : c.grids) {
    if (out.picture.empty() && fs::exists(dir / ("lit_grid_" + grid + ".png")))
      out.picture = (dir / ("lit_grid_" + grid + ".png")).string();
    std::ifstream csv(dir / ("lit_grid_" + grid + ".csv"));
    if (!csv) {
      out.failure = "no grid " + grid + " in the solve's output";
      return out;
    }
    std::string line;
    std::getline(csv, line);  // header: x,y,z,illuminance_lx,...
    while (std::getline(csv, line)) {
      double x = 0, y = 0, z = 0, e = 0;
      if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &x, &y, &z, &e) != 4) continue;
      compared.push_back({fmt::format("grid {} ({:.3g}, {:.3g}, {:.3g})", grid, x, y, z), e, 0, 0});
      where.push_back({Vec3d(x, y, z), Vec3d(0, 0, 1)});
    }
  }
  // References, in parallel (numerical integrals over openings).
  tbb::parallel_for(std::size_t(0), where.size(),
                    [&](std::size_t i) { compared[i].reference = c.reference(where[i].first, where[i].second); });
  double scale = 0;
  for (const Compared& p : compared) scale = std::max(scale, std::abs(p.reference));
  for (Compared& p : compared) {
    p.error = relative(p.value, p.reference, scale);
    p.strict = std::abs(p.reference) > 0 ? std::abs(p.value - p.reference) / std::abs(p.reference) : p.error;
    if (std::abs(p.reference) < kShadeFloor * scale) ++out.floored;
  }
  // Areas of the lit mesh: the illuminance integrated over their triangles.
  if (!c.areas.empty()) {
    const LitMesh mesh = read_lit(lit.string());
    if (mesh.illuminance.size() != mesh.positions.size()) {
      out.failure = "the lit mesh has no illuminance (not a photometric solve)";
      return out;
    }
    for (const validate::AreaCheck& a : c.areas) {
      double flux = 0;
      for (const auto& t : mesh.triangles) {
        const Vec3d& p0 = mesh.positions[t[0]];
        const Vec3d& p1 = mesh.positions[t[1]];
        const Vec3d& p2 = mesh.positions[t[2]];
        const Vec3d centroid = (p0 + p1 + p2) / 3.0;
        bool inside = true;
        for (int k = 0; k < 3; ++k) inside = inside && centroid[k] >= a.lo[k] && centroid[k] <= a.hi[k];
        const Vec3d cross = OpenMesh::cross(p1 - p0, p2 - p0);
        if (!inside || !(cross.norm() > 0)) continue;
        if (a.normal.norm() > 0 && OpenMesh::dot(cross.normalized(), a.normal) < 0.999) continue;
        flux += 0.5 * cross.norm() * (mesh.illuminance[t[0]] + mesh.illuminance[t[1]] + mesh.illuminance[t[2]]) / 3;
      }
      const double part = a.reference - a.base;
      const double error = std::abs(flux - a.reference) / (std::abs(part) > 0 ? std::abs(part) : std::abs(a.base));
      compared.push_back({"area " + a.label, flux - a.base, part, error, error});
    }
  }
  if (compared.empty()) out.failure = "nothing compared";
  for (const Compared& p : compared) {
    out.mean += p.error / static_cast<double>(compared.size());
    out.strict_worst = std::max(out.strict_worst, p.strict);
    if (p.error >= out.worst) {
      out.worst = p.error;
      out.worst_where = p.where;
    }
  }
  out.points = std::move(compared);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

// Runs of blanks as one space, none at the ends: a line copied from --list matches.
std::string collapse_blanks(const std::string& text) {
  std::string out;
  for (char ch : text) {
    const bool blank = ch == ' ' || ch == '\t';
    if (!blank) out.push_back(ch);
    else if (!out.empty() && out.back() != ' ') out.push_back(' ');
  }
  if (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// A case is named by its id, by the start of "id variant", or by the start of a line
// of --list ("id title variant").
bool matches(const std::vector<std::string>& patterns, const validate::Case& c) {
  for (const std::string& s : patterns) {
    const std::string p = collapse_blanks(s);
    if (p.empty()) continue;
    if (p == c.id || (c.id + " " + c.variant).rfind(p, 0) == 0 ||
        collapse_blanks(c.id + " " + c.title + " " + c.variant).rfind(p, 0) == 0)
      return true;
  }
  return false;
}

bool selected(const ValidateOptions& options, const validate::Case& c) {
  return (options.cases.empty() || matches(options.cases, c)) && !matches(options.skip, c);
}

int run_validate(const ValidateOptions& options) {
  const std::vector<validate::Case> cases = validate::cie171_cases();
  if (options.list) {
    for (const validate::Case& c : cases)
      std::cout << fmt::format("{:<5} {:<40} {}\n", c.id, c.title, c.variant);
    return kExitOk;
  }
  std::vector<const validate::Case*> chosen;
  for (const validate::Case& c : cases)
    if (selected(options, c)) chosen.push_back(&c);
  if (chosen.empty())
    throw InputError("--case", 0, "no case matches; `dynrad validate --list` lists them (give an id such as 5.11).");
  if (!options.json.empty()) check_output_writable(options.json);
  if (!options.html.empty()) check_output_writable(options.html);
  fs::path base;
  if (!options.keep.empty()) {
    base = options.keep;
  } else {
    char pattern[] = "/tmp/dynrad-validate-XXXXXX";
    if (!mkdtemp(pattern)) throw std::runtime_error("cannot make a temporary folder in /tmp");
    base = pattern;
  }
  std::string how = options.quality.empty() ? "the default (normal)" : options.quality;
  how += " quality";
  if (options.converge > 0) how += fmt::format(", shot until {:g}% of the light is unshot", 100 * options.converge);
  std::cout << fmt::format("CIE 171:2006 analytical cases, {} runs at {} (work in {})\n", chosen.size(), how,
                           base.string());
  std::cout << "errors relative to the reference; where it is below 1% of the case's largest (shade), to that 1% "
               "(\"strict\": to the reference alone)\n";
  std::cout << fmt::format("{:<5} {:<40} {:<34} {:>6} {:>8} {:>8} {:>6} {:>5} {:>8}  {}\n", "case", "what", "variant",
                           "points", "worst", "mean", "goal", "CIE", "strict", "worst at");
  std::vector<Outcome> outcomes;
  bool all_passed = true;
  // The handlers hold while the cases run, and go however this function ends.
  struct SignalGuard {
    SignalGuard() {
      g_validate_stop.store(false);
      std::signal(SIGINT, on_validate_signal);
      std::signal(SIGTERM, on_validate_signal);
    }
    ~SignalGuard() {
      std::signal(SIGINT, SIG_DFL);
      std::signal(SIGTERM, SIG_DFL);
    }
  } signals;
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const validate::Case& c = *chosen[k];
    std::string folder = fmt::format("{:02}_{}_{}", k, c.id, c.variant);
    for (char& ch : folder)
      if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '_') ch = '_';
    Outcome o = run_case(c, base / folder, options);
    if (g_validate_stop.load()) break;
    all_passed = all_passed && o.passed();
    if (!o.failure.empty())
      std::cout << fmt::format("{:<5} {:<40} {:<34} FAILED: {}\n", c.id, c.title, c.variant, o.failure);
    else
      std::cout << fmt::format("{:<5} {:<40} {:<34} {:>6} {:>7.3f}% {:>7.3f}% {:>5.1f}% {:>4.0f}% {:>7.2f}%  {}{}\n",
                               c.id, c.title, c.variant, o.points.size(), 100 * o.worst, 100 * o.mean, 100 * c.goal,
                               100 * c.cie_tolerance, 100 * o.strict_worst, o.worst_where,
                               o.passed() ? "" : "   ** over the goal **");
    std::cout.flush();
    outcomes.push_back(std::move(o));
  }
  if (!options.json.empty() || !options.html.empty()) {
    nlohmann::json j = nlohmann::json::array();
    for (const Outcome& o : outcomes) {
      nlohmann::json points = nlohmann::json::array();
      for (const Compared& p : o.points)
        points.push_back({{"where", p.where}, {"value", p.value}, {"reference", p.reference}, {"error", p.error},
                          {"strict_error", p.strict}});
      j.push_back({{"case", o.c->id}, {"variant", o.c->variant}, {"title", o.c->title}, {"choices", o.c->choices},
                   {"goal", o.c->goal}, {"cie_tolerance", o.c->cie_tolerance}, {"worst", o.worst}, {"mean", o.mean},
                   {"worst_at", o.worst_where}, {"strict_worst", o.strict_worst},
                   {"points_in_shade", o.floored}, {"passed", o.passed()}, {"failure", o.failure},
                   {"seconds", o.seconds}, {"points", points}});
    }
    if (!options.json.empty()) {
      AtomicFile file(options.json, std::ios::out);
      file.stream() << j.dump(1) << "\n";
      file.commit();
    }
    if (!options.html.empty()) {
      // The pictures are read now, before the work folder goes.
      for (std::size_t k = 0; k < outcomes.size(); ++k)
        j[k]["picture"] = outcomes[k].picture.empty() ? nlohmann::json() : nlohmann::json(outcomes[k].picture);
      write_validation_report(options.html, j, how);
    }
  }
  if (options.keep.empty()) fs::remove_all(base);
  if (g_validate_stop.load()) {
    std::cout << fmt::format("interrupted after {} of {} runs\n", outcomes.size(), chosen.size());
    return kExitInterrupted;
  }
  std::cout << (all_passed ? "every case within its goal\n" : "some cases are over their goal\n");
  return all_passed ? kExitOk : kExitValidation;
}

}  // namespace

Command add_validate_command(CLI::App& app) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* command = app.add_subcommand(
      "validate", "Run the analytical test cases of CIE 171:2006 and compare with their references (see docs/validation.md)");
  command->add_option("--case", options->cases, "Only these cases: a section (5.11), the start of 'id variant', or a line of --list");
  command->add_option("--skip", options->skip, "Leave these cases out (as --case names them)");
  command->add_flag("--list", options->list, "List the cases and exit");
  command->add_option("--quality", options->quality, "Solve every case at this quality (draft, normal, high)")
      ->check(CLI::IsMember({"draft", "normal", "high"}));
  command->add_option("--converge", options->converge,
                      "Shoot every case until this fraction of its light is unshot (dynrad solve --converge), so that "
                      "the mesh alone is measured, not where the error estimate stops the solve")
      ->check(CLI::Range(0.0, 1.0));
  command->add_option("--json", options->json, "Write every compared point and each case's figures here");
  command->add_option("--html", options->html,
                      "Write the validation report here: one HTML page, the tables and each run's work-plane plan");
  command->add_option("--keep", options->keep, "Keep each case's scene, lit mesh and logs in this folder");
  return [options] { return run_validate(*options); };
}

}  // namespace dynrad::cli
