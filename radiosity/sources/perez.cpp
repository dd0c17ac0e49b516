// The Perez all-weather sky and luminous efficacy (perez.h: the models, their sources and
// the safeguards).
#include "radiosity/sources/perez.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace dynrad::rad {

namespace {

constexpr double kDegree = M_PI / 180.0;
constexpr double kSolarConstant = 1367;  // W/m2, the value both Perez papers use
constexpr double kDefaultWater = 2;      // cm of precipitable water when the dew point is unknown

// Where the fits are used (perez.h, "Safeguards").
constexpr double kLowestZenith = 3 * kDegree, kHighestZenith = 90 * kDegree;
constexpr double kDimmest = 0.01, kBrightest = 0.6;
constexpr double kDimmestInBins2To5 = 0.2;

// The clearness bins' lower bounds (bin 8 has no upper one).
constexpr std::array<double, 8> kBinFloor = {1.000, 1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};

// Perez, Seals and Michalsky (1993), Table 1: per clearness bin, the rows x1-x4 of a, b,
// c, d and e.
constexpr std::array<std::array<std::array<double, 4>, 5>, 8> kSkyTable = {{
    // bin 1: epsilon 1.000-1.065 (overcast)
    {{
        {1.3525, -0.2576, -0.2690, -1.4366},  // a
        {-0.7670, 0.0007, 1.2734, -0.1233},   // b
        {2.8000, 0.6004, 1.2375, 1.0000},     // c
        {1.8734, 0.6297, 0.9738, 0.2809},     // d
        {0.0356, -0.1246, -0.5718, 0.9938},   // e
    }},
    // bin 2: epsilon 1.065-1.230
    {{
        {-1.2219, -0.7730, 1.4148, 1.1016},   // a
        {-0.2054, 0.0367, -3.9128, 0.9156},   // b
        {6.9750, 0.1774, 6.4477, -0.1239},    // c
        {-1.5798, -0.5081, -1.7812, 0.1080},  // d
        {0.2624, 0.0672, -0.2190, -0.4285},   // e
    }},
    // bin 3: epsilon 1.230-1.500
    {{
        {-1.1000, -0.2515, 0.8952, 0.0156},      // a
        {0.2782, -0.1812, -4.5000, 1.1766},      // b
        {24.7219, -13.0812, -37.7000, 34.8438},  // c
        {-5.0000, 1.5218, 3.9229, -2.6204},      // d
        {-0.0156, 0.1597, 0.4199, -0.5562},      // e
    }},
    // bin 4: epsilon 1.500-1.950
    {{
        {-0.5484, -0.6654, -0.2672, 0.7117},     // a
        {0.7234, -0.6219, -5.6812, 2.6297},      // b
        {33.3389, -18.3000, -62.2500, 52.0781},  // c
        {-3.5000, 0.0016, 1.1477, 0.1062},       // d
        {0.4659, -0.3296, -0.0876, -0.0329},     // e
    }},
    // bin 5: epsilon 1.950-2.800
    {{
        {-0.6000, -0.3566, -2.5000, 2.3250},   // a
        {0.2937, 0.0496, -5.6812, 1.8415},     // b
        {21.0000, -4.7656, -21.5906, 7.2492},  // c
        {-3.5000, -0.1554, 1.4062, 0.3988},    // d
        {0.0032, 0.0766, -0.0656, -0.1294},    // e
    }},
    // bin 6: epsilon 2.800-4.500
    {{
        {-1.0156, -0.3670, 1.0078, 1.4051},   // a
        {0.2875, -0.5328, -3.8500, 3.3750},   // b
        {14.0000, -0.9999, -7.1406, 7.5469},  // c
        {-3.4000, -0.1078, -1.0750, 1.5702},  // d
        {-0.0672, 0.4016, 0.3017, -0.4844},   // e
    }},
    // bin 7: epsilon 4.500-6.200
    {{
        {-1.0000, 0.0211, 0.5025, -0.5119},   // a
        {-0.3000, 0.1922, 0.7023, -1.6317},   // b
        {19.0000, -5.0000, 1.2438, -1.9094},  // c
        {-4.0000, 0.0250, 0.3844, 0.2656},    // d
        {1.0468, -0.3788, -2.4517, 1.4656},   // e
    }},
    // bin 8: epsilon 6.200 and clearer
    {{
        {-1.0500, 0.0289, 0.4260, 0.3590},       // a
        {-0.3250, 0.1156, 0.7781, 0.0025},       // b
        {31.0625, -14.5000, -46.1148, 55.3750},  // c
        {-7.2312, 0.4050, 13.3500, 0.6234},      // d
        {1.5000, -0.6426, 1.8564, 0.5636},       // e
    }},
}};

// Perez et al. (1990), Table 4: per clearness bin, a, b, c and d of the diffuse and of
// the direct efficacy.
struct EfficacyTerms {
  double a, b, c, d;
};
constexpr std::array<EfficacyTerms, 8> kDiffuseEfficacy = {{
    {97.24, -0.46, 12.00, -8.91},
    {107.22, 1.15, 0.59, -3.95},
    {104.97, 2.96, -5.53, -8.77},
    {102.39, 5.59, -13.95, -13.90},
    {100.71, 5.94, -22.75, -23.74},
    {106.42, 3.83, -36.15, -28.83},
    {141.88, 1.90, -53.24, -14.03},
    {152.23, 0.35, -45.27, -7.98},
}};
constexpr std::array<EfficacyTerms, 8> kDirectEfficacy = {{
    {57.20, -4.55, -2.98, 117.12},
    {98.99, -3.46, -1.21, 12.38},
    {109.83, -4.90, -1.71, -8.81},
    {110.34, -5.84, -1.99, -4.56},
    {106.36, -3.97, -1.75, -6.16},
    {107.19, -1.25, -1.51, -26.73},
    {105.75, 0.77, -1.26, -34.44},
    {101.18, 1.58, -1.10, -8.29},
}};

double model_zenith(double zenith) { return std::clamp(zenith, kLowestZenith, kHighestZenith); }
double model_brightness(double brightness) { return std::clamp(brightness, kDimmest, kBrightest); }

void check_bin(int bin) {
  if (bin < 1 || bin > 8) throw std::invalid_argument("Perez clearness bins are numbered 1 to 8");
}

}  // namespace

