#include "synthetic_weather.h"

#include "radiosity/sources/sky.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace dynrad::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180;
constexpr double kMeinelConstant = 1353;  // W/m2, the solar constant of Meinel's clear-sky model

bool leap(int year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

int days_in(int month, int year) {
  constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && leap(year) ? 29 : kDays[month - 1];
}

int day_of_year(int month, int day, int year) {
  for (int m = 1; m < month; ++m) day += days_in(m, year);
  return day;
}

// 0 = Sunday (Sakamoto's method).
int weekday(int year, int month, int day) {
  constexpr int kOffset[12] = {0, 3, 2, 5, 0, 3, 5, 1, 4, 6, 2, 4};
  if (month < 3) year -= 1;
  return (year + year / 4 - year / 100 + year / 400 + kOffset[month - 1] + day) % 7;
}

// printf into a string; the attribute lets the compiler check the arguments.
__attribute__((format(printf, 1, 2))) std::string format(const char* pattern, ...) {
  va_list args, again;
  va_start(args, pattern);
  va_copy(again, args);
  std::string out(static_cast<std::size_t>(std::vsnprintf(nullptr, 0, pattern, args)), '\0');
  std::vsnprintf(out.data(), out.size() + 1, pattern, again);
  va_end(again);
  va_end(args);
  return out;
}

long whole(double v) { return std::lround(v); }

// One data line of 35 fields.
std::string data_line(const SyntheticYear& o, int month, int day, int hour) {
  const SyntheticHour h = synthetic_hour(o, month, day, hour);
  const bool overcast = o.sky == SyntheticYear::Sky::overcast;
  const double cos_zenith = h.zenith < 90 ? std::cos(h.zenith * kDegree) : 0;
  // Smooth annual and daily swings, warmest in late July and mid-afternoon.
  const double season = std::sin(2 * kPi * (day_of_year(month, day, o.year) - 110) / 365.0);
  const double dry_bulb = 10 + 8 * season + 4 * std::sin(2 * kPi * (hour - 9) / 24.0);
  const double dew_point = dry_bulb - (overcast ? 2 : 6);
  const double pressure = 101325 * std::pow(1 - 2.25577e-5 * o.elevation, 5.25588);

  std::string illuminances;
  if (o.illuminance) {
    const double direct = o.direct_efficacy * h.direct_normal, diffuse = o.diffuse_efficacy * h.diffuse_horizontal;
    // 9999 and above say "missing": the field cannot hold a brighter zenith.
    const double zenith_luminance = overcast ? std::min(9 * diffuse / (7 * kPi), 9999.0) : 9999;
    illuminances = format("%ld,%ld,%ld,%ld", whole(direct * cos_zenith + diffuse), whole(direct), whole(diffuse),
                          whole(zenith_luminance));
  } else {
    illuminances = "999999,999999,999999,9999";
  }
  return format(
      "%d,%d,%d,%d,0,?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9?9?9*9*9?9*9*9,%.1f,%.1f,%d,%ld,%ld,%ld,%d,"
      "%ld,%ld,%ld,%s,180,3.0,%d,%d,%s,%s,9,999999999,15,0.1000,0,88,0.200,0.0,1.0\n",
      o.year, month, day, hour, dry_bulb, dew_point, overcast ? 88 : 65, whole(pressure),
      whole(kMeinelConstant * cos_zenith), cos_zenith > 0 ? whole(kMeinelConstant) : 0L, overcast ? 340 : 280,
      whole(h.global_horizontal), whole(h.direct_normal), whole(h.diffuse_horizontal), illuminances.c_str(),
      overcast ? 10 : 0, overcast ? 10 : 0, overcast ? "8.0" : "30.0", overcast ? "600" : "77777");
}

}  // namespace

