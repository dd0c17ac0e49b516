#include "plugin/validate/reference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynrad::validate {

double polygon_factor(const Vec3d& x, const Vec3d& n, const std::vector<Vec3d>& corners) {
  double sum = 0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Vec3d a = (corners[i] - x).normalized();
    const Vec3d b = (corners[(i + 1) % corners.size()] - x).normalized();
    const Vec3d normal = OpenMesh::cross(a, b);
    const double length = normal.norm();
    if (!(length > 0)) continue;
    const double angle = std::atan2(length, OpenMesh::dot(a, b));
    sum += angle * OpenMesh::dot(normal / length, n);
  }
  // Corners counter-clockwise seen from x give a negative sum: the magnitude is F.
  return std::abs(sum) / (2 * M_PI);
}

namespace {

// Gradation (a, b) of the six groups, then indicatrix (c, d, e) of the six groups, and
// each of the 15 types' pair of groups (ISO 15469:2004, table 1).
constexpr double kGradation[6][2] = {{4.0, -0.70}, {1.1, -0.8}, {0.0, -1.0}, {-1.0, -0.55}, {-1.0, -0.32}, {-1.0, -0.15}};
constexpr double kIndicatrix[6][3] = {{0, -1.0, 0},      {2, -1.5, 0.15},   {5, -2.5, 0.30},
                                      {10, -3.0, 0.45}, {16, -3.0, 0.30}, {24, -2.8, 0.15}};
constexpr int kGroups[15][2] = {{0, 0}, {0, 1}, {1, 0}, {1, 1}, {2, 0}, {2, 1}, {2, 2}, {2, 3},
                                {3, 1}, {3, 2}, {3, 3}, {4, 3}, {4, 4}, {5, 4}, {5, 5}};

}  // namespace

GeneralSky::GeneralSky(int type, const Vec3d& sun) : sun_(sun.normalized()) {
  if (type < 1 || type > 15) throw std::invalid_argument("CIE sky type out of 1-15");
  const auto& g = kGradation[kGroups[type - 1][0]];
  const auto& i = kIndicatrix[kGroups[type - 1][1]];
  a_ = g[0];
  b_ = g[1];
  c_ = i[0];
  d_ = i[1];
  e_ = i[2];
  at_zenith_ = 1;
  at_zenith_ = relative(Vec3d(0, 0, 1));
}

double GeneralSky::relative(const Vec3d& d) const {
  const double cos_z = d[2];
  if (cos_z <= 0) return 0;
  const double gradation = 1 + a_ * std::exp(b_ / cos_z);
  const double chi = std::acos(std::clamp(OpenMesh::dot(d, sun_), -1.0, 1.0));
  const double cos_chi = std::cos(chi);
  const double indicatrix = 1 + c_ * (std::exp(d_ * chi) - std::exp(d_ * M_PI / 2)) + e_ * cos_chi * cos_chi;
  return gradation * indicatrix / at_zenith_;
}

double GeneralSky::horizontal() const { return sky_on_plane(*this, 1.0, Vec3d(0, 0, 1)); }

namespace {

template <class Luminance>
double on_plane(const Luminance& luminance, const Vec3d& n) {
  const int azimuths = 1440, zeniths = 720;
  double sum = 0;
  for (int j = 0; j < zeniths; ++j) {
    const double z = (j + 0.5) / zeniths * (M_PI / 2);
    const double cell = (M_PI / 2 / zeniths) * (2 * M_PI / azimuths) * std::sin(z);
    for (int i = 0; i < azimuths; ++i) {
      const double phi = (i + 0.5) / azimuths * 2 * M_PI;
      const Vec3d d(std::sin(z) * std::cos(phi), std::sin(z) * std::sin(phi), std::cos(z));
      const double c = OpenMesh::dot(d, n);
      if (c > 0) sum += luminance(d) * c * cell;
    }
  }
  return sum;
}

double overcast_luminance(double horizontal, const Vec3d& d) {
  return d[2] > 0 ? 9 * horizontal / (7 * M_PI) * (1 + 2 * d[2]) / 3 : 0.0;
}

}  // namespace

double sky_on_plane(const GeneralSky& sky, double scale, const Vec3d& n) {
  return on_plane([&](const Vec3d& d) { return scale * sky.relative(d); }, n);
}

double overcast_on_plane(double horizontal, const Vec3d& n) {
  return on_plane([&](const Vec3d& d) { return overcast_luminance(horizontal, d); }, n);
}

bool blocked(const std::vector<Rect>& masks, const Vec3d& x, const Vec3d& d) {
  for (const Rect& r : masks) {
    const Vec3d normal = OpenMesh::cross(r.u, r.v);
    const double along = OpenMesh::dot(normal, d);
    if (along == 0) continue;
    const double t = OpenMesh::dot(normal, r.origin - x) / along;
    if (t <= 0) continue;
    const Vec3d p = x + d * t - r.origin;
    const double s = OpenMesh::dot(p, r.u) / r.u.sqrnorm(), q = OpenMesh::dot(p, r.v) / r.v.sqrnorm();
    if (s >= 0 && s <= 1 && q >= 0 && q <= 1) return true;
  }
  return false;
}

