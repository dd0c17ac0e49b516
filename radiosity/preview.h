// A quick picture of a lit mesh: primary rays through Embree, radiosity interpolated
// from the hit face's corner values, the same exposure and sRGB curve as the PLY
// colours. Back faces show dark red, so flipped faces in a model stand out.
#pragma once

#include "mesh/scene_mesh.h"
#include "mesh/vertex_split.h"
#include "radiosity/visibility.h"

#include <cstdint>
#include <vector>

namespace dynrad::rad {

struct Camera {
  Vec3d eye, target, up;
  double fov_degrees = 50;  // vertical
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first
};

// Tries views from outside each side of the scene and from inside looking along each
// axis, and keeps the one whose rays meet the most front faces. "Up" is opposite to
// the main emitters' facing when they face along an axis (lights hang from ceilings),
// else +z.
Camera default_camera(const SceneMesh& scene, const Visibility& visibility);

Image render_preview(const VertexSplit& split, const std::vector<Rgb>& values,
                     double exposure, const Camera& camera, int width, int height, const Visibility& visibility);

}  // namespace dynrad::rad
