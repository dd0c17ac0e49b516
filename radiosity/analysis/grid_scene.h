// Calculation grids declared in a JSON scene file's "grids" array (see
// grid_scene.cpp for the keys).
#pragma once

#include "radiosity/analysis/grid.h"

#include <string>
#include <vector>

namespace dynrad::rad {

// Empty when the file is not a scene (.json) or has no "grids". Throws InputError
// naming the scene file and the entry.
std::vector<GridSpec> read_grids(const std::string& scene_path);

}  // namespace dynrad::rad
