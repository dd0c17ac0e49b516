// Rays: the first face a ray meets, by slab tests against every box (no acceleration
// structure), with the hit point put exactly on the face.
#include "reference/box_tracer_internal.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace dynrad_test::reference::detail {

// The first face that the ray o + t d (t > 0) meets, ignoring face `from` (the face o
// lies on, or -1). The hit point is put exactly on the face's plane and inside its box.
Hit first_hit(const Scene& scene, const Vec3& o, const Vec3& d, int from) {
  double best_t = std::numeric_limits<double>::infinity();
  Hit hit;
  int hit_box = -1;
  for (std::size_t b = 0; b < scene.boxes.size(); ++b) {
    const BoxScene::Box& box = scene.boxes[b];
    double t_in = -std::numeric_limits<double>::infinity(), t_out = std::numeric_limits<double>::infinity();
    int face_in = -1, face_out = -1;
    bool miss = false;
    for (int a = 0; a < 3 && !miss; ++a) {
      if (d[a] == 0) {
        miss = o[a] < box.lo[a] || o[a] > box.hi[a];
        continue;
      }
      double t0 = (box.lo[a] - o[a]) / d[a], t1 = (box.hi[a] - o[a]) / d[a];
      int f0 = 2 * a, f1 = 2 * a + 1;
      if (t0 > t1) {
        std::swap(t0, t1);
        std::swap(f0, f1);
      }
      if (t0 > t_in) t_in = t0, face_in = f0;
      if (t1 < t_out) t_out = t1, face_out = f1;
    }
    if (miss || t_in > t_out) continue;
    // Entering a solid or leaving a room meets a face's front; the other way its back.
    const int base = static_cast<int>(b) * 6;
    if (t_in > 0 && t_in < best_t && base + face_in != from) {
      best_t = t_in, hit.face = base + face_in, hit.front = !box.room, hit_box = static_cast<int>(b);
    }
    if (t_out > 0 && t_out < best_t && base + face_out != from) {
      best_t = t_out, hit.face = base + face_out, hit.front = box.room, hit_box = static_cast<int>(b);
    }
  }
  if (hit.face < 0) return hit;
  const BoxScene::Box& box = scene.boxes[hit_box];
  const FaceInfo& face = scene.faces[hit.face];
  hit.point = o + d * best_t;
  for (int c = 0; c < 3; ++c) hit.point[c] = std::clamp(hit.point[c], box.lo[c], box.hi[c]);
  hit.point[face.axis] = face.plane;
  return hit;
}

}  // namespace dynrad_test::reference::detail
