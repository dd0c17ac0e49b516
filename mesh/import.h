// Reading models and scenes into a polygon soup. Every reader validates what it reads
// and throws InputError naming the file (and line where the format has lines).
#pragma once

#include "mesh/soup.h"

#include <string>

namespace dynrad {

// Reads one model file, chosen by extension: .obj (with its .mtl libraries), .ply,
// .off, .stl. Materials come from MTL (Kd -> reflectance, Ke -> emission) or from
// per-face colours (PLY/OFF, read as sRGB and linearised); faces without either get
// the material "default". Materials referenced but not defined are kept with
// `defined == false` so that a scene file can supply them; read_input() refuses any
// that remain undefined.
PolygonSoup read_model(const std::string& path);

// Reads a JSON scene file (see README, "Scene files"): mesh files with transforms,
// material definitions and assignments by material or group name.
PolygonSoup read_scene(const std::string& path);

// read_scene for .json, read_model otherwise; then checks that every material used is
// defined and physically valid (reflectance in [0, 1), emission >= 0, all finite).
PolygonSoup read_input(const std::string& path);

// Validates a material; throws InputError naming `where` when it is not usable.
void check_material(const Material& m, const std::string& where);

}  // namespace dynrad