double relative_air_mass(double zenith) {
  return 1 / (std::cos(zenith) + 0.50572 * std::pow(96.07995 - zenith / kDegree, -1.6364));
}

double extraterrestrial_irradiance(int day_of_year) {
  if (day_of_year == 0) return kSolarConstant;
  const double g = 2 * M_PI * (day_of_year - 1) / 365;  // Spencer's day angle
  return kSolarConstant * (1.00011 + 0.034221 * std::cos(g) + 0.00128 * std::sin(g) + 0.000719 * std::cos(2 * g) +
                           0.000077 * std::sin(2 * g));
}

double precipitable_water(double dew_point) { return std::exp(0.07 * dew_point - 0.075); }

int perez_clearness_bin(double clearness) {
  for (int bin = 8; bin > 1; --bin)
    if (clearness >= kBinFloor[static_cast<std::size_t>(bin - 1)]) return bin;
  return 1;
}

PerezConditions perez_conditions(const PerezInputs& in) {
  if (!std::isfinite(in.zenith) || in.zenith < 0 || in.zenith > M_PI)
    throw std::invalid_argument("the sun's zenith angle must be from 0 to pi radians");
  if (!std::isfinite(in.diffuse_horizontal) || !(in.diffuse_horizontal > 0))
    throw std::invalid_argument("a Perez sky needs a diffuse horizontal irradiance above 0 W/m2");
  if (!std::isfinite(in.direct_normal) || in.direct_normal < 0)
    throw std::invalid_argument("the direct normal irradiance must be 0 W/m2 or more");
  if (in.day_of_year < 0 || in.day_of_year > 366)
    throw std::invalid_argument("the day of the year must be from 1 to 366 (0: the mean Sun-Earth distance)");
  if (in.dew_point && !std::isfinite(*in.dew_point)) throw std::invalid_argument("the dew point must be finite");
  PerezConditions c;
  c.zenith = model_zenith(in.zenith);
  c.air_mass = relative_air_mass(c.zenith);
  c.extraterrestrial = extraterrestrial_irradiance(in.day_of_year);
  const double z3 = 1.041 * c.zenith * c.zenith * c.zenith;
  const double ed = in.diffuse_horizontal, ee = in.direct_normal;
  c.clearness = std::max(1.0, ((ed + ee) / ed + z3) / (1 + z3));
  c.brightness = ed * c.air_mass / c.extraterrestrial;
  c.bin = perez_clearness_bin(c.clearness);
  c.precipitable_water = in.dew_point ? precipitable_water(*in.dew_point) : kDefaultWater;
  return c;
}

