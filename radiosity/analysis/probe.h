// Values at arbitrary points of a lit mesh: the face containing the point (on the
// surface facing `normal`) and linear interpolation of its corner values.
#pragma once

#include "mesh/core/scene_mesh.h"
#include "mesh/core/vertex_split.h"

#include <optional>
#include <vector>

namespace dynrad::rad {

// The radiosity at `point` on the surface whose normal is within 25 degrees of
// `normal`, or nothing when no such face contains the point (within a tolerance
// relative to the scene size). Brute force over faces: for reports and tests.
std::optional<Rgb> probe(const SceneMesh& scene, const VertexSplit& split, const std::vector<Rgb>& values,
                         const Vec3d& point, const Vec3d& normal);

}  // namespace dynrad::rad
