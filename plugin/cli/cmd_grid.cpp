// `dynrad grid LIT.ply --model SCENE`: calculation grids over a lit result, without
// solving again. The grids are the scene file's ("grids"), or one given by --grid. The
// direct light comes from the model (its luminaires, its emitting faces), the rest from
// the lit PLY's radiosity (radiosity/analysis/grid.h). With --views or --html, also the views
// (the scene's cameras, plans and rooms) and the one-file report; with --pdf, the
// printable report (plugin/cli/pdf_report.h).
#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "mesh/load.h"
#include "plugin/cli/commands.h"
#include "plugin/report/design_output.h"
#include "plugin/report/grid_output.h"
#include "plugin/report/html_report.h"
#include "plugin/cli/pdf_report.h"
#include "plugin/report/view_output.h"
#include "plugin/cli/lit_mesh.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/design/light_scenes.h"
#include "radiosity/analysis/grid_scene.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/solver/solve_types.h"
#include "radiosity/analysis/tonemap.h"
#include "radiosity/analysis/views.h"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <sstream>

namespace dynrad::cli {
using namespace dynrad::report;  // the report's writers (plugin/report/)
namespace {

struct GridOptions {
  std::string lit, model, grid, output;
  double height = 0.8, spacing = 0, border = 0;
  std::string up = "z", name = "grid";
  bool views = false;
  std::string html, pdf;
  double exposure = 0;  // 0: automatic, as solve's
  LoadOptions model_load;
};

int run_grid(const GridOptions& options) {
  // Observers, emergency routes, the project block (plugin/report/design_output.h); light
  // scenes are checked here too, before any work, though only a solve computes them.
  const bool design = check_design_inputs(options.model);
  const bool light_scenes = !rad::read_light_scenes(options.model, rad::read_luminaires(options.model)).empty();
  std::vector<rad::GridSpec> grids;
  if (!options.grid.empty()) {
    std::vector<double> v;
    std::istringstream in(options.grid);
    for (std::string field; std::getline(in, field, ',');) {
      char* end = nullptr;
      const double x = std::strtod(field.c_str(), &end);
      if (field.empty() || *end != '\0' || !std::isfinite(x))
        throw InputError("--grid", 0, "'" + field + "' is not a number; --grid is x0,y0,x1,y1.");
      v.push_back(x);
    }
    if (v.size() != 4 || !(v[2] > v[0] && v[3] > v[1]))
      throw InputError("--grid", 0, "expects x0,y0,x1,y1 with x1 > x0 and y1 > y0.");
    rad::GridSpec g;
    g.name = options.name;
    g.polygon = {{v[0], v[1]}, {v[2], v[1]}, {v[2], v[3]}, {v[0], v[3]}};
    g.height = options.height;
    g.spacing = options.spacing;
    g.border = options.border;
    g.up = options.up == "x" ? 0 : options.up == "y" ? 1 : options.up == "z" ? 2 : -1;
    if (g.up < 0) throw InputError("--up", 0, "'" + options.up + "' is not an axis; use x, y or z.");
    if (rad::grid_points(g).empty()) throw InputError("--grid", 0, "has no point: the border leaves nothing.");
    grids.push_back(g);
  } else {
    grids = rad::read_grids(options.model);
    if (grids.empty() && !design && !options.views && options.html.empty() && options.pdf.empty())
      throw InputError(options.model, 0,
                       "declares no \"grids\"; give one with --grid x0,y0,x1,y1 (and --height, --spacing).");
  }
  const std::string prefix =
      options.output.empty()
          ? (std::filesystem::path(options.lit).parent_path() / std::filesystem::path(options.lit).stem()).string()
          : options.output;
  check_grid_outputs(prefix, grids);
  const std::vector<rad::View> cameras = rad::read_cameras(options.model);
  const bool automatic_views = options.views || !options.html.empty() || !options.pdf.empty();
  check_view_outputs(prefix, cameras, automatic_views, options.html);
  if (!options.pdf.empty()) check_output_writable(options.pdf);

  const LitMesh lit = read_lit(options.lit);
  LoadedScene loaded = load_scene(options.model, options.model_load.cleanup(), {}, options.model_load.read());
  for (const auto& w : loaded.warnings) spdlog::warn("{}", w);
  const SceneMesh& model = *loaded.mesh;
  check_model_matches(lit, options.lit, model, options.model);
  const rad::Visibility model_index(model);
  rad::LitScene scene;
  scene.positions = lit.positions;
  scene.triangles = lit.triangles;
  scene.radiosity = lit.radiosity;
  scene.photometric = lit.photometric;
  scene.luminaires = rad::read_daylight(options.model, loaded.glazing, loaded.openings);
  for (rad::Luminaire& l : rad::read_luminaires(options.model)) scene.luminaires.push_back(std::move(l));
  // Each lit triangle's emission: the model's material where its centroid lies.
  const double scale = lit.photometric ? rad::kLumensPerWatt : 1.0;
  for (const auto& t : lit.triangles) {
    const Vec3d &a = lit.positions[t[0]], &b = lit.positions[t[1]], &c = lit.positions[t[2]];
    const Vec3d n = OpenMesh::cross(b - a, c - a);
    const Material* m = n.norm() > 0 ? material_at(model, model_index, (a + b + c) / 3.0, n.normalized()) : nullptr;
    scene.emission.push_back(m ? m->emission * scale : Rgb());
  }
  scene.prepare();
  nlohmann::json report = {{"dynrad_version", DYNRAD_VERSION},
                           {"input", options.model},
                           {"output", options.lit},
                           {"units", lit.photometric ? "photometric" : "radiometric"},
                           {"grids", nlohmann::json::array()}};
  const std::vector<rad::GridResult> gathered = rad::gather_grids(scene, grids);
  if (!grids.empty()) report["grids"] = write_grid_results(prefix, options.model, gathered, scene.photometric);
  report["luminaires"] = nlohmann::json::array();
  for (const rad::Luminaire& l : scene.luminaires) report["luminaires"].push_back(luminaire_json(l));
  add_design_checks(report, options.model, scene, gathered);
  if (light_scenes)
    spdlog::info("the scene's light scenes are left out: they come from a solve (dynrad solve), whose groups travel "
                 "in channels of their own; a lit PLY holds the light of every group together.");
  std::vector<char> include(scene.radiosity.size(), 1);
  for (std::size_t f = 0; f < scene.triangles.size(); ++f)
    if (!scene.emission[f].is_zero())
      for (std::uint32_t v : scene.triangles[f]) include[v] = 0;
  const double exposure = options.exposure > 0 ? options.exposure : rad::auto_exposure(scene.radiosity, include, rad::vertex_areas(scene.positions, scene.triangles));
  rad::ViewOptions view_options;
  view_options.exposure = exposure;
  const std::vector<rad::View> views =
      automatic_views ? rad::merge_views(cameras, rad::automatic_views(scene, grids, view_options)) : cameras;
  if (!views.empty()) {
    report["exposure"] = exposure;
    report["views"] = views_json(write_views(prefix, scene, views, exposure));
  }
  if (!options.html.empty()) {
    write_html_report(options.html, report);
    spdlog::info("wrote {}", options.html);
  }
  if (!options.pdf.empty()) {
    write_pdf_report(options.pdf, report);
    spdlog::info("wrote {}", options.pdf);
  }
  return kExitOk;
}

}  // namespace

Command add_grid_command(CLI::App& app) {
  auto options = std::make_shared<GridOptions>();
  CLI::App* command = app.add_subcommand(
      "grid", "Illuminance on calculation grids (work planes) of a lit mesh: figures, CSV and false-colour plans; "
      "with --views, --html or --pdf, views and the report");
  command->add_option("lit", options->lit, "Lit PLY written by dynrad solve")->required();
  command->add_option("--model", options->model,
                      "The model or scene file the PLY was lit from: its luminaires, emitting faces and grids")
      ->required();
  command->add_option("--grid", options->grid, "x0,y0,x1,y1: one rectangular grid instead of the scene's");
  command->add_option("--height", options->height, "Height of --grid along the up axis")->capture_default_str();
  command->add_option("--spacing", options->spacing, "Spacing of --grid (default: 0.2 x 5^log10(d))")
      ->check(CLI::PositiveNumber);
  command->add_option("--border", options->border, "Band along --grid's edges left out")->check(CLI::NonNegativeNumber);
  command->add_option("--up", options->up, "Up axis of --grid: x, y or z")->capture_default_str();
  command->add_option("--name", options->name, "Name of --grid, in results and file names")->capture_default_str();
  command->add_option("-o,--output", options->output,
                      "Prefix of the results: PREFIX_grids.json, PREFIX_grid_NAME.csv and .png (default: the PLY's "
                      "path without .ply)");
  command->add_flag("--views", options->views,
                    "Also render the views: the scene's cameras, a plan of each storey and a view of each room "
                    "(PREFIX_view_NAME.png and PREFIX_view_NAME_luminance.png)");
  command->add_option("--html", options->html, "Write a one-file HTML report of the grids and views here (implies --views)");
  command->add_option("--pdf", options->pdf,
                      "Write a printable PDF report (A4) of the grids and views here (implies --views)");
  command->add_option("--exposure", options->exposure, "Exposure of the true-colour views (default: automatic)")
      ->check(CLI::PositiveNumber);
  add_cleanup_options(*command, options->model_load);
  add_model_axis_options(*command, options->model_load);
  return [options] { return run_grid(*options); };
}

}  // namespace dynrad::cli
