// EnergyPlus weather (EPW) reader: see epw.h for what it accepts and refuses.
#include "radiosity/climate/epw.h"

#include "mesh/core/error.h"
#include "mesh/io/io_util.h"
#include "mesh/io/text_lines.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

namespace dynrad::rad {
namespace {

constexpr std::size_t kHeaderRecords = 8;
constexpr std::size_t kDataFields = 35;
// Missing-value codes (EPW data dictionary): a value at or above these is missing.
constexpr double kMissingRadiation = 9999;  // W/m2, and cd/m2 for the zenith luminance
constexpr double kMissingIlluminance = 999900;
constexpr double kMissingDewPoint = 99.9;
// Beyond anything at the ground: the solar constant is 1361 W/m2 and the sun's
// illuminance outside the atmosphere about 128,000 lx. Such a value is a garbled field,
// not weather.
constexpr double kMaxIrradiance = 2000;
constexpr double kMaxIlluminance = 250000;
// Real time zones differ from the longitude's solar time by up to about 3 hours
// (western China); a larger difference is a sign error in the longitude or the zone.
constexpr double kMaxClockOffset = 4;

// February with 29 days: whether the file has February 29 is decided by its lines.
constexpr std::array<int, 12> kDaysInMonth = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
constexpr std::array<const char*, 12> kMonthNames = {"January",   "February", "March",    "April",
                                                     "May",       "June",     "July",     "August",
                                                     "September", "October",  "November", "December"};
constexpr int kHoursInLeapYear = 366 * 24;

// The header records, by their first field (EnergyPlus reads them in any order).
constexpr std::array<const char*, kHeaderRecords> kRecords = {"LOCATION",
                                                              "DESIGN CONDITIONS",
                                                              "TYPICAL/EXTREME PERIODS",
                                                              "GROUND TEMPERATURES",
                                                              "HOLIDAYS/DAYLIGHT SAVINGS",
                                                              "COMMENTS 1",
                                                              "COMMENTS 2",
                                                              "DATA PERIODS"};
constexpr std::size_t kLocation = 0, kHolidays = 4, kDataPeriods = 7;

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool blank(std::string_view s) { return trimmed(s).empty(); }

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// A piece of the file for a message: quoted, at most 60 characters, control bytes as '?'.
std::string shown(std::string_view s) {
  constexpr std::size_t kMax = 60;
  std::string out = "'";
  for (std::size_t i = 0; i < s.size() && i < kMax; ++i)
    out += std::iscntrl(static_cast<unsigned char>(s[i])) ? '?' : s[i];
  return out + (s.size() > kMax ? "...'" : "'");
}

std::string number_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

std::string when(int month, int day, int hour) {
  return std::string(kMonthNames[month - 1]) + " " + std::to_string(day) + " hour " + std::to_string(hour);
}

// Hours since January 1 0:00 of the hour ending at `hour`, in a leap year's calendar
// (so that February 29 has its place whether or not the file has it).
int hour_of_year(int month, int day, int hour) {
  int days = day - 1;
  for (int m = 1; m < month; ++m) days += kDaysInMonth[m - 1];
  return days * 24 + hour - 1;
}
const int kFeb28Hour24 = hour_of_year(2, 28, 24), kMar1Hour1 = hour_of_year(3, 1, 1);

// A decimal number, surrounded by blanks or not; false if the text is not one. NaN and
// infinity parse (callers refuse them with their own message).
bool to_number(std::string_view s, double& value) {
  s = trimmed(s);
  if (!s.empty() && s.front() == '+') {
    s.remove_prefix(1);
    if (!s.empty() && s.front() == '-') return false;
  }
  if (s.empty()) return false;
  const char* end = s.data() + s.size();
  const auto result = std::from_chars(s.data(), end, value, std::chars_format::general);
  return result.ec == std::errc() && result.ptr == end;
}

// Comma-separated fields of a header record; a field in double quotes may hold commas
// (COMMENTS records, city names). Trailing empty fields are dropped.
std::vector<std::string> header_fields(std::string_view line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (const char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  for (auto& f : fields) f = std::string(trimmed(f));
  while (fields.size() > 1 && fields.back().empty()) fields.pop_back();
  return fields;
}

class EpwParser {
 public:
  EpwParser(std::string_view text, const std::string& name, const EpwOptions& options)
      : text_(text), name_(name), options_(options) {}

  Weather parse() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
    weather_.path = name_;
    if (blank_from(0))
      fail(0,
           "is empty. An EnergyPlus weather file starts with a LOCATION line (LOCATION,city,region,country,"
           "source,WMO,latitude,longitude,time zone,elevation).");
    read_header();
    read_hours();
    return std::move(weather_);
  }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& what) const { throw InputError(name_, line, what); }

