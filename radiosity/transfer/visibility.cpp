#include "radiosity/transfer/visibility.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace dynrad::rad {
namespace {

void embree_error(void* /*user*/, RTCError code, const char* message) {
  // Embree reports through this callback; we turn its errors into exceptions at the
  // call site by checking the device, so here we only log.
  spdlog::error("Embree error {}: {}", static_cast<int>(code), message ? message : "");
}

// A ray from `origin` (already in Embree's centred, scaled frame) along `direction`.
RTCRayHit make_ray_hit(const Vec3d& origin, const Vec3d& direction, float tnear) {
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(origin[0]);
  rh.ray.org_y = static_cast<float>(origin[1]);
  rh.ray.org_z = static_cast<float>(origin[2]);
  rh.ray.dir_x = static_cast<float>(direction[0]);
  rh.ray.dir_y = static_cast<float>(direction[1]);
  rh.ray.dir_z = static_cast<float>(direction[2]);
  rh.ray.tnear = tnear;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.time = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

void check(RTCDevice device, const char* what) {
  const RTCError code = rtcGetDeviceError(device);
  if (code != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree failed while ") + what);
}

}  // namespace

Visibility::Visibility(const SceneMesh& scene) {
  const TriMesh& mesh = scene.mesh();
  build(
      scene.bounds(), mesh.n_vertices(), mesh.n_faces(), [&](std::size_t v) { return mesh.point(VertexHandle(int(v))); },
      [&](std::size_t f, unsigned* corners) {
        int k = 0;
        for (auto v : mesh.fv_range(FaceHandle(int(f)))) corners[k++] = static_cast<unsigned>(v.idx());
        return mesh.normal(FaceHandle(int(f)));
      });
}

Visibility::Visibility(const std::vector<Vec3d>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  Bounds bounds;
  for (const Vec3d& p : positions) bounds.extend(p);
  for (const auto& t : triangles)
    for (std::uint32_t v : t)
      if (v >= positions.size()) throw std::invalid_argument("Visibility: a triangle indexes past the points");
  build(
      bounds, positions.size(), triangles.size(), [&](std::size_t v) { return positions[v]; },
      [&](std::size_t f, unsigned* corners) {
        const auto& t = triangles[f];
        for (int k = 0; k < 3; ++k) corners[k] = t[k];
        const Vec3d n = OpenMesh::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
        const double length = n.norm();
        return length > 0 ? Vec3d(n / length) : Vec3d(0, 0, 0);
      });
}

void Visibility::build(const Bounds& bounds, std::size_t vertex_count, std::size_t face_count,
                       const std::function<Vec3d(std::size_t)>& position,
                       const std::function<Vec3d(std::size_t, unsigned*)>& face) {
  centre_ = (bounds.lo + bounds.hi) * 0.5;
  // Embree sees the scene centred and scaled to a unit diagonal, whatever the model's
  // units: in micrometres or light years, floats then keep the same relative precision.
  scale_ = 1.0 / std::max(bounds.diagonal(), 1e-300);
  // Offsets (world units): large against float rounding at the scene's scale, small
  // against any feature a model of that size has. Both terms scale with the scene.
  epsilon_ = 1e-6 * bounds.diagonal() + 4 * std::numeric_limits<float>::epsilon() * (bounds.hi - centre_).norm();

  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree could not create a device");
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertex_count));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), face_count));
  check(device_, "allocating geometry");
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const Vec3d p = (position(v) - centre_) * scale_;
    for (int c = 0; c < 3; ++c) vertices[3 * v + c] = static_cast<float>(p[c]);
  }
  face_normals_.resize(face_count);
  for (std::size_t f = 0; f < face_count; ++f) face_normals_[f] = face(f, indices + 3 * f);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_);
  check(device_, "building the scene");
}

template <class Call>
void Visibility::embree(const Call& call) const {
  if (!time_calls_) {
    call();
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  call();
  embree_ns_.local() += static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count());
}

Visibility::~Visibility() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

