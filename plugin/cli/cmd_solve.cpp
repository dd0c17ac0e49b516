// `dynrad solve INPUT -o OUT.ply`: light a model and write per-vertex radiosity.
//
// Exit codes: 0 the solve stopped by one of its rules (converged, --iterations,
// --time-limit) and the output is written; 2 bad input, output path or options; 3
// interrupted (Ctrl-C or SIGTERM): the current solution is written all the same,
// since progressive refinement is usable at any moment; 1 internal error.
#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "mesh/io/io_util.h"
#include "mesh/io/lit_decimate.h"
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "plugin/cli/commands.h"
#include "plugin/cli/progress.h"
#include "plugin/report/design_output.h"
#include "plugin/report/grid_output.h"
#include "plugin/report/html_report.h"
#include "plugin/report/report_document.h"
#include "plugin/cli/pdf_report.h"
#include "plugin/report/view_output.h"
#include "plugin/report/png.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/design/light_scenes.h"
#include "radiosity/analysis/grid_scene.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/analysis/render.h"
#include "radiosity/analysis/views.h"
#include "radiosity/transfer/visibility.h"
#include "radiosity/pipeline/pipeline.h"
#include "radiosity/pipeline/report_json.h"
#include "radiosity/solver/settings.h"
#include "radiosity/solver/solver.h"
#include "radiosity/analysis/tonemap.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace dynrad::cli {
using namespace dynrad::report;  // the report's writers (plugin/report/)
namespace {

struct SolveCliOptions {
  LoadOptions load;
  std::string output;
  std::string report;
  std::string preview;
  int preview_width = 800;
  std::string html;    // the one-file HTML report
  std::string pdf;     // the paginated PDF report
  bool views = false;  // also the automatic views (plans, rooms)
  std::string method = "dynamic";
  std::string quality = "normal";
  double patch_size = 0;  // 0: chosen from the model (radiosity/solver/settings.h)
  int max_level = -1;     // -1: the quality's
  double converge = -1;   // -1: stop by the quality's error target (dynamic), or at 1% unshot
  bool ambient = true;
  double threshold = -1;  // -1: the method's default
  std::string oracle = "pushdown";
  std::size_t max_elements = 0;
  double memory_budget_mb = -1;  // -1: half of the memory available at the start
  bool no_pushdown_ambient = false;
  bool clusters = true;
  bool shadow_outlines = false;  // hard shadows' outlines as mesh edges (radiosity/sources/shadow_outlines.h)
  bool direct_in_mesh = false;   // RefineSettings::exact_direct off
  double overshoot = -1;  // -1: the method's (radiosity/solver/settings.h)
  double cumulated_gradient = -1, current_gradient = -1, current_ratio = -1, pushdown = -1, pushdown_floor = -1;  // -1: default
  double exposure = 0;    // 0: automatic
  bool ascii = false;
  std::size_t max_triangles = 500000;  // decimate the written mesh above this (0: never)
  // "auto": photometric (lux, cd/m^2) when the scene has luminaires or a sky (a luminaire
  // here), else radiometric.
  std::string units = "auto";
  rad::SolveOptions solve;
};

int run_solve(SolveCliOptions& options) {
  // The request to the pipeline (radiosity/pipeline/pipeline.h) from the options.
  rad::SceneRequest request;
  request.path = options.load.input;
  rad::RefineSettings& refine = request.refine;
  try {
    refine.method = rad::parse_method(options.method);
  } catch (const std::invalid_argument& e) {
    throw InputError("--method", 0, e.what());
  }
  rad::Quality quality;
  try {
    quality = rad::parse_quality(options.quality);
  } catch (const std::invalid_argument& e) {
    throw InputError("--quality", 0, e.what());
  }
  rad::OracleThresholds& oracle = refine.dynamic;
  if (options.threshold > 0) {
    refine.adaptive_threshold = options.threshold;
    oracle.cumulated_gradient = oracle.current_gradient = oracle.current_ratio = options.threshold;
  }
  if (options.oracle == "pushdown") {
    oracle.variant = rad::OracleThresholds::Variant::pushdown;
    if (options.cumulated_gradient >= 0) oracle.pushdown_cumulated_gradient = options.cumulated_gradient;
  } else if (options.oracle == "paper") {
    oracle.variant = rad::OracleThresholds::Variant::paper;
    if (options.cumulated_gradient >= 0) oracle.cumulated_gradient = options.cumulated_gradient;
  } else {
    throw InputError("--oracle", 0, "'" + options.oracle + "' is not an oracle; available: pushdown, paper.");
  }
  if (options.current_gradient >= 0) oracle.current_gradient = options.current_gradient;
  if (options.current_ratio >= 0) oracle.current_ratio = options.current_ratio;
  if (options.no_pushdown_ambient) oracle.pushdown_ambient = false;
  refine.max_elements = options.max_elements;
  options.solve.ambient_display = options.ambient;
  if (options.units == "photometric")
    request.units = rad::Units::photometric;
  else if (options.units == "radiometric")
    request.units = rad::Units::radiometric;
  else if (options.units != "auto")
    throw InputError("--units", 0, "'" + options.units + "' is not a unit system; available: auto, photometric, radiometric.");
  {
    std::string ext = std::filesystem::path(options.output).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".ply" && ext != ".off" && ext != ".glb")
      throw OutputError(options.output, "unsupported output type '" + ext + "'; use .ply, .off or .glb (binary glTF).");
  }
  check_output_writable(options.output);
  if (!options.report.empty()) check_output_writable(options.report);
  // Calculation grids of the scene file: results beside the output, named after it
  // (OUT_grids.json, OUT_grid_NAME.csv), checked before any work.
  const std::vector<rad::GridSpec> grids = rad::read_grids(options.load.input);
  const std::string grid_prefix = (std::filesystem::path(options.output).parent_path() /
                                   std::filesystem::path(options.output).stem()).string();
  check_grid_outputs(grid_prefix, grids);
  if (!options.preview.empty()) check_output_writable(options.preview);
  // Views: the scene file's cameras always; the automatic ones (whose names come from
  // the model) with --views or --html, checked here by the directory they go to.
  const std::vector<rad::View> cameras = rad::read_cameras(options.load.input);
  const bool automatic_views = options.views || !options.html.empty() || !options.pdf.empty();
  check_view_outputs(grid_prefix, cameras, automatic_views, options.html);
  if (!options.pdf.empty()) check_output_writable(options.pdf);
  // Observers, emergency routes, the project block (plugin/report/design_output.h).
  const bool design = check_design_inputs(options.load.input);

