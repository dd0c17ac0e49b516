// The EnergyPlus weather reader (radiosity/climate/epw.h): synthetic years read back
// hour by hour, header and data lines as published files write them, and every kind
// of bad file refused with its line and what to do.
#include "radiosity/climate/epw.h"

#include "mesh/core/error.h"
#include "synthetic_weather.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace dynrad::rad {
namespace {

using test::SyntheticYear;
using test::TempWeatherFile;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end - start));
    start = end == std::string::npos ? text.size() : end + 1;
  }
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  return text;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields(1);
  for (const char c : line) {
    if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

std::string line_of(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + fields[i];
  return line;
}

// `line` (1-based) of `lines` with field `field` (1-based) replaced by `value`.
void set_field(std::vector<std::string>& lines, std::size_t line, std::size_t field, const std::string& value) {
  std::vector<std::string> fields = fields_of(lines[line - 1]);
  fields[field - 1] = value;
  lines[line - 1] = line_of(fields);
}

// The default synthetic year (2023, clear, near London), made once.
const std::vector<std::string>& clear_year() {
  static const std::vector<std::string> lines = lines_of(test::synthetic_epw(SyntheticYear{}));
  return lines;
}

// The file line of a date's hour in a year without February 29.
std::size_t line_at(int month, int day, int hour) {
  constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  int days = day - 1;
  for (int m = 1; m < month; ++m) days += kDays[m - 1];
  return 8 + static_cast<std::size_t>(days * 24 + hour);
}

// Parsing `text` throws InputError at `line` with every one of `words` in its message.
void expect_refused(const std::string& text, std::size_t line, const std::vector<std::string>& words,
                    const EpwOptions& options = {}) {
  try {
    parse_epw(text, "site.epw", options);
    ADD_FAILURE() << "accepted; expected an error on line " << line;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "site.epw");
    EXPECT_EQ(e.line(), line) << e.what();
    const std::string what = e.what();
    if (line > 0) {
      EXPECT_NE(what.find("site.epw:" + std::to_string(line) + ": "), std::string::npos) << what;
    }
    for (const auto& w : words) EXPECT_NE(what.find(w), std::string::npos) << "'" << w << "' not in: " << what;
  }
}

// The clear year with one change.
void expect_refused_change(const std::function<void(std::vector<std::string>&)>& change, std::size_t line,
                           const std::vector<std::string>& words) {
  std::vector<std::string> lines = clear_year();
  change(lines);
  expect_refused(joined(lines), line, words);
}

// ---------------------------------------------------------------------------
// Synthetic years.

TEST(Epw, SyntheticYearReadsBackEveryHour) {
  const SyntheticYear options;
  const Weather w = parse_epw(joined(clear_year()), "london.epw");
  EXPECT_EQ(w.path, "london.epw");
  EXPECT_EQ(w.site.city, "Synthetic City");
  EXPECT_EQ(w.site.region, "-");
  EXPECT_EQ(w.site.country, "GBR");
  EXPECT_EQ(w.site.source, "dynrad synthetic");
  EXPECT_EQ(w.site.wmo, "999999");
  EXPECT_EQ(w.site.latitude, 51.5);
  EXPECT_EQ(w.site.longitude, -0.12);
  EXPECT_EQ(w.site.timezone, 0);
  EXPECT_EQ(w.site.elevation, 11);
  ASSERT_EQ(w.hours.size(), 8760u);
  EXPECT_EQ(w.hours.front().line, 9u);
  EXPECT_EQ(w.hours.back().line, 8768u);
  EXPECT_EQ(w.hours.back().month, 12);
  EXPECT_EQ(w.hours.back().day, 31);
  EXPECT_EQ(w.hours.back().hour, 24);
  for (const WeatherHour& h : w.hours) {
    const test::SyntheticHour s = test::synthetic_hour(options, h.month, h.day, h.hour);
    ASSERT_EQ(h.year, 2023);
    ASSERT_EQ(h.direct_normal, std::round(s.direct_normal)) << h.line;
    ASSERT_EQ(h.diffuse_horizontal, std::round(s.diffuse_horizontal)) << h.line;
    ASSERT_EQ(h.global_horizontal, std::round(s.global_horizontal)) << h.line;
    ASSERT_EQ(h.direct_normal_illuminance, std::round(105 * s.direct_normal)) << h.line;
    ASSERT_EQ(h.diffuse_illuminance, std::round(120 * s.diffuse_horizontal)) << h.line;
    ASSERT_TRUE(std::isnan(h.zenith_luminance)) << "a clear sky's is written missing";
    ASSERT_TRUE(std::isfinite(h.dew_point));
  }
}