  // The next line without its line break ("\n", "\r\n" or "\r"); false at the end.
  bool next_line(std::string_view& line) {
    if (!next_text_line(text_, pos_, line)) return false;
    ++line_;
    return true;
  }

  bool blank_from(std::size_t from) const {
    for (std::size_t i = from; i < text_.size(); ++i)
      if (!std::isspace(static_cast<unsigned char>(text_[i]))) return false;
    return true;
  }

  // ---------------------------------------------------------------------------
  // Header.

  void read_header() {
    std::array<std::size_t, kHeaderRecords> seen_on{};  // line of each record, 0: not yet
    std::string_view line;
    for (std::size_t n = 1; n <= kHeaderRecords; ++n) {
      if (!next_line(line) || (n > 1 && blank(line) && blank_from(pos_)))
        fail(line_, "the file ends inside the header, after " + std::to_string(n - 1) +
                        " of its 8 records (LOCATION, DESIGN CONDITIONS, TYPICAL/EXTREME PERIODS, GROUND "
                        "TEMPERATURES, HOLIDAYS/DAYLIGHT SAVINGS, COMMENTS 1, COMMENTS 2, DATA PERIODS). Is it "
                        "truncated?");
      const std::size_t record = record_of(line);
      if (record == kHeaderRecords) {
        if (n == 1)
          fail(line_,
               "the first line should be the LOCATION record (LOCATION,city,region,country,source,WMO,"
               "latitude,longitude,time zone,elevation); found " +
                   shown(line) + ". Is this an EnergyPlus weather (.epw) file?");
        std::string absent;
        for (std::size_t i = 0; i < kHeaderRecords; ++i)
          if (seen_on[i] == 0) absent += std::string(absent.empty() ? "" : ", ") + kRecords[i];
        fail(line_, "this line should be one of the 8 header records that precede the hourly data; found " +
                        shown(line) + ". Is a header record missing? Not given yet: " + absent + ".");
      }
      if (seen_on[record] != 0)
        fail(line_, std::string("the ") + kRecords[record] + " record appears again (first on line " +
                        std::to_string(seen_on[record]) + "); each of the 8 header records appears once.");
      seen_on[record] = line_;
      if (record == kLocation) read_location(line);
      if (record == kDataPeriods) read_data_periods(line);
    }
  }

  // Which header record `line` is (kHeaderRecords: none).
  static std::size_t record_of(std::string_view line) {
    const std::string key = upper(trimmed(line.substr(0, line.find(','))));
    for (std::size_t i = 0; i < kHeaderRecords; ++i)
      if (key == kRecords[i]) return i;
    // The data dictionary spells it HOLIDAYS/DAYLIGHT SAVING; the files, SAVINGS.
    if (key == "HOLIDAYS/DAYLIGHT SAVING") return kHolidays;
    return kHeaderRecords;
  }

  double location_number(const std::string& text, const char* what, double low, double high,
                         const std::string& advice) const {
    double v = 0;
    if (!to_number(text, v))
      fail(line_,
           std::string("the ") + what + " in the LOCATION record, " + shown(text) + ", is not a number. " + advice);
    if (!(v >= low && v <= high))
      fail(line_, std::string("the ") + what + " in the LOCATION record is " + shown(text) + ", outside " +
                      number_text(low) + " to " + number_text(high) + ". " + advice);
    return v;
  }

