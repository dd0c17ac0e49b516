// The scene as the tracer holds it: the input checked, its triangles put into Embree
// (Tracer's constructor), and the two ray queries on them, a first hit and a shadow ray.
#include "reference/mesh_tracer.h"
#include "reference/mesh_tracer_internal.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace dynrad_test::mesh_tracer {
using namespace detail;
namespace {

// ---------------------------------------------------------------------------------
// Embree: the ray context carries the triangles a ray must ignore.

struct RayContext {
  RTCIntersectContext embree;  // first: Embree hands the filter a pointer to it
  unsigned ignore[2] = {RTC_INVALID_GEOMETRY_ID, RTC_INVALID_GEOMETRY_ID};
};

void ignore_listed_triangles(const RTCFilterFunctionNArguments* args) {
  const RayContext* context = reinterpret_cast<const RayContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    if (prim == context->ignore[0] || prim == context->ignore[1]) args->valid[i] = 0;
  }
}

void record_embree_error(void* message, RTCError code, const char* text_) {
  if (code == RTC_ERROR_NONE) return;
  std::string& out = *static_cast<std::string*>(message);
  if (out.empty()) out = text_ ? text_ : "unknown error";
}

}  // namespace

// The first triangle the ray from x + offset * n along unit d meets, ignoring `from`.
Tracer::Impl::Hit Tracer::Impl::first_hit(const Vec3& x, const Vec3& n, const Vec3& d, int from, double offset) const {
  const Vec3 o = x + n * offset;
  RayContext context;
  rtcInitIntersectContext(&context.embree);
  context.ignore[0] = from < 0 ? RTC_INVALID_GEOMETRY_ID : static_cast<unsigned>(from);
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(o.x), rh.ray.org_y = static_cast<float>(o.y),
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(d.x), rh.ray.dir_y = static_cast<float>(d.y),
  rh.ray.dir_z = static_cast<float>(d.z);
  rh.ray.tnear = static_cast<float>(t_min);
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.time = 0;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &context.embree, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.prim = static_cast<int>(rh.hit.primID);
  const Prim& p = prims[rh.hit.primID];
  hit.front = dot(d, p.normal) < 0;
  hit.point = p.a + p.e1 * static_cast<double>(rh.hit.u) + p.e2 * static_cast<double>(rh.hit.v);
  return hit;
}

// Nothing lies between x + offset * n and `target` (the last `stop_short` of the way
// not tested), ignoring triangles `from` and `to` (-1: none).
bool Tracer::Impl::visible(const Vec3& x, const Vec3& n, const Vec3& target, int from, int to, double offset,
                           double stop_short) const {
  const Vec3 o = x + n * offset;
  const Vec3 d = target - o;
  const double r = length(d);
  if (!(r > stop_short)) return true;
  const Vec3 u = d * (1 / r);
  RayContext context;
  rtcInitIntersectContext(&context.embree);
  context.ignore[0] = from < 0 ? RTC_INVALID_GEOMETRY_ID : static_cast<unsigned>(from);
  context.ignore[1] = to < 0 ? RTC_INVALID_GEOMETRY_ID : static_cast<unsigned>(to);
  RTCRay ray;
  ray.org_x = static_cast<float>(o.x), ray.org_y = static_cast<float>(o.y), ray.org_z = static_cast<float>(o.z);
  ray.dir_x = static_cast<float>(u.x), ray.dir_y = static_cast<float>(u.y), ray.dir_z = static_cast<float>(u.z);
  ray.tnear = static_cast<float>(t_min);
  ray.tfar = static_cast<float>(r - stop_short);
  ray.time = 0;
  ray.mask = 0xffffffffu;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(scene, &context.embree, &ray);
  return ray.tfar >= 0;  // Embree sets it to -inf when something blocks the ray
}