  request.cleanup = options.load.cleanup();
  request.simplify.enabled = options.load.simplify;
  request.read = options.load.read();
  request.settings.quality = quality;
  request.settings.patch_size = options.patch_size;
  request.settings.max_level = options.max_level;
  request.settings.converge = options.converge;
  request.settings.pushdown = options.pushdown;
  request.settings.pushdown_floor = options.pushdown_floor;
  request.settings.memory_budget_mib = options.memory_budget_mb;
  request.settings.clusters = options.clusters;
  request.settings.overshoot = options.overshoot;
  request.shadow_outlines = options.shadow_outlines;
  refine.exact_direct = !options.direct_in_mesh;
  request.solve = options.solve;
  // Load, repair, light sources, settings, patches.
  rad::PreparedScene prepared = rad::prepare_scene(request);
  LoadedScene& scene = prepared.scene;
  SceneMesh& mesh = *scene.mesh;
  const std::vector<rad::Luminaire>& luminaires = prepared.luminaires;
  const bool photometric = prepared.photometric;
  const std::vector<rad::LightScene>& light_scenes = prepared.light_scenes;
  const rad::ChannelPlan& channels = prepared.channels;
  const std::vector<Material>& materials = prepared.materials;
  const ElementHierarchy& hierarchy = *prepared.hierarchy;