  void read_location(std::string_view line) {
    const std::vector<std::string> f = header_fields(line);
    if (f.size() != 10)
      fail(line_, "the LOCATION record has " + std::to_string(f.size()) +
                      " fields; it has 10: LOCATION,city,state/region,country,source,WMO,latitude,longitude,time "
                      "zone,elevation (a city name with a comma must be in double quotes).");
    WeatherSite& s = weather_.site;
    s.city = f[1];
    s.region = f[2];
    s.country = f[3];
    s.source = f[4];
    s.wmo = f[5];
    s.latitude = location_number(f[6], "latitude", -90, 90, "It is in degrees, north positive.");
    s.longitude = location_number(f[7], "longitude", -180, 180, "It is in degrees, east positive, west negative.");
    // The data dictionary stops at +12; Kiribati and Tonga keep +13 and +14.
    s.timezone = location_number(f[8], "time zone", -12, 14,
                                 "It is the file's standard time in hours from GMT, east positive (Denver -7, "
                                 "Berlin 1).");
    s.elevation = location_number(f[9], "elevation", -1000, 9999.9, "It is in metres above sea level.");
    // Local solar time runs longitude / 15 hours ahead of GMT; the clock, `timezone`.
    double offset = std::fmod(s.timezone - s.longitude / 15, 24.0);
    if (offset > 12) offset -= 24;
    if (offset < -12) offset += 24;
    if (std::abs(offset) > kMaxClockOffset)
      fail(line_, "the time zone " + number_text(s.timezone) + " h does not fit the longitude " +
                      number_text(s.longitude) + " degrees (about " + number_text(std::round(s.longitude / 15)) +
                      " h from GMT): the sun would be placed at the wrong hours. Is a sign swapped? EPW longitudes "
                      "are east positive (Denver -105, Berlin 13.4) and so are time zones (Denver -7, Berlin 1).");
  }

  void read_data_periods(std::string_view line) {
    const std::vector<std::string> f = header_fields(line);
    double periods = 0, per_hour = 0;
    if (f.size() < 3 || !to_number(f[1], periods) || !to_number(f[2], per_hour) || periods != std::floor(periods) ||
        per_hour != std::floor(per_hour) || periods < 1 || per_hour < 1)
      fail(line_,
           "the DATA PERIODS record should start with the number of data periods and the number of records "
           "per hour, such as DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31; found " +
               shown(line) + ".");
    if (per_hour != 1)
      fail(line_, "the file has " + number_text(per_hour) +
                      " records per hour (DATA PERIODS, second number). dynrad reads hourly weather, one record "
                      "per hour, as EnergyPlus and climate.onebuilding.org publish it: average each hour's records "
                      "into one (radiation and illuminance as means) and set that number to 1.");
    if (periods != 1)
      fail(line_, "the file has " + number_text(periods) +
                      " data periods (DATA PERIODS, first number). dynrad reads one period, a whole year; join the "
                      "periods into one if they make a year, or use a file of one year.");
  }

  // ---------------------------------------------------------------------------
  // Hourly data.

  using Fields = std::array<std::string_view, kDataFields>;

  void read_hours() {
    // A data line has at least 34 commas: no more hours than the text can hold.
    weather_.hours.reserve(std::min<std::size_t>(kHoursInLeapYear, text_.size() / 35 + 1));
    std::string_view line;
    while (next_line(line)) {
      if (blank(line)) {
        if (blank_from(pos_)) break;  // blank lines at the end
        fail(line_, "this line is empty, but hourly data follow: data lines must follow one another. Delete it.");
      }
      weather_.hours.push_back(read_hour(line));
      check_sequence();
    }
    if (weather_.hours.empty()) fail(line_, "the file has no hourly data after its 8 header records. Is it truncated?");
    const WeatherHour& last = weather_.hours.back();
    if (options_.whole_year && hour_of_year(last.month, last.day, last.hour) != kHoursInLeapYear - 1)
      fail(last.line, "the data end on " + when(last.month, last.day, last.hour) + " after " +
                          std::to_string(weather_.hours.size()) +
                          " hours; a year ends on December 31 hour 24 (8760 hours, 8784 with February 29). "
                          "Annual daylight metrics need every hour of a year. Is the file truncated?");
  }