namespace {

// One polarisation: the pane passes (1 - r)^2 a, then (1 - r)^2 a (r a)^2, ...
double pane_series(double r, double a) {
  double sum = 0, term = (1 - r) * (1 - r) * a;
  for (int k = 0; k < 200 && term > 1e-16; ++k, term *= r * r * a * a) sum += term;
  return sum;
}

double unpolarised(double one_pass, double c) {
  const double n = 1.52;
  c = std::clamp(c, 0.0, 1.0);
  const double sin_t = std::sqrt(1 - c * c) / n, cos_t = std::sqrt(1 - sin_t * sin_t);
  const double rs = std::pow((c - n * cos_t) / (c + n * cos_t), 2);
  const double rp = std::pow((n * c - cos_t) / (n * c + cos_t), 2);
  const double a = std::pow(one_pass, 1 / cos_t);
  return 0.5 * (pane_series(rs, a) + pane_series(rp, a));
}

}  // namespace

ClearGlass::ClearGlass(double normal) {
  const double most = unpolarised(1, 1);
  if (normal >= most) {
    scale_ = normal / most;
    return;
  }
  double lo = 0, hi = 1;  // bisection on what the pane passes face on
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (unpolarised(mid, 1) < normal ? lo : hi) = mid;
  }
  one_pass_ = 0.5 * (lo + hi);
}

double ClearGlass::operator()(double cos_incidence) const { return scale_ * unpolarised(one_pass_, cos_incidence); }

namespace {

// The midpoint rule on cells of 1 cm of the opening; a cell whose corners a mask's edge
// separates (some seen, some hidden) is summed on 16 x 16 sub-cells instead, so the
// edge's staircase is 16 times finer where the integrand jumps.
template <class Luminance>
double through(const Luminance& luminance, const Rect& opening, const std::vector<Rect>& masks, const Vec3d& x,
               const Vec3d& n, double glass) {
  const int cells_u = std::max(1, static_cast<int>(std::lround(opening.u.norm() / 0.01)));
  const int cells_v = std::max(1, static_cast<int>(std::lround(opening.v.norm() / 0.01)));
  const Vec3d facing = OpenMesh::cross(opening.u, opening.v).normalized();
  const double area = OpenMesh::cross(opening.u, opening.v).norm();
  const ClearGlass pane(glass > 0 ? glass : 1);
  auto at = [&](double s, double t) { return opening.origin + opening.u * s + opening.v * t; };
  auto hidden = [&](const Vec3d& p) { return blocked(masks, x, (p - x).normalized()); };
  // The integrand at p times the area it stands for.
  auto term = [&](const Vec3d& p, double cell) {
    const Vec3d to = p - x;
    const double r2 = to.sqrnorm();
    const Vec3d d = to / std::sqrt(r2);
    const double at_x = OpenMesh::dot(d, n), at_opening = std::abs(OpenMesh::dot(d, facing));
    if (at_x <= 0 || blocked(masks, x, d)) return 0.0;
    return luminance(d) * (glass > 0 ? pane(at_opening) : 1.0) * at_x * at_opening / r2 * cell;
  };
  std::vector<char> corner;  // hidden at each cell corner
  if (!masks.empty()) {
    corner.resize(static_cast<std::size_t>(cells_u + 1) * (cells_v + 1));
    for (int i = 0; i <= cells_u; ++i)
      for (int j = 0; j <= cells_v; ++j)
        corner[static_cast<std::size_t>(i * (cells_v + 1) + j)] =
            hidden(at(static_cast<double>(i) / cells_u, static_cast<double>(j) / cells_v));
  }
  const double cell = area / (static_cast<double>(cells_u) * cells_v);
  const int sub = 16;
  double sum = 0;
  for (int i = 0; i < cells_u; ++i)
    for (int j = 0; j < cells_v; ++j) {
      bool mixed = false;
      if (!masks.empty()) {
        const auto c = [&](int a, int b) { return corner[static_cast<std::size_t>((i + a) * (cells_v + 1) + j + b)]; };
        mixed = c(0, 0) != c(1, 0) || c(0, 0) != c(0, 1) || c(0, 0) != c(1, 1);
      }
      if (!mixed) {
        sum += term(at((i + 0.5) / cells_u, (j + 0.5) / cells_v), cell);
        continue;
      }
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b)
          sum += term(at((i + (a + 0.5) / sub) / cells_u, (j + (b + 0.5) / sub) / cells_v), cell / (sub * sub));
    }
  return sum;
}

}  // namespace

double sky_through(const GeneralSky& sky, double scale, const Rect& opening, const std::vector<Rect>& masks,
                   const Vec3d& x, const Vec3d& n, double glass, double ground) {
  return through([&](const Vec3d& d) { return d[2] > 0 ? scale * sky.relative(d) : ground; }, opening, masks, x, n,
                 glass);
}

double overcast_through(double horizontal, const Rect& opening, const std::vector<Rect>& masks, const Vec3d& x,
                        const Vec3d& n, double glass, double ground) {
  return through([&](const Vec3d& d) { return d[2] > 0 ? overcast_luminance(horizontal, d) : ground; }, opening,
                 masks, x, n, glass);
}

}  // namespace dynrad::validate