  // The solve, with progress; a first SIGINT or SIGTERM stops it at the next shot.
  Progress progress(prepared.solve.error_target > 0 ? prepared.solve.error_target : prepared.solve.converge);
  prepared.solve.should_stop = [] { return g_stop_requested.load(); };
  prepared.request.on_shot = [&](const rad::Solver& running, std::size_t shot, double unshot) {
    const rad::SolveReport& so_far = running.report();
    const double error = so_far.estimated_error.total() > 0 ? so_far.estimated_error.total() : -1;
    progress.update(shot, unshot, error, hierarchy.element_count());
  };
  prepared.solve.on_busy = [&](std::size_t points, double seconds) {
    progress.busy(points, seconds, g_stop_requested.load());
  };
  prepared.solve.on_pass = [&](const char* pass, std::size_t done, std::size_t total, double seconds) {
    progress.pass(pass, done, total, seconds, g_stop_requested.load());
  };
  options.solve = prepared.solve;  // as the settings left it: the report gives it
  g_stop_requested = false;
  // Until the files are written: a first Ctrl-C or SIGTERM stops the shots, cuts the
  // passes after them short and skips what is left to skip (the decimation); a second
  // one ends the program at once.
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  struct DefaultSignals {
    ~DefaultSignals() {
      std::signal(SIGINT, SIG_DFL);
      std::signal(SIGTERM, SIG_DFL);
    }
  } restore_signals;
  const bool glb = std::filesystem::path(options.output).extension() == ".glb";
  // Grids, views, the preview, the glTF's cameras and the designer's checks gather from
  // or render the lit mesh (radiosity/analysis/lit_scene.h).
  rad::SolvedScene solved = rad::solve_scene(
      prepared, !cameras.empty() || automatic_views || !options.preview.empty() || glb || design);
  progress.finish();
  rad::SolveReport& report = solved.report;
  // Output: per-vertex radiosity, display colours through an exposure.
  rad::Solver::Output& result = solved.output;
  std::unique_ptr<rad::LitScene>& scene_lit = solved.lit;
  const std::vector<rad::GridResult>& gathered = solved.grids;
  nlohmann::json scenes_report = nlohmann::json::array();
  if (!light_scenes.empty()) {
    scenes_report = light_scene_results(light_scenes, channels, gathered);
    // Everything else grey again: a white-light solve's values.
    for (Rgb& b : result.radiosity) b = rad::grey(b);
    for (Rgb& e : result.irradiance) e = rad::grey(e);
    for (Rgb* e : {&report.energy.emitted, &report.energy.absorbed, &report.energy.escaped, &report.energy.unshot})
      *e = rad::grey(*e);
    scene_lit->radiosity = result.radiosity;
    for (Rgb& e : scene_lit->emission) e = rad::grey(e);
    for (rad::Luminaire& l : scene_lit->luminaires) l.colour = Rgb(1, 1, 1);
    for (std::size_t m = 0; m < materials.size(); ++m) mesh.set_material(m, materials[m]);
  }
  std::vector<char> lit(result.emitter.size());
  for (std::size_t x = 0; x < lit.size(); ++x) lit[x] = !result.emitter[x];
  const double exposure = options.exposure > 0 ? options.exposure : rad::auto_exposure(result.radiosity, lit, split_vertex_areas(mesh, result.split));
  VertexValues values = rad::tone_map(result.radiosity, exposure, "radiosity");
  if (photometric) {
    // Illuminance (lx) arriving and luminance (cd/m^2) leaving, L = B / pi for a
    // diffuse surface; MeshLab's `quality` shows the illuminance.
    std::vector<float> illuminance(result.irradiance.size()), luminance(result.radiosity.size());
    for (std::size_t v = 0; v < illuminance.size(); ++v) {
      illuminance[v] = static_cast<float>(result.irradiance[v].luminance());
      luminance[v] = static_cast<float>(result.radiosity[v].luminance() / M_PI);
    }
    values.quality = illuminance;
    values.scalars.emplace_back("illuminance", std::move(illuminance));
    values.scalars.emplace_back("luminance", std::move(luminance));
  }
  // The estimated relative error at each vertex (Solver::Output::error), in the PLY (the
  // glTF's attributes are for viewers: colour and light).
  if (!glb) values.scalars.emplace_back("error", result.error);
  std::vector<rad::View> found_views;
  if (automatic_views || !options.preview.empty() || glb) {
    rad::ViewOptions view_options;
    view_options.exposure = exposure;
    found_views = rad::automatic_views(*scene_lit, grids, view_options);
  }
  // The view that shows the most lit surface: from outside an open model (a Cornell box),
  // from a room's corner in a closed building.
  std::optional<rad::View> chosen_view;
  if (!options.preview.empty() || glb) {
    const int w = options.preview_width, h = options.preview_width * 3 / 4;
    std::vector<rad::View> candidates = rad::overview_candidates(*scene_lit, w, h);
    for (rad::View v : found_views)
      if (v.kind == rad::View::Kind::room) {
        v.width = w;
        v.height = h;
        candidates.push_back(v);
      }
    chosen_view = rad::best_lit_view(*scene_lit, candidates, exposure);
  }

