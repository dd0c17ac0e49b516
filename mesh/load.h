// The whole input path in one call: read (model or scene file), clean, build the
// half-edge scene mesh.
#pragma once

#include "mesh/cleanup.h"
#include "mesh/scene_mesh.h"

#include <memory>
#include <string>
#include <vector>

namespace dynrad {

struct LoadedScene {
  std::unique_ptr<SceneMesh> mesh;
  CleanupReport cleanup;
  std::size_t input_files = 0;
  std::vector<std::string> warnings;
};

// Throws InputError for unusable input, including a scene that cleanup empties.
LoadedScene load_scene(const std::string& path, const CleanupOptions& options = {});

}  // namespace dynrad
