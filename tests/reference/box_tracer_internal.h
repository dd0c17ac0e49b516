// The box tracer's private parts, shared by its sources and used nowhere else: small
// vector helpers, the scene as the tracer uses it, and the two exact pieces that the
// estimate (box_tracer.cpp) builds on: first hits (box_tracer_rays.cpp) and direct light
// (box_tracer_direct.cpp).
#pragma once

#include "reference/box_tracer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace dynrad_test::reference::detail {

inline constexpr double kPi = 3.14159265358979323846;

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(const Vec3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }

inline std::string text(const Vec3& p) {
  return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}

inline int axis_of(Face face) { return static_cast<int>(face) / 2; }
inline bool on_plus_side(Face face) { return static_cast<int>(face) % 2 == 1; }

// ---------------------------------------------------------------------------------
// The scene as the tracer uses it: faces numbered box * 6 + face.

struct Bounds {
  Vec3 lo, hi;
};

struct FaceInfo {
  int axis = 0;
  double plane = 0;  // the face lies in coordinate[axis] == plane
  double sign = 1;   // its front faces sign * (unit vector along axis)
  Vec3 normal;
  double reflectance = 0;
  std::vector<int> emitters;  // emitters on this face
};

struct EmitterInfo {
  int axis = 0;
  double plane = 0, sign = 1;
  Vec3 lo, hi;  // the rectangle (lo[axis] == hi[axis] == plane)
  double exitance = 0, reflectance = 0;
};

// The open rectangle [lo, hi] in the two axes other than `axis` contains p.
inline bool inside_open(const Vec3& lo, const Vec3& hi, int axis, const Vec3& p) {
  for (int c = 0; c < 3; ++c)
    if (c != axis && !(lo[c] < p[c] && p[c] < hi[c])) return false;
  return true;
}

struct Scene {
  explicit Scene(const BoxScene& scene) : boxes(scene.boxes()) {
    for (const BoxScene::Box& box : boxes)
      for (int f = 0; f < 6; ++f) {
        const Face face = static_cast<Face>(f);
        FaceInfo info;
        info.axis = axis_of(face);
        info.plane = on_plus_side(face) ? box.hi[info.axis] : box.lo[info.axis];
        info.sign = (on_plus_side(face) != box.room) ? 1.0 : -1.0;
        info.normal[info.axis] = info.sign;
        info.reflectance = box.reflectance.of_face[f];
        faces.push_back(info);
      }
    for (const Emitter& e : scene.emitters()) {
      const int id = e.box * 6 + static_cast<int>(e.face);
      const FaceInfo& face = faces[id];
      emitters.push_back({face.axis, face.plane, face.sign, e.lo, e.hi, e.exitance, e.reflectance});
      faces[id].emitters.push_back(static_cast<int>(emitters.size()) - 1);
    }
    Bounds all{boxes.front().lo, boxes.front().hi};
    for (const BoxScene::Box& box : boxes)
      for (int c = 0; c < 3; ++c) {
        all.lo[c] = std::min(all.lo[c], box.lo[c]);
        all.hi[c] = std::max(all.hi[c], box.hi[c]);
      }
    scale = length(all.hi - all.lo);
  }

  // Reflectance at point p of face `face`: an emitter's if p is on one.
  double reflectance_at(int face, const Vec3& p) const {
    const FaceInfo& info = faces[face];
    for (int e : info.emitters)
      if (inside_open(emitters[e].lo, emitters[e].hi, info.axis, p)) return emitters[e].reflectance;
    return info.reflectance;
  }

  // Exitance (W/m^2) emitted at point p of face `face`.
  double emission_at(int face, const Vec3& p) const {
    for (int e : faces[face].emitters)
      if (inside_open(emitters[e].lo, emitters[e].hi, faces[face].axis, p)) return emitters[e].exitance;
    return 0;
  }

  // The face that p lies on with its front facing unit normal n, or -1. p may be off
  // the face by 1e-12 of the scene's size (rounding).
  int face_at(const Vec3& p, const Vec3& n) const {
    const double tolerance = 1e-12 * scale;
    for (std::size_t id = 0; id < faces.size(); ++id) {
      const FaceInfo& face = faces[id];
      const BoxScene::Box& box = boxes[id / 6];
      if (dot(n, face.normal) < 1 - 1e-9 || std::abs(p[face.axis] - face.plane) > tolerance) continue;
      bool inside = true;
      for (int c = 0; c < 3; ++c)
        if (c != face.axis && (p[c] < box.lo[c] - tolerance || p[c] > box.hi[c] + tolerance)) inside = false;
      if (inside) return static_cast<int>(id);
    }
    return -1;
  }

  const std::vector<BoxScene::Box>& boxes;
  std::vector<FaceInfo> faces;
  std::vector<EmitterInfo> emitters;
  double scale = 1;  // diagonal of the scene's bounding box (m)
};

// ---------------------------------------------------------------------------------
// Rays.

struct Hit {
  int face = -1;  // -1: the ray left the scene
  bool front = false;
  Vec3 point;
};

// The first face a ray meets (box_tracer_rays.cpp).
Hit first_hit(const Scene& scene, const Vec3& o, const Vec3& d, int from);

// Direct irradiance from every emitter, exact (box_tracer_direct.cpp).
double direct(const Scene& scene, const Vec3& x, const Vec3& n);

}  // namespace dynrad_test::reference::detail
