// Annual daylight metrics from hourly illuminances at the points of a grid: pure
// functions, no scene. Shares are fractions (0-1), never percentages, except daylight
// factors (%).
//
// Definitions, their sources, and the conventions chosen where a source leaves one open:
//
//   DA (daylight autonomy; Reinhart & Walkenhorst 2001, as reviewed by Reinhart,
//     Mardaljevic & Rogers, LEUKOS 3(1) 2006): per point, the share of analysis hours
//     with E >= threshold (300 lx).
//   cDA (continuous DA; Rogers 2006, same review): as DA, but an hour below the
//     threshold earns E / threshold instead of 0.
//   UDI (useful daylight illuminance; Nabil & Mardaljevic, LRT 37(1) 2005, where the
//     useful range was 100-2000 lx, later raised to 100-3000 lx): per point, the shares
//     of analysis hours that fell short (E < 100), were useful (100 <= E <= 3000) and
//     were exceeded (E > 3000). The paper says "within the range"; both bounds belong to
//     the useful band here, so the three shares sum to 1 exactly.
//   sDA300/50% (IES LM-83-12, 2.1): the share of points with E >= 300 lx for at least
//     50% of the analysis hours (>= 1825 of 3650), with the operable blinds of 2.2.6.
//   ASE1000,250h (IES LM-83-12, 3): the share of points whose direct sunlight exceeds
//     1000 lx (E > 1000) for more than 250 analysis hours (> 250), from the sun alone:
//     no sky, no interreflection (zero bounce), window transmittance included, every
//     blind open.
//   LM-83's blinds (2.2.6): in an hour when more than 2% of the points receive direct
//     sun, the blinds close and sDA takes that hour's illuminance with them closed.
//     Direct sun is 1000 lx or more (>= 1000) of the same zero-bounce sun as ASE's.
//     Here every window is one group: its blinds open and close together (LM-83 lets
//     several groups close in any combination; a caller with several groups runs them
//     as separate grids or merges them beforehand). Without closed-blinds illuminance
//     (or a transmittance standing for it) there are no blinds, and GridMetrics::notes
//     says so: the sDA is then the DA-based share, not LM-83's.
//   Analysis hours (LM-83-12, 2.1.2 and 2.2.1): 08:00-18:00 every day of the year, 10 h
//     x 365 = 3650 h. LM-83-12 is quoted as saying "local clock time"; this code counts
//     local standard time unless a daylight saving period is given (occupied_hours).
//     See occupied_hours for which weather-file rows that selects.
//   EN 17037:2018 daylight provision, illuminance method (Annex A): a level is met when
//     the target illuminance is reached over 50% of the reference plane, and the minimum
//     illuminance over 95% of it, each for at least 50% of the daylight hours. Levels
//     (target / minimum, lx): minimum 300 / 100, medium 500 / 300, high 750 / 500.
//     Daylight hours: the half of the year's hours with the most daylight (4380 of
//     8760); as ClimateStudio does, the hours of highest diffuse horizontal illuminance
//     (en17037_daylight_hours). Each hour is judged on its own: "reached over F of the
//     plane" means at least ceil(F N) of the N points (equal areas: a regular grid)
//     have E >= the value, i.e. the ceil(F N)-th largest illuminance reaches it
//     (hourly_illuminance_reached). Some tools instead take each point's DA over the
//     daylight hours and then the share of points with DA >= 50%; that is not this.
//     Blinds play no part: EN 17037 is computed from the blinds-open illuminance.
//   EN 17037 daylight factor method: D_T = E_T / E_v,d,med (and D_TM = E_TM /
//     E_v,d,med) over the same plane fractions, E_v,d,med being the median diffuse
//     horizontal illuminance over the daylight hours (its Table A.3 gives it per capital;
//     median_diffuse_illuminance computes it from a weather year).
//
// Comparisons are exact on the float illuminances against double thresholds. Counts of
// a share ("at least 50% of 3650 hours", "more than 2% of N points") are integers: the
// product fraction x total is taken as an integer when it lies within rounding of one,
// so that 55% of 100 hours is 55 and not 55.00000000000001 (0.55 x 100 in doubles).
//
// Cost: one pass over the analysis hours (and one over the daylight hours for EN 17037),
// counting per point and per hour; nothing is sorted (en17037_daylight_hours and
// hourly_illuminance_reached select with nth_element). 10,000 points x 8760 hours take
// under a second on one core.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dynrad::rad {