TEST(Epw, SyntheticClearDaysAreLongInJuneAndShortInDecember) {
  // London: about 16.6 hours of day at midsummer and 7.8 at midwinter; an hour counts
  // when the sun is up at its middle. The clear midsummer noon sun is some 62 degrees
  // high: air mass 1.13, and Meinel's direct normal about 920 W/m2.
  const Weather w = parse_epw(joined(clear_year()), "london.epw");
  auto sunlit = [&](int month, int day) {
    int count = 0;
    for (const WeatherHour& h : w.hours)
      if (h.month == month && h.day == day && h.diffuse_horizontal > 0) ++count;
    return count;
  };
  EXPECT_GE(sunlit(6, 21), 16);
  EXPECT_LE(sunlit(6, 21), 18);
  EXPECT_GE(sunlit(12, 21), 7);
  EXPECT_LE(sunlit(12, 21), 9);
  const WeatherHour& noon = w.hours[line_at(6, 21, 13) - 9];
  EXPECT_NEAR(noon.direct_normal, 920, 20);
  EXPECT_EQ(w.hours[line_at(6, 21, 1) - 9].direct_normal, 0);
}

TEST(Epw, LeapYearHas8784Hours) {
  SyntheticYear options;
  options.year = 2024;
  const Weather w = parse_epw(test::synthetic_epw(options), "leap.epw");
  ASSERT_EQ(w.hours.size(), 8784u);
  const WeatherHour& h = w.hours[(31 + 28) * 24];
  EXPECT_EQ(h.month, 2);
  EXPECT_EQ(h.day, 29);
  EXPECT_EQ(h.hour, 1);
  EXPECT_EQ(w.hours.back().day, 31);

  // Without February 29 the same year is 8760 hours, as typical years are written
  // whatever the year field says.
  std::vector<std::string> lines = lines_of(test::synthetic_epw(options));
  lines.erase(lines.begin() + 8 + (31 + 28) * 24, lines.begin() + 8 + (31 + 29) * 24);
  EXPECT_EQ(parse_epw(joined(lines), "typical.epw").hours.size(), 8760u);

  // And February 29 in a file whose year field is not a leap year: the year field is
  // the source of each month in typical years, not the calendar.
  std::vector<std::string> with_leap_day = lines_of(test::synthetic_epw(options));
  for (std::size_t i = 8; i < with_leap_day.size(); ++i) set_field(with_leap_day, i + 1, 1, "1997");
  EXPECT_EQ(parse_epw(joined(with_leap_day), "typical.epw").hours.size(), 8784u);
}

TEST(Epw, OvercastWithoutIlluminanceGivesMissingIlluminances) {
  SyntheticYear options;
  options.sky = SyntheticYear::Sky::overcast;
  options.illuminance = false;
  const TempWeatherFile file(options);
  const Weather w = read_epw(file.path());
  EXPECT_EQ(w.path, file.path());
  ASSERT_EQ(w.hours.size(), 8760u);
  for (const WeatherHour& h : w.hours) {
    ASSERT_EQ(h.direct_normal, 0);
    ASSERT_GE(h.diffuse_horizontal, 0);
    ASSERT_EQ(h.global_horizontal, h.diffuse_horizontal);
    ASSERT_TRUE(std::isnan(h.global_illuminance));
    ASSERT_TRUE(std::isnan(h.direct_normal_illuminance));
    ASSERT_TRUE(std::isnan(h.diffuse_illuminance));
    ASSERT_TRUE(std::isnan(h.zenith_luminance));
  }
  // Midsummer noon: 0.25 x 1353 x cos(28 degrees), about 300 W/m2.
  EXPECT_NEAR(w.hours[line_at(6, 21, 13) - 9].diffuse_horizontal, 300, 10);
}

