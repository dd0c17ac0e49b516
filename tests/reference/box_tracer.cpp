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
#include "reference/box_tracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

namespace dynrad_test::reference {
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

std::string text(const Vec3& p) {
  return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}

int axis_of(Face face) { return static_cast<int>(face) / 2; }
bool on_plus_side(Face face) { return static_cast<int>(face) % 2 == 1; }

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
bool inside_open(const Vec3& lo, const Vec3& hi, int axis, const Vec3& p) {
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

// ---------------------------------------------------------------------------------
// Direct light, exact.

// A convex polygon, at most kMaxVertices corners.
struct Polygon {
  static constexpr int kMaxVertices = 64;
  std::array<Vec3, kMaxVertices> v;
  int count = 0;
};

// The part of p on the side q.(y - x) >= 0 of the plane through x with normal q.
Polygon clip(const Polygon& p, const Vec3& x, const Vec3& q) {
  Polygon out;
  for (int i = 0; i < p.count; ++i) {
    const Vec3& a = p.v[i];
    const Vec3& b = p.v[(i + 1) % p.count];
    const double da = dot(q, a - x), db = dot(q, b - x);
    if (out.count + 2 > Polygon::kMaxVertices) throw std::length_error("box tracer: too many overlapping blockers");
    if (da >= 0) out.v[out.count++] = a;
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) out.v[out.count++] = a + (b - a) * (da / (da - db));
  }
  return out;
}

// Point-to-polygon form factor (dimensionless) from the differential area at x with
// unit normal n to polygon p, which lies above x's horizon: Lambert's contour
// integral. The sign, set by the polygon's orientation, is dropped.
double form_factor(const Polygon& p, const Vec3& x, const Vec3& n) {
  double sum = 0;
  for (int i = 0; i < p.count; ++i) {
    const Vec3 a = p.v[i] - x, b = p.v[(i + 1) % p.count] - x;
    const Vec3 c = cross(a, b);
    const double c_length = length(c);
    if (c_length == 0) continue;
    const double gamma = std::atan2(c_length, dot(a, b));  // angle between a and b
    sum += gamma * dot(n, c) / c_length;
  }
  return std::abs(sum) / (2 * kPi);
}

// The cone of points that box b hides from x, as half-spaces q.(y - x) >= 0: one plane
// through x and each silhouette edge of b (an edge between a face that x sees and one
// it does not). x inside b (no face seen): no planes, b hides everything.
struct ShadowCone {
  std::array<Vec3, 12> planes;
  int count = 0;
};

ShadowCone shadow_cone(const Bounds& b, const Vec3& x) {
  bool sees[3][2];  // x sees face (axis, side): it is on or in front of the face's plane
  for (int a = 0; a < 3; ++a) {
    sees[a][0] = x[a] <= b.lo[a];
    sees[a][1] = x[a] >= b.hi[a];
  }
  const Vec3 center = (b.lo + b.hi) * 0.5;
  ShadowCone cone;
  for (int a = 0; a < 3; ++a) {  // edges along axis a, where faces of axes u and v meet
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    for (int su = 0; su < 2; ++su)
      for (int sv = 0; sv < 2; ++sv) {
        if (sees[u][su] == sees[v][sv]) continue;
        Vec3 p0, p1;
        p0[u] = p1[u] = su ? b.hi[u] : b.lo[u];
        p0[v] = p1[v] = sv ? b.hi[v] : b.lo[v];
        p0[a] = b.lo[a];
        p1[a] = b.hi[a];
        Vec3 q = cross(p0 - x, p1 - x);
        if (dot(q, q) == 0) continue;  // x in line with the edge: its neighbours bound the cone
        if (dot(q, center - x) < 0) q = q * -1.0;
        cone.planes[cone.count++] = q;
      }
  }
  return cone;
}

// Cone c covers all of polygon p.
bool covers(const ShadowCone& c, const Polygon& p, const Vec3& x) {
  for (int k = 0; k < c.count; ++k)
    for (int i = 0; i < p.count; ++i)
      if (dot(c.planes[k], p.v[i] - x) < 0) return false;
  return true;
}

// Form factor from x (normal n) to the part of polygon p outside cones[first...].
double unblocked_form_factor(const Polygon& p, const std::vector<ShadowCone>& cones, std::size_t first, const Vec3& x,
                             const Vec3& n) {
  for (std::size_t j = first; j < cones.size(); ++j)
    if (covers(cones[j], p, x)) return 0;  // the common case in a shadow: no integral
  double f = form_factor(p, x, n);
  for (std::size_t j = first; j < cones.size(); ++j) {
    Polygon hidden = p;
    for (int k = 0; k < cones[j].count && hidden.count >= 3; ++k) hidden = clip(hidden, x, cones[j].planes[k]);
    if (hidden.count >= 3) f -= unblocked_form_factor(hidden, cones, j + 1, x, n);
  }
  return f;
}

// Form factor from x (unit normal n) to the part of emitter e that x sees.
double visible_form_factor(const Scene& scene, const EmitterInfo& e, const Vec3& x, const Vec3& n) {
  const double height = (x[e.axis] - e.plane) * e.sign;  // x above the emitter's front
  if (!(height > 0)) return 0;
  const int u = (e.axis + 1) % 3, v = (e.axis + 2) % 3;
  Polygon p;
  p.count = 4;
  for (int k = 0; k < 4; ++k) {
    p.v[k][e.axis] = e.plane;
    p.v[k][u] = (k == 1 || k == 2) ? e.hi[u] : e.lo[u];
    p.v[k][v] = (k >= 2) ? e.hi[v] : e.lo[v];
  }
  p = clip(p, x, n);  // above x's horizon
  if (p.count < 3) return 0;

  Bounds hull{x, x};  // of x and what it may see of the emitter
  for (int k = 0; k < p.count; ++k)
    for (int c = 0; c < 3; ++c) {
      hull.lo[c] = std::min(hull.lo[c], p.v[k][c]);
      hull.hi[c] = std::max(hull.hi[c], p.v[k][c]);
    }
  // A box can hide part of the emitter only if it reaches strictly between the two
  // planes (emitter's and x's, along the emitter's axis) and into the hull's box; only
  // that slice of it matters.
  std::vector<ShadowCone> cones;
  const double near = std::min(e.plane, x[e.axis]), far = std::max(e.plane, x[e.axis]);
  auto add_blocker = [&](const Bounds& b) {
    if (!(b.lo[e.axis] < far && b.hi[e.axis] > near)) return;
    for (int c = 0; c < 3; ++c) {
      if (c != e.axis && !(b.lo[c] < hull.hi[c] && b.hi[c] > hull.lo[c])) return;
      if (b.lo[c] == b.hi[c] && x[c] == b.lo[c]) return;  // a wall in a plane through x
    }
    Bounds slice = b;
    slice.lo[e.axis] = std::max(b.lo[e.axis], near);
    slice.hi[e.axis] = std::min(b.hi[e.axis], far);
    cones.push_back(shadow_cone(slice, x));
  };
  for (const BoxScene::Box& box : scene.boxes) {
    if (!box.room) {
      add_blocker({box.lo, box.hi});
      continue;
    }
    bool hull_inside = true;  // then the room's faces hide nothing
    for (int c = 0; c < 3; ++c) hull_inside = hull_inside && box.lo[c] <= hull.lo[c] && hull.hi[c] <= box.hi[c];
    if (hull_inside) continue;
    for (int f = 0; f < 6; ++f) {  // each face as a box of zero thickness
      const int a = axis_of(static_cast<Face>(f));
      Bounds wall{box.lo, box.hi};
      wall.lo[a] = wall.hi[a] = on_plus_side(static_cast<Face>(f)) ? box.hi[a] : box.lo[a];
      add_blocker(wall);
    }
  }
  return std::max(0.0, unblocked_form_factor(p, cones, 0, x, n));
}

// Direct irradiance (W/m^2) at x, unit normal n, from every emitter.
double direct(const Scene& scene, const Vec3& x, const Vec3& n) {
  double h = 0;
  for (const EmitterInfo& e : scene.emitters)
    if (e.exitance > 0) h += e.exitance * visible_form_factor(scene, e, x, n);
  return h;
}

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

// ---------------------------------------------------------------------------------
// Building a scene.

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("box scene: " + what);
}

