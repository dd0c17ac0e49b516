// Reading back a binary glTF (.glb) that a viewer is to show: what it holds, checked
// deeply enough that a browser's loader will not fail on it. Uses tinygltf (Debian's
// libtinygltf) to parse; images are not decoded.
//
// Checked: the GLB container and its JSON; at least one triangle primitive; every
// primitive's POSITION, COLOR_0, indices and `_`-prefixed float attributes lie inside
// their buffer views and buffers, have the same vertex count, and are finite; indices
// point at vertices that exist. Anything else is an InputError naming the file and the
// mesh or accessor at fault.
#pragma once

#include "mesh/core/types.h"

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace dynrad {

struct GlbSummary {
  std::size_t meshes = 0, primitives = 0, triangles = 0;
  std::size_t vertices = 0;       // distinct vertices, counted once per shared accessor
  std::size_t coloured_primitives = 0;  // with COLOR_0 (lit surfaces; glass has none)
  std::vector<std::string> cameras;  // perspective cameras on nodes, by node name, in node order
  Bounds bounds;                  // of the positions, in the file's (y-up) axes
  // Float SCALAR attributes whose names start with '_' (e.g. "_LUMINANCE"), the values
  // of each distinct accessor once, in accessor order.
  std::map<std::string, std::vector<float>> scalars;
};

GlbSummary read_glb_summary(const std::string& path);
// The same from bytes in memory; `name` names them in errors.
GlbSummary glb_summary_from_memory(const std::string& bytes, const std::string& name);

}  // namespace dynrad
