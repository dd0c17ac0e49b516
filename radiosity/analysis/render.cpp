#include "radiosity/analysis/render.h"

#include "radiosity/analysis/tonemap.h"

#include <tbb/parallel_for.h>

#include <cmath>

namespace dynrad::rad {

Ray camera_ray(const Camera& c, double aspect, double px, double py) {
  const Vec3d forward = (c.target - c.eye).normalized();
  const Vec3d right = OpenMesh::cross(forward, c.up).normalized();
  const Vec3d up = OpenMesh::cross(right, forward);
  if (c.orthographic) {
    const double half = 0.5 * c.view_height;
    return {c.eye + right * (px * half * aspect) + up * (py * half), forward};
  }
  const double half = std::tan(0.5 * c.fov_degrees * M_PI / 180.0);
  return {c.eye, (forward + right * (px * half * aspect) + up * (py * half)).normalized()};
}

namespace {

bool inside_solid(const LitScene& scene, const Vec3d& p, const Vec3d& right, const Vec3d& up) {
  int backs = 0;
  for (const Vec3d& d : {right, up, right * -1.0, up * -1.0}) {
    const auto hit = scene.visibility->intersect(p, d);
    backs += hit.hit && !hit.front;
  }
  return backs >= 3;
}

}  // namespace

RenderedView render_view(const LitScene& scene, const Camera& camera, int width, int height) {
  RenderedView view;
  view.width = width;
  view.height = height;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  view.radiosity.assign(n, Rgb());
  view.kind.assign(n, PixelKind::nothing);
  view.emitter.assign(n, 0);
  const double aspect = static_cast<double>(width) / height;
  const Vec3d forward = (camera.target - camera.eye).normalized();
  const Vec3d right = OpenMesh::cross(forward, camera.up).normalized();
  const Vec3d up = OpenMesh::cross(right, forward);
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
      const Ray ray = camera_ray(camera, aspect, (x + 0.5) / width * 2 - 1, 1 - (y + 0.5) / height * 2);
      // A plan's ray that starts inside a solid shows the cut, whether or not the solid
      // is closed underneath: inside, when at least three of four rays across the
      // picture meet the backs of faces (the solid's sides, seen from within; its top and
      // bottom may lie in a ceiling's or floor's plane).
      if (camera.orthographic && inside_solid(scene, ray.origin, right, up)) {
        view.kind[pixel] = PixelKind::back;
        continue;
      }
      const auto hit = scene.visibility->intersect(ray.origin, ray.direction);
      if (!hit.hit) continue;
      if (!hit.front) {
        view.kind[pixel] = PixelKind::back;
        continue;
      }
      const auto& t = scene.triangles[static_cast<std::size_t>(hit.face)];
      view.kind[pixel] = PixelKind::front;
      view.radiosity[pixel] = scene.radiosity[t[0]] * (1 - hit.u - hit.v) + scene.radiosity[t[1]] * hit.u +
                              scene.radiosity[t[2]] * hit.v;
      view.emitter[pixel] = !scene.emission[static_cast<std::size_t>(hit.face)].is_zero();
    }
  });
  return view;
}

Image colour_image(const RenderedView& view, double exposure, std::array<std::uint8_t, 3> back,
                   std::array<std::uint8_t, 3> background) {
  Image image;
  image.width = view.width;
  image.height = view.height;
  image.rgb.resize(view.kind.size() * 3);
  for (std::size_t p = 0; p < view.kind.size(); ++p) {
    std::uint8_t* out = &image.rgb[3 * p];
    if (view.kind[p] == PixelKind::front) {
      const Rgb& v = view.radiosity[p];
      out[0] = encode_srgb(v.r * exposure);
      out[1] = encode_srgb(v.g * exposure);
      out[2] = encode_srgb(v.b * exposure);
    } else {
      const auto& c = view.kind[p] == PixelKind::back ? back : background;
      out[0] = c[0];
      out[1] = c[1];
      out[2] = c[2];
    }
  }
  return image;
}

}  // namespace dynrad::rad