void check_reflectance(double rho, const std::string& what) {
  require(rho >= 0 && rho < 1, what + " reflectance " + std::to_string(rho) + " is not in [0, 1)");
}

}  // namespace

Reflectances Reflectances::uniform(double rho) { return {{rho, rho, rho, rho, rho, rho}}; }

Reflectances Reflectances::walls_floor_ceiling(double walls, double floor, double ceiling) {
  return {{walls, walls, walls, walls, floor, ceiling}};
}

int BoxScene::add_box(const Vec3& lo, const Vec3& hi, bool room, const Reflectances& reflectance) {
  const std::string name = "box " + std::to_string(boxes_.size());
  for (int c = 0; c < 3; ++c)
    require(std::isfinite(lo[c]) && std::isfinite(hi[c]) && lo[c] < hi[c],
            name + " from " + text(lo) + " to " + text(hi) + " is empty or not finite: need lo < hi on every axis");
  for (double rho : reflectance.of_face) check_reflectance(rho, name);
  boxes_.push_back({lo, hi, room, reflectance});
  return static_cast<int>(boxes_.size()) - 1;
}

int BoxScene::add_room(const Vec3& lo, const Vec3& hi, const Reflectances& reflectance) {
  return add_box(lo, hi, true, reflectance);
}

int BoxScene::add_solid(const Vec3& lo, const Vec3& hi, const Reflectances& reflectance) {
  return add_box(lo, hi, false, reflectance);
}

