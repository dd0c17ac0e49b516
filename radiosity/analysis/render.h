// Pictures of a lit scene: one primary ray per pixel through Embree, the radiosity
// interpolated from the hit triangle's corner values. Perspective cameras for views of
// rooms, orthographic ones for plans (rays start at the cut plane, so everything above
// it is gone; a ray that starts inside a solid shows as the cut).
#pragma once

#include "radiosity/analysis/lit_scene.h"

#include <array>
#include <cstdint>
#include <vector>

namespace dynrad::rad {

struct Camera {
  Vec3d eye, target, up;
  double fov_degrees = 50;    // vertical field of view, perspective cameras
  bool orthographic = false;  // parallel rays along eye -> target, starting in the plane through eye
  double view_height = 0;     // orthographic: model units from the picture's bottom to its top
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first
};

struct Ray {
  Vec3d origin, direction;  // direction of unit length
};

// The ray through picture point (px, py), both in [-1, 1], y up, for a picture of
// width / height `aspect`.
Ray camera_ray(const Camera& camera, double aspect, double px, double py);

enum class PixelKind : std::uint8_t { nothing, front, back };

// What each pixel sees, in linear units, before any display encoding.
struct RenderedView {
  int width = 0, height = 0;
  std::vector<Rgb> radiosity;     // front-face pixels; zero elsewhere
  std::vector<PixelKind> kind;
  std::vector<char> emitter;      // the pixel shows an emitting triangle
  // Luminance of a diffuse surface, B / pi: cd/m^2 in photometric units, W/(m^2 sr) else.
  double luminance(std::size_t pixel) const { return radiosity[pixel].luminance() / M_PI; }
};

RenderedView render_view(const LitScene& scene, const Camera& camera, int width, int height);

// True colour: the same exposure and sRGB curve as the PLY's vertex colours. Pixels
// that meet the back of a face get `back` (a flipped face in a view; the cut through a
// solid in a plan), pixels that meet nothing get `background`.
Image colour_image(const RenderedView& view, double exposure, std::array<std::uint8_t, 3> back,
                   std::array<std::uint8_t, 3> background);

}  // namespace dynrad::rad
