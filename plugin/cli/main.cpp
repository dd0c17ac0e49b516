// dynrad: radiosity lighting for meshes. This file only dispatches subcommands and
// turns errors into messages and exit codes; the work is in the libraries.
#include "mesh/core/error.h"
#include "plugin/cli/commands.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <map>

namespace dynrad::cli {

void add_cleanup_options(CLI::App& command, LoadOptions& options) {
  command
      .add_option("--merge-tolerance", options.merge_tolerance,
                  "Merge points closer than this fraction of the scene's bounding-box diagonal")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.01));
  command.add_flag("!--no-imprint", options.imprint,
                   "Do not imprint where surfaces cross or touch, and keep the parts no light reaches (for comparison)");
  command.add_flag("--strict", options.strict,
                   "Refuse (exit 2) what is otherwise read with a warning: a missing .mtl library, a material defined "
                   "nowhere, a reflectance of 1 or more, an unknown PLY header line");
}

void add_load_options(CLI::App& command, LoadOptions& options) {
  command.add_option("input", options.input,
                     "Model (.obj, .ply, .off, .stl; through assimp .ifc, .gltf, .glb, .dae, .3ds, .fbx, ...) or scene "
                     "file (.json)")
      ->required();
  command.add_option("--up", options.up,
                     "The model's up axis: y (turned to z up) or z; auto: y for what assimp reads (it turns IFC and COLLADA to y up itself), z for .obj, .ply, .off and .stl")
      ->check(CLI::IsMember({"auto", "y", "z"}))
      ->capture_default_str();
  command.add_option("--scale", options.scale, "Multiply the model's coordinates by this (0.001: millimetres to metres)")
      ->check(CLI::PositiveNumber);
  add_cleanup_options(command, options);
}

void add_model_axis_options(CLI::App& command, LoadOptions& options) {
  command.add_option("--model-up", options.up, "--model's up axis, as given to solve with --up: auto, y or z")
      ->check(CLI::IsMember({"auto", "y", "z"}))
      ->capture_default_str();
  command.add_option("--model-scale", options.scale, "--model's scale to metres, as given to solve with --scale")
      ->check(CLI::PositiveNumber);
}

void add_simplify_flag(CLI::App& command, LoadOptions& options) {
  command.add_flag("!--no-simplify", options.simplify,
                   "Keep every cleaned triangle: do not merge the triangles of flat regions before patching");
}

}  // namespace dynrad::cli

int main(int argc, char** argv) {
  using namespace dynrad;
  auto logger = spdlog::stderr_color_mt("dynrad");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("%^%l%$: %v");

  CLI::App app{"dynrad: radiosity lighting for meshes (Dynamic Subdivision, Dubuis & Bieri)"};
  app.set_version_flag("--version", std::string("dynrad ") + DYNRAD_VERSION);
  app.require_subcommand(1);
  app.fallthrough();  // -v and -q also after the subcommand
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Print debug messages");
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "Print only warnings and errors: no progress, no summary");
  std::map<CLI::App*, cli::Command> commands;
  for (auto add : {cli::add_solve_command, cli::add_info_command, cli::add_clean_command, cli::add_diff_command,
                    cli::add_plot_command, cli::add_probe_command, cli::add_grid_command, cli::add_view_command,
                    cli::add_validate_command, cli::add_annual_command}) {
    auto run = add(app);
    commands[app.get_subcommands({}).back()] = run;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? cli::kExitOk : cli::kExitBadInput;
  }
  if (verbose) spdlog::set_level(spdlog::level::debug);
  if (quiet) spdlog::set_level(spdlog::level::warn);
  try {
    for (auto* sub : app.get_subcommands())
      if (commands.count(sub)) return commands[sub]();
    return cli::kExitBadInput;
  } catch (const InputError& e) {
    spdlog::error("{}", e.what());
    return cli::kExitBadInput;
  } catch (const OutputError& e) {
    spdlog::error("{}", e.what());
    return cli::kExitBadInput;
  } catch (const std::bad_alloc&) {
    spdlog::error("out of memory. Try a coarser --patch-size or a smaller model.");
    return cli::kExitInternal;
  } catch (const std::exception& e) {
    spdlog::error("internal error: {}. Please report this with the input file.", e.what());
    return cli::kExitInternal;
  }
}
