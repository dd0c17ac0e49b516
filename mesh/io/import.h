// Reading models and scenes into a polygon soup. Every reader validates what it reads
// and throws InputError naming the file (and line where the format has lines).
//
// Lenient where mature tools (Blender, MeshLab, assimp) are lenient: a missing MTL
// library, a material used but defined nowhere, a reflectance of 1 or more and an
// unknown PLY header line are read with a warning (PolygonSoup::warnings) that names
// the file and line or the material. ReadOptions::strict refuses them instead. Damaged
// data (truncated files, numbers that do not parse, bad indices) is always refused.
#pragma once

#include "mesh/core/soup.h"

#include <string>
#include <vector>

namespace dynrad {

struct ReadOptions {
  // Refuse (InputError) what is otherwise read with a warning: a missing `mtllib`, a
  // `usemtl` or scene assignment naming a material defined nowhere, a reflectance of 1
  // or more, an unknown PLY header line. Text encodings (a byte-order mark, UTF-16)
  // are decoded either way: they are not defects.
  bool strict = false;
  // Top-level keys of a JSON scene file that the caller reads itself (the light
  // sources, say): accepted and left alone here. Any other unknown key is an error.
  std::vector<std::string> other_scene_keys;
  // The model file's up axis: 2 (z, dynrad's own), 1 (y: turned so that +y becomes +z,
  // (x, y, z) -> (x, -z, y)), or -1: the reader's convention (y for what assimp reads,
  // since it hands every format over y up; z for dynrad's own readers).
  int up = -1;
  // Model units to metres (or whatever unit the scene's lights and grids are in):
  // 0.001 for millimetres. Applied after the turn.
  double scale = 1;
};

// What a reflectance of 1 or more becomes when read leniently: each of its channels
// above this is lowered to it (the Blender add-on and PLY face colours use the same
// limit). Reflectances below 1 are kept as they are.
constexpr double kMaxReflectance = 0.95;

// Reads one model file, chosen by extension: .obj (with its .mtl libraries), .ply,
// .off, .stl with dynrad's own readers; IFC, glTF (.gltf, .glb), COLLADA, 3DS, FBX and
// whatever else assimp reads through assimp (mesh/io/read_assimp.cpp). Then turned to z
// up and scaled (ReadOptions::up, scale). Materials come from MTL (Kd -> reflectance, Ke -> emission) or from
// per-face colours (PLY/OFF, read as sRGB and linearised); faces without either get
// the material "default". Materials referenced but not defined are kept with
// `defined == false` so that a scene file can supply them; read_input() settles any
// that remain undefined. OBJ and MTL text may be UTF-8 or UTF-16 with a byte-order mark.
PolygonSoup read_model(const std::string& path, const ReadOptions& options = {});

// Reads a JSON scene file (see docs/scene-files.md, "Scene files"): mesh files with transforms,
// material definitions and assignments by material or group name.
PolygonSoup read_scene(const std::string& path, const ReadOptions& options = {});

// read_scene for .json, read_model otherwise; then settles every material used: one
// defined nowhere gets the default (grey, reflectance 0.5, no emission) with a warning
// naming where it was first used, and each is checked by accept_material. Strict
// reading refuses an undefined material.
PolygonSoup read_input(const std::string& path, const ReadOptions& options = {});

// Validates a material; throws InputError naming `where` when it is not usable: a value
// that is not finite, a negative one, or a reflectance of 1 or more (the C ABI uses
// this as it is: its callers set reflectance themselves).
void check_material(const Material& m, const std::string& where);

// check_material for materials read from files. Unless `options.strict`, a reflectance
// of 1 or more in some channel is first lowered (each channel above kMaxReflectance
// becomes kMaxReflectance), and a warning naming the material and where it is defined is appended to
// `warnings`. Not finite or negative values are refused either way.
void accept_material(Material& m, const std::string& where, const ReadOptions& options,
                     std::vector<std::string>& warnings);

}  // namespace dynrad
