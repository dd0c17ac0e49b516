// A year of daylight at grid points, from the daylight coefficients of one solve
// (coefficient_solve.h) and a weather file (epw.h).
//
// Per hour of the file (row h covers (h-1):00 to h:00 local standard time):
//   - the sun's position at the middle of the hour, (h-1):30 standard time, of a
//     reference year (2019, or 2020 when the file has a 29 February), as Radiance's
//     gendaymtx places it;
//   - the sky: the Perez all-weather model from the row's diffuse horizontal and direct
//     normal irradiance, its illuminances from the Perez efficacy model (the file's
//     illuminance fields are not read: many files fill them from the same model, some
//     leave them missing); the ground's luminance ground_reflectance x the horizontal
//     illuminance of sky and sun / pi;
//   - a row whose diffuse horizontal irradiance is 0, or whose sun is below the horizon
//     and whose diffuse irradiance is under 1 W/m2, is dark.
// Then each point's illuminance is its coefficients times the hour's sky vectors, plus
// the sun's direct light by a shadow ray (which alone is ASE's "direct sunlight").
#pragma once

#include "radiosity/climate/annual_metrics.h"
#include "radiosity/climate/coefficient_solve.h"
#include "radiosity/climate/epw.h"

#include <string>
#include <vector>

namespace dynrad::rad {

struct AnnualOptions {
  double ground_reflectance = 0.2;
  Vec3d up{0, 0, 1}, north{0, 1, 0};
  CoefficientOptions coefficients;
};

// Every hour of the weather as the coefficients see it.
struct YearSky {
  std::vector<HourEnding> rows;
  std::vector<HourSky> hours;              // per row (dark rows: empty vectors)
  std::vector<char> dark;                  // per row
  std::vector<double> diffuse_horizontal;  // lx per row, the sky's (EN 17037's daylight hours)
  std::vector<Vec3d> suns;                 // the sun positions (coefficient_solve.h)
  int reference_year = 2019;
};

// Throws InputError naming the weather file's line for an hour the sky models cannot
// take.
YearSky year_sky(const Weather& weather, const SkyPatches& fine, const SkyPatches& indirect,
                 const AnnualOptions& options);

// A grid's year: the illuminance per hour and point (hour-major), the sun's alone, and
// per point its coefficients' masking.
struct AnnualGridHours {
  HourlyIlluminance total, sun;
  std::vector<char> masked;
};
AnnualGridHours grid_year(const std::vector<PointCoefficients>& points, const std::vector<Vec3d>& positions,
                          const Vec3d& normal, const Visibility& visibility, const Glazing* glazing,
                          const YearSky& year);

}  // namespace dynrad::rad
