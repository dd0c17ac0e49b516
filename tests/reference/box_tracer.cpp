// The box path tracer (see box_tracer.h for what it answers).
//
// Irradiance at x with normal n:  H(x) = D(x) + I(x).
// - D(x), direct light, is exact. For each emitter: clip its rectangle to x's horizon,
//   then take Lambert's contour integral, F = 1/(2 pi) sum_i gamma_i n.(R_i x R_i+1)/|R_i x R_i+1|,
//   over the part of it that x sees. Boxes that might hide part of it (those that meet
//   the bounding box of x and the rectangle between their two planes) are not sampled
//   but cut out exactly: each casts a convex shadow cone from x (planes through x and
//   the box's silhouette edges), and the visible form factor is
//   F(P) - sum_j F((P inside cone j) outside cones j+1...), computed recursively.
// - I(x) is a path estimate. From x a cosine-weighted direction finds the first face y
//   (slab tests against every box, no acceleration structure); the path adds its
//   throughput times D(y) and continues from y, the throughput multiplied by rho(y),
//   so its expected value is the sum over bounces of rho(y1)...rho(yk) D(yk). Once the
//   throughput is low, Russian roulette ends paths fairly (TraceOptions::roulette_below).
//   Reaching an emitter adds nothing: D already counts emitted light (no double count).
//   Self-intersection is avoided by face identity: a ray ignores the face it leaves.
// - Sampling is randomised quasi-Monte Carlo. A replicate is N paths whose bounce-k
//   decisions (two for the direction, one for the roulette) come from the first N
//   points of the 3-D Sobol' sequence, digitally shifted at random and, for k >= 1,
//   assigned to paths by a random permutation (padding: bounces stay independent).
//   Replicates are independent, so their spread gives an honest standard error.
//
// Files: this one holds the sampling and the estimate; box_tracer_direct.cpp the direct
// light; box_tracer_rays.cpp the first hits; box_tracer_scene.cpp the building of a
// BoxScene; box_tracer_internal.h what they share.
#include "reference/box_tracer.h"
#include "reference/box_tracer_internal.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace dynrad_test::reference {
using namespace detail;
namespace {

// ---------------------------------------------------------------------------------
// Random numbers.

// SplitMix64's finaliser: a well-mixed 64-bit hash of z.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

struct Rng {  // SplitMix64
  std::uint64_t state;
  std::uint64_t next() { return mix(state += 0x9e3779b97f4a7c15ULL); }
  double uniform() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1p-53; }  // in (0, 1)
};

// Direction numbers of the first three dimensions of Sobol's sequence (primitive
// polynomials x + 1 and x^2 + x + 1 after the van der Corput dimension), 32 bits.
struct SobolDirections {
  std::uint32_t v[3][32];
  SobolDirections() {
    for (int k = 0; k < 32; ++k) v[0][k] = 1u << (31 - k);
    v[1][0] = v[2][0] = 1u << 31;
    v[2][1] = 3u << 30;
    for (int k = 1; k < 32; ++k) v[1][k] = v[1][k - 1] ^ (v[1][k - 1] >> 1);
    for (int k = 2; k < 32; ++k) v[2][k] = v[2][k - 1] ^ v[2][k - 2] ^ (v[2][k - 2] >> 2);
  }
};
const SobolDirections kSobol;

std::uint32_t sobol(int dimension, std::uint32_t index) {
  std::uint32_t x = 0;
  for (int k = 0; index != 0; index >>= 1, ++k)
    if (index & 1u) x ^= kSobol.v[dimension][k];
  return x;
}

// Bounces drawn from Sobol' points; later ones from a path's own generator.
constexpr int kStratifiedBounces = 8;

// The random choices of one replicate of `paths` paths.
class Replicate {
 public:
  Replicate(std::uint64_t key, int paths) : key_(key), paths_(paths) {
    Rng rng{key};
    for (auto& shift : shift_)
      for (std::uint32_t& s : shift) s = static_cast<std::uint32_t>(rng.next() >> 32);
    order_.resize(static_cast<std::size_t>(kStratifiedBounces - 1) * paths);
    for (int k = 1; k < kStratifiedBounces; ++k) {
      std::uint32_t* order = &order_[static_cast<std::size_t>(k - 1) * paths];
      for (int i = 0; i < paths; ++i) order[i] = static_cast<std::uint32_t>(i);
      for (int i = paths - 1; i > 0; --i) std::swap(order[i], order[rng.next() % (i + 1)]);
    }
  }

  // Three numbers in (0, 1) for bounce `bounce` of path `path`: direction, roulette.
  std::array<double, 3> sample(int path, int bounce, Rng& path_rng) const {
    std::array<double, 3> u;
    if (bounce >= kStratifiedBounces) {
      for (double& x : u) x = path_rng.uniform();
      return u;
    }
    const std::uint32_t index =
        bounce == 0 ? static_cast<std::uint32_t>(path) : order_[static_cast<std::size_t>(bounce - 1) * paths_ + path];
    for (int d = 0; d < 3; ++d) u[d] = ((sobol(d, index) ^ shift_[bounce][d]) + 0.5) * 0x1p-32;
    return u;
  }