TEST(Epw, OvercastZenithLuminanceIsTheCieOvercastSkys) {
  // CIE overcast sky: horizontal illuminance 7 pi Lz / 9 (radiosity/sources/sky.h). From 9999
  // cd/m2 (about 24,400 lx) the field can only say "missing".
  SyntheticYear options;
  options.sky = SyntheticYear::Sky::overcast;
  options.start_month = 3;
  options.start_day = 20;
  options.days = 1;
  EpwOptions part;
  part.whole_year = false;
  const Weather w = parse_epw(test::synthetic_epw(options), "overcast.epw", part);
  ASSERT_EQ(w.hours.size(), 24u);
  int bright = 0, dim = 0;
  for (const WeatherHour& h : w.hours) {
    EXPECT_EQ(h.global_illuminance, h.diffuse_illuminance);
    EXPECT_EQ(h.direct_normal_illuminance, 0);
    const double zenith = 9 * h.diffuse_illuminance / (7 * M_PI);
    if (std::round(zenith) >= 9999) {
      EXPECT_TRUE(std::isnan(h.zenith_luminance)) << h.hour;
      ++bright;
    } else {
      EXPECT_NEAR(h.zenith_luminance, zenith, 1) << h.hour;  // both rounded in the file
      dim += h.diffuse_illuminance > 1000;
    }
  }
  EXPECT_GT(bright, 0);
  EXPECT_GT(dim, 0);
}

TEST(Epw, PartOfAYearOnlyWhenAskedFor) {
  SyntheticYear options;
  options.start_month = 6;
  options.start_day = 20;
  options.days = 2;
  const std::string text = test::synthetic_epw(options);
  EpwOptions part;
  part.whole_year = false;
  const Weather w = parse_epw(text, "two_days.epw", part);
  ASSERT_EQ(w.hours.size(), 48u);
  EXPECT_EQ(w.hours.front().month, 6);
  EXPECT_EQ(w.hours.front().day, 20);
  EXPECT_EQ(w.hours.back().day, 21);
  EXPECT_EQ(w.hours.back().hour, 24);
  expect_refused(text, 9, {"start on June 20 hour 1", "January 1 hour 1"});

  // A whole year ends on December 31 hour 24.
  options.start_month = 1;
  options.start_day = 1;
  expect_refused(test::synthetic_epw(options), 56, {"end on January 2 hour 24 after 48 hours", "truncated"});
}

// ---------------------------------------------------------------------------
// As published files are written.

// The header of NREL's TMY3 file for Golden, Colorado (WMO 724666), as distributed with
// EnergyPlus, and its first daylight hours of January 1.
const char* const kGoldenHeader =
    "LOCATION,Denver Centennial  Golden   Nr,CO,USA,TMY3,724666,39.74,-105.18,-7.0,1829.0\n"
    "DESIGN CONDITIONS,1,Climate Design Data 2009 ASHRAE Handbook,,Heating,12,-18.8,-15.5,-21.6,0.7,-10.9,-18.8,"
    "0.9,-7.5,12.2,3.9,10.9,3.8,3,340,Cooling,7,15.2,33,15.7,32,15.5,30.2,15.3,18.4,27.3,17.5,26.4,16.8,25.6,4.9,0,"
    "16.1,14.3,20.2,14.9,13.2,19.9,13.9,12.3,19.6,59.7,27.3,56.6,26.6,54,25.7,760,Extremes,11.1,9.5,8.4,22.9,-22.9,"
    "36.1,3.8,1.2,-25.7,37,-27.9,37.7,-30.1,38.3,-32.8,39.2\n"
    "TYPICAL/EXTREME PERIODS,6,Summer - Week Nearest Max Temperature For Period,Extreme,7/ 6,7/12,Summer - Week "
    "Nearest Average Temperature For Period,Typical,7/27,8/ 2,Winter - Week Nearest Min Temperature For Period,"
    "Extreme,12/15,12/21,Winter - Week Nearest Average Temperature For Period,Typical,12/ 1,12/ 7,Autumn - Week "
    "Nearest Average Temperature For Period,Typical,10/20,10/26,Spring - Week Nearest Average Temperature For "
    "Period,Typical,4/26,5/ 2\n"
    "GROUND TEMPERATURES,3,.5,,,,-0.60,1.34,5.12,8.69,15.46,19.02,20.00,18.20,14.02,8.83,3.71,0.32,2,,,,2.08,2.55,"
    "4.70,7.10,12.30,15.62,17.28,16.91,14.53,10.94,6.90,3.72,4,,,,4.84,4.51,5.45,6.81,10.25,12.82,14.49,14.90,"
    "13.86,11.74,9.00,6.53\n"
    "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\n"
    "COMMENTS 1,Custom/User Format -- WMO#724666; NREL TMY Data Set (2008); Period of Record 1973-2005 (Generally)\n"
    "COMMENTS 2, -- Ground temps produced with a standard soil diffusivity of 2.3225760E-03 {m**2/day}\n"
    "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";