Tracer::Tracer(Scene input, int build_threads) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  auto fail = [](const std::string& what) { throw std::invalid_argument("mesh tracer: " + what); };
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi = lo * -1.0;
  for (std::size_t i = 0; i < input.triangles.size(); ++i) {
    const Triangle& t = input.triangles[i];
    const std::string name = "triangle " + std::to_string(i);
    for (const Vec3& c : t.corners) {
      if (!finite(c)) fail(name + " has a corner that is not finite");
      lo = {std::min(lo.x, c.x), std::min(lo.y, c.y), std::min(lo.z, c.z)};
      hi = {std::max(hi.x, c.x), std::max(hi.y, c.y), std::max(hi.z, c.z)};
    }
    for (int c = 0; c < 3; ++c) {
      if (!(t.reflectance[c] >= 0 && t.reflectance[c] <= 1))
        fail(name + " has reflectance " + std::to_string(t.reflectance[c]) + ", outside [0, 1]");
      if (!(t.exitance[c] >= 0) || !std::isfinite(t.exitance[c]))
        fail(name + " has exitance " + std::to_string(t.exitance[c]) + ": it must be finite and >= 0");
    }
    Impl::Prim p;
    p.a = t.corners[0];
    p.e1 = t.corners[1] - t.corners[0];
    p.e2 = t.corners[2] - t.corners[0];
    const Vec3 area_normal = cross(p.e1, p.e2);
    const double twice_area = length(area_normal);
    if (!(twice_area > 0)) {
      ++s.degenerate;
      continue;
    }
    p.normal = area_normal * (1 / twice_area);
    p.area = 0.5 * twice_area;
    p.reflectance = t.reflectance;
    p.exitance = t.exitance;
    s.prims.push_back(p);
  }
  if (s.prims.empty()) fail("the scene has no triangles of non-zero area");
  s.scale = length(hi - lo);
  if (!(s.scale > 0)) fail("the scene is a single point");
  s.t_min = 1e-7 * s.scale;
  for (std::size_t i = 0; i < input.lights.size(); ++i) {
    const PointLight& l = input.lights[i];
    if (!finite(l.position)) fail("point light " + std::to_string(i) + " is at " + text(l.position));
    if (!(l.flux >= 0) || !std::isfinite(l.flux))
      fail("point light " + std::to_string(i) + " has flux " + std::to_string(l.flux));
    s.lights.push_back({l.position, l.flux / (4 * kPi)});
  }
  double total = 0;
  for (std::size_t j = 0; j < s.prims.size(); ++j) {
    const double power = luminance(s.prims[j].exitance) * s.prims[j].area;
    if (!(power > 0)) continue;
    total += power;
    s.emitters.push_back(static_cast<unsigned>(j));
    s.emitter_cdf.push_back(total);
  }

  const std::string config = build_threads > 0 ? "threads=" + std::to_string(build_threads) : "";
  s.device = rtcNewDevice(config.c_str());
  if (!s.device) throw std::runtime_error("mesh tracer: Embree could not create a device");
  rtcSetDeviceErrorFunction(s.device, record_embree_error, &s.embree_error);
  if (rtcGetDeviceProperty(s.device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED) == 0)
    throw std::runtime_error("mesh tracer: this Embree was built without filter functions, which the tracer needs");
  s.scene = rtcNewScene(s.device);
  rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry mesh = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), 3 * s.prims.size()));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), s.prims.size()));
  s.throw_if_embree_failed("to allocate the mesh");
  for (std::size_t j = 0; j < s.prims.size(); ++j) {
    const Impl::Prim& p = s.prims[j];
    const Vec3 corners[3] = {p.a, p.a + p.e1, p.a + p.e2};
    for (int k = 0; k < 3; ++k) {
      float* v = vertices + 9 * j + 3 * k;
      v[0] = static_cast<float>(corners[k].x), v[1] = static_cast<float>(corners[k].y);
      v[2] = static_cast<float>(corners[k].z);
      indices[3 * j + k] = static_cast<unsigned>(3 * j + k);
    }
  }
  rtcSetGeometryIntersectFilterFunction(mesh, ignore_listed_triangles);
  rtcSetGeometryOccludedFilterFunction(mesh, ignore_listed_triangles);
  rtcCommitGeometry(mesh);
  rtcAttachGeometry(s.scene, mesh);
  rtcReleaseGeometry(mesh);
  rtcCommitScene(s.scene);
  s.throw_if_embree_failed("to build the scene");
}

Tracer::~Tracer() = default;

std::size_t Tracer::triangle_count() const { return impl_->prims.size(); }
std::size_t Tracer::degenerate_triangles() const { return impl_->degenerate; }
double Tracer::scene_size() const { return impl_->scale; }

}  // namespace dynrad_test::mesh_tracer