// Illuminances (lx) of `points` points for `hours` hours, hour-major:
// lux[hour * points + point]. Hour-major because the simulation produces one hour's
// grid at a time and the blinds rule and EN 17037 judge each hour across the points.
struct HourlyIlluminance {
  std::size_t points = 0, hours = 0;
  std::vector<float> lux;
  HourlyIlluminance() = default;
  HourlyIlluminance(std::size_t points_, std::size_t hours_) : points(points_), hours(hours_), lux(points_ * hours_) {}
  float& at(std::size_t hour, std::size_t point) { return lux[hour * points + point]; }
  float at(std::size_t hour, std::size_t point) const { return lux[hour * points + point]; }
  const float* hour(std::size_t h) const { return lux.data() + h * points; }
};

// Which hours (rows of a HourlyIlluminance) a metric counts.
struct AnalysisHours {
  std::vector<char> in;     // one per hour row; nonzero: counted
  std::string description;  // how they were chosen, for reports
  std::size_t count() const;
};

// A weather file's row: EPW's month (1-12), day (1-31) and hour (1-24), the hour ending
// at that time of local standard time: hour h covers (h-1):00 to h:00, and its sky is
// taken at its middle, (h-1):30.
struct HourEnding {
  int month = 1, day = 1, hour = 1;
};

// The rows of a year in weather-file order: 8760 (8784 with 29 February when `leap`).
std::vector<HourEnding> year_hours(bool leap = false);

// Daylight saving: clocks one hour ahead of standard time on the days from `start`
// (inclusive) to `end` (exclusive), as the clocks change at night; month and day.
// A start after the end wraps round the new year (southern hemisphere).
struct DaylightSaving {
  int start_month = 3, start_day = 1, end_month = 11, end_day = 1;
};

// The rows whose whole hour lies within [first_hour, last_hour] of clock time. Without
// daylight saving, 08:00-18:00 is hour-ending 9 to 18: 10 rows a day, 3650 in a
// 365-day year. With it, on saving days 08:00-18:00 clock time is 07:00-17:00 standard
// time, rows 8 to 17. LM-83's period is the default. Throws std::invalid_argument for
// hours outside 0 <= first_hour < last_hour <= 24 or a row out of range.
AnalysisHours occupied_hours(const std::vector<HourEnding>& rows, int first_hour = 8, int last_hour = 18,
                             const DaylightSaving* saving = nullptr);

// EN 17037's daylight hours: the `count` rows of highest diffuse horizontal illuminance
// (lx), ties to the earlier row; count 0 takes half the rows (4380 of 8760). Throws
// std::invalid_argument for a value that is negative or not finite (a missing hour).
AnalysisHours en17037_daylight_hours(const std::vector<double>& diffuse_horizontal, std::size_t count = 0);

// E_v,d,med: the median (the mean of the middle two for an even count) of the diffuse
// horizontal illuminance over `daylight_hours`; by default its own daylight hours,
// which makes it the year's 75th percentile. Throws std::invalid_argument when no hour
// is counted, the sizes differ or a counted value is negative or not finite.
double median_diffuse_illuminance(const std::vector<double>& diffuse_horizontal,
                                  const AnalysisHours* daylight_hours = nullptr);

// The daylight factor (%) equivalent to `lux` where the median diffuse illuminance is
// `median_diffuse`: 100 lux / median_diffuse.
double daylight_factor_target(double lux, double median_diffuse);

struct En17037Level {
  const char* name;
  double target_lux, minimum_lux;
};
inline constexpr std::array<En17037Level, 3> kEn17037Levels{{
    {"minimum", 300, 100},
    {"medium", 500, 300},
    {"high", 750, 500},
}};

struct En17037Options {
  double target_plane_fraction = 0.5;    // the target over this share of the points
  double minimum_plane_fraction = 0.95;  // the minimum over this share
  double time_fraction = 0.5;            // for at least this share of the daylight hours
};

struct En17037LevelResult {
  std::string level;
  double target_lux = 0, minimum_lux = 0;
  double target_hours = 0;   // share of daylight hours the target is reached over its plane fraction
  double minimum_hours = 0;  // likewise the minimum
  bool target_met = false, minimum_met = false;
  bool met() const { return target_met && minimum_met; }
};

struct En17037Result {
  std::size_t daylight_hours = 0, points = 0;
  std::array<En17037LevelResult, 3> levels;  // minimum, medium, high
  std::string achieved;                      // the highest level met, or "none"
};

