// The parts of a JSON scene file that the radiosity layer reads itself ("luminaires",
// "grids"; the mesh layer reads the geometry and materials and leaves these alone).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace dynrad::rad {

// The value of top-level `key` of the scene file at `path`, or null when the file is
// not a scene (.json) or has no such key. Throws InputError for invalid JSON.
nlohmann::json scene_section(const std::string& path, const std::string& key);

// `value` as a finite number; otherwise InputError naming the scene file and `where`.
double scene_number(const std::string& path, const nlohmann::json& value, const std::string& where);

}  // namespace dynrad::rad
