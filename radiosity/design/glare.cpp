// The Unified Glare Rating: Guth's position index, luminaires as glare sources, UGR at
// an observer, and the tabular method.
//
// Tabular method. The rooms, reflectances and layout are CIE 190:2010's: rooms X x Y
// in multiples of H (X across the line of sight), H = 2 m from the eye to the
// luminaires' plane, luminaires in a square array at spacing S = 0.25 H (the first at
// S/2 from the walls), the observer at the middle of one wall, looking horizontally
// along the room; the five reflectance sets of ceiling, walls and floor (the floor
// being the plane at eye level, 0.2 in all of them).
//
// The background is where dynrad differs from CIE 190. CIE 190 takes Lb = E_WID / pi,
// E_WID the mean indirect illuminance on the walls between eye level and the
// luminaires' plane, which it finds from the luminaires' zonal fluxes and tabulated
// transfer factors per room index and reflectance set. dynrad finds the same quantity
// from its own interreflection model of the standard room: ceiling, walls and floor as
// three uniform diffuse surfaces of a box H high, the direct flux onto each from the
// whole array by integrating the distribution over directions (upward flux onto the
// ceiling), exact view factors for the box, and the three radiosities solved exactly.
// E_WID is then what the walls receive from the three surfaces. The values are close
// to, not the same as, a table computed with CIE 190's transfer factors.
#include "radiosity/design/glare.h"

#include "radiosity/transfer/random.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace dynrad::rad {