  Rng path_rng(int path) const { return Rng{mix(key_ ^ mix(static_cast<std::uint64_t>(path) + 1))}; }

 private:
  std::uint64_t key_;
  int paths_;
  std::array<std::array<std::uint32_t, 3>, kStratifiedBounces> shift_;
  std::vector<std::uint32_t> order_;  // path -> Sobol' index, per bounce >= 1
};

// A direction about unit normal n with density cos(theta) / pi, from (u0, u1) in
// (0, 1)^2 by Shirley and Chiu's concentric map (which keeps strata compact).
Vec3 cosine_direction(const Vec3& n, double u0, double u1) {
  const double a = 2 * u0 - 1, b = 2 * u1 - 1;
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a, phi = (kPi / 4) * (b / a);
  } else {
    r = b, phi = kPi / 2 - (kPi / 4) * (a / b);
  }
  const double dx = r * std::cos(phi), dy = r * std::sin(phi);
  const double dz = std::sqrt(std::max(0.0, 1 - dx * dx - dy * dy));
  // Tangents of n (Duff et al. 2017, "Building an orthonormal basis, revisited").
  const double sign = std::copysign(1.0, n.z), k = -1 / (sign + n.z), m = n.x * n.y * k;
  const Vec3 t{1 + sign * n.x * n.x * k, sign * m, -sign * n.x};
  const Vec3 s{m, sign + n.y * n.y * k, -n.y};
  return t * dx + s * dy + n * dz;
}

// ---------------------------------------------------------------------------------
// Estimation.

// What is estimated: emission + reflectance * H(point) (radiosity, or H alone with
// emission 0 and reflectance 1).
struct Query {
  Vec3 point, normal;
  int face = -1;  // the face the point lies on, or -1 (mid-air)
  double emission = 0;
  double reflectance = 1;
  std::uint64_t key = 0;  // random stream of this query
};

// One path's estimate of the indirect irradiance (W/m^2) at the query. The path's
// throughput (product of the reflectances so far) is kept while it is at least
// `roulette_below`; under it, Russian roulette: the path survives with probability
// throughput / roulette_below and then carries roulette_below.
double indirect_path(const Scene& scene, const Query& q, const Replicate& replicate, int path, double roulette_below) {
  Rng rng = replicate.path_rng(path);
  Vec3 x = q.point, n = q.normal;
  int face = q.face;
  double sum = 0, throughput = 1;
  for (int bounce = 0;; ++bounce) {
    const std::array<double, 3> u = replicate.sample(path, bounce, rng);
    const Hit hit = first_hit(scene, x, cosine_direction(n, u[0], u[1]), face);
    if (hit.face < 0 || !hit.front) return sum;
    const double rho = scene.reflectance_at(hit.face, hit.point);
    if (rho == 0) return sum;
    throughput *= rho;
    sum += throughput * direct(scene, hit.point, scene.faces[hit.face].normal);
    if (throughput < roulette_below) {
      if (u[2] * roulette_below >= throughput) return sum;
      throughput = roulette_below;
    }
    x = hit.point, n = scene.faces[hit.face].normal, face = hit.face;
  }
}

