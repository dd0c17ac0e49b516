#include "plugin/capi/capi_report.h"

#include "mesh/core/error.h"
#include "mesh/io/atomic_file.h"
#include "plugin/report/design_output.h"
#include "plugin/report/grid_output.h"
#include "plugin/report/html_report.h"
#include "plugin/report/report_document.h"
#include "plugin/report/view_output.h"
#include "radiosity/analysis/views.h"
#include "radiosity/pipeline/report_json.h"

#include <filesystem>

namespace dynrad::capi {

void write_report(const std::string& html, const ReportInputs& inputs) {
  const rad::PreparedScene& prepared = *inputs.prepared;
  const rad::SolvedScene& solved = *inputs.solved;
  const std::filesystem::path path(html);
  const std::string prefix = (path.parent_path() / path.stem()).string();
  const bool scene_file = solved.lit != nullptr && !prepared.request.path.empty();

  // Every file's place first, so that a report that cannot be written leaves nothing.
  std::vector<rad::View> cameras;
  if (scene_file) cameras = rad::read_cameras(prepared.request.path);
  report::check_grid_outputs(prefix, prepared.grids);
  report::check_view_outputs(prefix, cameras, scene_file, html);
  check_output_writable(html);

  report::ReportHost host;
  host.version = inputs.version;
  host.input = inputs.input;
  host.output = "none: the lit mesh is the host's (C ABI)";
  if (!solved.grids.empty())
    host.grids = report::write_grid_results(prefix, inputs.input, solved.grids, prepared.photometric);
  if (scene_file) {
    rad::ViewOptions view_options;
    view_options.exposure = inputs.exposure;
    const std::vector<rad::View> views =
        rad::merge_views(cameras, rad::automatic_views(*solved.lit, prepared.grids, view_options));
    host.pictures = report::write_views(prefix, *solved.lit, views, inputs.exposure);
  }
  if (!prepared.light_scenes.empty())
    host.scenes = report::light_scene_results(prepared.light_scenes, prepared.channels, solved.grids);
  const nlohmann::json j = report::report_document(prepared, solved, inputs.exposure, host);
  report::write_html_report(html, j);
}

}  // namespace dynrad::capi