namespace {

constexpr double kDegree = M_PI / 180.0;

// CIE 117:1995 Table 4.1: rows T/R = 0, 0.1, ..., 3.0; columns H/R = 0, 0.1, ..., 1.9.
// 0 marks the void cells (positions hidden by the brows). The entry at T/R 2.7,
// H/R 0.6 is kept as published (7.50), though its neighbours suggest about 7.05.
constexpr int kGuthRows = 31, kGuthColumns = 20;
// clang-format off
constexpr double kGuth[kGuthRows][kGuthColumns] = {
    {1.00, 1.26, 1.53, 1.90, 2.35, 2.86, 3.50, 4.20, 5.00, 6.00, 7.00, 8.10, 9.25, 10.35, 11.70, 13.15, 14.70, 16.20, 0, 0},
    {1.05, 1.22, 1.46, 1.80, 2.20, 2.75, 3.40, 4.10, 4.80, 5.80, 6.80, 8.00, 9.10, 10.30, 11.60, 13.00, 14.60, 16.10, 0, 0},
    {1.12, 1.30, 1.50, 1.80, 2.20, 2.66, 3.18, 3.88, 4.60, 5.50, 6.50, 7.60, 8.75, 9.85, 11.20, 12.70, 14.00, 15.70, 0, 0},
    {1.22, 1.38, 1.60, 1.97, 2.25, 2.70, 3.25, 3.90, 4.60, 5.45, 6.45, 7.40, 8.40, 9.50, 10.85, 12.10, 13.70, 15.00, 0, 0},
    {1.32, 1.47, 1.70, 1.96, 2.35, 2.80, 3.30, 3.90, 4.60, 5.40, 6.40, 7.30, 8.30, 9.40, 10.60, 11.90, 13.20, 14.60, 16.00, 0},
    {1.43, 1.60, 1.82, 2.10, 2.48, 2.91, 3.40, 3.98, 4.70, 5.50, 6.40, 7.30, 8.30, 9.40, 10.50, 11.75, 13.00, 14.40, 15.70, 0},
    {1.55, 1.72, 1.98, 2.30, 2.65, 3.10, 3.60, 4.10, 4.80, 5.50, 6.40, 7.35, 8.40, 9.40, 10.50, 11.70, 13.00, 14.10, 15.40, 0},
    {1.70, 1.88, 2.12, 2.48, 2.87, 3.30, 3.78, 4.30, 4.88, 5.60, 6.50, 7.40, 8.50, 9.50, 10.50, 11.70, 12.85, 14.00, 15.20, 0},
    {1.82, 2.00, 2.32, 2.70, 3.08, 3.50, 3.92, 4.50, 5.10, 5.75, 6.60, 7.50, 8.60, 9.50, 10.60, 11.75, 12.80, 14.00, 15.10, 0},
    {1.96, 2.20, 2.54, 2.90, 3.30, 3.70, 4.20, 4.75, 5.30, 6.00, 6.75, 7.70, 8.70, 9.65, 10.75, 11.80, 12.90, 14.00, 15.00, 16.00},
    {2.11, 2.40, 2.75, 3.10, 3.50, 3.91, 4.40, 5.00, 5.60, 6.20, 7.00, 7.90, 8.80, 9.75, 10.80, 11.90, 12.95, 14.00, 15.00, 16.00},
    {2.30, 2.55, 2.92, 3.30, 3.72, 4.20, 4.70, 5.25, 5.80, 6.55, 7.20, 8.15, 9.00, 9.90, 10.95, 12.00, 13.00, 14.00, 15.00, 16.00},
    {2.40, 2.75, 3.12, 3.50, 3.90, 4.35, 4.85, 5.50, 6.05, 6.70, 7.50, 8.30, 9.20, 10.00, 11.02, 12.10, 13.10, 14.00, 15.00, 16.00},
    {2.55, 2.90, 3.30, 3.70, 4.20, 4.65, 5.20, 5.70, 6.30, 7.00, 7.70, 8.55, 9.35, 10.20, 11.20, 12.25, 13.20, 14.00, 15.00, 16.00},
    {2.70, 3.10, 3.50, 3.90, 4.35, 4.85, 5.35, 5.85, 6.50, 7.25, 8.00, 8.70, 9.50, 10.40, 11.40, 12.40, 13.25, 14.05, 15.00, 16.00},
    {2.85, 3.15, 3.65, 4.10, 4.55, 5.00, 5.50, 6.20, 6.80, 7.50, 8.20, 8.85, 9.70, 10.55, 11.50, 12.50, 13.30, 14.05, 15.02, 16.00},
    {2.95, 3.40, 3.80, 4.25, 4.75, 5.20, 5.75, 6.30, 7.00, 7.65, 8.40, 9.00, 9.80, 10.80, 11.75, 12.60, 13.40, 14.20, 15.10, 16.00},
    {3.10, 3.55, 4.00, 4.50, 4.90, 5.40, 5.95, 6.50, 7.20, 7.80, 8.50, 9.20, 10.00, 10.85, 11.85, 12.75, 13.45, 14.20, 15.10, 16.00},
    {3.25, 3.70, 4.20, 4.65, 5.10, 5.60, 6.10, 6.75, 7.40, 8.00, 8.65, 9.35, 10.10, 11.00, 11.90, 12.80, 13.50, 14.20, 15.10, 16.00},
    {3.43, 3.86, 4.30, 4.75, 5.20, 5.70, 6.30, 6.90, 7.50, 8.17, 8.80, 9.50, 10.20, 11.00, 12.00, 12.82, 13.55, 14.20, 15.10, 16.00},
    {3.50, 4.00, 4.50, 4.90, 5.35, 5.80, 6.40, 7.10, 7.70, 8.30, 8.90, 9.60, 10.40, 11.10, 12.00, 12.85, 13.60, 14.30, 15.10, 16.00},
    {3.60, 4.17, 4.65, 5.05, 5.50, 6.00, 6.60, 7.20, 7.82, 8.45, 9.00, 9.75, 10.50, 11.20, 12.10, 12.90, 13.70, 14.35, 15.10, 16.00},
    {3.75, 4.25, 4.72, 5.20, 5.60, 6.10, 6.70, 7.35, 8.00, 8.55, 9.15, 9.85, 10.60, 11.30, 12.10, 12.90, 13.70, 14.40, 15.15, 16.00},
    {3.85, 4.35, 4.80, 5.25, 5.70, 6.22, 6.80, 7.40, 8.10, 8.65, 9.30, 9.90, 10.70, 11.40, 12.20, 12.95, 13.70, 14.40, 15.20, 16.00},
    {3.95, 4.40, 4.90, 5.35, 5.80, 6.30, 6.90, 7.50, 8.20, 8.80, 9.40, 10.00, 10.80, 11.50, 12.25, 13.00, 13.75, 14.45, 15.20, 16.00},
    {4.00, 4.50, 4.96, 5.40, 5.85, 6.40, 6.95, 7.55, 8.25, 8.85, 9.50, 10.05, 10.85, 11.55, 12.30, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.07, 4.55, 5.05, 5.47, 5.95, 6.46, 7.00, 7.65, 8.35, 8.95, 9.55, 10.10, 10.90, 11.60, 12.32, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.10, 4.60, 5.10, 5.53, 6.00, 6.50, 7.50, 7.70, 8.40, 9.00, 9.60, 10.16, 10.92, 11.63, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.15, 4.62, 5.15, 5.56, 6.05, 6.55, 7.08, 7.73, 8.45, 9.05, 9.65, 10.20, 10.95, 11.65, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.20, 4.65, 5.17, 5.60, 6.07, 6.57, 7.12, 7.75, 8.50, 9.10, 9.70, 10.23, 10.95, 11.65, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00},
    {4.22, 4.67, 5.20, 5.65, 6.12, 6.60, 7.15, 7.80, 8.55, 9.12, 9.70, 10.23, 10.95, 11.65, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00},
};
// clang-format on

// The range CIE 117 is commonly cited for (see glare.h).
constexpr double kSmallSolidAngle = 3e-4, kLargeSolidAngle = 1e-1;
constexpr double kSmallArea = 0.005, kLargeArea = 1.5;

// The opening's area seen from direction (gamma, C) of the luminaire's frame: the
// bottom foreshortened by cos(gamma), and the luminous sides.
double projected_opening(double length, double width, double height, bool round, double cos_gamma, double sin_gamma,
                         double cos_c, double sin_c) {
  const double bottom = round ? M_PI * 0.25 * length * length : length * width;
  double area = bottom * std::max(cos_gamma, 0.0);
  if (height > 0) {
    if (round)
      area += length * height * sin_gamma;
    else
      area += sin_gamma * height * (width * std::abs(cos_c) + length * std::abs(sin_c));
  }
  return area;
}

// Luminance and solid angle of an opening (length along c0, width along c90) seen
// along unit `to_eye` (from the luminaire) at `distance`, sending `intensity` there.
LuminaireAppearance appearance(double length, double width, double height, bool round, const Vec3d& nadir,
                               const Vec3d& c0, const Vec3d& c90, const Vec3d& to_eye, double distance,
                               double intensity) {
  LuminaireAppearance a;
  a.distance = distance;
  a.intensity = intensity;
  const double cos_gamma = std::clamp(OpenMesh::dot(to_eye, nadir), -1.0, 1.0);
  const double sin_gamma = std::sqrt(std::max(0.0, 1 - cos_gamma * cos_gamma));
  const double x = OpenMesh::dot(to_eye, c0), y = OpenMesh::dot(to_eye, c90);
  const double h = std::hypot(x, y);
  const double cos_c = h > 0 ? x / h : 1.0, sin_c = h > 0 ? y / h : 0.0;
  a.projected_area = projected_opening(length, width, height, round, cos_gamma, sin_gamma, cos_c, sin_c);
  if (a.projected_area > 0 && distance > 0) {
    a.luminance = intensity / a.projected_area;
    a.solid_angle = a.projected_area / (distance * distance);
  }
  return a;
}

// Note on a counted source's size against the method's range, or empty.
std::string size_note(const LuminaireAppearance& a) {
  if (a.solid_angle < kSmallSolidAngle || a.projected_area < kSmallArea)
    return fmt::format(
        "small source ({:.2g} sr, {:.2g} m^2 projected): below the range the UGR formula is meant for "
        "(about 3e-4 sr; CIE 147 treats sources under 0.005 m^2 apart)",
        a.solid_angle, a.projected_area);
  if (a.solid_angle > kLargeSolidAngle || a.projected_area > kLargeArea)
    return fmt::format(
        "large source ({:.2g} sr, {:.2g} m^2 projected): above the range the UGR formula is meant for "
        "(about 0.1 sr; CIE 147 treats sources over 1.5 m^2 apart)",
        a.solid_angle, a.projected_area);
  return {};
}

// Form factor between two equal, parallel, directly opposed rectangles a x b, c apart.
double opposed_rectangles(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double x1 = std::sqrt(1 + x * x), y1 = std::sqrt(1 + y * y);
  const double sum = 0.5 * std::log((1 + x * x) * (1 + y * y) / (1 + x * x + y * y)) + x * y1 * std::atan(x / y1) +
                     y * x1 * std::atan(y / x1) - x * std::atan(x) - y * std::atan(y);
  return 2 / (M_PI * x * y) * sum;
}

// How many of n positions (i + 1/2) s, i = 0 .. n-1, lie in [lo, hi].
long positions_within(long n, double s, double lo, double hi) {
  const long first = std::max(0L, static_cast<long>(std::ceil(lo / s - 0.5)));
  const long last = std::min(n - 1, static_cast<long>(std::floor(hi / s - 0.5)));
  return std::max(0L, last - first + 1);
}

// The luminaire's distribution sampled over the sphere for the flux split: unit
// directions in the room (z up) and the flux each carries, per lm of the luminaire.
struct FluxSample {
  double dx, dy, tan_gamma, share;  // horizontal unit direction, tan(gamma), flux share
  bool up;                          // gamma above 90 degrees
};

std::vector<FluxSample> sample_distribution(const Photometry& p, const Vec3d& c0, const Vec3d& c90) {
  // Midpoints of 0.25 degree steps in gamma and 2 degree steps in C.
  const int gammas = 720, cs = 180;
  const double dg = 180.0 / gammas, dc = 360.0 / cs;
  std::vector<FluxSample> out;
  out.reserve(static_cast<std::size_t>(gammas) * cs);
  double total = 0;
  for (int i = 0; i < gammas; ++i) {
    const double g = (i + 0.5) * dg;
    const double weight = std::sin(g * kDegree) * dg * kDegree * dc * kDegree;
    for (int j = 0; j < cs; ++j) {
      const double c = (j + 0.5) * dc;
      const double flux = p.intensity(c, g) * weight;
      if (!(flux > 0)) continue;
      const Vec3d horizontal = c0 * std::cos(c * kDegree) + c90 * std::sin(c * kDegree);
      out.push_back({horizontal[0], horizontal[1], std::tan(g * kDegree), flux, g > 90});
      total += flux;
    }
  }
  for (FluxSample& s : out) s.share /= total;
  return out;
}

// Mean indirect illuminance on the walls (lx) of a room X x Y x H with n_x x n_y
// luminaires at spacing s on its ceiling, each of flux `flux`.
double wall_indirect_illuminance(const std::vector<FluxSample>& samples, double X, double Y, double H, long n_x,
                                 long n_y, double s, double flux, const UgrReflectances& rho) {
  // Direct flux onto the floor, per luminaire flux: each direction's share times the
  // number of luminaires whose ray through it lands inside the floor.
  double floor_share = 0, up_share = 0, down_share = 0;
  for (const FluxSample& d : samples) {
    if (d.up) {
      up_share += d.share;
      continue;
    }
    down_share += d.share;
    const double ox = H * d.tan_gamma * d.dx, oy = H * d.tan_gamma * d.dy;
    const double landing = static_cast<double>(positions_within(n_x, s, -ox, X - ox)) *
                           static_cast<double>(positions_within(n_y, s, -oy, Y - oy));
    floor_share += d.share * landing;
  }
  const double count = static_cast<double>(n_x * n_y);
  const double direct_floor = flux * floor_share;
  const double direct_walls = flux * (down_share * count - floor_share);
  const double direct_ceiling = flux * up_share * count;
  // Three surfaces: 0 ceiling, 1 floor, 2 walls.
  const double area[3] = {X * Y, X * Y, 2 * H * (X + Y)};
  const double f_cf = opposed_rectangles(X, Y, H);
  const double f_wc = area[0] * (1 - f_cf) / area[2];
  const double F[3][3] = {{0, f_cf, 1 - f_cf}, {f_cf, 0, 1 - f_cf}, {f_wc, f_wc, 1 - 2 * f_wc}};
  const double r[3] = {rho.ceiling, rho.floor, rho.walls};
  const double direct[3] = {direct_ceiling / area[0], direct_floor / area[1], direct_walls / area[2]};
  // B_i = r_i (E_i + sum_j F_ij B_j): (I - r F) B = r E, by Gaussian elimination
  // (diagonally dominant for reflectances below 1).
  double m[3][4];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m[i][j] = (i == j ? 1.0 : 0.0) - r[i] * F[i][j];
    m[i][3] = r[i] * direct[i];
  }
  for (int k = 0; k < 3; ++k)
    for (int i = k + 1; i < 3; ++i) {
      const double f = m[i][k] / m[k][k];
      for (int j = k; j < 4; ++j) m[i][j] -= f * m[k][j];
    }
  double b[3];
  for (int i = 2; i >= 0; --i) {
    double v = m[i][3];
    for (int j = i + 1; j < 3; ++j) v -= m[i][j] * b[j];
    b[i] = v / m[i][i];
  }
  return F[2][0] * b[0] + F[2][1] * b[1] + F[2][2] * b[2];
}

}  // namespace