void BoxScene::add_emitter(int box, Face face, const Vec3& lo, const Vec3& hi, double exitance, double reflectance) {
  const std::string name = "emitter " + std::to_string(emitters_.size());
  require(box >= 0 && box < static_cast<int>(boxes_.size()),
          name + " is on box " + std::to_string(box) + ", which does not exist");
  require(std::isfinite(exitance) && exitance >= 0, name + " has exitance " + std::to_string(exitance));
  check_reflectance(reflectance, name);
  const Box& b = boxes_[box];
  const int axis = axis_of(face);
  const double plane = on_plus_side(face) ? b.hi[axis] : b.lo[axis];
  Emitter e{box, face, lo, hi, exitance, reflectance};
  for (int c = 0; c < 3; ++c) {
    e.lo[c] = std::min(lo[c], hi[c]);
    e.hi[c] = std::max(lo[c], hi[c]);
    if (c == axis) {
      require(lo[c] == plane && hi[c] == plane, name + " from " + text(lo) + " to " + text(hi) +
                                                    " is not in the plane of its face (coordinate " +
                                                    std::to_string(c) + " = " + std::to_string(plane) + ")");
    } else {
      require(e.lo[c] < e.hi[c] && b.lo[c] <= e.lo[c] && e.hi[c] <= b.hi[c],
              name + " from " + text(lo) + " to " + text(hi) + " is empty or reaches outside its face");
    }
  }
  for (const Emitter& other : emitters_) {
    if (other.box != box || other.face != face) continue;
    bool overlap = true;
    for (int c = 0; c < 3; ++c)
      if (c != axis) overlap = overlap && e.lo[c] < other.hi[c] && other.lo[c] < e.hi[c];
    require(!overlap, name + " overlaps another emitter on the same face");
  }
  emitters_.push_back(e);
}

void BoxScene::add_emitter(int box, Face face, double exitance, double reflectance) {
  require(box >= 0 && box < static_cast<int>(boxes_.size()),
          "emitter on box " + std::to_string(box) + ", which does not exist");
  const Box& b = boxes_[box];
  const int axis = axis_of(face);
  Vec3 lo = b.lo, hi = b.hi;
  lo[axis] = hi[axis] = on_plus_side(face) ? b.hi[axis] : b.lo[axis];
  add_emitter(box, face, lo, hi, exitance, reflectance);
}

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