bool Visibility::make_segment(const Vec3d& from, const Vec3d& from_normal, const Vec3d& to, const Vec3d& to_normal,
                              RTCRay& ray) const {
  const Vec3d origin = (from + from_normal * epsilon_ - centre_) * scale_;
  Vec3d direction = (to + to_normal * epsilon_ - centre_) * scale_ - origin;
  const double distance = direction.norm();
  if (distance <= epsilon_ * scale_) return false;
  direction /= distance;
  ray.org_x = static_cast<float>(origin[0]);
  ray.org_y = static_cast<float>(origin[1]);
  ray.org_z = static_cast<float>(origin[2]);
  ray.dir_x = static_cast<float>(direction[0]);
  ray.dir_y = static_cast<float>(direction[1]);
  ray.dir_z = static_cast<float>(direction[2]);
  ray.tnear = 0.0f;
  ray.tfar = static_cast<float>(distance);
  ray.mask = 0xFFFFFFFFu;
  ray.time = 0;
  ray.flags = 0;
  ray.id = 0;
  return true;
}

bool Visibility::occluded(const Vec3d& from, const Vec3d& from_normal, const Vec3d& to,
                          const Vec3d& to_normal) const {
  return visible_count(from, from_normal, &to, 1, to_normal) == 0;
}

int Visibility::visible_count(const Vec3d& from, const Vec3d& from_normal, const Vec3d* targets, int count,
                              const Vec3d& to_normal) const {
  constexpr int kStream = 64;
  RTCRay rays[kStream];
  int visible = 0;
  for (int start = 0; start < count; start += kStream) {
    int n = 0;
    for (int i = start; i < std::min(count, start + kStream); ++i) {
      if (make_segment(from, from_normal, targets[i], to_normal, rays[n])) {
        if (record_) record_->push_back(rays[n]);
        ++n;
      } else {
        ++visible;  // the ends touch: nothing between them
      }
    }
    if (n == 0) continue;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    embree([&] { rtcOccluded1M(scene_, &context, rays, static_cast<unsigned>(n), sizeof(RTCRay)); });
    for (int i = 0; i < n; ++i) visible += rays[i].tfar >= 0;
    rays_.local() += static_cast<std::uint64_t>(n);
  }
  return visible;
}

std::size_t Visibility::replay(const RTCRay* rays, std::size_t count, int stream) const {
  std::size_t blocked = 0;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  if (stream <= 1) {
    for (std::size_t i = 0; i < count; ++i) {
      RTCRay ray = rays[i];
      rtcOccluded1(scene_, &context, &ray);
      blocked += ray.tfar < 0;
    }
  } else {
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    std::vector<RTCRay> batch(static_cast<std::size_t>(stream));
    for (std::size_t start = 0; start < count; start += batch.size()) {
      const std::size_t n = std::min(batch.size(), count - start);
      std::copy(rays + start, rays + start + n, batch.begin());
      rtcOccluded1M(scene_, &context, batch.data(), static_cast<unsigned>(n), sizeof(RTCRay));
      for (std::size_t i = 0; i < n; ++i) blocked += batch[i].tfar < 0;
    }
  }
  return blocked;
}

Visibility::Hit Visibility::trace(const Vec3d& origin_world, const Vec3d& normal, const Vec3d& direction) const {
  RTCRayHit rh = make_ray_hit((origin_world + normal * epsilon_ - centre_) * scale_, direction,
                              static_cast<float>(epsilon_ * scale_));
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  embree([&] { rtcIntersect1(scene_, &context, &rh); });
  ++rays_.local();
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return Hit::nothing;
  return OpenMesh::dot(face_normals_[rh.hit.primID], direction) < 0 ? Hit::front : Hit::back;
}

}  // namespace dynrad::rad

namespace dynrad::rad {

Visibility::Intersection Visibility::intersect(const Vec3d& origin_world, const Vec3d& direction) const {
  RTCRayHit rh = make_ray_hit((origin_world - centre_) * scale_, direction, 0.0f);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene_, &context, &rh);
  ++rays_.local();
  Intersection out;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return out;
  out.hit = true;
  out.face = static_cast<int>(rh.hit.primID);
  out.u = rh.hit.u;
  out.v = rh.hit.v;
  out.distance = rh.ray.tfar / scale_;
  out.front = OpenMesh::dot(face_normals_[rh.hit.primID], direction) < 0;
  return out;
}

}  // namespace dynrad::rad