double guth_position_index(double h_over_r, double t_over_r) {
  t_over_r = std::abs(t_over_r);
  if (!(h_over_r >= 0) || !(t_over_r <= 3.0) || h_over_r > 1.9) return 0;
  const double u = t_over_r * 10, v = h_over_r * 10;
  const int i = std::min(static_cast<int>(u), kGuthRows - 2), j = std::min(static_cast<int>(v), kGuthColumns - 2);
  const double fu = u - i, fv = v - j;
  const double a = kGuth[i][j], b = kGuth[i][j + 1], c = kGuth[i + 1][j], d = kGuth[i + 1][j + 1];
  // A void corner that the point actually draws on puts it outside the field.
  const double wa = (1 - fu) * (1 - fv), wb = (1 - fu) * fv, wc = fu * (1 - fv), wd = fu * fv;
  if ((a == 0 && wa > 0) || (b == 0 && wb > 0) || (c == 0 && wc > 0) || (d == 0 && wd > 0)) return 0;
  return wa * a + wb * b + wc * c + wd * d;
}

double kim_position_index(double tau_deg, double sigma_deg) {
  const double t = tau_deg, s = sigma_deg;
  const double ln_p = (35.2 - 0.31889 * t - 1.22 * std::exp(-2 * t / 9)) * 1e-3 * s +
                      (21 + 0.26667 * t - 0.002963 * t * t) * 1e-5 * s * s;
  return std::exp(ln_p);
}

