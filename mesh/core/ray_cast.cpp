#include "mesh/core/ray_cast.h"

#include <cmath>

#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace dynrad {

RayCaster::RayCaster(const std::vector<Vec3d>& points, const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  Bounds bounds;
  for (const auto& t : triangles)
    for (auto v : t) bounds.extend(points.at(v));
  centre_ = bounds.empty() ? Vec3d(0.0) : (bounds.lo + bounds.hi) * 0.5;
  scale_ = 1.0 / std::max(bounds.diagonal(), 1e-300);
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree could not create a device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), points.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), triangles.size()));
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE || !vertices || !indices) {
    rtcReleaseGeometry(geometry);
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
    throw std::runtime_error("Embree could not allocate the triangles");
  }
  for (std::size_t v = 0; v < points.size(); ++v) {
    const Vec3d p = (points[v] - centre_) * scale_;
    for (int c = 0; c < 3; ++c) vertices[3 * v + c] = static_cast<float>(p[c]);
  }
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) indices[3 * f + k] = triangles[f][k];
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_);
}

RayCaster::~RayCaster() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

std::vector<Vec3d> cosine_directions(int count) {
  std::vector<Vec3d> directions;
  const double golden = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double r2 = (i + 0.5) / count, phi = golden * i;
    const double r = std::sqrt(r2);
    directions.emplace_back(r * std::cos(phi), r * std::sin(phi), std::sqrt(1 - r2));
  }
  return directions;
}

Vec3d about_normal(const Vec3d& n, const Vec3d& local) {
  const Vec3d helper = std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  const Vec3d u = OpenMesh::cross(helper, n).normalized(), v = OpenMesh::cross(n, u);
  return u * local[0] + v * local[1] + n * local[2];
}

long RayCaster::first_hit(const Vec3d& origin_world, const Vec3d& direction) const {
  const Vec3d origin = (origin_world - centre_) * scale_;
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(origin[0]);
  rh.ray.org_y = static_cast<float>(origin[1]);
  rh.ray.org_z = static_cast<float>(origin[2]);
  rh.ray.dir_x = static_cast<float>(direction[0]);
  rh.ray.dir_y = static_cast<float>(direction[1]);
  rh.ray.dir_z = static_cast<float>(direction[2]);
  rh.ray.tnear = 0;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.time = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene_, &context, &rh);
  return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : static_cast<long>(rh.hit.primID);
}

}  // namespace dynrad
