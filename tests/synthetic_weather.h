// Synthetic EnergyPlus weather (.epw) for tests: a year (or a few days) of a cloudless
// or an overcast sky at a site, written as a weather file would be, deterministic.
//
// Each hour's sun is the one at its middle (hour h: (h - 0.5):00 local standard time,
// radiosity/sources/sky.h's sun_position), zenith angle Z; below the horizon every value is 0.
//   clear: direct normal E_n = 1353 * 0.7^(AM^0.678) W/m2 (Meinel and Meinel 1976), the
//     air mass AM = 1 / (cos Z + 0.50572 (96.07995 - Z)^-1.6364) (Kasten and Young
//     1989); diffuse horizontal 0.15 E_n (a clear sky gives 10-20% of the direct beam).
//   overcast: no direct; diffuse horizontal 0.25 * 1353 cos Z (a clearness index of a
//     quarter, all of it diffuse).
// Global horizontal: E_n cos Z + diffuse. Radiation is written in whole W/m2, as real
// files are. Illuminances: 105 lm/W for the direct beam and 120 lm/W for the sky, or the
// missing code (999999) in every illuminance field to exercise a luminous efficacy model.
// Zenith luminance: the CIE overcast sky's 9 E_vd / (7 pi) under overcast, missing
// (9999) under a clear sky and where the overcast value reaches 9999, the format's
// missing code. Temperatures, wind and the rest are plausible, constant or smooth:
// nothing reads them.
#pragma once

#include <string>

namespace dynrad::test {

struct SyntheticYear {
  enum class Sky { clear, overcast };
  Sky sky = Sky::clear;
  // The LOCATION record. The default is a site near London.
  std::string city = "Synthetic City", region = "-", country = "GBR", source = "dynrad synthetic", wmo = "999999";
  double latitude = 51.5;    // degrees north
  double longitude = -0.12;  // degrees east
  double timezone = 0;       // hours east of GMT
  double elevation = 11;     // m
  int year = 2023;           // a leap year (2024) has February 29: 8784 hours
  // Days written from the start date; 0: the whole year from January 1. The days stop
  // at December 31.
  int start_month = 1, start_day = 1;
  int days = 0;

  // false: every illuminance field says missing (999999).
  bool illuminance = true;
  double direct_efficacy = 105, diffuse_efficacy = 120;  // lm/W
};

// One hour as synthetic_epw computes it, before the file's rounding.
struct SyntheticHour {
  double zenith = 90;  // degrees, of the sun at the middle of the hour
  double direct_normal = 0, diffuse_horizontal = 0, global_horizontal = 0;  // W/m2
};
SyntheticHour synthetic_hour(const SyntheticYear& options, int month, int day, int hour);

// The whole file's text, "\n" line breaks. Throws std::invalid_argument for a start
// date that does not exist in options.year or a negative number of days.
std::string synthetic_epw(const SyntheticYear& options);

// A file in the system's temp directory with a name of its own, removed when this goes.
class TempWeatherFile {
 public:
  explicit TempWeatherFile(const std::string& text);
  explicit TempWeatherFile(const SyntheticYear& options) : TempWeatherFile(synthetic_epw(options)) {}
  ~TempWeatherFile();
  TempWeatherFile(const TempWeatherFile&) = delete;
  TempWeatherFile& operator=(const TempWeatherFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace dynrad::test
