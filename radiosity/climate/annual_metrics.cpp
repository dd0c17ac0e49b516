// Annual daylight metrics (annual_metrics.h has the definitions and their sources).
#include "radiosity/climate/annual_metrics.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace dynrad::rad {

namespace {

// The product fraction x total as an integer when it is one but for rounding: 0.55 x 100
// is 55.00000000000001 in doubles, and a ceiling of that would ask for 56 hours.
bool near_integer(double x, double& integer) {
  integer = std::round(x);
  return std::fabs(x - integer) <= 1e-9 * std::max(1.0, std::fabs(x));
}

// The smallest count k with k >= fraction x total ("at least 50% of the hours").
std::size_t count_at_least(double fraction, std::size_t total) {
  const double x = fraction * static_cast<double>(total);
  double integer;
  if (near_integer(x, integer)) return static_cast<std::size_t>(std::max(0.0, integer));
  return static_cast<std::size_t>(std::max(0.0, std::ceil(x)));
}

// The smallest count k with k > fraction x total ("more than 2% of the points").
std::size_t count_more_than(double fraction, std::size_t total) {
  const double x = fraction * static_cast<double>(total);
  double integer;
  if (near_integer(x, integer)) return static_cast<std::size_t>(std::max(0.0, integer)) + 1;
  return static_cast<std::size_t>(std::max(0.0, std::ceil(x)));
}

// Six significant digits, no trailing zeros: "1000", "2", "0.2".
std::string number_text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

void check_shape(const HourlyIlluminance& e, const char* what) {
  if (e.lux.size() != e.points * e.hours)
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(e.lux.size()) + " values for " +
                                std::to_string(e.points) + " points x " + std::to_string(e.hours) + " hours");
}

void check_same_shape(const HourlyIlluminance& e, const HourlyIlluminance& total, const char* what) {
  check_shape(e, what);
  if (e.points != total.points || e.hours != total.hours)
    throw std::invalid_argument(std::string(what) + " has " + std::to_string(e.points) + " points x " +
                                std::to_string(e.hours) + " hours, the total illuminance " +
                                std::to_string(total.points) + " x " + std::to_string(total.hours));
}

void check_fraction(double f, const char* what) {
  if (!(f > 0 && f <= 1)) throw std::invalid_argument(std::string(what) + " must lie in (0, 1]");
}

void check_positive(double x, const char* what) {
  if (!(x > 0) || !std::isfinite(x)) throw std::invalid_argument(std::string(what) + " must be a positive number");
}

[[noreturn]] void bad_value(const char* what, std::size_t hour, std::size_t point, float value) {
  throw std::invalid_argument(std::string(what) + " at hour row " + std::to_string(hour) + ", point " +
                              std::to_string(point) + " is " + std::to_string(value) +
                              "; illuminances must be finite and not negative");
}

// Throws naming the first value of row `hour` that is negative or not finite.
void check_row(const float* row, std::size_t n, std::size_t hour, const char* what) {
  for (std::size_t p = 0; p < n; ++p)
    if (!(row[p] >= 0.0f) || !std::isfinite(row[p])) bad_value(what, hour, p, row[p]);
}

bool row_ok(const float* row, std::size_t n) {
  // Branch-free accumulation so the common, valid case stays a straight loop.
  bool ok = true;
  for (std::size_t p = 0; p < n; ++p) ok &= (row[p] >= 0.0f) & (row[p] <= std::numeric_limits<float>::max());
  return ok;
}

int days_in_month(int month, bool leap) {
  static const int days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && leap ? 29 : days[month - 1];
}

bool saving_in_force(const DaylightSaving& s, int month, int day) {
  const int key = month * 100 + day, start = s.start_month * 100 + s.start_day, end = s.end_month * 100 + s.end_day;
  if (start <= end) return key >= start && key < end;
  return key >= start || key < end;  // wraps round the new year
}

}  // namespace

std::size_t AnalysisHours::count() const {
  return static_cast<std::size_t>(std::count_if(in.begin(), in.end(), [](char c) { return c != 0; }));
}

std::vector<HourEnding> year_hours(bool leap) {
  std::vector<HourEnding> rows;
  rows.reserve(leap ? 8784 : 8760);
  for (int m = 1; m <= 12; ++m)
    for (int d = 1; d <= days_in_month(m, leap); ++d)
      for (int h = 1; h <= 24; ++h) rows.push_back({m, d, h});
  return rows;
}

