// Occlusion queries against the scene's surfaces, with Embree 3.
//
// Refinement never moves a surface (midpoints lie on their flat triangles), so the
// Embree scene is built once from the patch mesh. Coordinates are shifted to the
// scene's centre and scaled to a unit diagonal before Embree's single-precision
// conversion, and every ray is kept off the surfaces it starts and ends on by a
// distance relative to the scene size.
#pragma once

#include "mesh/core/scene_mesh.h"

#include <embree3/rtcore.h>

#include <tbb/combinable.h>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace dynrad::rad {

class Visibility {
 public:
  explicit Visibility(const SceneMesh& scene);
  // Any triangles (a lit mesh read back from a file, say); face normals from the
  // corners' order (counter-clockwise seen from the front).
  Visibility(const std::vector<Vec3d>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles);
  ~Visibility();
  Visibility(const Visibility&) = delete;
  Visibility& operator=(const Visibility&) = delete;

  // True when the segment from `from` (on a surface with unit normal `from_normal`) to
  // `to` (on a surface with unit normal `to_normal`) is blocked. Both ends are lifted
  // off their surfaces along their normals, so a ray that reaches its target at a
  // grazing angle does not end inside the target's plane.
  bool occluded(const Vec3d& from, const Vec3d& from_normal, const Vec3d& to, const Vec3d& to_normal) const;

  // How many of `targets` (points on a surface with unit normal `to_normal`) are seen
  // from `from`, with the same offsets as occluded(). The rays go to Embree as one
  // stream (rtcOccluded1M, flagged coherent: they share their origin).
  int visible_count(const Vec3d& from, const Vec3d& from_normal, const Vec3d* targets, int count,
                    const Vec3d& to_normal) const;

  // For benchmarks: while set, every occlusion ray is also appended to `sink` (one
  // thread only: the sink is not locked). Null stops recording.
  void record_rays(std::vector<RTCRay>* sink) { record_ = sink; }
  // For benchmarks: while on, the time spent inside Embree's calls is summed over all
  // threads (two clock reads per call: a few percent slower).
  void time_calls(bool on) { time_calls_ = on; }
  double seconds_in_embree() const { return 1e-9 * static_cast<double>(embree_ns_.combine(std::plus<>())); }
  // Casts recorded rays as they are (one at a time, or as streams of `stream` rays);
  // returns how many were blocked. For the throughput benchmark's reference.
  std::size_t replay(const RTCRay* rays, std::size_t count, int stream = 1) const;

  enum class Hit { nothing, front, back };
  // What a ray from `origin` (on a surface with unit normal `normal`) in direction
  // `direction` meets first: nothing (it leaves the scene), a face's front, or a back.
  Hit trace(const Vec3d& origin, const Vec3d& normal, const Vec3d& direction) const;

  struct Intersection {
    bool hit = false;
    bool front = false;   // the ray met the face's front side
    int face = -1;        // mesh face index
    double u = 0, v = 0;  // barycentric weights of the face's 2nd and 3rd corners (fv order)
    double distance = 0;
  };
  // First surface along a ray from a free point (a camera), no offsets.
  Intersection intersect(const Vec3d& origin, const Vec3d& direction) const;

  std::uint64_t rays() const { return rays_.combine(std::plus<>()); }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  Vec3d centre_;
  double scale_ = 1;                 // world to Embree: (p - centre_) * scale_
  double epsilon_ = 0;               // world units
  std::vector<Vec3d> face_normals_;  // by Embree primitive id
  // Per thread: one shared counter, bumped for every receiver by every thread, cost
  // the parallel form factors a third of their scaling on two cores.
  mutable tbb::combinable<std::uint64_t> rays_{[] { return std::uint64_t(0); }};
  std::vector<RTCRay>* record_ = nullptr;
  bool time_calls_ = false;
  mutable tbb::combinable<std::uint64_t> embree_ns_{[] { return std::uint64_t(0); }};
  // Runs `call` (an Embree query), timing it when time_calls_ is on.
  template <class Call>
  void embree(const Call& call) const;
  // The Embree scene from `vertex_count` points and `face_count` triangles: `face(f,
  // corners)` writes face f's three point indices and returns its unit normal.
  void build(const Bounds& bounds, std::size_t vertex_count, std::size_t face_count,
             const std::function<Vec3d(std::size_t)>& position,
             const std::function<Vec3d(std::size_t, unsigned*)>& face);
  // Fills `ray` for the segment from `from` to `to`, offsets included; false when the
  // two ends are closer than the offsets (nothing can be between them).
  bool make_segment(const Vec3d& from, const Vec3d& from_normal, const Vec3d& to, const Vec3d& to_normal,
                    RTCRay& ray) const;
};

}  // namespace dynrad::rad
