// The mesh tracer's private parts, shared by its sources and used nowhere else:
// small vector and colour helpers, the random numbers, and the scene as the tracer
// holds it (Tracer::Impl), whose members are defined in mesh_tracer_scene.cpp (the
// scene put into Embree, and rays) and mesh_tracer.cpp (the estimate).
#pragma once

#include "reference/mesh_tracer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace dynrad_test::mesh_tracer {
namespace detail {

inline constexpr double kPi = 3.14159265358979323846;

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(const Vec3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline bool finite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

inline double luminance(const Rgb& c) {
  return kLuminanceWeights[0] * c[0] + kLuminanceWeights[1] * c[1] + kLuminanceWeights[2] * c[2];
}
inline double largest(const Rgb& c) { return std::max({c[0], c[1], c[2]}); }

inline std::string text(const Vec3& p) {
  std::ostringstream out;
  out << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return out.str();
}

// ---------------------------------------------------------------------------------
// Random numbers.

// A 64-bit hash with good avalanche (the SplitMix64 output function).
inline std::uint64_t mix(std::uint64_t z) {
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

}  // namespace detail

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

  // The rays (mesh_tracer_scene.cpp).
  Hit first_hit(const Vec3& x, const Vec3& n, const Vec3& d, int from, double offset) const;
  bool visible(const Vec3& x, const Vec3& n, const Vec3& target, int from, int to, double offset,
               double stop_short) const;

  // The estimate (mesh_tracer.cpp).
  double point_lights(const Vec3& x, const Vec3& n, int from, double offset) const;
  double emitter_density(unsigned j, double r2, double cos_y) const;
  Rgb sample_emitters(const Vec3& x, const Vec3& n, int from, double offset, double surface_offset,
                      detail::Rng& rng) const;
  double path(const Vec3& x0, const Vec3& n0, const TraceOptions& o, double surface_offset, detail::Rng& rng,
              bool& first_back) const;
  Estimate estimate(const Vec3& x, const Vec3& n, const TraceOptions& o, std::uint64_t key, int threads,
                    std::size_t index) const;
};

}  // namespace dynrad_test::mesh_tracer
