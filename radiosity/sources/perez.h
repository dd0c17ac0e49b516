// The Perez all-weather sky and the Perez luminous efficacy model: the sky of one hour of
// a weather file, from its diffuse horizontal and direct normal irradiance.
//
// Models:
//   Perez, Ineichen, Seals, Michalsky and Stewart (1990), "Modeling daylight availability
//   and irradiance components from direct and global irradiance", Solar Energy 44(5)
//   271-289: the sky's clearness and brightness from the diffuse horizontal Ed and direct
//   normal Ee irradiance at the sun's zenith angle Z (radians),
//     epsilon = ((Ed + Ee) / Ed + 1.041 Z^3) / (1 + 1.041 Z^3),  Delta = Ed m / Eext,
//   in 8 clearness bins with the bounds 1, 1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2 (a bin
//   holds its lower bound; bin 1 is overcast, bin 8 clear); the precipitable water
//   W = exp(0.07 Td - 0.075) cm from the dew point Td (C); and the luminous efficacy
//   (lm/W) of the diffuse and the direct light, per bin (Table 4):
//     diffuse = a + b W + c cos Z + d ln Delta,  direct = a + b W + c exp(5.73 Z - 5) + d Delta.
//   Perez, Seals and Michalsky (1993), "All-weather model for sky luminance distribution -
//   preliminary configuration and validation", Solar Energy 50(3) 235-245 (erratum in
//   51(5) 423): the relative luminance at zenith angle zeta, gamma from the sun,
//     lv = (1 + a exp(b / cos zeta)) (1 + c exp(d gamma) + e cos^2 gamma),
//   each coefficient x1 + x2 Z + Delta (x3 + x4 Z) from the bin's row of Table 1, but in
//   bin 1 c = exp((Delta (c1 + c2 Z))^c3) - c4 and d = -exp(Delta (d1 + d2 Z)) + d3 + Delta d4.
//   m is Kasten and Young's (1989) relative optical air mass,
//   1 / (cos Z + 0.50572 (96.07995 - Z in degrees)^-1.6364); Eext is 1367 W/m2 times
//   Spencer's (1971) eccentricity correction for the day of the year.
//
// The tables' numbers are the published ones as Radiance carries them in two separately
// typed copies, gendaylit.c (Delaunay's, one flat array) and gendaymtx.c (Ashdown's
// rewrite, a table by bin naming Table 1 and Table 4), which agree to the last digit; the
// efficacy tables agree with EnergyPlus's (WeatherManager, DayltgLuminousEfficacy) too.
//
// Safeguards. The fits describe the skies they were fitted to; elsewhere they give
// negative or unbounded luminance, which Radiance's sky generators guard against. Here:
//   - Z is taken from 3 to 90 degrees for every formula (gendaylit and gendaymtx keep the
//     sun 3 degrees off the zenith; below the horizon the air mass is undefined and
//     gendaymtx takes 90). The sun's direction itself is not moved.
//   - Delta is taken from 0.01 to 0.6 (gendaylit's range; ln Delta needs Delta > 0), and
//     at least 0.2 for the sky's coefficients in bins 2-5, as both Radiance generators do
//     (below it these bins give dim skies a zenith of negative luminance).
//   - epsilon is at least 1 (rounding only: it is 1 with no direct light).
//   - b is at most 0: with b > 0 (bins 6-8, within the ranges above) the gradation runs to
//     plus or minus infinity at the horizon. gendaylit writes a black "error sky" for such
//     hours instead, which would lose the hour's diffuse light; with b = 0 the gradation
//     is flat, 1 + a.
//   - a factor of lv that is not positive at the zenith, the reference of relative
//     luminance, is dropped (a = 0, or c = e = 0); gendaymtx, more bluntly, makes a sky
//     uniform when it comes out black. Within the clamped ranges above this happens in
//     bin 4 with Z under 8.5 degrees and Delta over 0.56, and in bin 6 with Delta under 0.061.
//   - negative luminance elsewhere is taken as 0 (SkyModel::relative; gendaymtx clamps
//     its patches the same way; gendaylit's perezlum.cal does not and can emit negative
//     radiance).
//   - both efficacies are at least 0. The diffuse one always is in the ranges above; the
//     direct one falls below 0 for a low sun (in bin 1 below 3 to 12 degrees of altitude,
//     by Delta; in bins 3-5 near the horizon), where gendaylit, gendaymtx and EnergyPlus
//     take 0 too.
// Precipitable water is 2 cm when the dew point is unknown (gendaylit's default dew point,
// 10.97 C, gives the same).
#pragma once