  WriteOptions write;
  write.ascii = options.ascii;
  if (glb) {
    write.viewpoints = viewpoints(*chosen_view, rad::merge_views(cameras, found_views));  // all, for the viewer
    write.glass = scene.glazing;
    // Under a sky, a viewer's background is the sky as the model's colours show it: its
    // mean luminance 10 degrees above the horizon, as the radiosity of a surface of that
    // luminance (B = pi L) through the same exposure (usually white: brighter than
    // anything inside). Windows then look out into daylight, not into the dark.
    for (const rad::Luminaire& l : luminaires)
      if (l.kind == rad::Luminaire::Kind::sky && l.daylight) {
        const double b = M_PI * l.daylight->sky.mean_luminance_at(10);
        const auto shown = rad::tone_map({Rgb(b)}, exposure, "sky").display[0];
        write.background = Rgb(detail::srgb_to_linear(shown[0] / 255.0), detail::srgb_to_linear(shown[1] / 255.0),
                               detail::srgb_to_linear(shown[2] / 255.0));
      }
  }
  if (!found_views.empty() || chosen_view) prepared.phases.done("views");
  std::size_t written_vertices = result.split.size(), written_triangles = mesh.face_count();
  if (options.max_triangles > 0 && mesh.face_count() > options.max_triangles && g_stop_requested.load())
    spdlog::warn("interrupted: the lit mesh is written as it is, {} triangles, without decimating it for viewers",
                 mesh.face_count());
  if (options.max_triangles > 0 && mesh.face_count() > options.max_triangles && !g_stop_requested.load()) {
    spdlog::info("decimating the lit mesh for viewers: {} triangles, to at most {}", mesh.face_count(),
                 options.max_triangles);
    // Too fine for a viewer: decimated within a colour bound (mesh/io/lit_decimate.h).
    LitDecimateOptions decimate;
    decimate.max_triangles = options.max_triangles;
    const DecimatedLitMesh lighter = decimate_lit_scene(mesh, result.split, values, decimate);
    const LitDecimateReport& d = lighter.report;
    spdlog::info("decimated for viewers: {} -> {} triangles{}, worst colour error {:.2f} (8-bit units, {:.0f}% of the "
                 "bound), {:.1f} s",
                 d.triangles_before, d.triangles_after,
                 d.reached_target ? "" : fmt::format(" (the colour bound allows no fewer than the {} asked for)",
                                                     options.max_triangles),
                 d.worst_colour_error, 100 * d.worst_error_fraction, d.seconds);
    prepared.phases.add("decimation", d.seconds);
    write_mesh_with_values(options.output, *lighter.scene, lighter.split, lighter.values, write);
    written_vertices = lighter.split.size();
    written_triangles = lighter.scene->face_count();
  } else {
    write_mesh_with_values(options.output, mesh, result.split, values, write);
  }
  prepared.phases.done("writing the lit mesh");