const char* const kGoldenMorning =
    "1999,1,1,8,0,?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9?9?9*9*9?9?9?9,-1.0,-1.0,100,81100,41,861,281,4,119,2,906,"
    "6725,559,79,260,2.1,10,10,1.6,480,9,999999999,89,0.0310,0,88,0.330,0.0,1.0\n"
    "1999,1,1,9,0,?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9?9?9*9*9?9*9*9,0.0,-1.0,92,81300,242,1415,272,178,480,95,17449,"
    "32960,11774,1860,240,2.6,9,8,6.4,1500,9,999999999,89,0.0310,0,88,0.330,999.0,99.0\n"
    "1999,1,1,10,0,?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9?9?9*9*9?9*9*9,2.0,-1.0,80,81500,429,1415,294,49,0,49,5871,0,"
    "5871,2108,280,2.6,10,10,16.1,1500,9,999999999,89,0.0310,0,88,0.330,999.0,99.0\n";

// ASHRAE's IWEC file for London Gatwick (WMO 037760), as distributed with EnergyPlus:
// a quoted comment with commas, minute 60, and its first daylight hours.
const char* const kGatwickHeader =
    "LOCATION,LONDON/GATWICK,-,GBR,IWEC Data,037760,51.15,-0.18,0.0,62.0\n"
    "DESIGN CONDITIONS,1,Climate Design Data 2009 ASHRAE Handbook,,Heating,2,-4.6,-3,-7.6,2,-2.1,-6,2.3,-0.7,12.6,"
    "7.9,11.3,6.9,1.5,80,Cooling,7,9.7,27.2,18.7,25.2,17.8,23.8,17.2,19.7,25.4,18.7,23.8,17.8,22.1,3.5,90,17.8,12.9,"
    "21.9,16.9,12.2,20.5,16.1,11.5,19.6,56.3,25.7,53.2,23.9,50.4,22.2,1198,Extremes,9.8,8.6,7.6,23.6,-7.6,30.2,2.6,"
    "2.5,-9.5,32,-11,33.5,-12.5,34.9,-14.4,36.7\n"
    "TYPICAL/EXTREME PERIODS,6,Summer - Week Nearest Max Temperature For Period,Extreme,8/17,8/23,Summer - Week "
    "Nearest Average Temperature For Period,Typical,6/29,7/ 5,Winter - Week Nearest Min Temperature For Period,"
    "Extreme,12/ 1,12/ 7,Winter - Week Nearest Average Temperature For Period,Typical,1/20,1/26,Autumn - Week "
    "Nearest Average Temperature For Period,Typical,11/10,11/16,Spring - Week Nearest Average Temperature For "
    "Period,Typical,4/19,4/25\n"
    "GROUND TEMPERATURES,3,.5,,,,4.16,5.30,7.51,9.61,13.58,15.67,16.24,15.18,12.74,9.69,6.69,4.70,2,,,,5.73,6.01,"
    "7.27,8.68,11.72,13.67,14.64,14.43,13.03,10.93,8.56,6.69,4,,,,7.35,7.16,7.71,8.51,10.52,12.03,13.01,13.25,12.64,"
    "11.40,9.79,8.34\n"
    "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\n"
    "COMMENTS 1,\"IWEC- WMO#037760 - Europe -- Original Source Data (c) 2001 American Society of Heating, "
    "Refrigerating and Air-Conditioning Engineers (ASHRAE), Inc., Atlanta, GA, USA.  www.ashrae.org  All rights "
    "reserved as noted in the License Agreement and Additional Conditions.\"\n"
    "COMMENTS 2, -- Ground temps produced with a standard soil diffusivity of 2.3225760E-03 {m**2/day}\n"
    "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";
