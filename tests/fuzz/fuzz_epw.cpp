// libFuzzer target for the EnergyPlus weather reader (radiosity/climate/epw.h), from
// memory. The input bytes are an EPW file's text.
//
// Each input is read twice: as part of a year (EpwOptions::whole_year false, which
// inputs under the fuzzer's size limit can satisfy) and as a whole year. InputError is
// the expected answer to bad input and is caught here. Anything else is a bug the
// fuzzer reports: another exception escaping, a crash, a sanitizer finding, an error
// naming a line the text does not have, or a read that succeeds with weather that is
// not weather: a site out of range, hours out of order, repeated or with a gap, a NaN,
// negative or impossible value where the reader promises a number, or the two reads
// disagreeing (a whole year read must also read as part of one, the same hours).
#include "mesh/core/error.h"
#include "radiosity/climate/epw.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace {

using dynrad::rad::Weather;
using dynrad::rad::WeatherHour;

[[noreturn]] void bug(const char* what) {
  std::fprintf(stderr, "fuzz: %s\n", what);
  std::abort();
}

// Written here rather than taken from the reader, so that both would have to be wrong.
int days_in_month(int month) {
  constexpr std::array<int, 12> kDays = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return kDays[static_cast<std::size_t>(month - 1)];
}

// The hour after h, in a calendar with February 29.
void advance(int& month, int& day, int& hour) {
  if (++hour <= 24) return;
  hour = 1;
  if (++day <= days_in_month(month)) return;
  day = 1;
  ++month;
}

bool missing_or_within(double v, double low, double high) { return std::isnan(v) || (v >= low && v <= high); }

void check(const Weather& w, bool whole_year) {
  const auto& s = w.site;
  if (!(s.latitude >= -90 && s.latitude <= 90) || !(s.longitude >= -180 && s.longitude <= 180) ||
      !(s.timezone >= -12 && s.timezone <= 14) || !(s.elevation >= -1000 && s.elevation <= 9999.9))
    bug("a site coordinate is NaN or out of range");
  double offset = std::fmod(s.timezone - s.longitude / 15 + 36, 24.0) - 12;  // in [-12, 12)
  if (std::abs(offset) > 4 + 1e-9) bug("the time zone is far from the longitude's solar time");
  if (w.hours.empty() || w.hours.size() > 8784) bug("no hours, or more than a leap year's");
  if (whole_year && w.hours.size() != 8760 && w.hours.size() != 8784) bug("a whole year of neither 8760 nor 8784");

  int month = w.hours[0].month, day = w.hours[0].day, hour = w.hours[0].hour;
  if (whole_year && (month != 1 || day != 1 || hour != 1)) bug("a whole year that does not start on January 1");
  std::size_t line = 8;
  for (std::size_t i = 0; i < w.hours.size(); ++i) {
    const WeatherHour& h = w.hours[i];
    if (i > 0) {
      advance(month, day, hour);
      if (month == 2 && day == 29 && hour == 1 && h.month == 3) {  // February 29 may be absent
        month = 3;
        day = 1;
      }
    }
    if (h.month != month || h.day != day || h.hour != hour) bug("hours out of order, repeated or with a gap");
    if (month > 12 || day > days_in_month(month)) bug("a date past the year or a day the month does not have");
    if (h.minute < 0 || h.minute > 60) bug("a minute out of range");
    if (h.line <= line) bug("line numbers that do not ascend after the header");
    line = h.line;
    if (!(h.direct_normal >= 0 && h.direct_normal <= 2000) ||
        !(h.diffuse_horizontal >= 0 && h.diffuse_horizontal <= 2000))
      bug("direct normal or diffuse horizontal radiation is NaN, negative or impossible");
    if (!missing_or_within(h.global_horizontal, 0, 2000) || !missing_or_within(h.global_illuminance, 0, 250000) ||
        !missing_or_within(h.direct_normal_illuminance, 0, 250000) ||
        !missing_or_within(h.diffuse_illuminance, 0, 250000) || !missing_or_within(h.zenith_luminance, 0, 9998.99) ||
        !missing_or_within(h.dew_point, -69.99, 69.99))
      bug("a value that may be missing is negative, infinite or impossible");
  }
  if (whole_year && (month != 12 || day != 31 || hour != 24)) bug("a whole year that does not end on December 31");
}

// The lines of `text` as the reader counts them ("\n", "\r\n" or "\r" end a line).
std::size_t lines_in(std::string_view text) {
  std::size_t lines = 1;
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'))) ++lines;
  return lines;
}

bool same(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string name = "fuzz.epw";
  Weather part, year;
  bool part_read = false, year_read = false;
  for (const bool whole_year : {false, true}) {
    dynrad::rad::EpwOptions options;
    options.whole_year = whole_year;
    try {
      (whole_year ? year : part) = dynrad::rad::parse_epw(text, name, options);
      (whole_year ? year_read : part_read) = true;
      check(whole_year ? year : part, whole_year);
    } catch (const dynrad::InputError& e) {
      // Refused with a message: the right answer to a bad file, if it names the file
      // and a line it has.
      if (e.file() != name || e.line() > lines_in(text)) bug("an error that names another file or no such line");
    }
  }
  if (year_read) {
    if (!part_read || part.hours.size() != year.hours.size()) bug("a whole year that does not read as a part");
    for (std::size_t i = 0; i < year.hours.size(); ++i) {
      const WeatherHour &a = part.hours[i], &b = year.hours[i];
      if (a.line != b.line || !same(a.direct_normal, b.direct_normal) || !same(a.dew_point, b.dew_point) ||
          !same(a.global_illuminance, b.global_illuminance))
        bug("the same hour read differently as a whole year and as a part");
    }
  }
  return 0;
}