AnalysisHours occupied_hours(const std::vector<HourEnding>& rows, int first_hour, int last_hour,
                             const DaylightSaving* saving) {
  if (!(0 <= first_hour && first_hour < last_hour && last_hour <= 24))
    throw std::invalid_argument("occupied hours must satisfy 0 <= first < last <= 24; got " +
                                std::to_string(first_hour) + " to " + std::to_string(last_hour));
  AnalysisHours result;
  result.in.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const HourEnding& r = rows[i];
    if (r.month < 1 || r.month > 12 || r.day < 1 || r.day > days_in_month(r.month, true) || r.hour < 1 || r.hour > 24)
      throw std::invalid_argument("row " + std::to_string(i) + " is not a month, day and hour ending 1-24: " +
                                  std::to_string(r.month) + "/" + std::to_string(r.day) + " " + std::to_string(r.hour));
    // The row covers (hour-1):00 to hour:00 standard time; on saving days the clocks
    // read one hour more. It counts when its whole hour lies within the clock period.
    const int clock_end = r.hour + (saving && saving_in_force(*saving, r.month, r.day) ? 1 : 0);
    result.in[i] = clock_end - 1 >= first_hour && clock_end <= last_hour;
  }
  auto two = [](int h) { return (h < 10 ? "0" : "") + std::to_string(h) + ":00"; };
  result.description = two(first_hour) + "-" + two(last_hour) +
                       (saving ? " local clock time (daylight saving applied)" : " local standard time") + ", " +
                       std::to_string(result.count()) + " hours";
  return result;
}

AnalysisHours en17037_daylight_hours(const std::vector<double>& diffuse_horizontal, std::size_t count) {
  const std::size_t n = diffuse_horizontal.size();
  // A NaN would also break the ordering below (it compares neither way).
  for (std::size_t i = 0; i < n; ++i)
    if (!(diffuse_horizontal[i] >= 0) || !std::isfinite(diffuse_horizontal[i]))
      throw std::invalid_argument("diffuse horizontal illuminance at row " + std::to_string(i) + " is " +
                                  std::to_string(diffuse_horizontal[i]) +
                                  "; fill missing hours (e.g. from the radiation by a luminous efficacy model)");
  if (count == 0) count = n / 2;
  if (count > n)
    throw std::invalid_argument("asked for " + std::to_string(count) + " daylight hours of " + std::to_string(n));
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  // A strict total order (value down, then row up) makes the choice among equal values
  // deterministic: the earlier rows win.
  auto brighter = [&](std::size_t a, std::size_t b) {
    if (diffuse_horizontal[a] != diffuse_horizontal[b]) return diffuse_horizontal[a] > diffuse_horizontal[b];
    return a < b;
  };
  if (count < n)
    std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(), brighter);
  AnalysisHours result;
  result.in.assign(n, 0);
  for (std::size_t i = 0; i < count; ++i) result.in[order[i]] = 1;
  result.description = "EN 17037 daylight hours: the " + std::to_string(count) + " of " + std::to_string(n) +
                       " hours of highest diffuse horizontal illuminance";
  return result;
}