// Runs fn(0) ... fn(count - 1) on `threads` threads; rethrows the first exception.
template <class Fn>
void parallel_for(int count, int threads, const Fn& fn) {
  threads = std::min(threads, count);
  if (threads <= 1) {
    for (int i = 0; i < count; ++i) fn(i);
    return;
  }
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  auto work = [&] {
    for (int i; (i = next.fetch_add(1)) < count;) {
      try {
        fn(i);
      } catch (...) {
        if (!failed.exchange(true)) error = std::current_exception();
        next = count;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

int thread_count(const TraceOptions& options) {
  if (options.threads > 0) return options.threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

// emission + reflectance * H at the query, traced until the options are met.
Estimate estimate(const Scene& scene, const Query& q, const TraceOptions& options, int threads) {
  if (q.reflectance == 0) return {q.emission, 0, 0};
  const double known = q.emission + q.reflectance * direct(scene, q.point, q.normal);
  const int paths = options.paths_per_replicate;
  std::vector<double> means;  // indirect irradiance, one mean per replicate
  auto run_until = [&](int replicates) {
    const int first = static_cast<int>(means.size());
    means.resize(replicates);
    parallel_for(replicates - first, threads, [&](int i) {
      const Replicate replicate(mix(q.key ^ mix(static_cast<std::uint64_t>(first + i))), paths);
      double sum = 0;
      for (int path = 0; path < paths; ++path) sum += indirect_path(scene, q, replicate, path, options.roulette_below);
      means[first + i] = sum / paths;
    });
  };
  auto result = [&] {
    const double r = static_cast<double>(means.size());
    double mean = 0, spread = 0;
    for (double m : means) mean += m;
    mean /= r;
    for (double m : means) spread += (m - mean) * (m - mean);
    const double std_error = std::sqrt(spread / (r - 1) / r);
    return Estimate{known + q.reflectance * mean, q.reflectance * std_error,
                    static_cast<std::int64_t>(means.size()) * paths};
  };
  if (options.samples > 0) {
    run_until(static_cast<int>(std::max<std::int64_t>(2, (options.samples + paths - 1) / paths)));
    return result();
  }
  const int most = static_cast<int>(std::max<std::int64_t>(2, options.max_samples / paths));
  run_until(std::min(most, std::max(2, options.min_replicates)));
  for (;;) {
    const Estimate e = result();
    const double goal = options.target_relative_error * std::abs(e.value);
    if (e.std_error <= goal || static_cast<int>(means.size()) >= most) return e;
    // The error falls as 1 / sqrt(replicates): aim 10% past the goal, but grow at most
    // four times per round, since a few replicates estimate the error roughly.
    const double now = static_cast<double>(means.size());
    const double needed = 1.1 * now * (e.std_error / goal) * (e.std_error / goal);
    const double next = std::clamp(needed, now + options.min_replicates, 4 * now);
    run_until(static_cast<int>(std::min<double>(most, next)));
  }
}

void check(const TraceOptions& options) {
  if (!(options.roulette_below > 0 && options.roulette_below <= 1))
    throw std::invalid_argument("box tracer: roulette_below must be in (0, 1], not " +
                                std::to_string(options.roulette_below));
  if (options.min_replicates < 2)
    throw std::invalid_argument("box tracer: min_replicates must be at least 2 (for a standard error)");
  const int paths = options.paths_per_replicate;
  if (paths <= 0 || (paths & (paths - 1)) != 0)
    throw std::invalid_argument("box tracer: paths_per_replicate must be a power of two, not " + std::to_string(paths));
  if (!(options.target_relative_error > 0) && options.samples <= 0)
    throw std::invalid_argument("box tracer: give samples or a positive target_relative_error");
}

// The query for `point` and `normal`, its random stream from the seed and both.
Query make_query(const Scene& scene, const Vec3& point, const Vec3& normal, std::uint64_t seed) {
  const double norm = length(normal);
  if (!(norm > 0) || !std::isfinite(norm)) throw std::invalid_argument("box tracer: the normal must be non-zero");
  Query q;
  q.point = point;
  q.normal = normal * (1 / norm);
  q.face = scene.face_at(point, q.normal);
  if (q.face >= 0) q.point[scene.faces[q.face].axis] = scene.faces[q.face].plane;
  q.key = mix(seed);
  for (double c : {point.x, point.y, point.z, q.normal.x, q.normal.y, q.normal.z}) {
    std::uint64_t bits;
    std::memcpy(&bits, &c, sizeof bits);
    q.key = mix(q.key ^ bits);
  }
  return q;
}

Query radiosity_query(const Scene& scene, const Vec3& point, const Vec3& normal, std::uint64_t seed) {
  Query q = make_query(scene, point, normal, seed);
  if (q.face < 0)
    throw std::invalid_argument("box tracer: radiosity asked at " + text(point) + " with normal " + text(normal) +
                                ", which is on no box face facing that way");
  q.emission = scene.emission_at(q.face, q.point);
  q.reflectance = scene.reflectance_at(q.face, q.point);
  return q;
}

void require_boxes(const BoxScene& scene) {
  if (scene.boxes().empty()) throw std::invalid_argument("box tracer: the scene has no boxes");
}

}  // namespace

Estimate radiosity(const BoxScene& scene, const Vec3& point, const Vec3& normal, const TraceOptions& options) {
  require_boxes(scene);
  check(options);
  const Scene s(scene);
  return estimate(s, radiosity_query(s, point, normal, options.seed), options, thread_count(options));
}

Estimate irradiance(const BoxScene& scene, const Vec3& point, const Vec3& normal, const TraceOptions& options) {
  require_boxes(scene);
  check(options);
  const Scene s(scene);
  return estimate(s, make_query(s, point, normal, options.seed), options, thread_count(options));
}

double direct_irradiance(const BoxScene& scene, const Vec3& point, const Vec3& normal) {
  require_boxes(scene);
  const Scene s(scene);
  const Query q = make_query(s, point, normal, 0);
  return direct(s, q.point, q.normal);
}

std::vector<Estimate> radiosity(const BoxScene& scene, const std::vector<SurfacePoint>& points,
                                const TraceOptions& options) {
  require_boxes(scene);
  check(options);
  const Scene s(scene);
  std::vector<Query> queries;
  for (const SurfacePoint& p : points) queries.push_back(radiosity_query(s, p.point, p.normal, options.seed));
  std::vector<Estimate> results(points.size());
  parallel_for(static_cast<int>(points.size()), thread_count(options),
               [&](int i) { results[i] = estimate(s, queries[i], options, 1); });
  return results;
}

}  // namespace dynrad_test::reference