const char* const kGatwickMorning =
    "1991,1,1,9,60,A7A7E8E8*0G9G9G9I9I9I9I9A7A7A7A7A7A7*0E8*0*0,0.6,0.0,96,101100,57,1415,255,19,0,19,2100,0,2100,"
    "580,0,0.0,6,1,30.0,7500,9,999999999,0,0.0400,0,88,0.000,0.0,0.0\n"
    "1991,1,1,10,60,A7A7E8E8*0G9G9G9I9I9I9I9A7A7A7A7A7A7*0E8*0*0,2.5,1.2,91,101000,206,1415,264,52,7,51,5700,100,"
    "5600,1700,210,2.6,9,1,30.0,7500,9,999999999,0,0.0400,0,88,0.000,0.0,0.0\n";

TEST(Epw, PublishedHeadersAndLinesRead) {
  EpwOptions part;
  part.whole_year = false;
  const Weather golden = parse_epw(std::string(kGoldenHeader) + kGoldenMorning, "golden.epw", part);
  EXPECT_EQ(golden.site.city, "Denver Centennial  Golden   Nr");
  EXPECT_EQ(golden.site.region, "CO");
  EXPECT_EQ(golden.site.source, "TMY3");
  EXPECT_EQ(golden.site.wmo, "724666");
  EXPECT_EQ(golden.site.latitude, 39.74);
  EXPECT_EQ(golden.site.longitude, -105.18);
  EXPECT_EQ(golden.site.timezone, -7);
  EXPECT_EQ(golden.site.elevation, 1829);
  ASSERT_EQ(golden.hours.size(), 3u);
  const WeatherHour& h = golden.hours[1];
  EXPECT_EQ(h.line, 10u);
  EXPECT_EQ(h.year, 1999);
  EXPECT_EQ(h.hour, 9);
  EXPECT_EQ(h.dew_point, -1);
  EXPECT_EQ(h.global_horizontal, 178);
  EXPECT_EQ(h.direct_normal, 480);
  EXPECT_EQ(h.diffuse_horizontal, 95);
  EXPECT_EQ(h.global_illuminance, 17449);
  EXPECT_EQ(h.direct_normal_illuminance, 32960);
  EXPECT_EQ(h.diffuse_illuminance, 11774);
  EXPECT_EQ(h.zenith_luminance, 1860);

  const Weather gatwick = parse_epw(std::string(kGatwickHeader) + kGatwickMorning, "gatwick.epw", part);
  EXPECT_EQ(gatwick.site.city, "LONDON/GATWICK");
  EXPECT_EQ(gatwick.site.wmo, "037760");
  EXPECT_EQ(gatwick.site.latitude, 51.15);
  ASSERT_EQ(gatwick.hours.size(), 2u);
  EXPECT_EQ(gatwick.hours[0].minute, 60);
  EXPECT_EQ(gatwick.hours[1].direct_normal, 7);
  EXPECT_EQ(gatwick.hours[1].diffuse_illuminance, 5600);

  // A whole year under Golden's header.
  SyntheticYear options;
  options.latitude = 39.74;
  options.longitude = -105.18;
  options.timezone = -7;
  std::vector<std::string> lines = lines_of(test::synthetic_epw(options));
  const std::vector<std::string> header = lines_of(kGoldenHeader);
  std::copy(header.begin(), header.end(), lines.begin());
  EXPECT_EQ(parse_epw(joined(lines), "golden.epw").hours.size(), 8760u);
}