SyntheticHour synthetic_hour(const SyntheticYear& o, int month, int day, int hour) {
  rad::LocalTime middle;
  middle.year = o.year;
  middle.month = month;
  middle.day = day;
  middle.hour = hour - 1;
  middle.minute = 30;
  middle.timezone = o.timezone;
  SyntheticHour h;
  h.zenith = rad::sun_position(o.latitude, o.longitude, middle).zenith;
  if (h.zenith >= 90) return h;
  const double cos_zenith = std::cos(h.zenith * kDegree);
  if (o.sky == SyntheticYear::Sky::clear) {
    const double air_mass = 1 / (cos_zenith + 0.50572 * std::pow(96.07995 - h.zenith, -1.6364));
    h.direct_normal = kMeinelConstant * std::pow(0.7, std::pow(air_mass, 0.678));
    h.diffuse_horizontal = 0.15 * h.direct_normal;
  } else {
    h.diffuse_horizontal = 0.25 * kMeinelConstant * cos_zenith;
  }
  h.global_horizontal = h.direct_normal * cos_zenith + h.diffuse_horizontal;
  return h;
}

std::string synthetic_epw(const SyntheticYear& o) {
  const bool whole_year = o.days == 0;
  const int first_month = whole_year ? 1 : o.start_month, first_day = whole_year ? 1 : o.start_day;
  if (o.days < 0 || first_month < 1 || first_month > 12 || first_day < 1 || first_day > days_in(first_month, o.year))
    throw std::invalid_argument("synthetic_epw: no such start date or a negative number of days");

  // The dates to write, to find the last one for the DATA PERIODS record.
  int last_month = first_month, last_day = first_day;
  const int count = whole_year ? (leap(o.year) ? 366 : 365) : o.days;
  for (int n = 1; n < count && !(last_month == 12 && last_day == 31); ++n) {
    if (++last_day > days_in(last_month, o.year)) {
      last_day = 1;
      ++last_month;
    }
  }

  static const char* const kWeekdays[7] = {"Sunday",   "Monday", "Tuesday", "Wednesday",
                                           "Thursday", "Friday", "Saturday"};
  const char* sky = o.sky == SyntheticYear::Sky::clear ? "clear sky (Meinel direct, 0.15 of it diffuse)"
                                                       : "overcast (no direct, diffuse 0.25 of extraterrestrial)";
  std::string text =
      format("LOCATION,%s,%s,%s,%s,%s,%.10g,%.10g,%.10g,%.10g\n", o.city.c_str(), o.region.c_str(), o.country.c_str(),
             o.source.c_str(), o.wmo.c_str(), o.latitude, o.longitude, o.timezone, o.elevation);
  text += "DESIGN CONDITIONS,0\nTYPICAL/EXTREME PERIODS,0\nGROUND TEMPERATURES,0\n";
  text += format("HOLIDAYS/DAYLIGHT SAVINGS,%s,0,0,0\n", leap(o.year) ? "Yes" : "No");
  text += format("COMMENTS 1,dynrad synthetic weather: %s\n", sky);
  text += "COMMENTS 2,Not measured data: for tests only\n";
  text += format("DATA PERIODS,1,1,Data,%s,%2d/%2d,%2d/%2d\n", kWeekdays[weekday(o.year, first_month, first_day)],
                 first_month, first_day, last_month, last_day);
  text.reserve(text.size() + static_cast<std::size_t>(count) * 24 * 200);
  for (int month = first_month, day = first_day;;) {
    for (int hour = 1; hour <= 24; ++hour) text += data_line(o, month, day, hour);
    if (month == last_month && day == last_day) break;
    if (++day > days_in(month, o.year)) {
      day = 1;
      ++month;
    }
  }
  return text;
}

TempWeatherFile::TempWeatherFile(const std::string& text) {
  static std::atomic<unsigned> counter{0};
  path_ = (std::filesystem::temp_directory_path() /
           ("dynrad-weather-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".epw"))
              .string();
  std::ofstream out(path_, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path_);
}

TempWeatherFile::~TempWeatherFile() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace dynrad::test
