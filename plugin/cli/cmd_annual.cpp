// `dynrad annual SCENE --weather FILE.epw [-o PREFIX] [--occupied 8-18]`: a year of
// daylight on the scene's grids from the daylight coefficients of one solve
// (radiosity/climate/coefficient_solve.h, annual.h) and the metrics of IES LM-83 and
// EN 17037 (radiosity/climate/annual_metrics.h).
//
// Writes, beside PREFIX:
//   PREFIX_annual.json           the site, the conventions, every grid's metrics
//   PREFIX_annual.html           the same as a report, with the plans (html_annual.h)
//   PREFIX_NAME_hourly.npy       per grid, the illuminance (lx, float32) per weather row
//                                and point, shape (rows, points): numpy.load() reads it
//   PREFIX_NAME_points.csv       per point: position, DA, cDA, UDI, sDA and ASE hours
//   PREFIX_NAME_DA300.png, _cDA300.png, _UDI.png, _ASE.png   false-colour plans: the
//                                share of occupied hours at 300 lx (the basis of sDA),
//                                continuous DA, useful UDI, and the hours of direct sun
//                                over 1000 lx (the basis of ASE)
#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "plugin/cli/annual_meshes.h"
#include "plugin/cli/commands.h"
#include "plugin/report/grid_picture.h"
#include "plugin/cli/html_annual.h"
#include "plugin/cli/npy.h"
#include "plugin/report/png.h"
#include "plugin/cli/progress.h"
#include "radiosity/climate/annual.h"
#include "radiosity/pipeline/pipeline.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/analysis/grid_scene.h"
#include "radiosity/analysis/lit_scene.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>

namespace dynrad::cli {
using namespace dynrad::report;  // the report's writers (plugin/report/)
namespace {

struct AnnualCliOptions {
  LoadOptions load;
  std::string weather, output, occupied = "8-18";
  std::vector<std::string> hours;    // --hour MM-DD-HH: a lit mesh of that weather row
  bool vertex_coefficients = false;  // every vertex's coefficients as .npy
  double blinds = -1;                // --blinds T: LM-83's blinds rule, closed blinds passing T; < 0: none
};

// "8-18": the first and last hour of the occupied day (08:00 to 18:00).
std::pair<int, int> parse_occupied(const std::string& text) {
  int first = -1, last = -1;
  char dash = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &first, &dash, &last, &extra) != 3 || dash != '-' || first < 0 ||
      last > 24 || first >= last)
    throw InputError("--occupied", 0, "'" + text + "' is not a span of hours; write FIRST-LAST, 0 <= FIRST < LAST <= 24, "
                                             "e.g. 8-18 for 08:00 to 18:00.");
  return {first, last};
}

// The scene file's "sky": its ground reflectance and north, when it has them (the rest
// of it, the hour's sky, is the weather's here).
void scene_sky_settings(const std::string& scene, rad::AnnualOptions& options) {
  if (std::filesystem::path(scene).extension() != ".json") return;
  std::ifstream in(scene);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object() || !j.contains("sky") || !j["sky"].is_object()) return;
  const auto& sky = j["sky"];
  if (sky.contains("ground_reflectance")) {
    const auto& g = sky["ground_reflectance"];
    if (!g.is_number() || !(g.get<double>() >= 0 && g.get<double>() < 1))
      throw InputError(scene, 0, "sky.ground_reflectance must be a number from 0 to below 1.");
    options.ground_reflectance = g.get<double>();
  }
  if (sky.contains("north")) {
    const auto& n = sky["north"];
    const bool numbers = n.is_array() && n.size() == 2 && n[0].is_number() && n[1].is_number();
    const Vec3d north = numbers ? Vec3d(n[0].get<double>(), n[1].get<double>(), 0) : Vec3d(0.0);
    if (!(north.norm() > 0) || !std::isfinite(north.norm()))
      throw InputError(scene, 0, "sky.north must be [x, y], a direction in the plan that is not [0, 0].");
    options.north = north.normalized();
  }
}