TEST(Epw, LineBreaksByteOrderMarkAndPadding) {
  const std::string text = joined(clear_year());
  const Weather plain = parse_epw(text, "plain.epw");
  auto replaced = [](std::string s, const std::string& from, const std::string& to) {
    std::string out;
    for (std::size_t at = 0;;) {
      const std::size_t next = s.find(from, at);
      out += s.substr(at, next - at);
      if (next == std::string::npos) return out;
      out += to;
      at = next + from.size();
    }
  };
  for (const std::string& variant : {replaced(text, "\n", "\r\n"), replaced(text, "\n", "\r"), "\xEF\xBB\xBF" + text,
                                     text + "\n \r\n\t\n", text.substr(0, text.size() - 1)}) {
    const Weather w = parse_epw(variant, "variant.epw");
    ASSERT_EQ(w.hours.size(), 8760u);
    EXPECT_EQ(w.site.city, plain.site.city);
    EXPECT_EQ(w.hours[4000].direct_normal, plain.hours[4000].direct_normal);
    EXPECT_EQ(w.hours.back().line, 8768u);
  }
  // With CRLF, errors name the same lines.
  std::vector<std::string> lines = clear_year();
  set_field(lines, 5000, 15, "abc");
  expect_refused(replaced(joined(lines), "\n", "\r\n"), 5000, {"field 15"});

  // Spreadsheets pad every line with commas to the longest one.
  lines = clear_year();
  for (auto& line : lines) line += ",,,,,";
  EXPECT_EQ(parse_epw(joined(lines), "padded.epw").hours.size(), 8760u);

  // read_epw decodes UTF-16 with a byte-order mark, as Windows editors save "Unicode".
  SyntheticYear day;
  day.days = 1;
  day.start_month = 7;
  std::string utf16 = "\xFF\xFE";
  for (const char c : test::synthetic_epw(day)) utf16 += std::string{c, '\0'};
  const TempWeatherFile file(utf16);
  EpwOptions part;
  part.whole_year = false;
  EXPECT_EQ(read_epw(file.path(), part).hours.size(), 24u);
}

TEST(Epw, MissingValues) {
  std::vector<std::string> lines = clear_year();
  const std::size_t noon = line_at(6, 21, 13);
  set_field(lines, noon, 8, "99.9");     // dew point
  set_field(lines, noon, 14, "9999");    // global horizontal
  set_field(lines, noon, 17, "999999");  // global illuminance
  set_field(lines, noon, 18, "999900");  // "missing if >= 999900"
  set_field(lines, noon, 19, "1000000");
  set_field(lines, noon, 20, "9999.0");  // zenith luminance
  const Weather w = parse_epw(joined(lines), "gaps.epw");
  const WeatherHour& h = w.hours[noon - 9];
  EXPECT_TRUE(std::isnan(h.dew_point));
  EXPECT_TRUE(std::isnan(h.global_horizontal));
  EXPECT_TRUE(std::isnan(h.global_illuminance));
  EXPECT_TRUE(std::isnan(h.direct_normal_illuminance));
  EXPECT_TRUE(std::isnan(h.diffuse_illuminance));
  EXPECT_TRUE(std::isnan(h.zenith_luminance));
  EXPECT_GT(h.direct_normal, 800);

  // What makes the sky may not be missing.
  expect_refused_change([&](auto& l) { set_field(l, noon, 15, "9999"); }, noon,
                        {"direct normal radiation (field 15) is missing (9999)", "fill the gap"});
  expect_refused_change([&](auto& l) { set_field(l, noon, 16, "99999"); }, noon,
                        {"diffuse horizontal radiation (field 16) is missing"});
  expect_refused_change([&](auto& l) { set_field(l, line_at(1, 1, 1), 15, "9999"); }, 9, {"missing (9999)"});
}

// ---------------------------------------------------------------------------
// Bad files: the line and what to do.