PerezSkyCoefficients perez_table_coefficients(int bin, double zenith, double brightness) {
  check_bin(bin);
  const auto& [a, b, c, d, e] = kSkyTable[static_cast<std::size_t>(bin - 1)];
  const double z = zenith, delta = brightness;
  auto linear = [&](const std::array<double, 4>& x) { return x[0] + x[1] * z + delta * (x[2] + x[3] * z); };
  PerezSkyCoefficients p;
  p.a = linear(a);
  p.b = linear(b);
  p.e = linear(e);
  if (bin == 1) {
    // The overcast bin's own forms for c and d.
    p.c = std::exp(std::pow(delta * (c[0] + c[1] * z), c[2])) - c[3];
    p.d = -std::exp(delta * (d[0] + d[1] * z)) + d[2] + delta * d[3];
  } else {
    p.c = linear(c);
    p.d = linear(d);
  }
  return p;
}

PerezSkyCoefficients perez_coefficients(int bin, double zenith, double brightness) {
  check_bin(bin);
  double delta = model_brightness(brightness);
  if (bin >= 2 && bin <= 5) delta = std::max(delta, kDimmestInBins2To5);
  PerezSkyCoefficients p = perez_table_coefficients(bin, model_zenith(zenith), delta);
  p.b = std::min(p.b, 0.0);
  // The zenith is the reference of relative luminance: a factor dark there is dropped.
  // Its angle from the sun is the sun's own zenith angle, as SkyModel sees it.
  const double zs = std::clamp(zenith, 0.0, M_PI);
  if (!(1 + p.a * std::exp(p.b) > 0)) p.a = 0;
  if (!(1 + p.c * std::exp(p.d * zs) + p.e * std::cos(zs) * std::cos(zs) > 0)) p.c = p.e = 0;
  return p;
}

PerezEfficacy perez_efficacy(int bin, double zenith, double brightness, double water_cm) {
  check_bin(bin);
  const EfficacyTerms& f = kDiffuseEfficacy[static_cast<std::size_t>(bin - 1)];
  const EfficacyTerms& g = kDirectEfficacy[static_cast<std::size_t>(bin - 1)];
  const double z = model_zenith(zenith), delta = model_brightness(brightness);
  PerezEfficacy e;
  e.diffuse = std::max(0.0, f.a + f.b * water_cm + f.c * std::cos(z) + f.d * std::log(delta));
  e.direct = std::max(0.0, g.a + g.b * water_cm + g.c * std::exp(5.73 * z - 5) + g.d * delta);
  return e;
}

PerezEfficacy perez_efficacy(const PerezConditions& c) {
  return perez_efficacy(c.bin, c.zenith, c.brightness, c.precipitable_water);
}

PerezIlluminance perez_illuminance(const PerezInputs& in) {
  const PerezEfficacy e = perez_efficacy(perez_conditions(in));
  return {in.diffuse_horizontal * e.diffuse, in.direct_normal * e.direct};
}

SkyModel perez_sky(const PerezInputs& in, const Vec3d& sun_direction, const Vec3d& up, double diffuse_horizontal_lux) {
  if (!std::isfinite(diffuse_horizontal_lux) || diffuse_horizontal_lux < 0)
    throw std::invalid_argument("the diffuse horizontal illuminance must be 0 lx or more");
  const PerezConditions c = perez_conditions(in);
  SkyModel sky;
  sky.type = SkyModel::Type::perez;
  sky.up = up;
  sky.sun = sun_direction;
  sky.perez = perez_coefficients(c.bin, in.zenith, c.brightness);
  sky.zenith_luminance = 1;
  // Positive: the zenith is lit (perez_coefficients), and so is the sky round it.
  sky.zenith_luminance = diffuse_horizontal_lux / sky.horizontal_illuminance();
  return sky;
}

}  // namespace dynrad::rad