  if (!options.preview.empty()) {
    const int w = options.preview_width, h = options.preview_width * 3 / 4;
    const rad::RenderedView rendered = rad::render_view(*scene_lit, chosen_view->camera, w, h);
    write_png(options.preview, rad::colour_image(rendered, exposure, {90, 0, 0}, {0, 0, 0}));
    const Vec3d& eye = chosen_view->camera.eye;
    spdlog::info("wrote {} ({}: camera at ({:.4g}, {:.4g}, {:.4g}))", options.preview, chosen_view->description, eye[0],
                 eye[1], eye[2]);
  }
  nlohmann::json grid_results = nlohmann::json::array();
  if (!grids.empty()) grid_results = write_grid_results(grid_prefix, options.load.input, gathered, photometric);
  const std::vector<rad::View> views = automatic_views ? rad::merge_views(cameras, found_views) : cameras;
  std::vector<ViewPictures> pictures;
  if (!views.empty()) pictures = write_views(grid_prefix, *scene_lit, views, exposure);
  prepared.phases.done("grid files, preview and views");
  const auto& e = report.energy;
  spdlog::info("{} shots in {:.2f} s ({}), unshot {:.3f}%, estimated error {:.2f}% ({:.2f}% unshot light, {:.2f}% "
               "mesh, {:.2f}% shadows inside elements), {} visibility rays; exposure {:.4g}",
               report.iterations, report.seconds, rad::to_string(report.stopped_by), 100 * report.unshot_fraction,
               100 * report.estimated_error.total(), 100 * report.estimated_error.unshot,
               100 * report.estimated_error.discretisation, 100 * report.estimated_error.shadows,
               report.visibility_rays, exposure);
  spdlog::info("energy ({}): emitted {:.4g}, absorbed {:.4g}, escaped {:.4g}, unshot {:.4g} (sum over channels)",
               photometric ? "lm" : "W if the model is in metres",
               e.emitted.r + e.emitted.g + e.emitted.b, e.absorbed.r + e.absorbed.g + e.absorbed.b,
               e.escaped.r + e.escaped.g + e.escaped.b, e.unshot.r + e.unshot.g + e.unshot.b);
  spdlog::info("wrote {} ({} vertices, {} triangles, {} elements)", options.output, written_vertices,
               written_triangles, hierarchy.element_count());

  {
    ReportHost host;
    host.version = DYNRAD_VERSION;
    host.input = options.load.input;
    host.output = options.output;
    host.grids = grid_results;
    host.scenes = scenes_report;
    host.pictures = pictures;
    const nlohmann::json j = report_document(prepared, solved, exposure, host);
    if (!options.report.empty()) {
      AtomicFile file(options.report, std::ios::out);
      file.stream() << j.dump(2) << "\n";
      file.commit();
    }
    if (!options.html.empty()) {
      write_html_report(options.html, j);
      spdlog::info("wrote {} (the lighting report: the solve, {} grids, {} views)", options.html, grid_results.size(),
                   pictures.size());
    }
    if (!options.pdf.empty()) {
      write_pdf_report(options.pdf, j);
      spdlog::info("wrote {} (the lighting report, paginated)", options.pdf);
    }
  }
  if (!report.refinement_stopped.empty())
    spdlog::warn("refinement stopped at shot {} ({} reached, {} elements); the solve went on without it.",
                 report.refinement_stopped_at, report.refinement_stopped, report.elements);
  if (report.stopped_by == rad::StopReason::interrupted) {
    spdlog::warn("interrupted: wrote the solution so far, with {:.2f}% of the emitted power not yet shot.",
                 100 * report.unshot_fraction);
    return kExitInterrupted;
  }
  // The error and the target with as many decimals as it takes to tell them apart (an
  // error of 1.004% against a target of 1% would otherwise read "1.00%, above 1.00%").
  int decimals = 2;
  while (decimals < 4 && fmt::format("{:.{}f}", 100 * report.estimated_error.total(), decimals) ==
                             fmt::format("{:.{}f}", 100 * options.solve.error_target, decimals))
    ++decimals;
  if (report.stopped_by == rad::StopReason::error_floor)
    spdlog::warn("the estimated error is {:.{}f}%, above the target {:.{}f}%, and what is left is the mesh's ({:.2f}%): "
                 "shooting longer would not help. Try --quality high, or a smaller --patch-size or a larger "
                 "--max-level.",
                 100 * report.estimated_error.total(), decimals, 100 * options.solve.error_target, decimals,
                 100 * (report.estimated_error.discretisation + report.estimated_error.shadows));
  else if (report.stopped_by == rad::StopReason::error_target && report.estimated_error.total() > options.solve.error_target)
    spdlog::info("the estimated error is {:.{}f}%, above the target {:.{}f}%: {:.2f}% of it is shadows' edges inside "
                 "elements, which shooting longer does not change; the PLY's `error` shows where they are, and a "
                 "smaller --patch-size or a higher --quality draws them more finely.",
                 100 * report.estimated_error.total(), decimals, 100 * options.solve.error_target, decimals,
                 100 * report.estimated_error.shadows);
  else if (!rad::reached_target(report.stopped_by))
    spdlog::warn("stopped by {} with {:.2f}% of the emitted power not yet shot (target {:.2f}%).", rad::to_string(report.stopped_by),
                 100 * report.unshot_fraction, 100 * options.solve.converge);
  return kExitOk;
}

}  // namespace

