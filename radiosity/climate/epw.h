// EnergyPlus weather files (.epw): the site and the hourly solar radiation and daylight
// of a year, for climate-based daylight metrics (IES LM-83 sDA and ASE, EN 17037).
//
// The format (EnergyPlus "Auxiliary Programs", EPW data dictionary): comma-separated
// text. 8 header records: LOCATION,city,region,country,source,WMO,latitude (north +),
// longitude (east +),time zone (hours from GMT, east +),elevation (m); DESIGN
// CONDITIONS, TYPICAL/EXTREME PERIODS, GROUND TEMPERATURES, HOLIDAYS/DAYLIGHT SAVINGS,
// COMMENTS 1, COMMENTS 2 (not read); DATA PERIODS,periods,records per hour,... Then a
// line of 35 fields per hour: year, month, day, hour (1-24; hour 1 is 00:00-01:00 local
// standard time), minute, flags, dry bulb, dew point (8), ..., global horizontal (14),
// direct normal (15) and diffuse horizontal (16) radiation (Wh/m2 over the hour),
// global horizontal (17), direct normal (18) and diffuse horizontal (19) illuminance
// (lx), zenith luminance (20, cd/m2), wind and the rest (not read). Missing values:
// radiation and zenith luminance >= 9999, illuminance >= 999900, dew point >= 99.9.
//
// Accepted: a UTF-8 byte-order mark (read_epw also decodes UTF-16), "\n", "\r\n" or
// "\r" line breaks, blank lines at the end, empty fields after the 35th (spreadsheets
// pad lines with commas), quoted header fields with commas, the header records in any
// order (as EnergyPlus reads them), and any year field: typical years mix source years,
// so whether February 29 exists is decided by the lines, not the year.
//
// Refused, each an InputError naming the file and line and what to do:
//   - a header other than the 8 records once each; a latitude, longitude, time zone
//     (-12 to +14) or elevation out of range; a time zone more than 4 hours from the
//     longitude's solar time (real zones are within 3: a sign is swapped, and the sun
//     would be placed at the wrong hours);
//   - sub-hourly files and several data periods: averaging to hours is the user's
//     choice to make, not one to hide here;
//   - a data line of other than 35 fields, a field that is not a finite number, a
//     month, day, hour or minute out of range, an impossible date;
//   - negative radiation or illuminance, or more than any at the ground (2000 W/m2,
//     250,000 lx) below the missing code;
//   - direct normal or diffuse horizontal radiation missing: that hour's sky cannot be
//     made (EnergyPlus reads 0, a dark hour in daylight);
//   - hours out of order, repeated or missing, a second year and, unless
//     EpwOptions::whole_year is false, anything but January 1 hour 1 to December 31
//     hour 24: 8760 lines, 8784 with February 29.
// Global horizontal radiation, the illuminances, zenith luminance and dew point may be
// missing: they are NaN (illuminance then comes from radiation by a luminous efficacy).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace dynrad::rad {

struct WeatherSite {
  // As written; the WMO station number as text.
  std::string city, region, country, source, wmo;
  double latitude = 0;   // degrees, north positive
  double longitude = 0;  // degrees, east positive
  double timezone = 0;   // hours east of GMT of the file's (standard) times
  double elevation = 0;  // m above sea level
};

// One hour of the file. Radiation is the mean over the hour (the file's Wh/m2 over the
// hour ending at `hour`); NaN where the field may be missing and is.
struct WeatherHour {
  int year = 0, month = 1, day = 1;
  int hour = 1;    // 1-24 as in the file: hour h is from h-1:00 to h:00 local standard time
  int minute = 0;  // as in the file (0 or 60 in hourly files); not used

  double global_horizontal = 0;   // W/m^2 (NaN: missing)
  double direct_normal = 0;       // W/m^2, never missing
  double diffuse_horizontal = 0;  // W/m^2, never missing

  double global_illuminance = 0;         // lx on the horizontal (NaN: missing)
  double direct_normal_illuminance = 0;  // lx (NaN: missing)
  double diffuse_illuminance = 0;        // lx on the horizontal, from the sky (NaN: missing)
  double zenith_luminance = 0;           // cd/m^2 (NaN: missing)

  double dew_point = 0;  // degrees C, for the precipitable water of the Perez model (NaN: missing)
  std::size_t line = 0;  // in the file, 1-based, for messages about this hour
};

struct Weather {
  WeatherSite site;
  // In time order, one per hour without gaps (February 29 may be absent):
  // 8760 or 8784 for a whole year.
  std::vector<WeatherHour> hours;
  std::string path;  // the name given to the reader
};

struct EpwOptions {
  // false accepts any run of whole consecutive hours within one year (at least one):
  // for short test files and the fuzz target. Annual metrics need the whole year.
  bool whole_year = true;
};

// Reads an EPW file (UTF-8 or UTF-16 with a byte-order mark). Throws InputError.
Weather read_epw(const std::string& path, const EpwOptions& options = {});
// The same from text in memory; `name` stands for the file in messages and in path.
Weather parse_epw(std::string_view text, const std::string& name, const EpwOptions& options = {});

}  // namespace dynrad::rad
