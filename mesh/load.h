// The whole input path in one call: read (model or scene file), clean, build the
// half-edge scene mesh.
#pragma once

#include "mesh/repair/cleanup.h"
#include "mesh/io/import.h"
#include "mesh/core/scene_mesh.h"
#include "mesh/repair/simplify.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace dynrad {

struct LoadedScene {
  std::unique_ptr<SceneMesh> mesh;
  // The faces whose material transmits, triangulated: not lit, not blocking the lit
  // mesh's rays; light from outside (sky, sun) crossing them is scaled by their
  // transmittance.
  std::vector<GlazingTriangle> glazing;
  // The holes light from outside comes in through (mesh/core/openings.h), triangulated.
  std::vector<std::array<Vec3d, 3>> openings;
  CleanupReport cleanup;
  SimplifyReport simplify;  // all zero-change unless SimplifyOptions::enabled
  std::size_t input_files = 0;
  std::vector<std::string> warnings;
};

// Throws InputError for unusable input, including a scene that cleanup empties.
// `simplify` merges flat regions after cleanup (mesh/repair/simplify.h); off by default.
// `read` says whether what mature tools accept with a warning is accepted (the
// default; the warnings join LoadedScene::warnings) or refused (mesh/io/import.h).
LoadedScene load_scene(const std::string& path, const CleanupOptions& options = {},
                       const SimplifyOptions& simplify = {}, const ReadOptions& read = {});

// The same for a soup built in memory (the C ABI, host add-ons): cleans it and builds
// the mesh. Materials must already be checked (check_material in mesh/io/import.h);
// `label` stands in for the file name in messages. Throws InputError for non-finite
// coordinates or a soup that cleanup empties.
LoadedScene load_soup(const PolygonSoup& soup, const std::string& label, const CleanupOptions& options = {},
                      const SimplifyOptions& simplify = {});

}  // namespace dynrad
