// Skies and the sun for daylight.
//
// Sky luminance models, relative to the zenith luminance Lz:
//   uniform: L = Lz everywhere above the horizon;
//   traditional CIE overcast (Moon and Spencer 1942): L = Lz (1 + 2 sin(altitude)) / 3,
//     whose unobstructed horizontal illuminance is 7 pi Lz / 9;
//   CIE standard general sky (ISO 15469 / CIE S 011), types 1-15: at zenith angle Z and
//     angle chi from the sun, L / Lz = f(chi) phi(Z) / (f(Zs) phi(0)), with gradation
//     phi(Z) = 1 + a exp(b / cos Z) (phi = 1 at the horizon) and indicatrix
//     f(chi) = 1 + c (exp(d chi) - exp(d pi / 2)) + e cos^2 chi, Zs the sun's zenith angle;
//   Perez all-weather (Perez, Seals and Michalsky 1993): L / Lz = lv(Z, gamma) / lv(0, Zs),
//     lv = (1 + a exp(b / cos Z)) (1 + c exp(d gamma) + e cos^2 gamma), gamma the angle from
//     the sun, negative lv taken as 0; radiosity/sources/perez.h finds a..e for an hour of
//     weather.
// Below the horizon the ground: uniform, L = ground reflectance x the horizontal
// illuminance of sky and sun / pi (a diffuse ground, unobstructed).
//
// The sky is scaled by its zenith luminance or by its horizontal illuminance (from the
// sky alone, sun excluded), found by integrating the model.
//
// The sun: a direction and a direct normal illuminance; a point source at infinity
// (the 0.5 degree disc is not resolved: shadows are sharp).
//
// Coordinates: up is +z; north is +y unless told otherwise; east is north x up... that is,
// +x when north is +y.
#pragma once

#include "mesh/core/types.h"

#include <string>

namespace dynrad::rad {

struct CieSkyParameters {
  double a, b, c, d, e;
};

// Types 1 (overcast, steep gradation, sun invisible) to 15 (cloudless, turbid, broad
// solar corona). Throws std::invalid_argument outside 1-15.
const CieSkyParameters& cie_sky_parameters(int type);

// The Perez sky's coefficients. The form needs b <= 0 (the gradation is then bounded,
// and 1 at the horizon when b < 0) and a positive lv at the zenith; perez_coefficients
// (radiosity/sources/perez.h) sees to both. The default is a uniform sky.
struct PerezSkyCoefficients {
  double a = 0, b = 0, c = 0, d = 0, e = 0;
};

struct SkyModel {
  enum class Type { uniform, cie_overcast, cie, perez };
  Type type = Type::cie_overcast;
  int cie_type = 1;            // Type::cie
  PerezSkyCoefficients perez;  // Type::perez
  Vec3d up{0, 0, 1};
  Vec3d sun{0, 0, 1};          // unit, towards the sun (its position shapes CIE skies)
  double zenith_luminance = 1;  // cd/m^2
  double ground_luminance = 0;  // cd/m^2, below the horizon

  // cd/m^2 seen along unit direction d (from the observer).
  double luminance(const Vec3d& d) const;
  // Relative to the zenith: luminance(d) / zenith_luminance above the horizon.
  double relative(const Vec3d& d) const;
  // Unobstructed illuminance on a horizontal plane facing up, from the sky alone (lx):
  // Gauss-Legendre in cos Z (64 nodes) times 256 azimuths (exact to 1e-7 for the
  // overcast and uniform skies; the sun's corona of clear skies to about 1e-4).
  double horizontal_illuminance() const;
  // The mean luminance (cd/m^2) all round at `elevation` degrees above the horizon (72
  // azimuths): what one sees of the sky through a window.
  double mean_luminance_at(double elevation) const;
  // A short description: "CIE overcast sky, Lz 3183 cd/m2 (10000 lx horizontal)".
  std::string describe() const;
};

// The sun's position: NOAA's solar calculator (after Meeus, Astronomical Algorithms),
// with its refraction correction; about 0.01 degree between 1900 and 2100.
struct SunPosition {
  double zenith = 0;    // degrees from straight up, refraction included
  double azimuth = 0;   // degrees clockwise from north
  double declination = 0, equation_of_time = 0;  // degrees, minutes
};

struct LocalTime {
  int year = 2000, month = 1, day = 1, hour = 12, minute = 0;
  double second = 0;
  double timezone = 0;  // hours east of UTC (Central Europe +1, summer +2; Denver -7)
};

// `latitude` north positive, `longitude` east positive, degrees.
SunPosition sun_position(double latitude, double longitude, const LocalTime& time);

// "2026-06-21T12:00" or "2026-06-21T12:00:30" (local time); throws
// std::invalid_argument for anything else or an impossible date.
LocalTime parse_local_time(const std::string& text, double timezone);

// The unit vector towards a position, for a model whose up is `up` and whose north is
// `north` (perpendicular to up; east = north x up).
Vec3d sun_direction(const SunPosition& p, const Vec3d& up, const Vec3d& north);

}  // namespace dynrad::rad
