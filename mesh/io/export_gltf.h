// Writing a lit mesh as binary glTF 2.0 (.glb), with tinygltf (Debian's libtinygltf).
//
// Positions go from dynrad's z up to glTF's y up: (x, y, z) -> (x, z, -y) (a y-up model
// should be read with --up y to arrive standing). One buffer holds every vertex once:
// POSITION (float VEC3), COLOR_0 (float VEC3, the
// display colours made linear again, as glTF specifies: what MeshLab shows from the PLY's
// bytes, a viewer shows from these), and custom attributes `_<NAME>` (the linear values,
// float VEC3, e.g. `_RADIOSITY`) and `_<SCALAR>` for each named scalar (float, e.g.
// `_ILLUMINANCE`). One node and mesh per input group (its name), one primitive per
// material in it (its name; base colour its reflectance, KHR_materials_unlit so that
// viewers show the baked light as it is rather than lighting it again). Glass, which is
// not lit, follows as a node "glazing" with its own positions and no vertex colours,
// one primitive per transmittance, its material unlit, blended and two-sided (base
// colour the transmittance, opacity 0.2 + 0.5 (1 - its luminance); the transmittance in
// `extras`). Viewpoints become perspective cameras on nodes of their own, after the
// meshes' nodes, in order. A background colour goes into the scene's extras.
#pragma once

#include "mesh/io/export.h"

namespace dynrad {

// Writes atomically; OutputError when the file cannot be written.
void write_glb(const std::string& path, const SceneMesh& scene, const VertexSplit& split, const VertexValues& values,
               const WriteOptions& options = {});

}  // namespace dynrad
