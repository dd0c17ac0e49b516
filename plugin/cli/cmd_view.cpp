// `dynrad view LIT.glb -o view.html`: a walk-through of a lit model in the browser, as
// one self-contained HTML page (the .glb as base64, three.js and the page's script
// inlined; plugin/cli/viewer/). Whoever receives the file opens it in a browser, offline,
// with nothing to install.
//
// The .glb is read first (mesh/io/read_glb.h) and refused with the reason when a browser's
// loader would fail on it, so that a page once written shows its model. Nothing is
// written on refusal.
#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "mesh/io/io_util.h"
#include "mesh/io/read_glb.h"
#include "plugin/cli/commands.h"
#include "plugin/report/grid_picture.h"
#include "plugin/report/html_report.h"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <string_view>

namespace dynrad::cli {
using namespace dynrad::report;  // the report's writers (plugin/report/)

namespace embedded {
extern const std::string_view three_js, gltf_loader_js, viewer_js, viewer_page;
}

namespace {

struct ViewOptions {
  std::string input, output, title;
  double top = 0;  // the false colour's top in luminance units; 0: automatic
};

// JSON inside a <script> element: "<" escaped, so no "</script>" can end it early.
std::string script_json(const nlohmann::json& j) {
  std::string out;
  for (char c : j.dump()) {
    if (c == '<') out += "\\u003c";
    else out += c;
  }
  return out;
}

int run_view(const ViewOptions& options) {
  if (std::filesystem::path(options.output).extension() != ".html")
    throw OutputError(options.output, "the walk-through is an HTML page; name it NAME.html.");
  check_output_writable(options.output);
  const std::string bytes = detail::read_file(options.input);
  const GlbSummary summary = glb_summary_from_memory(bytes, options.input);
  if (summary.coloured_primitives == 0)
    throw InputError(options.input, 0,
                     "has no vertex colours (COLOR_0), so there is no light to show. Give the .glb that "
                     "`dynrad solve -o OUT.glb` wrote.");

  nlohmann::json config;
  const std::string title =
      options.title.empty() ? std::filesystem::path(options.input).stem().string() : options.title;
  nlohmann::json palette = nlohmann::json::array();
  for (const auto& stop : false_colour_stops()) palette.push_back({stop[0], stop[1], stop[2]});
  config["palette"] = palette;
  config["top"] = options.top;
  const bool photometric = summary.scalars.count("_LUMINANCE") > 0;
  config["luminance_unit"] = photometric ? "cd/m\u00b2" : "W/(m\u00b2 sr)";
  config["length_unit"] = "m";

  // The page, with its markers replaced by the pieces in order.
  const std::string_view page = embedded::viewer_page;
  const std::pair<std::string_view, std::string> pieces[] = {
      {"<!--@TITLE@-->", html_escape(title)},      {"<!--@TITLE@-->", html_escape(title)},
      {"<!--@CONFIG@-->", script_json(config)},    {"<!--@MODEL@-->", base64(bytes)},
      {"<!--@THREE@-->", std::string(embedded::three_js)},
      {"<!--@GLTFLOADER@-->", std::string(embedded::gltf_loader_js)},
      {"<!--@VIEWER@-->", std::string(embedded::viewer_js)}};
  std::string html;
  std::size_t at = 0;
  for (const auto& [marker, text] : pieces) {
    const std::size_t found = page.find(marker, at);
    if (found == std::string_view::npos) throw std::logic_error("the viewer page lacks " + std::string(marker));
    html.append(page.substr(at, found - at));
    html += text;
    at = found + marker.size();
  }
  html.append(page.substr(at));

  AtomicFile file(options.output);
  file.stream().write(html.data(), static_cast<std::streamsize>(html.size()));
  file.commit();
  spdlog::info("wrote {} ({:.1f} MB): {} triangles, {} vertices, {} viewpoints{}; open it in a browser", options.output,
               static_cast<double>(html.size()) / 1e6, summary.triangles, summary.vertices, summary.cameras.size(),
               summary.cameras.empty() ? "" : " (first: " + summary.cameras.front() + ")");
  return kExitOk;
}

}  // namespace

Command add_view_command(CLI::App& app) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* command = app.add_subcommand(
      "view", "A walk-through of a lit .glb in the browser: one self-contained HTML page (three.js inlined) with "
              "first-person navigation, the file's viewpoints, exposure and false-colour luminance");
  command->add_option("lit", options->input, "Lit .glb written by dynrad solve -o OUT.glb")->required();
  command->add_option("-o,--output", options->output, "The page to write: NAME.html")->required();
  command->add_option("--title", options->title, "The page's title (default: the .glb's name)");
  command->add_option("--top", options->top,
                      "Top of the false-colour scale, in cd/m^2 (W/(m^2 sr) for radiometric solves); default: a round "
                      "value at or above the 98th percentile of the vertices' luminance")
      ->check(CLI::PositiveNumber);
  return [options] { return run_view(*options); };
}

}  // namespace dynrad::cli