// EN 17037 by illuminance over the counted hours of `daylight_hours`.
En17037Result en17037_daylight_provision(const HourlyIlluminance& illuminance, const AnalysisHours& daylight_hours,
                                         const En17037Options& options = {});

struct En17037DaylightFactorResult {
  std::string level;
  double target_df = 0, minimum_df = 0;        // %: D_T and D_TM for the site
  double target_share = 0, minimum_share = 0;  // share of points reaching each
  bool met = false;
};
// EN 17037 by daylight factor: per level, the share of points with D >= D_T and
// D >= D_TM, met when they reach the plane fractions. `daylight_factor` in %.
std::array<En17037DaylightFactorResult, 3> en17037_daylight_factor(const std::vector<float>& daylight_factor,
                                                                   double median_diffuse,
                                                                   const En17037Options& options = {});

// Per counted hour, the illuminance reached by `fraction` of the points: the
// ceil(fraction N)-th largest (fraction 0.5: the plane's median as EN 17037 reads it).
std::vector<float> hourly_illuminance_reached(const HourlyIlluminance& illuminance, const AnalysisHours& hours,
                                              double fraction);

struct AnnualMetricsOptions {
  double da_threshold = 300;
  double sda_threshold = 300, sda_fraction = 0.5;  // E >= threshold for >= fraction of the hours
  double ase_threshold = 1000, ase_hours = 250;    // direct sun > threshold for > hours
  double udi_low = 100, udi_high = 3000;           // useful: low <= E <= high
  double blinds_sun_threshold = 1000;              // direct sun >= this ...
  double blinds_point_fraction = 0.02;             // ... at more than this share of points closes them
  En17037Options en17037;
};

// What the metrics are computed from. `total` and `occupied` are required; the rest
// may be null.
struct AnnualInputs {
  // Every source (sun, sky, ground), interreflected, blinds open.
  const HourlyIlluminance* total = nullptr;
  // The sun alone, zero bounce, window transmittance, blinds open: ASE and the blinds
  // rule. Null: no ASE and no blinds.
  const HourlyIlluminance* direct_sun = nullptr;
  // The illuminance with the blinds closed, or when null and blinds_transmittance >= 0,
  // total x blinds_transmittance (cruder: it keeps the sun patches, dimmed). Neither:
  // no blinds.
  const HourlyIlluminance* blinds_closed = nullptr;
  double blinds_transmittance = -1;
  // LM-83's analysis hours (occupied_hours): DA, cDA, UDI, sDA, ASE.
  const AnalysisHours* occupied = nullptr;
  // EN 17037's daylight hours (en17037_daylight_hours); null: EN 17037 not evaluated.
  const AnalysisHours* daylight_hours = nullptr;
};

struct PointMetrics {
  float da = 0, cda = 0;                            // shares of the analysis hours
  float udi_low = 0, udi_useful = 0, udi_high = 0;  // sum to 1
  std::uint32_t sda_hours = 0;                      // hours with E >= sda_threshold
  bool sda_met = false;
  std::uint32_t ase_hours = 0;  // hours with direct sun > ase_threshold
  bool ase_exceeded = false;
};

struct GridMetrics {
  std::size_t points = 0, analysis_hours = 0;
  double sda = 0;  // share of points meeting sDA
  bool ase_computed = false;
  double ase = 0;  // share of points exceeding ASE; 0 when not computed
  double mean_da = 0, mean_cda = 0;
  double mean_udi_low = 0, mean_udi_useful = 0, mean_udi_high = 0;
  bool blinds = false;                  // LM-83's blinds rule was applied
  std::size_t blinds_closed_hours = 0;  // analysis hours the blinds were closed
  std::optional<En17037Result> en17037;
  std::vector<std::string> notes;  // what was and was not done (no blinds, no ASE, ...)
};

// DA, cDA, UDI and sDA from the total illuminance with LM-83's blinds applied when
// given; ASE from the direct sun; EN 17037 from the blinds-open total over the
// daylight hours. `per_point` (optional) receives one entry per point. Throws
// std::invalid_argument for sizes that disagree, no point, no analysis hour, a
// negative or non-finite illuminance (naming its hour and point) or options out of
// range.
GridMetrics annual_metrics(const AnnualInputs& inputs, const AnnualMetricsOptions& options = {},
                           std::vector<PointMetrics>* per_point = nullptr);

}  // namespace dynrad::rad
