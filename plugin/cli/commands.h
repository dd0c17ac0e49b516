// Subcommands of the `dynrad` command line. Each registers its options on the app and
// returns the function that runs it.
#pragma once

#include "mesh/repair/cleanup.h"
#include "mesh/io/import.h"
#include "radiosity/pipeline/scene_sections.h"

#include <CLI/CLI.hpp>

#include <functional>

namespace dynrad::cli {

using Command = std::function<int()>;

// Exit codes, also listed in the README.
constexpr int kExitOk = 0;
constexpr int kExitInternal = 1;  // a bug: please report it
constexpr int kExitBadInput = 2;  // unusable input, unwritable output, bad options
constexpr int kExitInterrupted = 3;  // stopped by a signal; the current solution was written
constexpr int kExitValidation = 4;   // validate: a case is over its goal

Command add_info_command(CLI::App& app);
Command add_clean_command(CLI::App& app);
Command add_solve_command(CLI::App& app);
Command add_diff_command(CLI::App& app);
Command add_plot_command(CLI::App& app);
Command add_probe_command(CLI::App& app);
Command add_grid_command(CLI::App& app);
Command add_view_command(CLI::App& app);
Command add_validate_command(CLI::App& app);
Command add_annual_command(CLI::App& app);

// Options every command that loads a scene shares.
struct LoadOptions {
  std::string input;
  double merge_tolerance = 1e-6;
  bool imprint = true;   // imprint where surfaces meet, remove hidden parts (mesh/repair/imprint.h)
  bool simplify = true;  // merge flat regions before patching (mesh/repair/simplify.h)
  bool strict = false;   // refuse what is otherwise read with a warning (mesh/io/import.h)
  std::string up = "auto";  // the model's up axis: auto (the format's), y or z
  double scale = 1;         // model units to metres

  CleanupOptions cleanup() const {
    CleanupOptions options;
    options.merge_tolerance = merge_tolerance;
    options.imprint = imprint;
    return options;
  }
  ReadOptions read() const {
    ReadOptions options;
    options.strict = strict;
    options.up = up == "y" ? 1 : up == "z" ? 2 : -1;
    options.scale = scale;
    options.other_scene_keys = rad::scene_file_sections();
    return options;
  }
};
void add_load_options(CLI::App& command, LoadOptions& options);
// `--merge-tolerance`, `--no-imprint` and `--strict` alone, for a command that loads a
// second model.
void add_cleanup_options(CLI::App& command, LoadOptions& options);
// `--no-simplify`, for the commands that patch the model (solve, info).
void add_simplify_flag(CLI::App& command, LoadOptions& options);
// --model-up and --model-scale: how a command that reads a lit mesh reads the model it
// was lit from, as `solve` read it with --up and --scale.
void add_model_axis_options(CLI::App& command, LoadOptions& options);

}  // namespace dynrad::cli