TEST(Epw, BadHeaders) {
  expect_refused("", 0, {"is empty", "LOCATION"});
  expect_refused(" \r\n\n", 0, {"is empty"});
  expect_refused("solid cube\nfacet normal 0 0 1\n", 1, {"LOCATION record", "'solid cube'", ".epw"});
  expect_refused(joined({clear_year().begin(), clear_year().begin() + 5}), 5, {"ends inside the header", "5 of"});

  auto location = [](const std::string& line, const std::vector<std::string>& words) {
    expect_refused_change([&](auto& l) { l[0] = line; }, 1, words);
  };
  location("LOCATION,Nowhere,-,XXX,src,000000,51.5,-0.12,0", {"has 9 fields", "it has 10"});
  location("LOCATION,Nowhere,-,XXX,src,000000,51.5,-0.12,0,11,12", {"has 11 fields"});
  location("LOCATION,Nowhere,-,XXX,src,000000,95,-0.12,0,11", {"latitude", "'95'", "outside -90 to 90"});
  location("LOCATION,Nowhere,-,XXX,src,000000,north,-0.12,0,11", {"latitude", "'north'", "not a number"});
  location("LOCATION,Nowhere,-,XXX,src,000000,51.5,-190,0,11", {"longitude", "outside -180 to 180"});
  location("LOCATION,Nowhere,-,XXX,src,000000,51.5,-0.12,15,11", {"time zone", "outside -12 to 14"});
  location("LOCATION,Nowhere,-,XXX,src,000000,51.5,-0.12,0,nan", {"elevation"});
  location("LOCATION,Nowhere,-,XXX,src,000000,51.5,-0.12,0,", {"has 9 fields"});
  // Denver's longitude with the time zone's sign swapped.
  location("LOCATION,Golden,CO,USA,TMY3,724666,39.74,-105.18,7.0,1829.0", {"time zone 7 h", "sign swapped"});
  // A city with a comma, quoted, and the date line's neighbours: Samoa (-171.8, +13).
  std::vector<std::string> lines = clear_year();
  lines[0] = "LOCATION,\"Apia, Upolu\",-,WSM,src,917620,-13.8,-171.78,13.0,2";
  EXPECT_EQ(parse_epw(joined(lines), "apia.epw").site.city, "Apia, Upolu");

  // Header records: one missing (the first data line then stands where DATA PERIODS
  // should), one twice, the records in another order (accepted, as EnergyPlus does).
  expect_refused_change(
      [](auto& l) { l.erase(l.begin() + 4); }, 8,
      {"this line should be one of the 8 header records", "'2023,1,1,1,", "Not given yet: HOLIDAYS/DAYLIGHT SAVINGS."});
  expect_refused_change([](auto& l) { l[6] = "COMMENTS 1,again"; }, 7,
                        {"COMMENTS 1 record appears again (first on line 6)"});
  lines = clear_year();
  std::swap(lines[1], lines[5]);
  lines[4] = "HOLIDAYS/DAYLIGHT SAVING,No,0,0,0";  // as the data dictionary spells it
  EXPECT_EQ(parse_epw(joined(lines), "order.epw").hours.size(), 8760u);

  expect_refused_change([](auto& l) { l[7] = "DATA PERIODS,1,4,Data,Sunday, 1/ 1,12/31"; }, 8,
                        {"4 records per hour", "average"});
  expect_refused_change([](auto& l) { l[7] = "DATA PERIODS,2,1,Winter,Sunday, 1/ 1,3/31,Rest,Saturday,4/1,12/31"; }, 8,
                        {"2 data periods"});
  expect_refused_change([](auto& l) { l[7] = "DATA PERIODS,one,1"; }, 8, {"DATA PERIODS record should start"});
  expect_refused_change([](auto& l) { l[7] = "DATA PERIODS"; }, 8, {"DATA PERIODS record should start"});
}

TEST(Epw, BadFields) {
  const std::size_t n = line_at(3, 10, 14);
  auto field = [&](std::size_t index, const std::string& value, const std::vector<std::string>& words) {
    expect_refused_change([&](auto& l) { set_field(l, n, index, value); }, n, words);
  };
  field(15, "abc", {"direct normal radiation (field 15) is 'abc', not a number"});
  field(15, "", {"field 15) is empty"});
  field(15, "12 3", {"not a number"});
  field(15, "nan", {"not a finite number"});
  field(16, "inf", {"not a finite number"});
  field(16, "1e999", {"not a number"});
  field(15, "-5", {"-5 W/m2, negative", "9999"});
  field(16, "-9999", {"negative"});
  field(15, "5000", {"5000 W/m2, more than any daylight"});
  field(14, "-1", {"global horizontal radiation (field 14)", "negative"});
  field(17, "-1", {"global horizontal illuminance (field 17)", "negative"});
  field(18, "300000", {"direct normal illuminance (field 18) is 300000 lx", "999999"});
  field(20, "-3", {"zenith luminance (field 20)"});
  field(8, "80", {"dew point (field 8) is 80 C"});
  field(8, "-70", {"outside -70 to 70"});
  field(1, "-1", {"the year (field 1)"});
  field(2, "13", {"the month (field 2) is 13"});
  field(2, "0", {"the month"});
  field(3, "32", {"the day (field 3) is 32"});
  field(4, "0", {"the hour (field 4) is 0", "hour 1 is 00:00 to 01:00"});
  field(4, "25", {"the hour (field 4) is 25"});
  field(4, "13.5", {"whole number"});
  field(5, "61", {"the minute (field 5)"});
  // Impossible dates.
  const std::size_t april_30 = line_at(4, 30, 1);
  expect_refused_change([&](auto& l) { set_field(l, april_30, 3, "31"); }, april_30, {"April 31 is not a date"});
  const std::size_t february_28 = line_at(2, 28, 5);
  expect_refused_change([&](auto& l) { set_field(l, february_28, 3, "30"); }, february_28,
                        {"February 30 is not a date"});

  // Fields: 34, 36 with a value in the 36th, a comma lost in the middle.
  expect_refused_change([&](auto& l) { l[n - 1] = l[n - 1].substr(0, l[n - 1].rfind(',')); }, n,
                        {"has 34 fields", "35"});
  expect_refused_change([&](auto& l) { l[n - 1] += ",7"; }, n, {"has 36 fields"});
  expect_refused_change(
      [&](auto& l) {
        std::vector<std::string> f = fields_of(l[n - 1]);
        f[13] += f[14];  // "69275": global horizontal and direct normal run together
        f.erase(f.begin() + 14);
        l[n - 1] = line_of(f);
      },
      n, {"has 34 fields"});
}