  // The 35 fields; more are allowed only when empty (a spreadsheet's padding).
  Fields split(std::string_view line) const {
    Fields f;
    std::size_t count = 0;
    bool padding_only = true;
    for (std::size_t start = 0;; ++count) {
      const std::size_t comma = line.find(',', start);
      const std::string_view field = line.substr(start, comma == std::string_view::npos ? comma : comma - start);
      if (count < kDataFields) {
        f[count] = field;
      } else if (!blank(field)) {
        padding_only = false;
      }
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    ++count;
    if (count < kDataFields || !padding_only)
      fail(line_, "this data line has " + std::to_string(count) +
                      " fields; an EPW data line has 35 (year, month, day, hour, minute, flags, then 29 values). "
                      "Is a comma missing or one too many?");
    return f;
  }

  // Field `index` (1-based, as the data dictionary numbers them) as a finite number.
  double number(const Fields& f, std::size_t index, const char* what) const {
    const std::string_view text = f[index - 1];
    double v = 0;
    if (!to_number(text, v))
      fail(line_, std::string(what) + " (field " + std::to_string(index) + ") is " +
                      (blank(text) ? std::string("empty") : shown(text)) + ", not a number.");
    if (!std::isfinite(v))
      fail(line_,
           std::string(what) + " (field " + std::to_string(index) + ") is " + shown(text) + ", not a finite number.");
    return v;
  }

  int whole(const Fields& f, std::size_t index, const char* what, int low, int high, const std::string& advice) const {
    const double v = number(f, index, what);
    if (v != std::floor(v) || v < low || v > high)
      fail(line_, std::string(what) + " (field " + std::to_string(index) + ") is " + number_text(v) +
                      "; it is a whole number from " + std::to_string(low) + " to " + std::to_string(high) + "." +
                      (advice.empty() ? "" : " " + advice));
    return static_cast<int>(v);
  }

  // A radiation or luminance value: NaN if missing (at or above `missing`), refused if
  // negative or above `high` below the missing code.
  double measured(const Fields& f, std::size_t index, const char* what, const char* unit, double high, double missing,
                  const char* missing_code) const {
    const double v = number(f, index, what);
    if (v >= missing) return std::numeric_limits<double>::quiet_NaN();
    if (v < 0)
      fail(line_, std::string(what) + " (field " + std::to_string(index) + ") is " + number_text(v) + " " + unit +
                      ", negative. A missing value is written " + missing_code + "; otherwise it is 0 or more.");
    if (v > high)
      fail(line_, std::string(what) + " (field " + std::to_string(index) + ") is " + number_text(v) + " " + unit +
                      ", more than any daylight at the ground (" + number_text(high) + " " + unit +
                      "). Is the field garbled? A missing value is written " + missing_code + ".");
    return v;
  }

  double irradiance(const Fields& f, std::size_t index, const char* what) const {
    return measured(f, index, what, "W/m2", kMaxIrradiance, kMissingRadiation, "9999");
  }
  double illuminance(const Fields& f, std::size_t index, const char* what) const {
    return measured(f, index, what, "lx", kMaxIlluminance, kMissingIlluminance, "999999");
  }

  [[noreturn]] void missing_sky(const std::string& what) const {
    fail(line_, what +
                    " is missing (9999). dynrad makes each hour's sky from the direct normal and diffuse "
                    "horizontal radiation and cannot guess them: fill the gap (from the hours around it, or "
                    "another source), or use a weather file without gaps.");
  }

  WeatherHour read_hour(std::string_view line) const {
    const Fields f = split(line);
    WeatherHour h;
    h.line = line_;
    h.year = whole(f, 1, "the year", 1, 9999, "");
    h.month = whole(f, 2, "the month", 1, 12, "");
    h.day = whole(f, 3, "the day", 1, 31, "");
    if (h.day > kDaysInMonth[h.month - 1])
      fail(line_, std::string(kMonthNames[h.month - 1]) + " " + std::to_string(h.day) +
                      " is not a date (month field 2, day field 3).");
    h.hour = whole(f, 4, "the hour", 1, 24,
                   "EPW hours end at the time given: hour 1 is 00:00 to 01:00, hour 24 is 23:00 to 24:00.");
    h.minute = whole(f, 5, "the minute", 0, 60, "");
    const double dew_point = number(f, 8, "the dew point");
    if (dew_point >= kMissingDewPoint) {
      h.dew_point = std::numeric_limits<double>::quiet_NaN();
    } else if (dew_point <= -70 || dew_point >= 70) {
      fail(line_, "the dew point (field 8) is " + number_text(dew_point) +
                      " C, outside -70 to 70 C. A missing value is written 99.9.");
    } else {
      h.dew_point = dew_point;
    }
    h.global_horizontal = irradiance(f, 14, "global horizontal radiation");
    h.direct_normal = irradiance(f, 15, "direct normal radiation");
    h.diffuse_horizontal = irradiance(f, 16, "diffuse horizontal radiation");
    if (std::isnan(h.direct_normal)) missing_sky("direct normal radiation (field 15)");
    if (std::isnan(h.diffuse_horizontal)) missing_sky("diffuse horizontal radiation (field 16)");
    h.global_illuminance = illuminance(f, 17, "global horizontal illuminance");
    h.direct_normal_illuminance = illuminance(f, 18, "direct normal illuminance");
    h.diffuse_illuminance = illuminance(f, 19, "diffuse horizontal illuminance");
    h.zenith_luminance = measured(f, 20, "zenith luminance", "cd/m2", kMissingRadiation, kMissingRadiation, "9999");
    return h;
  }

  // The hour just read follows the one before by one hour (or skips February 29), and
  // a whole year starts on January 1 hour 1.
  void check_sequence() const {
    const std::vector<WeatherHour>& hours = weather_.hours;
    const WeatherHour& h = hours.back();
    const int at = hour_of_year(h.month, h.day, h.hour);
    if (hours.size() == 1) {
      if (options_.whole_year && at != 0)
        fail(line_, "the data start on " + when(h.month, h.day, h.hour) +
                        "; a year starts on January 1 hour 1 (00:00 to 01:00). Annual daylight metrics need every "
                        "hour of a year.");
      return;
    }
    const WeatherHour& p = hours[hours.size() - 2];
    const int before = hour_of_year(p.month, p.day, p.hour);
    const std::string here = when(h.month, h.day, h.hour);
    const std::string previous = "line " + std::to_string(p.line) + " (" + when(p.month, p.day, p.hour) + ")";
    if (at == before) fail(line_, here + " appears twice, here and on " + previous + ". Each hour has one line.");
    if (at == 0 && before == kHoursInLeapYear - 1)
      fail(line_, "a second year starts here, after December 31 hour 24 on " + previous +
                      ". dynrad reads one year per file: keep the year to simulate and delete the rest.");
    if (at < before)
      fail(line_, here + " comes after a later hour, " + previous + ": the lines must be in time order.");
    if (at != before + 1 && !(before == kFeb28Hour24 && at == kMar1Hour1)) {
      // Every hour in between, but February 29's when the gap spans it (the file may not have it).
      const int missing = at - before - 1 - (before <= kFeb28Hour24 && at >= kMar1Hour1 ? 24 : 0);
      fail(line_, std::to_string(missing) + (missing == 1 ? " hour is" : " hours are") + " missing between " +
                      previous + " and this line (" + here +
                      "). dynrad needs every hour: fill the gap or use a file without one.");
    }
  }

  std::string_view text_;
  const std::string& name_;
  EpwOptions options_;
  std::size_t pos_ = 0, line_ = 0;
  Weather weather_;
};

}  // namespace

Weather parse_epw(std::string_view text, const std::string& name, const EpwOptions& options) {
  return EpwParser(text, name, options).parse();
}

Weather read_epw(const std::string& path, const EpwOptions& options) {
  return parse_epw(detail::read_text_file(path), path, options);
}

}  // namespace dynrad::rad