Command add_solve_command(CLI::App& app) {
  auto options = std::make_shared<SolveCliOptions>();
  CLI::App* command = app.add_subcommand("solve", "Light a model with radiosity and write per-vertex results");
  add_load_options(*command, options->load);
  add_simplify_flag(*command, options->load);
  command->add_option("-o,--output", options->output, "Lit mesh to write: .ply, .off or .glb (binary glTF 2.0)")->required();
  command->add_option("--quality", options->quality,
                      "draft, normal or high: the estimated error to stop at (3%, 1%, 0.3%) and the patches, levels "
                      "and oracle that reach it; options below override")
      ->capture_default_str();
  command->add_option("--method", options->method, "progressive, adaptive (Cohen et al. 1986) or dynamic (Dubuis & Bieri)")
      ->capture_default_str();
  command->add_option("--patch-size", options->patch_size,
                      "Longest patch edge, model units (default: from the model's mean free path and the quality; "
                      "progressive and adaptive: a tenth of the bounding-box diagonal)")
      ->check(CLI::PositiveNumber);
  command->add_option("--max-level", options->max_level,
                      "1->4 splits allowed below a patch (the paper's level L is --max-level L-1; default: the quality's, "
                      "3 for progressive and adaptive; given, it holds for a small emitting patch's first shot too, which "
                      "otherwise refines 2 levels deeper)")
      ->check(CLI::Range(0, 12));
  command->add_option("--threshold", options->threshold,
                      "Adaptive's gradient threshold (default 0.25); also all three of the paper oracle's")
      ->check(CLI::PositiveNumber);
  command->add_option("--oracle", options->oracle,
                      "Dynamic's refinement oracle: pushdown (bounds push-down error) or paper (Figure 6); see docs/algorithm.md")
      ->capture_default_str();
  command->add_option("--cumulated-gradient", options->cumulated_gradient,
                      "Dynamic: threshold on the cumulated gradient (both oracles)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--current-gradient", options->current_gradient, "Paper oracle: threshold on the current gradient")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--current-ratio", options->current_ratio, "Paper oracle: threshold on current/cumulated")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--pushdown-error", options->pushdown,
                      "Push-down oracle: largest push-down error allowed, as a fraction of the transfer")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--pushdown-floor", options->pushdown_floor,
                      "Push-down oracle: errors are measured against at least this fraction of the element's B")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--no-pushdown-ambient", options->no_pushdown_ambient,
                    "Push-down oracle: floor against B so far, not B plus the ambient share of unshot light");
  command->add_option("--max-elements", options->max_elements,
                      "Stop refining (and go on solving) once the element tree holds this many (0: no limit)");
  command->add_option("--memory-budget", options->memory_budget_mb,
                      "Stop refining (and go on solving) once the process uses this many MiB (default: half of the memory "
                      "available at the start; 0: no limit)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--converge", options->converge,
                      "Stop when unshot power falls below this fraction of emitted, instead of by estimated error "
                      "(progressive and adaptive: 0.01)")
      ->check(CLI::Range(0.0, 1.0));
  command->add_option("--iterations", options->solve.max_iterations, "Stop after this many shots (0: no limit)");
  command->add_option("--time-limit", options->solve.time_limit, "Stop after this many seconds, writing what there is")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--threads", options->solve.threads, "Worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  command->add_option("--seed", options->solve.seed, "Seed of all ray sampling")->capture_default_str();
  command->add_option("--report", options->report, "Write a JSON report of the solve here");
  command->add_option("--pdf", options->pdf,
                      "Write the lighting report as a paginated A4 PDF here: title block, luminaire schedule, "
                      "EN 12464-1 per room, UGR per observer, emergency lighting, grids and views (implies --views)");
  command->add_option("--exposure", options->exposure,
                      "Multiply radiosity by this before the sRGB curve (default: automatic)")
      ->check(CLI::PositiveNumber);
  command->add_option("--crease-angle", options->solve.crease_angle, "Split vertices where faces meet at more than this")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 180.0));
  command->add_option("--overshoot", options->overshoot,
                      "Over-relax each shot by this factor (default 1: none; 1.3 reaches a given unshot fraction in "
                      "fewer shots)")
      ->check(CLI::Range(0.5, 1.9));
  command->add_option("--negligible-share", options->solve.negligible_share,
                      "Per shot, skip receivers whose bounded share of its power is below this over the patch count "
                      "(0: never)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.1));
  command->add_flag("!--flat-senders", options->solve.shaped_senders,
                   "Shoot every patch's unshot radiosity evenly (Cohen et al. 1988) instead of shaped by its "
                   "corners and a quarter grid of points on it");
  command->add_flag("--shadow-outlines,!--no-shadow-outlines", options->shadow_outlines,
                    "Make the outlines of hard shadows (from luminaires small for their distance, and the sun) mesh "
                    "edges, drawn into the mesh after the shots (before them with --direct-in-mesh). Off (the "
                    "default): a shadow's edge is refined to 2% of its distance from the light");
  command->add_flag("--direct-in-mesh", options->direct_in_mesh,
                    "Refine the element hierarchy for the light of luminaires and the sun in their own shots and keep "
                    "it in the element values, instead of evaluating it exactly at every written vertex and refining "
                    "the written mesh for it after the shots (for comparison; much slower on buildings)");
  command->add_flag("!--no-clusters", options->clusters,
                    "Solve every small patch on its own instead of grouping small patches (frames, handles, "
                    "furniture parts) into face clusters that send and receive light as one");
  command->add_flag("--ambient,!--no-ambient", options->ambient,
                   "Add (the default) or leave out the ambient estimate of light not yet shot in the written values "
                   "(Cohen et al. 1988)");
  command->add_flag("--ascii", options->ascii, "Write ASCII PLY instead of binary");
  command->add_option("--max-triangles", options->max_triangles,
                      "Decimate the written mesh to at most this many triangles where no vertex's display colour "
                      "moves by more than 1% (at least 1 of 255) and the surface stays the same (0: never)")
      ->capture_default_str();
  command->add_option("--units", options->units,
                      "auto, photometric or radiometric. Photometric (the default when the scene has luminaires or a sky): "
                      "lumens, lux and cd/m^2; emitting faces' W/m^2 are converted at 179 lm/W. The PLY then also "
                      "holds float 'illuminance' (lx, also in 'quality') and 'luminance' (cd/m^2)")
      ->capture_default_str();
  command->add_option("--preview", options->preview,
                      "Also render a PNG picture of the result, from the view that shows the most lit surface (from "
                      "outside an open model, from a room's corner inside a building)");
  command->add_flag("--views", options->views,
                    "Also render the automatic views: a plan of each storey cut at 0.45 of its ceiling height and a "
                    "view of each room, as OUT_view_NAME.png and OUT_view_NAME_luminance.png (the scene file's "
                    "\"cameras\" are always rendered)");
  command->add_option("--html", options->html,
                      "Write the lighting report here: one HTML file with the solve's facts, the luminaires, the grids "
                      "and the views (implies --views)");
  command->add_option("--preview-width", options->preview_width, "Width of the preview in pixels")
      ->capture_default_str()
      ->check(CLI::Range(16, 8192));
  return [options] { return run_solve(*options); };
}

}  // namespace dynrad::cli
