// Small value types shared by the whole project: points, colours, boxes.
#pragma once

#include <OpenMesh/Core/Geometry/VectorT.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace dynrad {

using Vec3d = OpenMesh::Vec3d;

// A linear RGB triple (reflectance, emission, radiosity...). Plain data with the few
// operations the code needs; channels are independent.
struct Rgb {
  double r = 0, g = 0, b = 0;

  constexpr Rgb() = default;
  constexpr Rgb(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
  constexpr explicit Rgb(double v) : r(v), g(v), b(v) {}

  constexpr double operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
  Rgb& operator+=(const Rgb& o) { r += o.r; g += o.g; b += o.b; return *this; }
  friend Rgb operator+(Rgb a, const Rgb& o) { return a += o; }
  friend Rgb operator-(const Rgb& a, const Rgb& o) { return {a.r - o.r, a.g - o.g, a.b - o.b}; }
  friend Rgb operator*(const Rgb& a, const Rgb& o) { return {a.r * o.r, a.g * o.g, a.b * o.b}; }
  friend Rgb operator*(const Rgb& a, double s) { return {a.r * s, a.g * s, a.b * s}; }
  friend Rgb operator*(double s, const Rgb& a) { return a * s; }
  friend bool operator==(const Rgb& a, const Rgb& o) { return a.r == o.r && a.g == o.g && a.b == o.b; }
  friend bool operator!=(const Rgb& a, const Rgb& o) { return !(a == o); }

  double max_channel() const { return std::max({r, g, b}); }
  double min_channel() const { return std::min({r, g, b}); }
  bool is_zero() const { return r == 0 && g == 0 && b == 0; }
  bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
  // Rec. 709 / sRGB primaries, linear values.
  double luminance() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
};

// Axis-aligned bounding box; empty until the first point is added.
struct Bounds {
  Vec3d lo{std::numeric_limits<double>::infinity()};
  Vec3d hi{-std::numeric_limits<double>::infinity()};

  void extend(const Vec3d& p) {
    lo.minimize(p);
    hi.maximize(p);
  }
  bool empty() const { return !(lo[0] <= hi[0]); }
  Vec3d extent() const { return empty() ? Vec3d(0.0) : hi - lo; }
  double diagonal() const { return empty() ? 0.0 : (hi - lo).norm(); }
};

// A triangle of a window: glass (a material with a transmittance), kept out of the lit
// mesh (mesh/load.h) and carried along unlit into glTF output (mesh/io/export.h).
struct GlazingTriangle {
  std::array<Vec3d, 3> corners;
  Rgb transmittance;
};

inline bool is_finite(const Vec3d& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

}  // namespace dynrad