#include "radiosity/sources/sky.h"

#include <optional>

namespace dynrad::rad {

// One hour's weather.
struct PerezInputs {
  double zenith = 0;                // the sun's zenith angle (radians, refraction included)
  double diffuse_horizontal = 0;    // Ed, W/m2, above 0
  double direct_normal = 0;         // Ee, W/m2, 0 or more
  int day_of_year = 0;              // 1-366, for the Sun-Earth distance; 0: the mean distance
  std::optional<double> dew_point;  // C; unknown: precipitable water 2 cm
};

// The hour as the models see it (the sun's zenith angle and epsilon clamped, Delta not).
struct PerezConditions {
  double zenith = 0;               // radians: the sun's, taken from 3 to 90 degrees
  double air_mass = 1;             // at that zenith angle
  double extraterrestrial = 1367;  // W/m2 at normal incidence
  double clearness = 1;            // epsilon (at least 1)
  double brightness = 0;           // Delta, as computed (the formulas clamp it)
  int bin = 1;                     // 1 (overcast) to 8 (clear)
  double precipitable_water = 2;   // W, cm
};

// Throws std::invalid_argument for a value that is not finite, diffuse_horizontal not
// above 0, direct_normal below 0 or a day_of_year outside 0-366.
PerezConditions perez_conditions(const PerezInputs& in);

// Kasten and Young (1989); `zenith` in radians, from 0 to pi / 2.
double relative_air_mass(double zenith);
// W/m2 at normal incidence on `day_of_year` (1-366; 0: the mean distance, 1367).
double extraterrestrial_irradiance(int day_of_year);
// cm, from the dew point (C).
double precipitable_water(double dew_point);
// 1-8 for a clearness of at least 1.
int perez_clearness_bin(double clearness);

// Table 1's arithmetic alone, without the safeguards: `bin` 1-8, the sun's zenith angle
// (radians) and Delta. Throws std::invalid_argument for a bin outside 1-8.
PerezSkyCoefficients perez_table_coefficients(int bin, double zenith, double brightness);
// What the sky uses: the table with the safeguards (Z and Delta clamped, b <= 0, a lit
// zenith). `zenith` is the sun's own, as the SkyModel will see it. Throws as above.
PerezSkyCoefficients perez_coefficients(int bin, double zenith, double brightness);

// lm/W, at least 0; Z and Delta clamped as in the header. Throws for a bin outside 1-8.
struct PerezEfficacy {
  double diffuse = 0, direct = 0;
};
PerezEfficacy perez_efficacy(int bin, double zenith, double brightness, double water_cm);
PerezEfficacy perez_efficacy(const PerezConditions& c);

// The hour's illuminances (lx) from its irradiances, for weather files that give only
// irradiance: diffuse horizontal (the sky's) and direct normal (the sun's).
struct PerezIlluminance {
  double diffuse_horizontal = 0, direct_normal = 0;
};
PerezIlluminance perez_illuminance(const PerezInputs& in);

// The hour's sky: a SkyModel of Type::perez round `sun_direction` (unit, towards the sun;
// its angle from `up` should be in.zenith), scaled so that its unobstructed horizontal
// illuminance (the sky alone) is `diffuse_horizontal_lux` (0 or more; perez_illuminance
// gives it when the weather does not). The ground's luminance is left 0: it depends on
// the ground's reflectance and the sun, which the caller knows.
SkyModel perez_sky(const PerezInputs& in, const Vec3d& sun_direction, const Vec3d& up, double diffuse_horizontal_lux);

}  // namespace dynrad::rad
