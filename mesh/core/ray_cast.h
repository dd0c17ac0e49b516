// First hits of rays against a set of triangles, with Embree 3: cleanup's test of what
// the front of a surface sees (mesh/repair/hidden.cpp). The points are centred on their box and
// scaled to a unit diagonal before Embree's single-precision conversion, so a model in
// millimetres far from the origin keeps the same relative precision. (The solver's
// occlusion queries, with their offsets and ray streams, are radiosity/transfer/visibility.h.)
#pragma once

#include "mesh/core/types.h"

#include <array>
#include <cstdint>
#include <vector>

struct RTCDeviceTy;
struct RTCSceneTy;

namespace dynrad {

// `count` directions cosine-distributed about +z, evenly spread over the projected
// disc's area (a spiral with the golden angle), so that each carries the same share of
// what a surface sees.
std::vector<Vec3d> cosine_directions(int count);

// `local` (about +z) turned into the frame whose z axis is the unit vector `n`.
Vec3d about_normal(const Vec3d& n, const Vec3d& local);

class RayCaster {
 public:
  RayCaster(const std::vector<Vec3d>& points, const std::vector<std::array<std::uint32_t, 3>>& triangles);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // The index of the triangle first hit by the ray from `origin` along `direction`, or -1
  // when it leaves the scene. Degenerate triangles are never hit.
  long first_hit(const Vec3d& origin, const Vec3d& direction) const;

 private:
  RTCDeviceTy* device_ = nullptr;
  RTCSceneTy* scene_ = nullptr;
  Vec3d centre_;
  double scale_ = 1;
};

}  // namespace dynrad
