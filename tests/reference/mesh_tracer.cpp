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
//
// Files: this one holds the estimate; mesh_tracer_scene.cpp the scene in Embree and the
// rays; mesh_tracer_ply.cpp the PLY reader; mesh_tracer_internal.h what they share.
#include "reference/mesh_tracer.h"
#include "reference/mesh_tracer_internal.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace dynrad_test::mesh_tracer {
using namespace detail;
namespace {

// ---------------------------------------------------------------------------------
// Random numbers.

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
// The estimate.

// Point lights' irradiance at x (unit normal n), each checked by one shadow ray.
double Tracer::Impl::point_lights(const Vec3& x, const Vec3& n, int from, double offset) const {
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
double Tracer::Impl::emitter_density(unsigned j, double r2, double cos_y) const {
  const double total = emitter_cdf.back();
  const double chosen = luminance(prims[j].exitance) * prims[j].area / total;
  return chosen * r2 / (prims[j].area * cos_y);
}

// One area sample of the emitting triangles: an estimate of the irradiance they give
// x (unit normal n), weighted against cosine sampling by the power heuristic.
// `offset`: the ray's start off x; `surface_offset`: how far short of the emitter it
// stops.
Rgb Tracer::Impl::sample_emitters(const Vec3& x, const Vec3& n, int from, double offset, double surface_offset,
                                  Rng& rng) const {
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
double Tracer::Impl::path(const Vec3& x0, const Vec3& n0, const TraceOptions& o, double surface_offset, Rng& rng,
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
Estimate Tracer::Impl::estimate(const Vec3& x, const Vec3& n, const TraceOptions& o, std::uint64_t key, int threads,
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

}  // namespace dynrad_test::mesh_tracer
