// The mesh path tracer (see mesh_tracer.h for what it answers).
//
// Illuminance at a query point x0 facing n0:  E(x0) = D(x0) + I(x0).
// - D, the point lights' direct light, is exact: sum of I cos(theta) / d^2 over the
//   lights that one shadow ray finds unblocked (a point cannot be partly hidden).
// - I is a path estimate. Irradiance at any vertex v (a surface point, or x0) is
//   H(v) = D(v) + integral of L(w) cos dw over the hemisphere, where the radiance that
//   a surface point y sends is L(y) = (M(y) + rho(y) H(y)) / pi on its front and
//   nothing from its back (M the exitance of an emitting triangle). Sampling w with
//   density cos / pi turns the integral into pi * L(y), so one path from x0 sums,
//   vertex after vertex y1, y2, ..., with throughput T_k = rho(y1) ... rho(yk):
//     T_{k-1} * M(yk) * w_bsdf          the emission its ray found (MIS weight)
//     T_k * D(yk)                       the point lights at yk, exact but for the ray
//     T_k * [emitter sample at yk]      one area sample of the emitting triangles
//   with the emitter sample also taken at x0 itself (T_0 = 1). The two ways of finding
//   an emitter are combined by the power heuristic (Veach 1997), so that small and
//   large emitters alike are estimated with bounded variance. Russian roulette ends
//   paths whose throughput is low, fairly (TraceOptions::roulette_below).
// - Rays: Embree 3, in float. A ray leaving a surface starts a small offset in front
//   of it (TraceOptions::ray_offset) and a filter makes it ignore the triangle it
//   leaves (and a shadow ray the emitting triangle it aims at). Hit points are put on
//   the hit triangle from Embree's barycentric coordinates, in double. Rays from the
//   query point start at it (it is in mid-air: moving it would change the answer), and
//   every ray ignores hits nearer than 1e-7 of the scene's size.
// - Statistics: independent replicates of independent paths (SplitMix64 streams keyed
//   by the seed, the point's stream number and the replicate's number), the standard
//   error from the spread of the replicates' means. Replicates are added in rounds until
//   the target relative error or the path cap is reached; a round's replicates may run
//   on several threads, each writes its own mean, so the answer is the same on any
//   number of threads.
#include "reference/mesh_tracer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