int run_annual(const AnnualCliOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const auto [first_hour, last_hour] = parse_occupied(options.occupied);
  const rad::Weather weather = rad::read_epw(options.weather);
  const std::vector<rad::GridSpec> grids = rad::read_grids(options.load.input);
  if (grids.empty())
    throw InputError(options.load.input, 0,
                     "annual daylight is computed on calculation grids, and the scene has none: add \"grids\" (see "
                     "docs/scene-reference.md, grids[]).");
  for (const rad::GridSpec& g : grids)
    if (g.up != 2)
      throw InputError(options.load.input, 0,
                       "grid \"" + g.name + "\" faces another way than up (+z): annual daylight takes work planes, "
                       "horizontal, with +z up.");
  const std::string prefix =
      !options.output.empty() ? options.output
                              : (std::filesystem::path(options.load.input).parent_path() /
                                 std::filesystem::path(options.load.input).stem()).string();
  // The weather's rows, for --hour.
  std::vector<rad::HourEnding> rows;
  for (const auto& h : weather.hours) rows.push_back({h.month, h.day, h.hour});
  std::vector<AnnualHour> mesh_hours;
  for (const std::string& h : options.hours) mesh_hours.push_back(parse_annual_hour(h, rows));
  for (const std::string& file : annual_mesh_files(prefix, mesh_hours, rows, options.vertex_coefficients))
    check_output_writable(file);
  check_output_writable(prefix + "_annual.json");
  check_output_writable(prefix + "_annual.html");
  for (const rad::GridSpec& g : grids)
    for (const char* suffix : {"_hourly.npy", "_points.csv", "_DA300.png", "_cDA300.png", "_UDI.png", "_ASE.png"})
      check_output_writable(prefix + "_" + g.name + suffix);

  rad::AnnualOptions annual;
  scene_sky_settings(options.load.input, annual);
  const rad::CoefficientOptions& co = annual.coefficients;
  const rad::SkyPatches fine(co.fine_subdivision, annual.up, annual.north);
  const rad::SkyPatches indirect(co.indirect_subdivision, annual.up, annual.north);

  // Load, repair, the steering sky, settings, patches: the pipeline every host calls,
  // asked for annual daylight's solve (radiosity/pipeline/pipeline.h).
  rad::SceneRequest request;
  request.path = options.load.input;
  request.cleanup = options.load.cleanup();
  request.simplify.enabled = options.load.simplify;
  request.read = options.load.read();
  request.coefficients = rad::CoefficientRequest{annual.up, co, &indirect, nullptr};
  rad::PreparedScene prepared = rad::prepare_scene(request);
  SceneMesh& mesh = *prepared.scene.mesh;
  const rad::Luminaire& steering = prepared.luminaires.front();
  const rad::Glazing* glazing = prepared.glazing.get();

  spdlog::info("{}: {}, {}, {} (latitude {:.3f}, longitude {:.3f}, UTC{:+g}), {} hours", weather.path,
               weather.site.city, weather.site.region, weather.site.country, weather.site.latitude,
               weather.site.longitude, weather.site.timezone, weather.hours.size());
  auto since = [last = std::chrono::steady_clock::now()]() mutable {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last).count();
    last = now;
    return s;
  };
  const rad::YearSky year = rad::year_sky(weather, fine, indirect, annual);
  std::size_t lit_rows = 0;
  for (char d : year.dark) lit_rows += !d;
  spdlog::info("skies in {:.1f} s: {} daylit hours; {} sun positions {} degrees apart; direct sky on {} patches "
               "(MF:{}), interreflection on {} (MF:{})",
               since(), lit_rows, year.suns.size(), co.sun_spacing, fine.size(), co.fine_subdivision, indirect.size(),
               co.indirect_subdivision);
  prepared.request.coefficients->suns = &year.suns;

  // The solve, with progress as solve shows it; a first SIGINT or SIGTERM stops the solve
  // at the next shot, and the year is then computed from the light shot so far (exit
  // code 3).
  Progress progress(prepared.solve.error_target > 0 ? prepared.solve.error_target : prepared.solve.converge);
  prepared.solve.should_stop = [] { return g_stop_requested.load(); };
  prepared.request.on_shot = [&](const rad::Solver& running, std::size_t shot, double unshot) {
    progress.update(shot, unshot, -1, running.report().elements);
  };
  prepared.solve.on_busy = [&](std::size_t points, double seconds) {
    progress.busy(points, seconds, g_stop_requested.load());
  };
  g_stop_requested = false;
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  spdlog::info("solve: {} patches (patch size {:.3g}), {} channels", prepared.hierarchy->patch_count(),
               prepared.applied.patch_size, indirect.size() + 1 + year.suns.size());
  const rad::SolvedScene solved = rad::solve_scene(prepared, true);
  const rad::Solver& solver = *solved.solver;
  const rad::SolveReport& report = solved.report;
  progress.finish();
  const bool interrupted = g_stop_requested.load();
  if (interrupted)
    spdlog::warn("interrupted: the year is computed from the light shot so far ({:.2g}% unshot); a second signal "
                 "ends at once",
                 100 * report.unshot_fraction);
  spdlog::info("solved in {:.1f} s: {} shots, {:.2g}% unshot", report.seconds, report.iterations,
               100 * report.unshot_fraction);
  const rad::Solver::Output& result = solved.output;
  const rad::LitScene& lit = *solved.lit;

  const rad::AnalysisHours occupied = rad::occupied_hours(year.rows, first_hour, last_hour);
  const rad::AnalysisHours daylight_hours = rad::en17037_daylight_hours(year.diffuse_horizontal);
  const double median_diffuse = rad::median_diffuse_illuminance(year.diffuse_horizontal, &daylight_hours);
  nlohmann::json out;
  out["weather"] = {{"file", weather.path},
                    {"city", weather.site.city},
                    {"country", weather.site.country},
                    {"latitude", weather.site.latitude},
                    {"longitude", weather.site.longitude},
                    {"timezone", weather.site.timezone},
                    {"elevation", weather.site.elevation},
                    {"hours", weather.hours.size()}};
  out["conventions"] = {
      {"time", fmt::format("weather rows are hours ending at local standard time; each hour's sun at its middle "
                           "((h-1):30 standard time, reference year {}); no daylight saving time",
                           year.reference_year)},
      {"sky", "Perez all-weather sky (1993) from each row's diffuse horizontal and direct normal irradiance; "
              "illuminances from the Perez (1990) efficacy model; the file's illuminance fields are not used"},
      {"ground_reflectance", annual.ground_reflectance},
      {"north", {annual.north[0], annual.north[1]}},
      {"occupied", occupied.description},
      {"en17037_daylight_hours", daylight_hours.description},
      {"median_diffuse_illuminance", median_diffuse},
      {"coefficients",
       fmt::format("direct sky on Reinhart MF:{} ({} patches), interreflection on MF:{} ({}), {} sun positions every "
                   "{} degrees, one solve of {} patches",
                   co.fine_subdivision, fine.size(), co.indirect_subdivision, indirect.size(), year.suns.size(),
                   co.sun_spacing, prepared.hierarchy->patch_count())},
      {"blinds",
       options.blinds < 0
           ? std::string("none (LM-83's operable-blinds rule is not applied; --blinds T applies it)")
           : fmt::format("LM-83's operable blinds: closed in an occupied hour when more than 2% of a grid's points get "
                         "1000 lx or more of direct sun; closed, they block the direct sun and pass {} of the rest "
                         "(sky, ground and every interreflection)",
                         options.blinds)}};
  // Every output is written at the end, once every grid has been computed: a grid that
  // fails leaves nothing behind.
  std::vector<std::function<void()>> writes;
  std::vector<std::vector<std::pair<std::string, std::string>>> plans;  // per grid: caption, PNG
  for (const rad::GridSpec& spec : grids) {
    rad::GridResult layout;
    layout.spec = spec;
    std::vector<std::array<long, 2>> cells;
    const std::vector<Vec3d> points = rad::grid_points(spec, &layout.spacing, &cells, &layout.cells);
    Vec3d normal(0.0);
    normal[spec.up] = 1;
    std::vector<rad::PointCoefficients> coefficients(points.size());
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
      coefficients[k] = rad::point_coefficients(lit, mesh, solver, steering, fine, indirect, points[k], normal, co,
                                                0x6E1Dull + k);
    });
    const double coefficient_seconds = since();
    rad::AnnualGridHours hours =
        rad::grid_year(coefficients, points, normal, *lit.visibility, glazing, year);
    spdlog::info("grid {}: coefficients of {} points in {:.1f} s, {} hours in {:.1f} s", spec.name, points.size(),
                 coefficient_seconds, hours.total.hours, since());
    // The metrics over the points that are not inside a solid.
    std::vector<std::size_t> kept;
    for (std::size_t k = 0; k < points.size(); ++k)
      if (!hours.masked[k]) kept.push_back(k);
    if (kept.empty()) throw InputError(options.load.input, 0, "grid \"" + spec.name + "\" lies wholly inside solids.");
    rad::HourlyIlluminance total(kept.size(), hours.total.hours), sun(kept.size(), hours.total.hours);
    rad::HourlyIlluminance closed(options.blinds >= 0 ? kept.size() : 0, options.blinds >= 0 ? hours.total.hours : 0);
    for (std::size_t h = 0; h < hours.total.hours; ++h)
      for (std::size_t k = 0; k < kept.size(); ++k) {
        total.at(h, k) = hours.total.at(h, kept[k]);
        sun.at(h, k) = hours.sun.at(h, kept[k]);
        if (options.blinds >= 0)
          closed.at(h, k) = static_cast<float>(options.blinds * std::max(0.0f, total.at(h, k) - sun.at(h, k)));
      }
    rad::AnnualInputs inputs;
    inputs.total = &total;
    inputs.direct_sun = &sun;
    inputs.occupied = &occupied;
    inputs.daylight_hours = &daylight_hours;
    if (options.blinds >= 0) inputs.blinds_closed = &closed;
    std::vector<rad::PointMetrics> per_point;
    const rad::GridMetrics m = rad::annual_metrics(inputs, {}, &per_point);
    nlohmann::json g = {{"name", spec.name},
                        {"points", kept.size()},
                        {"masked", points.size() - kept.size()},
                        {"sDA300_50", 100 * m.sda},
                        {"ASE1000_250h", 100 * m.ase},
                        {"DA300_mean", 100 * m.mean_da},
                        {"cDA300_mean", 100 * m.mean_cda},
                        {"UDI_below_100", 100 * m.mean_udi_low},
                        {"UDI_100_3000", 100 * m.mean_udi_useful},
                        {"UDI_above_3000", 100 * m.mean_udi_high},
                        {"blinds_closed_hours", m.blinds ? nlohmann::json(m.blinds_closed_hours) : nlohmann::json()},
                        {"notes", m.notes}};
    if (m.en17037) {
      nlohmann::json levels = nlohmann::json::array();
      for (const auto& l : m.en17037->levels)
        levels.push_back({{"level", l.level},
                          {"target_lux", l.target_lux},
                          {"minimum_lux", l.minimum_lux},
                          {"target_hours_percent", 100 * l.target_hours},
                          {"minimum_hours_percent", 100 * l.minimum_hours},
                          {"met", l.met()}});
      g["EN17037"] = {{"daylight_hours", m.en17037->daylight_hours}, {"levels", levels}, {"achieved", m.en17037->achieved}};
    }
    out["grids"].push_back(g);
    spdlog::info("grid {}: {} points: sDA300/50% {:.1f}%, ASE1000,250h {:.1f}%, UDI {:.0f}/{:.0f}/{:.0f}%, "
                 "mean DA300 {:.0f}%, EN 17037: {}",
                 spec.name, kept.size(), 100 * m.sda, 100 * m.ase, 100 * m.mean_udi_low, 100 * m.mean_udi_useful,
                 100 * m.mean_udi_high, 100 * m.mean_da, m.en17037 ? m.en17037->achieved : "-");
    // Outputs: the hourly file (every point, masked ones 0), the points (with their column
    // in the hourly file), the plans.
    std::string csv = "point,x,y,z,DA300,cDA300,UDI_below_100,UDI_100_3000,UDI_above_3000,hours_300lx,sDA_met,"
                      "sun_hours_1000lx,ASE_exceeded\n";
    for (std::size_t i = 0; i < kept.size(); ++i) {
      const Vec3d& p = points[kept[i]];
      const rad::PointMetrics& q = per_point[i];
      csv += fmt::format("{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{},{},{},{}\n", kept[i], p[0], p[1],
                         p[2], q.da, q.cda, q.udi_low, q.udi_useful, q.udi_high, q.sda_hours, q.sda_met ? 1 : 0,
                         q.ase_hours, q.ase_exceeded ? 1 : 0);
    }
    const std::string stem = prefix + "_" + spec.name;
    writes.push_back([stem, lux = std::move(hours.total.lux), rows = hours.total.hours, columns = points.size(),
                      csv = std::move(csv)] {
      write_npy(stem + "_hourly.npy", lux, rows, columns);
      AtomicFile file(stem + "_points.csv", std::ios::out);
      file.stream() << csv;
      file.commit();
    });
    plans.emplace_back();
    auto plan = [&](const char* name, const std::string& unit, auto value) {
      rad::GridResult r = layout;
      r.points.resize(points.size());
      for (std::size_t k = 0; k < points.size(); ++k) {
        r.points[k].position = points[k];
        r.points[k].cell = cells[k];
        r.points[k].masked = true;
      }
      for (std::size_t i = 0; i < kept.size(); ++i) {
        rad::GridPointResult& p = r.points[kept[i]];
        p.masked = false;
        p.illuminance = value(per_point[i]);
      }
      static_cast<rad::PointStatistics&>(r) = rad::point_statistics(r.points);
      std::string png = encode_png(grid_picture(r, unit));
      plans.back().emplace_back(std::string(name) + ": " + unit, png);
      writes.push_back([path = stem + "_" + name + ".png", png = std::move(png)] {
        AtomicFile file(path);
        file.stream() << png;
        file.commit();
      });
    };
    plan("DA300", "% hours >= 300 lx", [](const rad::PointMetrics& q) { return 100.0 * q.da; });
    plan("cDA300", "% cDA300", [](const rad::PointMetrics& q) { return 100.0 * q.cda; });
    plan("UDI", "% UDI 100-3000", [](const rad::PointMetrics& q) { return 100.0 * q.udi_useful; });
    plan("ASE", "h sun > 1000 lx", [](const rad::PointMetrics& q) { return static_cast<double>(q.ase_hours); });
  }
  std::unique_ptr<rad::VertexCoefficients> vertices;
  if (!mesh_hours.empty() || options.vertex_coefficients) {
    vertices = std::make_unique<rad::VertexCoefficients>(rad::vertex_coefficients(
        mesh, solver, result, indirect.size() + 1, steering.daylight->sky.ground_luminance));
    annual_mesh_outputs(prefix, mesh, result.split, *vertices, year, mesh_hours, options.vertex_coefficients,
                        *lit.visibility, glazing, indirect, writes, out);
    spdlog::info("the model: coefficients of {} vertices in {:.1f} s", vertices->size(), since());
  }
  for (const auto& write : writes) write();
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  out["solve"] = {{"patches", prepared.hierarchy->patch_count()},
                  {"channels", solver.coefficient_count()},
                  {"shots", report.iterations},
                  {"unshot_percent", 100 * report.unshot_fraction},
                  {"stopped_by", rad::to_string(report.stopped_by)}};
  if (interrupted) out["interrupted"] = true;
  {
    AtomicFile json(prefix + "_annual.json", std::ios::out);
    json.stream() << out.dump(2) << "\n";
    json.commit();
  }
  write_annual_html(prefix + "_annual.html", out, plans);
  spdlog::info("wrote {}_annual.json, .html and each grid's _hourly.npy, _points.csv and plans in {:.1f} s", prefix,
               out["seconds"].get<double>());
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  return interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace

