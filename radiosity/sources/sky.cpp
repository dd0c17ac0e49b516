#include "radiosity/sources/sky.h"

#include <boost/math/quadrature/gauss.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

namespace dynrad::rad {

namespace {

constexpr double kDegree = M_PI / 180.0;

// Two unit axes in the horizon's plane, at right angles, for rings of directions about
// `up` (unit).
std::pair<Vec3d, Vec3d> horizon_axes(const Vec3d& up) {
  const Vec3d east = OpenMesh::cross(std::abs(up[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0), up).normalized();
  return {east, OpenMesh::cross(up, east)};
}

}  // namespace

const CieSkyParameters& cie_sky_parameters(int type) {
  // Six gradation groups (a, b) and six indicatrix groups (c, d, e), combined into the
  // 15 standard types (ISO 15469 / CIE S 011, Table 1).
  static const std::array<CieSkyParameters, 15> table = {{
      {4.0, -0.70, 0, -1.0, 0.00},    // 1  overcast, steep gradation towards the zenith, azimuthal uniformity
      {4.0, -0.70, 2, -1.5, 0.15},    // 2  overcast, steep gradation, slight brightening towards the sun
      {1.1, -0.80, 0, -1.0, 0.00},    // 3  overcast, moderate gradation, azimuthal uniformity
      {1.1, -0.80, 2, -1.5, 0.15},    // 4  overcast, moderate gradation, slight brightening towards the sun
      {0.0, -1.00, 0, -1.0, 0.00},    // 5  sky of uniform luminance
      {0.0, -1.00, 2, -1.5, 0.15},    // 6  partly cloudy, no gradation towards the zenith, slight brightening
      {0.0, -1.00, 5, -2.5, 0.30},    // 7  partly cloudy, brighter circumsolar region
      {0.0, -1.00, 10, -3.0, 0.45},   // 8  partly cloudy, distinct solar corona
      {-1.0, -0.55, 2, -1.5, 0.15},   // 9  partly cloudy, obscured sun
      {-1.0, -0.55, 5, -2.5, 0.30},   // 10 partly cloudy, brighter circumsolar region
      {-1.0, -0.55, 10, -3.0, 0.45},  // 11 white-blue sky, distinct solar corona
      {-1.0, -0.32, 10, -3.0, 0.45},  // 12 CIE standard clear sky, low luminance turbidity
      {-1.0, -0.32, 16, -3.0, 0.30},  // 13 CIE standard clear sky, polluted atmosphere
      {-1.0, -0.15, 16, -3.0, 0.30},  // 14 cloudless turbid sky, broad solar corona
      {-1.0, -0.15, 24, -2.8, 0.15},  // 15 white-blue turbid sky, broad solar corona
  }};
  if (type < 1 || type > 15) throw std::invalid_argument("CIE sky types are numbered 1 to 15");
  return table[static_cast<std::size_t>(type - 1)];
}

double SkyModel::relative(const Vec3d& d) const {
  const double cos_z = OpenMesh::dot(d, up);
  if (cos_z <= 0) return 0;
  switch (type) {
    case Type::uniform:
      return 1;
    case Type::cie_overcast:
      return (1 + 2 * cos_z) / 3;  // sin(altitude) = cos(zenith angle)
    case Type::cie: {
      const CieSkyParameters& p = cie_sky_parameters(cie_type);
      auto gradation = [&](double cz) { return 1 + p.a * std::exp(p.b / cz); };
      auto indicatrix = [&](double chi) {
        const double c = std::cos(chi);
        return 1 + p.c * (std::exp(p.d * chi) - std::exp(p.d * M_PI / 2)) + p.e * c * c;
      };
      const double chi = std::acos(std::clamp(OpenMesh::dot(d, sun), -1.0, 1.0));
      const double zs = std::acos(std::clamp(OpenMesh::dot(sun, up), -1.0, 1.0));
      return indicatrix(chi) * gradation(cos_z) / (indicatrix(zs) * gradation(1.0));
    }
    case Type::perez: {
      // Perez's lv, relative to its value at the zenith. Negative lv (the fits' skies
      // outside the conditions they were fitted to) is taken as 0; a dark zenith leaves
      // nothing to be relative to (perez_coefficients never gives one).
      const PerezSkyCoefficients& p = perez;
      auto lv = [&](double cz, double angle_to_sun) {
        const double c = std::cos(angle_to_sun);
        return (1 + p.a * std::exp(p.b / cz)) * (1 + p.c * std::exp(p.d * angle_to_sun) + p.e * c * c);
      };
      const double gamma = std::acos(std::clamp(OpenMesh::dot(d, sun), -1.0, 1.0));
      const double zs = std::acos(std::clamp(OpenMesh::dot(sun, up), -1.0, 1.0));
      const double zenith = lv(1.0, zs);
      if (!(zenith > 0)) return 0;
      return std::max(0.0, lv(cos_z, gamma)) / zenith;
    }
  }
  return 0;
}

double SkyModel::mean_luminance_at(double elevation) const {
  const auto [east, north] = horizon_axes(up);
  const double e = elevation * M_PI / 180;
  const int n = 72;
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const double azimuth = 2 * M_PI * k / n;
    sum += luminance((east * std::cos(azimuth) + north * std::sin(azimuth)) * std::cos(e) + up * std::sin(e));
  }
  return sum / n;
}

double SkyModel::luminance(const Vec3d& d) const {
  return OpenMesh::dot(d, up) > 0 ? zenith_luminance * relative(d) : ground_luminance;
}

double SkyModel::horizontal_illuminance() const {
  // (plain variables, not a structured binding: the lambda below captures them)
  const std::pair<Vec3d, Vec3d> axes = horizon_axes(up);
  const Vec3d east = axes.first, north = axes.second;
  const int azimuths = 256;
  // E = integral of L cos Z d(omega): over cos Z in (0, 1) (Gauss-Legendre, Boost.Math)
  // and the azimuth (midpoint rule, exact for the smooth periodic integrand).
  auto ring = [&](double cz) {
    const double sz = std::sqrt(std::max(0.0, 1 - cz * cz));
    double sum = 0;
    for (int k = 0; k < azimuths; ++k) {
      const double phi = 2 * M_PI * (k + 0.5) / azimuths;
      sum += relative(up * cz + east * (sz * std::cos(phi)) + north * (sz * std::sin(phi)));
    }
    return cz * sum * (2 * M_PI / azimuths);
  };
  return zenith_luminance * boost::math::quadrature::gauss<double, 64>::integrate(ring, 0.0, 1.0);
}

std::string SkyModel::describe() const {
  std::string kind = type == Type::uniform        ? "uniform sky"
                     : type == Type::cie_overcast ? "traditional CIE overcast sky"
                     : type == Type::cie
                         ? fmt::format("CIE standard general sky type {}", cie_type)
                         : fmt::format("Perez all-weather sky (a {:.4g}, b {:.4g}, c {:.4g}, d {:.4g}, e {:.4g})",
                                       perez.a, perez.b, perez.c, perez.d, perez.e);
  return fmt::format("{}, zenith luminance {:.4g} cd/m2, horizontal illuminance {:.4g} lx from the sky, ground "
                     "{:.4g} cd/m2",
                     kind, zenith_luminance, horizontal_illuminance(), ground_luminance);
}

SunPosition sun_position(double latitude, double longitude, const LocalTime& t) {
  // Julian day of the date at 0h UT, then the time of day in UT.
  int y = t.year, m = t.month;
  if (m <= 2) {
    y -= 1;
    m += 12;
  }
  const double a = std::floor(y / 100.0), b = 2 - a + std::floor(a / 4);
  const double day_minutes = t.hour * 60.0 + t.minute + t.second / 60.0;
  const double jd = std::floor(365.25 * (y + 4716)) + std::floor(30.6001 * (m + 1)) + t.day + b - 1524.5 +
                    (day_minutes / 60.0 - t.timezone) / 24.0;
  const double T = (jd - 2451545.0) / 36525.0;  // Julian centuries since J2000
  const double mean_longitude = std::fmod(280.46646 + T * (36000.76983 + T * 0.0003032), 360.0);
  const double mean_anomaly = 357.52911 + T * (35999.05029 - 0.0001537 * T);
  const double eccentricity = 0.016708634 - T * (0.000042037 + 0.0000001267 * T);
  const double M = mean_anomaly * kDegree;
  const double centre = std::sin(M) * (1.914602 - T * (0.004817 + 0.000014 * T)) +
                        std::sin(2 * M) * (0.019993 - 0.000101 * T) + std::sin(3 * M) * 0.000289;
  const double omega = (125.04 - 1934.136 * T) * kDegree;
  const double apparent = (mean_longitude + centre - 0.00569 - 0.00478 * std::sin(omega)) * kDegree;
  const double mean_obliquity = 23 + (26 + (21.448 - T * (46.815 + T * (0.00059 - T * 0.001813))) / 60) / 60;
  const double obliquity = (mean_obliquity + 0.00256 * std::cos(omega)) * kDegree;
  const double declination = std::asin(std::sin(obliquity) * std::sin(apparent));
  const double v = std::tan(obliquity / 2) * std::tan(obliquity / 2);
  const double L0 = mean_longitude * kDegree;
  const double eot = 4 / kDegree *
                     (v * std::sin(2 * L0) - 2 * eccentricity * std::sin(M) +
                      4 * eccentricity * v * std::sin(M) * std::cos(2 * L0) - 0.5 * v * v * std::sin(4 * L0) -
                      1.25 * eccentricity * eccentricity * std::sin(2 * M));
  double solar_minutes = std::fmod(day_minutes + eot + 4 * longitude - 60 * t.timezone, 1440.0);
  if (solar_minutes < 0) solar_minutes += 1440;
  const double hour_angle = (solar_minutes / 4 < 0 ? solar_minutes / 4 + 180 : solar_minutes / 4 - 180) * kDegree;
  const double phi = latitude * kDegree;
  const double cos_zenith = std::clamp(
      std::sin(phi) * std::sin(declination) + std::cos(phi) * std::cos(declination) * std::cos(hour_angle), -1.0, 1.0);
  const double zenith = std::acos(cos_zenith);
  double azimuth = 0;
  const double denominator = std::cos(phi) * std::sin(zenith);
  if (std::abs(denominator) > 1e-12) {
    const double c = std::clamp((std::sin(phi) * cos_zenith - std::sin(declination)) / denominator, -1.0, 1.0);
    const double angle = std::acos(c) / kDegree;
    azimuth = hour_angle > 0 ? std::fmod(angle + 180, 360.0) : std::fmod(540 - angle, 360.0);
  } else {
    azimuth = latitude > 0 ? 180 : 0;
  }
  // Atmospheric refraction, by the elevation (NOAA's piecewise fit, arcseconds).
  const double elevation = 90 - zenith / kDegree;
  double refraction = 0;
  if (elevation <= 85) {
    const double te = std::tan(elevation * kDegree);
    if (elevation > 5) refraction = 58.1 / te - 0.07 / (te * te * te) + 0.000086 / std::pow(te, 5);
    else if (elevation > -0.575)
      refraction = 1735 + elevation * (-518.2 + elevation * (103.4 + elevation * (-12.79 + elevation * 0.711)));
    else refraction = -20.772 / te;
  }
  SunPosition p;
  p.zenith = zenith / kDegree - refraction / 3600;
  p.azimuth = azimuth;
  p.declination = declination / kDegree;
  p.equation_of_time = eot;
  return p;
}

LocalTime parse_local_time(const std::string& text, double timezone) {
  LocalTime t;
  t.timezone = timezone;
  int consumed = 0;
  double second = 0;
  const int n = std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d%n", &t.year, &t.month, &t.day, &t.hour, &t.minute,
                            &consumed);
  if (n != 5) throw std::invalid_argument("'" + text + "' is not a local time like 2026-06-21T12:00");
  std::string rest = text.substr(static_cast<std::size_t>(consumed));
  if (!rest.empty()) {
    int more = 0;
    if (std::sscanf(rest.c_str(), ":%lf%n", &second, &more) != 1 || static_cast<std::size_t>(more) != rest.size())
      throw std::invalid_argument("'" + text + "' is not a local time like 2026-06-21T12:00 or 2026-06-21T12:00:30");
  }
  t.second = second;
  static const int days[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (t.year % 4 == 0 && t.year % 100 != 0) || t.year % 400 == 0;
  if (t.month < 1 || t.month > 12 || t.day < 1 || t.day > days[t.month - 1] || (t.month == 2 && t.day == 29 && !leap) ||
      t.hour < 0 || t.hour > 23 || t.minute < 0 || t.minute > 59 || !(second >= 0 && second < 60) || t.year < 1900 ||
      t.year > 2100)
    throw std::invalid_argument("'" + text + "' is not a valid date and time between 1900 and 2100");
  return t;
}

Vec3d sun_direction(const SunPosition& p, const Vec3d& up, const Vec3d& north) {
  const Vec3d east = OpenMesh::cross(north, up);
  const double z = p.zenith * kDegree, a = p.azimuth * kDegree;
  return (up * std::cos(z) + (north * std::cos(a) + east * std::sin(a)) * std::sin(z)).normalized();
}

}  // namespace dynrad::rad