namespace dynrad_test::mesh_tracer {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(const Vec3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
bool finite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

double luminance(const Rgb& c) {
  return kLuminanceWeights[0] * c[0] + kLuminanceWeights[1] * c[1] + kLuminanceWeights[2] * c[2];
}
double largest(const Rgb& c) { return std::max({c[0], c[1], c[2]}); }

std::string text(const Vec3& p) {
  std::ostringstream out;
  out << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return out.str();
}

// ---------------------------------------------------------------------------------
// Random numbers.

// A 64-bit hash with good avalanche (the SplitMix64 output function).
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class Rng {
 public:
  explicit Rng(std::uint64_t key) : state_(key) {}
  // Uniform in the open interval (0, 1).
  double uniform() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return (static_cast<double>(mix(state_) >> 11) + 0.5) * 0x1p-53;
  }

 private:
  std::uint64_t state_;
};

std::uint64_t point_key(std::uint64_t seed, std::uint64_t stream) { return mix(mix(seed) ^ mix(stream + 0x5eed)); }
std::uint64_t replicate_key(std::uint64_t point, std::uint64_t replicate) { return mix(point ^ mix(~replicate)); }

// A unit vector with density cos(theta) / pi about unit normal n.
Vec3 cosine_direction(const Vec3& n, double u0, double u1) {
  const double r = std::sqrt(u0), phi = 2 * kPi * u1;
  const double along = std::sqrt(std::max(0.0, 1 - u0));
  // Two tangents: n crossed with the axis it is least aligned with, then n x t.
  const Vec3 axis = std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 t = cross(n, axis);
  t = t * (1 / length(t));
  const Vec3 s = cross(n, t);
  return t * (r * std::cos(phi)) + s * (r * std::sin(phi)) + n * along;
}

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

// Runs fn(0) ... fn(count - 1) on up to `threads` threads; rethrows the first exception.
template <class Fn>
void parallel_for(std::size_t count, int threads, const Fn& fn) {
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(std::max(1, threads)), count);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) fn(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < count;) {
      try {
        fn(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = count;
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

int thread_count(int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void check(const TraceOptions& o) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("mesh tracer: " + what); };
  if (!(o.roulette_below > 0 && o.roulette_below <= 1)) fail("roulette_below must be in (0, 1]");
  if (o.paths_per_replicate < 1) fail("paths_per_replicate must be at least 1");
  if (o.min_replicates < 2) fail("min_replicates must be at least 2 (for a standard error)");
  if (!(o.ray_offset >= 0 && o.ray_offset < 1e-2)) fail("ray_offset must be in [0, 0.01)");
  if (o.paths <= 0 && !(o.target_relative_error > 0)) fail("give paths or a positive target_relative_error");
  if (o.paths <= 0 && o.max_paths < 1) fail("max_paths must be positive");
}

Vec3 unit_normal(const Vec3& normal) {
  const double n = length(normal);
  if (!(n > 0) || !std::isfinite(n)) throw std::invalid_argument("mesh tracer: the normal must be non-zero and finite");
  return normal * (1 / n);
}

}  // namespace

// ---------------------------------------------------------------------------------
// The scene as the tracer uses it.

struct Tracer::Impl {
  struct Prim {
    Vec3 a, e1, e2;  // corner a and the edges b - a, c - a
    Vec3 normal;     // unit, the front
    double area = 0;
    Rgb reflectance{}, exitance{};
  };
  struct Light {
    Vec3 position;
    double intensity = 0;  // cd (or W/sr), every channel
  };
  struct Hit {
    int prim = -1;  // -1: the ray left the scene
    bool front = false;
    Vec3 point;
  };

  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string embree_error;
  std::vector<Prim> prims;  // by Embree's primID
  std::vector<Light> lights;
  std::vector<unsigned> emitters;   // prims that emit
  std::vector<double> emitter_cdf;  // running sum of area * luminance(exitance)
  double scale = 1;                 // bounding-box diagonal
  double t_min = 0;                 // hits nearer than this are ignored: 1e-7 of the scale
  std::size_t degenerate = 0;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void throw_if_embree_failed(const char* doing) const {
    if (!embree_error.empty())
      throw std::runtime_error(std::string("mesh tracer: Embree failed ") + doing + ": " + embree_error);
  }

  // The first triangle the ray from x + offset * n along unit d meets, ignoring `from`.
  Hit first_hit(const Vec3& x, const Vec3& n, const Vec3& d, int from, double offset) const {
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
  bool visible(const Vec3& x, const Vec3& n, const Vec3& target, int from, int to, double offset,
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

  // Point lights' irradiance at x (unit normal n), each checked by one shadow ray.
  double point_lights(const Vec3& x, const Vec3& n, int from, double offset) const {
    double e = 0;
    for (const Light& l : lights) {
      const Vec3 d = l.position - x;
      const double r2 = dot(d, d);
      if (!(r2 > 0) || l.intensity == 0) continue;
      const double cos_x = dot(n, d) / std::sqrt(r2);
      if (cos_x <= 0) continue;
      if (visible(x, n, l.position, from, -1, offset, 0)) e += l.intensity * cos_x / r2;
    }
    return e;
  }

  // Probability density, per steradian seen from x, of the area sample picking the
  // point y of emitting prim j at distance^2 r2, seen at cos_y from its front.
  double emitter_density(unsigned j, double r2, double cos_y) const {
    const double total = emitter_cdf.back();
    const double chosen = luminance(prims[j].exitance) * prims[j].area / total;
    return chosen * r2 / (prims[j].area * cos_y);
  }

  // One area sample of the emitting triangles: an estimate of the irradiance they give
  // x (unit normal n), weighted against cosine sampling by the power heuristic.
  // `offset`: the ray's start off x; `surface_offset`: how far short of the emitter it
  // stops.
  Rgb sample_emitters(const Vec3& x, const Vec3& n, int from, double offset, double surface_offset, Rng& rng) const {
    const double total = emitter_cdf.back();
    const double pick = rng.uniform() * total;
    std::size_t k =
        static_cast<std::size_t>(std::upper_bound(emitter_cdf.begin(), emitter_cdf.end(), pick) - emitter_cdf.begin());
    k = std::min(k, emitters.size() - 1);
    const unsigned j = emitters[k];
    const Prim& p = prims[j];
    const double s = std::sqrt(rng.uniform()), t = rng.uniform();
    const Vec3 y = p.a + p.e1 * (s * (1 - t)) + p.e2 * (s * t);
    const Vec3 d = y - x;
    const double r2 = dot(d, d);
    if (!(r2 > 0)) return {};
    const double r = std::sqrt(r2);
    const double cos_x = dot(n, d) / r, cos_y = -dot(p.normal, d) / r;
    if (cos_x <= 0 || cos_y <= 0) return {};
    if (!visible(x, n, y, from, static_cast<int>(j), offset, surface_offset)) return {};
    const double light_pdf = emitter_density(j, r2, cos_y), cosine_pdf = cos_x / kPi;
    const double weight = light_pdf * light_pdf / (light_pdf * light_pdf + cosine_pdf * cosine_pdf);
    // Radiance M / pi times cos_x over the density.
    const double factor = weight * cos_x / (kPi * light_pdf);
    return {p.exitance[0] * factor, p.exitance[1] * factor, p.exitance[2] * factor};
  }

  // One path's estimate of the indirect illuminance (luminance of the RGB irradiance
  // without the point lights' direct part) at x0 facing unit n0. Rays from x0 start at
  // x0 itself (it is in mid-air); rays from a surface `surface_offset` in front of it.
  // `first_back` is set when the first ray met the back of a face.
  double path(const Vec3& x0, const Vec3& n0, const TraceOptions& o, double surface_offset, Rng& rng,
              bool& first_back) const {
    first_back = false;
    Rgb sum{}, throughput{1, 1, 1};
    Vec3 x = x0, n = n0;
    int from = -1;
    double offset = 0;
    auto add = [&](const Rgb& scale_by, const Rgb& value) {
      for (int c = 0; c < 3; ++c) sum[c] += scale_by[c] * value[c];
    };
    for (int bounce = 0;; ++bounce) {
      if (bounce > 0) {
        const double e = point_lights(x, n, from, offset);
        if (e > 0) add(throughput, {e, e, e});
      }
      if (!emitters.empty()) add(throughput, sample_emitters(x, n, from, offset, surface_offset, rng));
      const double u0 = rng.uniform(), u1 = rng.uniform();
      const Vec3 d = cosine_direction(n, u0, u1);
      const Hit hit = first_hit(x, n, d, from, offset);
      if (hit.prim >= 0 && !hit.front && bounce == 0) first_back = true;
      if (hit.prim < 0 || !hit.front) break;
      const Prim& p = prims[hit.prim];
      if (luminance(p.exitance) > 0) {
        const Vec3 to = hit.point - x;
        const double r2 = dot(to, to), cos_x = dot(n, d), cos_y = -dot(p.normal, d);
        if (r2 > 0 && cos_x > 0 && cos_y > 0) {
          const double light_pdf = emitter_density(static_cast<unsigned>(hit.prim), r2, cos_y);
          const double cosine_pdf = cos_x / kPi;
          const double weight = cosine_pdf * cosine_pdf / (light_pdf * light_pdf + cosine_pdf * cosine_pdf);
          add(throughput, {p.exitance[0] * weight, p.exitance[1] * weight, p.exitance[2] * weight});
        }
      }
      for (int c = 0; c < 3; ++c) throughput[c] *= p.reflectance[c];
      const double carried = largest(throughput);
      if (!(carried > 0)) break;
      if (carried < o.roulette_below) {
        const double survive = carried / o.roulette_below;
        if (rng.uniform() >= survive) break;
        for (double& c : throughput) c /= survive;
      }
      x = hit.point, n = p.normal, from = hit.prim, offset = surface_offset;
    }
    return luminance(sum);
  }

  // The estimate at x facing unit n from the stream `key`, replicates on `threads`.
  Estimate estimate(const Vec3& x, const Vec3& n, const TraceOptions& o, std::uint64_t key, int threads,
                    std::size_t index) const {
    const double surface_offset = o.ray_offset * scale;
    Estimate result;
    result.direct = point_lights(x, n, -1, 0);
    const int per = o.paths_per_replicate;
    std::vector<double> means;
    std::vector<std::int64_t> backs;  // per replicate: paths whose first ray met a back
    auto run_until = [&](std::size_t replicates) {
      const std::size_t first = means.size();
      means.resize(replicates);
      backs.resize(replicates);
      parallel_for(replicates - first, threads, [&](std::size_t i) {
        Rng rng(replicate_key(key, first + i));
        double sum = 0;
        std::int64_t back_count = 0;
        for (int k = 0; k < per; ++k) {
          bool back = false;
          sum += path(x, n, o, surface_offset, rng, back);
          back_count += back;
        }
        means[first + i] = sum / per;
        backs[first + i] = back_count;
      });
      const double count = static_cast<double>(means.size());
      double mean = 0, spread = 0;
      for (double m : means) mean += m;
      mean /= count;
      for (double m : means) spread += (m - mean) * (m - mean);
      result.indirect = mean;
      result.value = result.direct + mean;
      result.std_error = std::sqrt(spread / (count - 1) / count);
      result.paths = static_cast<std::int64_t>(means.size()) * per;
      std::int64_t back_total = 0;
      for (std::int64_t b : backs) back_total += b;
      result.back_share = static_cast<double>(back_total) / static_cast<double>(result.paths);
    };
    if (o.paths > 0) {
      run_until(static_cast<std::size_t>(std::max<std::int64_t>(2, (o.paths + per - 1) / per)));
      if (o.progress) o.progress(index, result, true);
      return result;
    }
    const std::size_t most = static_cast<std::size_t>(std::max<std::int64_t>(2, o.max_paths / per));
    run_until(std::min<std::size_t>(most, static_cast<std::size_t>(o.min_replicates)));
    for (;;) {
      const double goal = o.target_relative_error * std::abs(result.value);
      const bool finished = result.std_error <= goal || means.size() >= most;
      if (o.progress) o.progress(index, result, finished);
      if (finished) return result;
      // The error falls as 1 / sqrt(replicates): aim 10% past the goal, but at most
      // four times as many per round, since the error so far is itself rough.
      const double now = static_cast<double>(means.size());
      const double wanted = goal > 0 ? 1.1 * now * (result.std_error / goal) * (result.std_error / goal) : 4 * now;
      const double next = std::clamp(wanted, now + o.min_replicates, 4 * now);
      run_until(static_cast<std::size_t>(std::min(static_cast<double>(most), next)));
    }
  }
};

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

Estimate Tracer::illuminance(const Vec3& point, const Vec3& normal, const TraceOptions& options,
                             std::uint64_t stream) const {
  check(options);
  if (!finite(point)) throw std::invalid_argument("mesh tracer: the point " + text(point) + " is not finite");
  return impl_->estimate(point, unit_normal(normal), options, point_key(options.seed, stream),
                         thread_count(options.threads), static_cast<std::size_t>(stream));
}

std::vector<Estimate> Tracer::illuminance(const std::vector<Vec3>& points, const Vec3& normal,
                                          const TraceOptions& options) const {
  check(options);
  const Vec3 n = unit_normal(normal);
  for (const Vec3& p : points)
    if (!finite(p)) throw std::invalid_argument("mesh tracer: the point " + text(p) + " is not finite");
  std::vector<Estimate> out(points.size());
  parallel_for(points.size(), thread_count(options.threads), [&](std::size_t i) {
    out[i] = impl_->estimate(points[i], n, options, point_key(options.seed, i), 1, i);
  });
  return out;
}

double Tracer::direct_illuminance(const Vec3& point, const Vec3& normal) const {
  if (!finite(point)) throw std::invalid_argument("mesh tracer: the point " + text(point) + " is not finite");
  return impl_->point_lights(point, unit_normal(normal), -1, 0);
}

std::size_t Tracer::triangle_count() const { return impl_->prims.size(); }
std::size_t Tracer::degenerate_triangles() const { return impl_->degenerate; }
double Tracer::scene_size() const { return impl_->scale; }

// ---------------------------------------------------------------------------------
// PLY.

namespace {

enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

int size_of(PlyType t) {
  switch (t) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32:
      return 4;
    case PlyType::float64:
      return 8;
  }
  return 0;
}

bool parse_type(const std::string& name, PlyType& t) {
  static const std::pair<const char*, PlyType> names[] = {
      {"char", PlyType::int8},      {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},    {"short", PlyType::int16},     {"int16", PlyType::int16},
      {"ushort", PlyType::uint16},  {"uint16", PlyType::uint16},   {"int", PlyType::int32},
      {"int32", PlyType::int32},    {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
      {"float", PlyType::float32},  {"float32", PlyType::float32}, {"double", PlyType::float64},
      {"float64", PlyType::float64}};
  for (const auto& [text_, type] : names)
    if (name == text_) {
      t = type;
      return true;
    }
  return false;
}

struct PlyProperty {
  std::string name;
  bool list = false;
  PlyType count_type = PlyType::uint8;  // lists only
  PlyType type = PlyType::float32;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { ascii, little_endian, big_endian };

// Reads the values of a PLY's body, one at a time, in the file's format.
class PlyBody {
 public:
  PlyBody(std::istream& in, PlyFormat format) : in_(in), format_(format) {
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    swap_ = (format == PlyFormat::little_endian) != (first == 1);
  }

  // False at the end of the file or on a malformed value.
  bool read(PlyType t, double& value) {
    if (format_ == PlyFormat::ascii) {
      std::string token;
      if (!(in_ >> token)) return false;
      char* end = nullptr;
      value = std::strtod(token.c_str(), &end);
      return end != token.c_str() && *end == '\0';
    }
    unsigned char bytes[8];
    const int n = size_of(t);
    if (!in_.read(reinterpret_cast<char*>(bytes), n)) return false;
    if (swap_) std::reverse(bytes, bytes + n);
    switch (t) {
      case PlyType::int8:
        value = static_cast<std::int8_t>(bytes[0]);
        break;
      case PlyType::uint8:
        value = bytes[0];
        break;
      case PlyType::int16:
        value = as<std::int16_t>(bytes);
        break;
      case PlyType::uint16:
        value = as<std::uint16_t>(bytes);
        break;
      case PlyType::int32:
        value = as<std::int32_t>(bytes);
        break;
      case PlyType::uint32:
        value = as<std::uint32_t>(bytes);
        break;
      case PlyType::float32:
        value = as<float>(bytes);
        break;
      case PlyType::float64:
        value = as<double>(bytes);
        break;
    }
    return true;
  }

 private:
  template <class T>
  static T as(const unsigned char* bytes) {
    T v;
    std::memcpy(&v, bytes, sizeof v);
    return v;
  }
  std::istream& in_;
  PlyFormat format_;
  bool swap_ = false;
};

}  // namespace

Scene read_ply(const std::string& path) {
  auto fail = [&path](const std::string& what) -> void { throw std::runtime_error(path + ": " + what); };
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(std::string("cannot open it (") + std::strerror(errno) + ")");

  // Header.
  std::string line;
  int line_number = 0;
  auto next_line = [&]() -> bool {
    if (!std::getline(in, line)) return false;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  };
  if (!next_line() || line != "ply") fail("not a PLY file (its first line is not \"ply\")");
  PlyFormat format = PlyFormat::ascii;
  bool has_format = false;
  std::vector<PlyElement> elements;
  for (;;) {
    if (!next_line()) fail("the header has no end_header line");
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    const std::string where = "header line " + std::to_string(line_number) + " (\"" + line + "\"): ";
    if (keyword == "end_header") break;
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      std::string name, version;
      words >> name >> version;
      if (name == "ascii") {
        format = PlyFormat::ascii;
      } else if (name == "binary_little_endian") {
        format = PlyFormat::little_endian;
      } else if (name == "binary_big_endian") {
        format = PlyFormat::big_endian;
      } else {
        fail(where + "unknown format \"" + name + "\"");
      }
      has_format = true;
    } else if (keyword == "element") {
      PlyElement e;
      long long count = -1;
      if (!(words >> e.name >> count) || count < 0) fail(where + "an element needs a name and a count");
      e.count = static_cast<std::uint64_t>(count);
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) fail(where + "a property before any element");
      PlyProperty p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> p.name;
        p.list = true;
        if (!parse_type(count_type, p.count_type) || !parse_type(item_type, p.type))
          fail(where + "unknown list types \"" + count_type + "\", \"" + item_type + "\"");
      } else {
        words >> p.name;
        if (!parse_type(type, p.type)) fail(where + "unknown type \"" + type + "\"");
      }
      if (p.name.empty()) fail(where + "a property without a name");
      elements.back().properties.push_back(p);
    } else {
      fail(where + "unknown keyword \"" + keyword + "\"");
    }
  }
  if (!has_format) fail("the header has no format line");

  // Body.
  PlyBody body(in, format);
  std::vector<Vec3> positions;
  std::vector<Rgb> reflectances;
  Scene scene;
  bool seen_vertices = false, seen_faces = false;
  for (const PlyElement& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int role[64];  // vertex: property -> 0..2 position, 3..5 reflectance, -1 other
    int faces_from = -1;
    if (e.properties.size() > 64) fail("element \"" + e.name + "\" has more than 64 properties");
    if (is_vertex) {
      if (seen_faces) fail("the faces come before the vertices");
      static const char* names[6] = {"x", "y", "z", "reflectance_r", "reflectance_g", "reflectance_b"};
      bool found[6] = {};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        role[k] = -1;
        for (int r = 0; r < 6; ++r)
          if (e.properties[k].name == names[r] && !e.properties[k].list) role[k] = r, found[r] = true;
      }
      for (int r = 0; r < 6; ++r)
        if (!found[r])
          fail(std::string("the vertices have no \"") + names[r] + "\" property" +
               (r >= 3 ? " (write the PLY with `dynrad clean`, which adds reflectance_r, _g and _b)" : ""));
      seen_vertices = true;
      positions.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(e.count, 1u << 24)));
      reflectances.reserve(positions.capacity());
    }
    if (is_face) {
      if (!seen_vertices) fail("the faces come before the vertices");
      for (std::size_t k = 0; k < e.properties.size(); ++k)
        if (e.properties[k].list &&
            (e.properties[k].name == "vertex_indices" || e.properties[k].name == "vertex_index"))
          faces_from = static_cast<int>(k);
      if (faces_from < 0) fail("the faces have no vertex_indices list");
      seen_faces = true;
    }
    for (std::uint64_t item = 0; item < e.count; ++item) {
      const std::string where = e.name + " " + std::to_string(item);
      Vec3 position;
      Rgb rho{};
      std::array<double, 3> corner_ids{};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        double value = 0;
        if (!p.list) {
          if (!body.read(p.type, value)) fail("ends early or has a bad value, at " + where + " property " + p.name);
          if (!is_vertex || role[k] < 0) continue;
          if (role[k] < 3) {
            (role[k] == 0 ? position.x : role[k] == 1 ? position.y : position.z) = value;
          } else {
            rho[role[k] - 3] = value;
          }
          continue;
        }
        double count = 0;
        if (!body.read(p.count_type, count) || count < 0 || count != std::floor(count))
          fail("ends early or has a bad list length, at " + where + " property " + p.name);
        const bool corners = is_face && static_cast<int>(k) == faces_from;
        if (corners && count != 3)
          fail(where + " has " + std::to_string(static_cast<long long>(count)) +
               " corners; only triangles are read (write the PLY with `dynrad clean`, which triangulates)");
        for (long long i = 0; i < static_cast<long long>(count); ++i) {
          if (!body.read(p.type, value)) fail("ends early or has a bad value, at " + where + " property " + p.name);
          if (corners) corner_ids[static_cast<std::size_t>(i)] = value;
        }
      }
      if (is_vertex) {
        if (!finite(position)) fail(where + " is at " + text(position));
        for (int c = 0; c < 3; ++c)
          if (!(rho[c] >= 0 && rho[c] <= 1))
            fail(where + " has reflectance " + std::to_string(rho[c]) + " in channel " + std::to_string(c) +
                 ", outside [0, 1]");
        positions.push_back(position);
        reflectances.push_back(rho);
      } else if (is_face) {
        Triangle t;
        for (int c = 0; c < 3; ++c) {
          const double id = corner_ids[static_cast<std::size_t>(c)];
          if (!(id >= 0 && id < static_cast<double>(positions.size())) || id != std::floor(id))
            fail(where + " uses vertex " + std::to_string(static_cast<long long>(id)) + ", but there are " +
                 std::to_string(positions.size()) + " vertices");
          const std::size_t v = static_cast<std::size_t>(id);
          t.corners[static_cast<std::size_t>(c)] = positions[v];
          for (int ch = 0; ch < 3; ++ch) t.reflectance[ch] += reflectances[v][ch] / 3;
        }
        scene.triangles.push_back(t);
      }
    }
  }
  if (!seen_vertices) fail("it has no vertex element");
  if (!seen_faces) fail("it has no face element");
  if (scene.triangles.empty()) fail("it has no faces");
  return scene;
}

}  // namespace dynrad_test::mesh_tracer
