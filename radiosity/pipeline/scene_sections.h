// The scene file's top-level sections the radiosity layer reads (beside "meshes" and
// "materials", which mesh/ reads): what ReadOptions::other_scene_keys must hold for the
// scene to be read whole. One list for every host and the fuzz targets.
#pragma once

#include <string>
#include <vector>

namespace dynrad::rad {

std::vector<std::string> scene_file_sections();

}  // namespace dynrad::rad