Command add_annual_command(CLI::App& app) {
  auto options = std::make_shared<AnnualCliOptions>();
  CLI::App* command = app.add_subcommand(
      "annual", "A year of daylight on the scene's grids from an EnergyPlus weather file: sDA, ASE, UDI, DA and "
                "EN 17037's daylight provision, hourly illuminance per point, plans");
  add_load_options(*command, options->load);
  add_simplify_flag(*command, options->load);
  command->add_option("--weather", options->weather, "EnergyPlus weather file (.epw) of the site")->required();
  command->add_option("-o,--output", options->output,
                      "Prefix of the results: PREFIX_annual.json, PREFIX_GRID_hourly.npy, PREFIX_GRID_points.csv and "
                      "plans (default: the scene's path without its extension)");
  command->add_option("--occupied", options->occupied,
                      "Occupied hours FIRST-LAST, local standard time, for sDA, ASE, UDI and DA")
      ->capture_default_str();
  command->add_option("--blinds", options->blinds,
                      "Apply LM-83's operable-blinds rule to sDA, DA, cDA and UDI: in an hour when more than 2% of the "
                      "points get direct sun of 1000 lx or more, the blinds close, block the direct sun and pass this "
                      "share of the rest (0 to 1; default: no blinds)")
      ->check(CLI::Range(0.0, 1.0));
  command->add_option("--hour", options->hours,
                      "MM-DD-HH: also write the model lit by that weather row's sky and sun (the hour ending at HH:00 "
                      "standard time), PREFIX_hour_MMDD_HH.ply; repeat for more hours");
  command->add_flag("--vertex-coefficients", options->vertex_coefficients,
                    "Also write every vertex's daylight coefficients, PREFIX_vertex_coefficients.npy (vertices x "
                    "channels), with PREFIX_vertices.ply, the mesh its rows belong to");
  return [options] { return run_annual(*options); };
}

}  // namespace dynrad::cli