double median_diffuse_illuminance(const std::vector<double>& diffuse_horizontal, const AnalysisHours* daylight_hours) {
  AnalysisHours own;
  if (!daylight_hours) {
    own = en17037_daylight_hours(diffuse_horizontal);
    daylight_hours = &own;
  }
  if (daylight_hours->in.size() != diffuse_horizontal.size())
    throw std::invalid_argument("daylight hours cover " + std::to_string(daylight_hours->in.size()) +
                                " rows, the diffuse illuminance " + std::to_string(diffuse_horizontal.size()));
  std::vector<double> values;
  for (std::size_t i = 0; i < diffuse_horizontal.size(); ++i) {
    if (!daylight_hours->in[i]) continue;
    if (!(diffuse_horizontal[i] >= 0) || !std::isfinite(diffuse_horizontal[i]))
      throw std::invalid_argument("diffuse horizontal illuminance at row " + std::to_string(i) + " is " +
                                  std::to_string(diffuse_horizontal[i]) + "; it must be finite and not negative");
    values.push_back(diffuse_horizontal[i]);
  }
  if (values.empty()) throw std::invalid_argument("no daylight hour to take the median over");
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

double daylight_factor_target(double lux, double median_diffuse) {
  check_positive(median_diffuse, "the median diffuse illuminance");
  return 100.0 * lux / median_diffuse;
}

En17037Result en17037_daylight_provision(const HourlyIlluminance& illuminance, const AnalysisHours& daylight_hours,
                                         const En17037Options& options) {
  check_shape(illuminance, "illuminance");
  check_fraction(options.target_plane_fraction, "the target's plane fraction");
  check_fraction(options.minimum_plane_fraction, "the minimum's plane fraction");
  check_fraction(options.time_fraction, "the time fraction");
  if (daylight_hours.in.size() != illuminance.hours)
    throw std::invalid_argument("daylight hours cover " + std::to_string(daylight_hours.in.size()) +
                                " rows, the illuminance " + std::to_string(illuminance.hours));
  const std::size_t n = illuminance.points;
  if (n == 0) throw std::invalid_argument("EN 17037 needs at least one point");

  const std::size_t target_points = count_at_least(options.target_plane_fraction, n);
  const std::size_t minimum_points = count_at_least(options.minimum_plane_fraction, n);
  std::array<std::size_t, 3> target_hours{}, minimum_hours{};
  std::size_t hours = 0;
  for (std::size_t h = 0; h < illuminance.hours; ++h) {
    if (!daylight_hours.in[h]) continue;
    ++hours;
    const float* row = illuminance.hour(h);
    if (!row_ok(row, n)) check_row(row, n, h, "illuminance");
    for (std::size_t l = 0; l < kEn17037Levels.size(); ++l) {
      const double target = kEn17037Levels[l].target_lux, minimum = kEn17037Levels[l].minimum_lux;
      std::size_t reach_target = 0, reach_minimum = 0;
      for (std::size_t p = 0; p < n; ++p) {
        reach_target += row[p] >= target;
        reach_minimum += row[p] >= minimum;
      }
      target_hours[l] += reach_target >= target_points;
      minimum_hours[l] += reach_minimum >= minimum_points;
    }
  }
  if (hours == 0) throw std::invalid_argument("EN 17037 needs at least one daylight hour");

  En17037Result result;
  result.daylight_hours = hours;
  result.points = n;
  result.achieved = "none";
  const std::size_t hours_needed = count_at_least(options.time_fraction, hours);
  for (std::size_t l = 0; l < kEn17037Levels.size(); ++l) {
    En17037LevelResult& r = result.levels[l];
    r.level = kEn17037Levels[l].name;
    r.target_lux = kEn17037Levels[l].target_lux;
    r.minimum_lux = kEn17037Levels[l].minimum_lux;
    r.target_hours = static_cast<double>(target_hours[l]) / static_cast<double>(hours);
    r.minimum_hours = static_cast<double>(minimum_hours[l]) / static_cast<double>(hours);
    r.target_met = target_hours[l] >= hours_needed;
    r.minimum_met = minimum_hours[l] >= hours_needed;
    // Levels rise in both illuminances, so a level met implies the ones below it.
    if (r.met()) result.achieved = r.level;
  }
  return result;
}

std::array<En17037DaylightFactorResult, 3> en17037_daylight_factor(const std::vector<float>& daylight_factor,
                                                                   double median_diffuse,
                                                                   const En17037Options& options) {
  check_fraction(options.target_plane_fraction, "the target's plane fraction");
  check_fraction(options.minimum_plane_fraction, "the minimum's plane fraction");
  const std::size_t n = daylight_factor.size();
  if (n == 0) throw std::invalid_argument("EN 17037 needs at least one point");
  check_row(daylight_factor.data(), n, 0, "daylight factor");
  std::array<En17037DaylightFactorResult, 3> result;
  for (std::size_t l = 0; l < kEn17037Levels.size(); ++l) {
    En17037DaylightFactorResult& r = result[l];
    r.level = kEn17037Levels[l].name;
    r.target_df = daylight_factor_target(kEn17037Levels[l].target_lux, median_diffuse);
    r.minimum_df = daylight_factor_target(kEn17037Levels[l].minimum_lux, median_diffuse);
    std::size_t reach_target = 0, reach_minimum = 0;
    for (float d : daylight_factor) {
      reach_target += d >= r.target_df;
      reach_minimum += d >= r.minimum_df;
    }
    r.target_share = static_cast<double>(reach_target) / static_cast<double>(n);
    r.minimum_share = static_cast<double>(reach_minimum) / static_cast<double>(n);
    r.met = reach_target >= count_at_least(options.target_plane_fraction, n) &&
            reach_minimum >= count_at_least(options.minimum_plane_fraction, n);
  }
  return result;
}

std::vector<float> hourly_illuminance_reached(const HourlyIlluminance& illuminance, const AnalysisHours& hours,
                                              double fraction) {
  check_shape(illuminance, "illuminance");
  check_fraction(fraction, "the fraction of points");
  if (hours.in.size() != illuminance.hours)
    throw std::invalid_argument("analysis hours cover " + std::to_string(hours.in.size()) + " rows, the illuminance " +
                                std::to_string(illuminance.hours));
  const std::size_t n = illuminance.points;
  std::vector<float> result;
  if (n == 0) return result;
  const std::size_t k = std::max<std::size_t>(1, count_at_least(fraction, n));  // the k-th largest
  std::vector<float> scratch(n);
  for (std::size_t h = 0; h < illuminance.hours; ++h) {
    if (!hours.in[h]) continue;
    std::copy(illuminance.hour(h), illuminance.hour(h) + n, scratch.begin());
    std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(k - 1), scratch.end(),
                     std::greater<float>());
    result.push_back(scratch[k - 1]);
  }
  return result;
}