LuminaireAppearance luminaire_appearance(const Luminaire& l, const Vec3d& eye) {
  Vec3d d = eye - l.position;
  const double distance = d.norm();
  if (!(distance > 0)) return {};
  d /= distance;
  const double height = l.photometry ? std::abs(l.photometry->height) : 0.0;
  return appearance(l.opening_length(), l.opening_width(), height, l.round_opening(), l.nadir, l.c0, l.c90, d, distance,
                    l.intensity_towards(d));
}

double unified_glare_rating(double background_luminance, double sum) {
  if (!(background_luminance > 0) || !(sum > 0)) return 0;
  return 8 * std::log10(0.25 * sum / background_luminance);
}

GlareResult observer_glare(const LitScene& scene, const Observer& observer, const GatherOptions& gather) {
  GlareResult result;
  result.observer = observer.name;
  result.limit = observer.limit;
  const Vec3d up(0, 0, 1);
  Vec3d view(observer.view[0], observer.view[1], 0);
  if (!(view.norm() > 1e-9)) {
    result.notes.push_back("the line of sight is vertical: UGR needs a horizontal one");
    return result;
  }
  view.normalize();
  const Vec3d side = OpenMesh::cross(view, up);
  const Vec3d& eye = observer.eye;

  for (const Luminaire& l : scene.luminaires) {
    GlareSource s;
    s.luminaire = l.name;
    const Vec3d v = l.position - eye;
    const double r = OpenMesh::dot(v, view), t = OpenMesh::dot(v, side), h = v[2];
    if (l.directional()) {
      s.note = "daylight: UGR counts luminaires only";
    } else if (l.kind != Luminaire::Kind::photometric || !(l.opening_size() > 0)) {
      s.note = "no luminous area (a point, a spot, or a file giving none): it cannot enter UGR";
    } else if (!(r > 0)) {
      s.note = "behind the observer: out of the field of view";
    } else if (!(h > 0)) {
      s.note = "at or below eye level: the position index is defined above the line of sight only";
    } else if ((s.position_index = guth_position_index(h / r, t / r)) == 0) {
      s.note =
          fmt::format("outside the field the position index covers (H/R {:.2f}, T/R {:.2f})", h / r, std::abs(t) / r);
    } else {
      const Vec3d to_eye = -v / v.norm();
      if (scene.visibility->occluded(eye, -to_eye, l.position, to_eye)) {
        s.note = "hidden: its centre is not visible from the eye";
      } else {
        const LuminaireAppearance a = luminaire_appearance(l, eye);
        s.luminance = a.luminance;
        s.solid_angle = a.solid_angle;
        s.term = a.luminance * a.luminance * a.solid_angle / (s.position_index * s.position_index);
        s.counted = true;
        s.note = a.intensity > 0 ? size_note(a) : "sends no light towards the eye";
        ++result.counted;
        result.sum += s.term;
      }
    }
    if (!s.counted) s.position_index = 0;
    result.sources.push_back(s);
  }

  const GridPointResult at_eye =
      gather_point(scene, eye, view, gather, mix(gather.seed ^ std::hash<std::string>()(observer.name)));
  if (at_eye.masked) {
    result.notes.push_back("the eye is inside a solid: no background luminance, UGR undefined");
    return result;
  }
  result.indirect_illuminance = at_eye.indirect;
  result.background_luminance = at_eye.indirect / M_PI;
  if (result.counted == 0) {
    result.notes.push_back("no luminaire counts (see each source's note): UGR undefined, no glare from luminaires");
    return result;
  }
  if (!(result.sum > 0)) {
    result.notes.push_back("the counted luminaires send no light to the eye: UGR undefined, no glare");
    return result;
  }
  if (!(result.background_luminance > 0)) {
    result.notes.push_back("no indirect light at the eye (background luminance 0): UGR undefined");
    return result;
  }
  result.ugr = unified_glare_rating(result.background_luminance, result.sum);
  result.defined = true;
  if (result.ugr < 10)
    result.notes.push_back("UGR below 10, where CIE 117's scale starts: report it as < 10");
  else if (result.ugr > 30)
    result.notes.push_back("UGR above 30, beyond CIE 117's scale: severe glare, the value itself is indicative");
  return result;
}