TEST(Epw, BadSequences) {
  const std::size_t n = line_at(5, 3, 7);
  // The same hour twice.
  expect_refused_change([&](auto& l) { l.insert(l.begin() + n, l[n - 1]); }, n + 1,
                        {"May 3 hour 7 appears twice", "line " + std::to_string(n)});
  // Sub-hourly records in an hourly file are duplicates too.
  expect_refused_change(
      [&](auto& l) {
        set_field(l, n, 5, "30");
        l.insert(l.begin() + n, l[n - 1]);
        set_field(l, n + 1, 5, "60");
      },
      n + 1, {"appears twice"});
  // An hour missing, and a day.
  expect_refused_change(
      [&](auto& l) { l.erase(l.begin() + n - 1); }, n,
      {"1 hour is missing between line " + std::to_string(n - 1) + " (May 3 hour 6)", "(May 3 hour 8)"});
  expect_refused_change([&](auto& l) { l.erase(l.begin() + n - 1, l.begin() + n + 23); }, n, {"24 hours are missing"});
  // An hour out of place.
  expect_refused_change([&](auto& l) { l[n - 1] = l[line_at(5, 2, 1) - 1]; }, n,
                        {"May 2 hour 1 comes after a later hour", "time order"});
  // Two lines swapped: the first sign is a gap.
  expect_refused_change([&](auto& l) { std::swap(l[n - 1], l[n]); }, n, {"1 hour is missing"});
  // February 29 begun but not finished.
  expect_refused_change(
      [&](auto& l) {
        const std::size_t march_1 = line_at(3, 1, 1);
        l.insert(l.begin() + march_1 - 1, l[march_1 - 1]);
        set_field(l, march_1, 2, "2");
        set_field(l, march_1, 3, "29");
      },
      line_at(3, 1, 1) + 1, {"23 hours are missing", "(February 29 hour 1)"});
  // The year incomplete at either end, or followed by another.
  expect_refused_change([](auto& l) { l.erase(l.begin() + 8, l.begin() + 32); }, 9,
                        {"start on January 2 hour 1", "January 1 hour 1"});
  expect_refused_change([](auto& l) { l.resize(l.size() - 24); }, 8744,
                        {"end on December 30 hour 24 after 8736 hours", "8760"});
  expect_refused_change([](auto& l) { l.push_back(l[8]); }, 8769, {"second year", "one year per file"});
  // A blank line inside the data.
  expect_refused_change([&](auto& l) { l.insert(l.begin() + n, "  "); }, n + 1, {"this line is empty"});
  expect_refused_change([](auto& l) { l.resize(8); }, 8, {"no hourly data"});
}

TEST(Epw, ReadEpwNamesAMissingFile) {
  try {
    read_epw("/nonexistent/weather.epw");
    FAIL() << "read a file that does not exist";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/weather.epw");
    EXPECT_EQ(e.line(), 0u);
    EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dynrad::rad