GridMetrics annual_metrics(const AnnualInputs& inputs, const AnnualMetricsOptions& options,
                           std::vector<PointMetrics>* per_point) {
  if (!inputs.total) throw std::invalid_argument("annual metrics need the total illuminance");
  if (!inputs.occupied) throw std::invalid_argument("annual metrics need the analysis hours");
  const HourlyIlluminance& total = *inputs.total;
  check_shape(total, "the total illuminance");
  if (inputs.direct_sun) check_same_shape(*inputs.direct_sun, total, "the direct sun illuminance");
  if (inputs.blinds_closed) check_same_shape(*inputs.blinds_closed, total, "the closed-blinds illuminance");
  if (inputs.occupied->in.size() != total.hours)
    throw std::invalid_argument("analysis hours cover " + std::to_string(inputs.occupied->in.size()) +
                                " rows, the illuminance " + std::to_string(total.hours));
  check_positive(options.da_threshold, "the DA threshold");
  check_positive(options.sda_threshold, "the sDA threshold");
  check_fraction(options.sda_fraction, "the sDA time fraction");
  check_positive(options.ase_threshold, "the ASE threshold");
  if (!(options.ase_hours >= 0) || !std::isfinite(options.ase_hours))
    throw std::invalid_argument("the ASE hours must be a number not below 0");
  if (!(options.udi_low >= 0 && options.udi_low < options.udi_high) || !std::isfinite(options.udi_high))
    throw std::invalid_argument("the UDI bounds must satisfy 0 <= low < high");
  check_positive(options.blinds_sun_threshold, "the blinds' direct sun threshold");
  check_fraction(options.blinds_point_fraction, "the blinds' point fraction");
  if (!inputs.blinds_closed && inputs.blinds_transmittance > 1)
    throw std::invalid_argument("the blinds' transmittance must lie in [0, 1]");

  const std::size_t n = total.points;
  if (n == 0) throw std::invalid_argument("annual metrics need at least one point");
  const std::size_t analysis_hours = inputs.occupied->count();
  if (analysis_hours == 0) throw std::invalid_argument("annual metrics need at least one analysis hour");

  GridMetrics grid;
  grid.points = n;
  grid.analysis_hours = analysis_hours;
  const bool closed_given = inputs.blinds_closed || inputs.blinds_transmittance >= 0;
  grid.blinds = closed_given && inputs.direct_sun;
  grid.ase_computed = inputs.direct_sun != nullptr;
  if (closed_given && !inputs.direct_sun)
    grid.notes.push_back("no direct sun illuminance: the blinds rule cannot run, sDA is without blinds");
  else if (!closed_given)
    grid.notes.push_back("no closed-blinds illuminance: no blinds; the sDA is the DA-based share, not LM-83's");
  else if (!inputs.blinds_closed)
    grid.notes.push_back("blinds closed by scaling the illuminance by " + number_text(inputs.blinds_transmittance));
  if (!inputs.direct_sun) grid.notes.push_back("no direct sun illuminance: ASE not computed");

  // Per point counters over the analysis hours. useful = hours - low - high, so the
  // three UDI shares sum to 1 exactly.
  std::vector<std::uint32_t> da(n, 0), sda(n, 0), low(n, 0), high(n, 0), ase(n, 0);
  std::vector<double> cda(n, 0.0);
  const std::size_t sun_points = count_more_than(options.blinds_point_fraction, n);
  const double da_threshold = options.da_threshold, sda_threshold = options.sda_threshold;
  const double udi_low = options.udi_low, udi_high = options.udi_high, ase_threshold = options.ase_threshold;

  for (std::size_t h = 0; h < total.hours; ++h) {
    if (!inputs.occupied->in[h]) continue;
    const float* open = total.hour(h);
    if (!row_ok(open, n)) check_row(open, n, h, "the total illuminance");
    const float* sun = inputs.direct_sun ? inputs.direct_sun->hour(h) : nullptr;
    if (sun) {
      if (!row_ok(sun, n)) check_row(sun, n, h, "the direct sun illuminance");
      for (std::size_t p = 0; p < n; ++p) ase[p] += sun[p] > ase_threshold;
    }

    const float* row = open;
    float scale = 1.0f;
    if (grid.blinds) {
      std::size_t in_sun = 0;
      for (std::size_t p = 0; p < n; ++p) in_sun += sun[p] >= options.blinds_sun_threshold;
      if (in_sun >= sun_points) {
        ++grid.blinds_closed_hours;
        if (inputs.blinds_closed) {
          row = inputs.blinds_closed->hour(h);
          if (!row_ok(row, n)) check_row(row, n, h, "the closed-blinds illuminance");
        } else {
          scale = static_cast<float>(inputs.blinds_transmittance);
        }
      }
    }

    for (std::size_t p = 0; p < n; ++p) {
      const float e = row[p] * scale;
      da[p] += e >= da_threshold;
      sda[p] += e >= sda_threshold;
      low[p] += e < udi_low;
      high[p] += e > udi_high;
      cda[p] += e >= da_threshold ? 1.0 : e / da_threshold;
    }
  }

  const std::size_t sda_needed = count_at_least(options.sda_fraction, analysis_hours);
  const double hours = static_cast<double>(analysis_hours);
  std::size_t sda_points = 0, ase_points = 0;
  double sum_da = 0, sum_cda = 0, sum_low = 0, sum_high = 0;
  if (per_point) per_point->assign(n, PointMetrics{});
  for (std::size_t p = 0; p < n; ++p) {
    const bool sda_met = sda[p] >= sda_needed;
    const bool ase_exceeded = grid.ase_computed && static_cast<double>(ase[p]) > options.ase_hours;
    sda_points += sda_met;
    ase_points += ase_exceeded;
    sum_da += da[p];
    sum_cda += cda[p];
    sum_low += low[p];
    sum_high += high[p];
    if (per_point) {
      PointMetrics& m = (*per_point)[p];
      m.da = static_cast<float>(da[p] / hours);
      m.cda = static_cast<float>(cda[p] / hours);
      m.udi_low = static_cast<float>(low[p] / hours);
      m.udi_high = static_cast<float>(high[p] / hours);
      m.udi_useful = static_cast<float>(static_cast<double>(analysis_hours - low[p] - high[p]) / hours);
      m.sda_hours = sda[p];
      m.sda_met = sda_met;
      m.ase_hours = ase[p];
      m.ase_exceeded = ase_exceeded;
    }
  }
  const double point_hours = hours * static_cast<double>(n);
  grid.sda = static_cast<double>(sda_points) / static_cast<double>(n);
  grid.ase = static_cast<double>(ase_points) / static_cast<double>(n);
  grid.mean_da = sum_da / point_hours;
  grid.mean_cda = sum_cda / point_hours;
  grid.mean_udi_low = sum_low / point_hours;
  grid.mean_udi_high = sum_high / point_hours;
  grid.mean_udi_useful = (point_hours - sum_low - sum_high) / point_hours;
  if (grid.blinds)
    grid.notes.push_back("LM-83 blinds: closed in " + std::to_string(grid.blinds_closed_hours) + " of " +
                         std::to_string(analysis_hours) +
                         " analysis hours (direct sun >= " + number_text(options.blinds_sun_threshold) +
                         " lx at more than " + number_text(options.blinds_point_fraction * 100) + "% of the points)");

  if (inputs.daylight_hours) {
    grid.en17037 = en17037_daylight_provision(total, *inputs.daylight_hours, options.en17037);
  } else {
    grid.notes.push_back("no daylight hours: EN 17037 not evaluated");
  }
  return grid;
}

}  // namespace dynrad::rad
