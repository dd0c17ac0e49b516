#include "radiosity/preview.h"

#include "radiosity/tonemap.h"

#include <tbb/parallel_for.h>

#include <cmath>

namespace dynrad::rad {
namespace {

struct Frame {
  Vec3d forward, right, up;
  double half_height;
};

Frame frame_of(const Camera& c) {
  Frame f;
  f.forward = (c.target - c.eye).normalized();
  f.right = OpenMesh::cross(f.forward, c.up).normalized();
  f.up = OpenMesh::cross(f.right, f.forward);
  f.half_height = std::tan(0.5 * c.fov_degrees * M_PI / 180.0);
  return f;
}

Vec3d ray_direction(const Frame& f, double aspect, double px, double py) {
  // px, py in [-1, 1], y up.
  return (f.forward + f.right * (px * f.half_height * aspect) + f.up * (py * f.half_height)).normalized();
}

}  // namespace

Camera default_camera(const SceneMesh& scene, const Visibility& visibility) {
  const Bounds b = scene.bounds();
  const Vec3d centre = (b.lo + b.hi) * 0.5, extent = b.extent();
  const double size = std::max({extent[0], extent[1], extent[2]});
  // Up: against the emitters' area-weighted facing, when that is clearly one axis.
  Vec3d facing(0.0);
  for (auto f : scene.mesh().faces())
    if (scene.material(f).emits()) facing += scene.normal(f) * scene.area(f);
  Vec3d up(0, 0, 1);
  if (facing.norm() > 0) {
    const Vec3d d = facing.normalized();
    for (int a = 0; a < 3; ++a)
      if (d[a] < -0.7) {
        up = Vec3d(0.0);
        up[a] = 1;
      }
  }
  // Scores count whole patches (faces before refinement), so a refined mesh is judged
  // like the model it came from.
  std::uint32_t patch_count = 0;
  for (auto f : scene.mesh().faces()) patch_count = std::max(patch_count, scene.patch(f) + 1);
  std::vector<double> patch_area(patch_count, 0.0);
  for (auto f : scene.mesh().faces()) patch_area[scene.patch(f)] += scene.area(f);
  Camera best;
  double best_score = -1;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {1, -1}) {
      Vec3d dir(0.0);
      dir[axis] = sign;
      if (std::abs(OpenMesh::dot(dir, up)) > 0.9) continue;  // never look straight up or down
      const Vec3d outside = centre - dir * (0.5 * extent[axis] + 1.5 * size);
      const Vec3d near_wall = centre - dir * (0.45 * extent[axis]);
      for (const Vec3d& eye : {outside, near_wall, centre}) {
        Camera c{eye, eye + dir, up, eye == outside ? 40.0 : 70.0};
        const Frame f = frame_of(c);
        // Score: total area of the distinct front patches the view reaches, so a view
        // that takes in the whole room beats one filled by a single wall.
        std::vector<char> seen(patch_count, 0);
        double score = 0;
        const int n = 48;
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) {
            const auto hit = visibility.intersect(c.eye, ray_direction(f, 4.0 / 3.0, (i + 0.5) / n * 2 - 1, (j + 0.5) / n * 2 - 1));
            if (!hit.hit || !hit.front) continue;
            const std::uint32_t patch = scene.patch(FaceHandle(hit.face));
            if (seen[patch]) continue;
            seen[patch] = 1;
            score += patch_area[patch];
          }
        if (score > best_score) {
          best_score = score;
          best = c;
        }
      }
    }
  }
  return best;
}

Image render_preview(const VertexSplit& split, const std::vector<Rgb>& values,
                     double exposure, const Camera& camera, int width, int height, const Visibility& visibility) {
  Image image;
  image.width = width;
  image.height = height;
  image.rgb.assign(static_cast<std::size_t>(width) * height * 3, 0);
  const Frame f = frame_of(camera);
  const double aspect = static_cast<double>(width) / height;
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const double px = (x + 0.5) / width * 2 - 1, py = 1 - (y + 0.5) / height * 2;
      const auto hit = visibility.intersect(camera.eye, ray_direction(f, aspect, px, py));
      std::uint8_t* pixel = &image.rgb[(static_cast<std::size_t>(y) * width + x) * 3];
      if (!hit.hit) continue;
      if (!hit.front) {
        pixel[0] = 90;  // back face
        continue;
      }
      const FaceHandle face(hit.face);
      const Rgb value = values[split.corner[3 * face.idx()]] * (1 - hit.u - hit.v) + values[split.corner[3 * face.idx() + 1]] * hit.u +
                        values[split.corner[3 * face.idx() + 2]] * hit.v;
      pixel[0] = encode_srgb(value.r * exposure);
      pixel[1] = encode_srgb(value.g * exposure);
      pixel[2] = encode_srgb(value.b * exposure);
    }
  });
  return image;
}

}  // namespace dynrad::rad
