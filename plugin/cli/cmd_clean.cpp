// `dynrad clean FILE -o OUT.ply`: the cleaned, triangulated mesh coloured by
// reflectance (emitters by their emission colour), with vertices split at creases and
// material borders exactly as lit output will be. Useful to check a model's materials
// and facing before a solve.
#include "mesh/io/atomic_file.h"
#include "mesh/load.h"
#include "mesh/core/vertex_split.h"
#include "plugin/cli/commands.h"
#include "radiosity/analysis/tonemap.h"

#include <spdlog/spdlog.h>

#include <memory>

namespace dynrad::cli {
namespace {

struct CleanOptions {
  LoadOptions load;
  std::string output;
  bool ascii = false;
  double crease_angle = 30.0;
};

int run_clean(const CleanOptions& options) {
  check_output_writable(options.output);  // fail before the work, not after
  const CleanupOptions cleanup = options.load.cleanup();
  LoadedScene scene = load_scene(options.load.input, cleanup, {}, options.load.read());
  for (const auto& w : scene.warnings) spdlog::warn("{}", w);
  const SceneMesh& mesh = *scene.mesh;
  const VertexSplit split = split_vertices(mesh, options.crease_angle);
  // Reflectance for surfaces; emitters show their emission colour scaled to 1.
  auto shown = [&mesh](FaceHandle f) {
    const Material& m = mesh.material(f);
    if (!m.emits()) return m.reflectance;
    return m.emission * (1.0 / m.emission.max_channel());
  };
  std::vector<Rgb> values = average_over_faces<Rgb>(mesh, split, shown);
  VertexValues out = rad::tone_map(std::move(values), 1.0, "reflectance");
  WriteOptions write;
  write.ascii = options.ascii;
  write_mesh_with_values(options.output, mesh, split, out, write);
  spdlog::info("wrote {} ({} vertices, {} triangles, {} repairs)", options.output, split.size(), mesh.face_count(),
               scene.cleanup.repairs());
  return kExitOk;
}

}  // namespace

Command add_clean_command(CLI::App& app) {
  auto options = std::make_shared<CleanOptions>();
  CLI::App* command =
      app.add_subcommand("clean", "Write the cleaned, triangulated model coloured by reflectance (.ply or .off)");
  add_load_options(*command, options->load);
  command->add_option("-o,--output", options->output, "Output file (.ply or .off)")->required();
  command->add_flag("--ascii", options->ascii, "Write ASCII PLY instead of binary");
  command->add_option("--crease-angle", options->crease_angle, "Split vertices where faces meet at more than this (degrees)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 180.0));
  return [options] { return run_clean(*options); };
}

}  // namespace dynrad::cli