std::vector<UgrRoom> standard_ugr_rooms() {
  return {{2, 2}, {2, 3},  {2, 4}, {2, 6}, {2, 8}, {2, 12}, {4, 2},  {4, 3},  {4, 4}, {4, 6},
          {4, 8}, {4, 12}, {8, 4}, {8, 6}, {8, 8}, {8, 12}, {12, 4}, {12, 6}, {12, 8}};
}

std::vector<UgrReflectances> standard_ugr_reflectances() {
  return {{0.7, 0.5, 0.2}, {0.7, 0.3, 0.2}, {0.5, 0.5, 0.2}, {0.5, 0.3, 0.2}, {0.3, 0.3, 0.2}};
}

UgrTable tabular_ugr(const Photometry& p, double flux) {
  UgrTable table;
  table.luminaire = p.name.empty() ? p.file : p.name;
  table.rooms = standard_ugr_rooms();
  table.reflectances = standard_ugr_reflectances();
  table.flux = flux > 0 ? flux : p.flux;
  const double length = std::abs(p.length), width = p.round ? std::abs(p.length) : std::abs(p.width);
  const double height = std::abs(p.height);
  if (!(p.flux > 0)) {
    table.notes.push_back("the file's distribution carries no flux: no table");
    return table;
  }
  if (!(std::max(length, width) > 0)) {
    table.notes.push_back("the file gives no luminous opening (a point): its luminance, and so UGR, is undefined");
    return table;
  }
  table.defined = true;
  const double scale = table.flux / p.flux;
  const double H = table.height, s = table.spacing * H;
  const Vec3d nadir(0, 0, -1);
  // Crosswise: C0 along x, across the line of sight (+y); endwise: C0 along +y.
  // C90 = up x C0 in both (luminaire.h).
  struct Orientation {
    Vec3d c0, c90;
  };
  const Orientation orientations[2] = {{Vec3d(1, 0, 0), Vec3d(0, 1, 0)}, {Vec3d(0, 1, 0), Vec3d(-1, 0, 0)}};
  for (int o = 0; o < 2; ++o) {
    const Orientation& frame = orientations[o];
    const std::vector<FluxSample> samples = sample_distribution(p, frame.c0, frame.c90);
    auto& out = o == 0 ? table.crosswise : table.endwise;
    for (const UgrRoom& room : table.rooms) {
      const double X = room.x * H, Y = room.y * H;
      const long n_x = std::lround(X / s), n_y = std::lround(Y / s);
      // The sum over the array, the eye at (X / 2, 0, 0), the luminaires at height H.
      double sum = 0;
      for (long i = 0; i < n_x; ++i)
        for (long j = 0; j < n_y; ++j) {
          const double t = (i + 0.5) * s - 0.5 * X, r = (j + 0.5) * s;
          const double index = guth_position_index(H / r, t / r);
          if (index == 0) continue;
          const Vec3d to_eye = Vec3d(-t, -r, -H) / std::sqrt(t * t + r * r + H * H);
          const double distance = std::sqrt(t * t + r * r + H * H);
          const double cos_gamma = OpenMesh::dot(to_eye, nadir);
          double c = std::atan2(OpenMesh::dot(to_eye, frame.c90), OpenMesh::dot(to_eye, frame.c0)) / kDegree;
          if (c < 0) c += 360;
          const double intensity = scale * p.intensity(c, std::acos(std::clamp(cos_gamma, -1.0, 1.0)) / kDegree);
          const LuminaireAppearance a =
              appearance(length, width, height, p.round, nadir, frame.c0, frame.c90, to_eye, distance, intensity);
          sum += a.luminance * a.luminance * a.solid_angle / (index * index);
        }
      std::vector<double> row;
      for (const UgrReflectances& rho : table.reflectances) {
        const double e_wid = wall_indirect_illuminance(samples, X, Y, H, n_x, n_y, s, table.flux, rho);
        row.push_back(unified_glare_rating(e_wid / M_PI, sum));
      }
      out.push_back(row);
    }
  }
  table.notes.push_back(
      fmt::format("for {:.0f} lm per luminaire; at k times the flux every value is 8 log10(k) higher", table.flux));
  table.notes.push_back(
      "background: mean indirect illuminance on the walls from dynrad's three-surface model of the standard room, "
      "not CIE 190's tabulated transfer factors");
  return table;
}

}  // namespace dynrad::rad
