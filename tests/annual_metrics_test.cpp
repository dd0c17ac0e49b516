// Annual daylight metrics (radiosity/climate/annual_metrics.h) on hand-built hours and
// planes whose every metric is known, including each threshold's edge.
// EN 17037's levels are in en17037_test.cpp.
#include "annual_metrics_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace dynrad::rad {
namespace {

using namespace annual_test;


TEST(AnnualHours, EightToEighteenIsRowsNineToEighteenTenADay) {
  const std::vector<HourEnding> rows = year_hours();
  ASSERT_EQ(rows.size(), 8760u);
  const AnalysisHours hours = occupied_hours(rows);
  EXPECT_EQ(hours.count(), 3650u);
  for (std::size_t day = 0; day < 365; ++day) {
    std::size_t in_day = 0;
    for (std::size_t h = 0; h < 24; ++h) {
      const std::size_t i = day * 24 + h;
      const bool expected = rows[i].hour >= 9 && rows[i].hour <= 18;
      EXPECT_EQ(hours.in[i] != 0, expected)
          << "month " << rows[i].month << " day " << rows[i].day << " hour " << rows[i].hour;
      in_day += hours.in[i] != 0;
    }
    EXPECT_EQ(in_day, 10u);
  }
  EXPECT_NE(hours.description.find("08:00-18:00 local standard time"), std::string::npos) << hours.description;
}

TEST(AnnualHours, LeapYearHas3660) {
  const std::vector<HourEnding> rows = year_hours(true);
  EXPECT_EQ(rows.size(), 8784u);
  EXPECT_EQ(occupied_hours(rows).count(), 3660u);
}

TEST(AnnualHours, OtherPeriodsCountWholeHours) {
  const std::vector<HourEnding> rows = year_hours();
  EXPECT_EQ(occupied_hours(rows, 0, 24).count(), 8760u);
  EXPECT_EQ(occupied_hours(rows, 9, 17).count(), 365u * 8);
  const AnalysisHours noon = occupied_hours(rows, 12, 13);  // the row ending at 13:00 only
  EXPECT_EQ(noon.count(), 365u);
  EXPECT_TRUE(noon.in[12]);  // 1 January, hour-ending 13 is row 12
}

TEST(AnnualHours, DaylightSavingShiftsTheRowsAnHourEarlier) {
  const std::vector<HourEnding> rows = year_hours();
  const DaylightSaving saving{3, 29, 10, 25};  // in force 29 March to 24 October
  const AnalysisHours hours = occupied_hours(rows, 8, 18, &saving);
  EXPECT_EQ(hours.count(), 3650u);
  auto row = [&](int month, int day, int hour) {
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (rows[i].month == month && rows[i].day == day && rows[i].hour == hour) return i;
    return rows.size();
  };
  // Summer: 08:00-18:00 clock time is 07:00-17:00 standard time, rows 8 to 17.
  EXPECT_TRUE(hours.in[row(7, 1, 8)]);
  EXPECT_TRUE(hours.in[row(7, 1, 17)]);
  EXPECT_FALSE(hours.in[row(7, 1, 18)]);
  EXPECT_FALSE(hours.in[row(7, 1, 7)]);
  // The first day is shifted, the end day is not (the clocks go back in its night).
  EXPECT_TRUE(hours.in[row(3, 29, 8)]);
  EXPECT_FALSE(hours.in[row(3, 28, 8)]);
  EXPECT_TRUE(hours.in[row(10, 24, 8)]);
  EXPECT_FALSE(hours.in[row(10, 25, 8)]);
  EXPECT_TRUE(hours.in[row(10, 25, 18)]);
  EXPECT_NE(hours.description.find("daylight saving"), std::string::npos);

  // Southern hemisphere: from October to April, across the new year.
  const DaylightSaving south{10, 6, 4, 7};
  const AnalysisHours southern = occupied_hours(rows, 8, 18, &south);
  EXPECT_TRUE(southern.in[row(1, 15, 8)]);
  EXPECT_FALSE(southern.in[row(1, 15, 18)]);
  EXPECT_TRUE(southern.in[row(6, 15, 18)]);
  EXPECT_FALSE(southern.in[row(6, 15, 8)]);
}

TEST(AnnualHours, RefusesAPeriodOrRowOutOfRange) {
  const std::vector<HourEnding> rows = year_hours();
  EXPECT_THROW(occupied_hours(rows, 18, 8), std::invalid_argument);
  EXPECT_THROW(occupied_hours(rows, 8, 25), std::invalid_argument);
  EXPECT_THROW(occupied_hours({{1, 1, 0}}), std::invalid_argument);  // hours end 1-24
  EXPECT_THROW(occupied_hours({{13, 1, 9}}), std::invalid_argument);
}

// --- DA, cDA, UDI ---------------------------------------------------------------------

TEST(AnnualMetrics, DaCountsExactly300AndCdaGivesPartialCredit) {
  const HourlyIlluminance e = one_point({300.0f, 299.0f, 150.0f, 0.0f, 10000.0f});
  const AnalysisHours hours = all_hours(5);
  std::vector<PointMetrics> points;
  const GridMetrics g = annual_metrics({&e, nullptr, nullptr, -1, &hours, nullptr}, {}, &points);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_FLOAT_EQ(points[0].da, 2.0f / 5);  // 300 and 10000
  EXPECT_FLOAT_EQ(points[0].cda, static_cast<float>((1 + 299.0 / 300 + 0.5 + 0 + 1) / 5));
  EXPECT_DOUBLE_EQ(g.mean_da, 2.0 / 5);
  EXPECT_NEAR(g.mean_cda, (1 + 299.0 / 300 + 0.5 + 0 + 1) / 5, 1e-12);
}

TEST(AnnualMetrics, UdiBoundsBelongToTheUsefulBand) {
  const HourlyIlluminance e = one_point({99.9f, 100.0f, 3000.0f, 3000.5f, 0.0f});
  const AnalysisHours hours = all_hours(5);
  std::vector<PointMetrics> points;
  annual_metrics({&e, nullptr, nullptr, -1, &hours, nullptr}, {}, &points);
  EXPECT_FLOAT_EQ(points[0].udi_low, 2.0f / 5);
  EXPECT_FLOAT_EQ(points[0].udi_useful, 2.0f / 5);
  EXPECT_FLOAT_EQ(points[0].udi_high, 1.0f / 5);

  // The original paper's 2000 lx upper bound, as an option.
  AnnualMetricsOptions options;
  options.udi_high = 2000;
  annual_metrics({&e, nullptr, nullptr, -1, &hours, nullptr}, options, &points);
  EXPECT_FLOAT_EQ(points[0].udi_useful, 1.0f / 5);
  EXPECT_FLOAT_EQ(points[0].udi_high, 2.0f / 5);
}

TEST(AnnualMetrics, UdiSharesSumToOnePerPointAndMeansAreThePointsMeans) {
  Lcg rng(17);
  HourlyIlluminance e(57, 300);
  for (float& v : e.lux) v = static_cast<float>(6000 * rng.uniform() * rng.uniform());
  AnalysisHours hours = all_hours(300);
  for (std::size_t h = 0; h < 300; h += 7) hours.in[h] = 0;
  std::vector<PointMetrics> points;
  const GridMetrics g = annual_metrics({&e, nullptr, nullptr, -1, &hours, nullptr}, {}, &points);
  double low = 0, useful = 0, high = 0, da = 0;
  for (const PointMetrics& m : points) {
    EXPECT_NEAR(m.udi_low + m.udi_useful + m.udi_high, 1.0, 1e-6);
    low += m.udi_low;
    useful += m.udi_useful;
    high += m.udi_high;
    da += m.da;
  }
  EXPECT_NEAR(g.mean_udi_low + g.mean_udi_useful + g.mean_udi_high, 1.0, 1e-12);
  EXPECT_NEAR(g.mean_udi_low, low / 57, 1e-6);
  EXPECT_NEAR(g.mean_udi_useful, useful / 57, 1e-6);
  EXPECT_NEAR(g.mean_udi_high, high / 57, 1e-6);
  EXPECT_NEAR(g.mean_da, da / 57, 1e-6);
}

// --- sDA ------------------------------------------------------------------------------

TEST(AnnualMetrics, SdaNeedsAtLeastHalfTheHoursAtOrAbove300) {
  // Over LM-83's 3650 hours: one point at 300 lx for exactly 1825 (50%), one for 1824.
  const std::vector<HourEnding> rows = year_hours();
  const AnalysisHours hours = occupied_hours(rows);
  HourlyIlluminance e(2, rows.size());
  std::size_t seen = 0;
  for (std::size_t h = 0; h < rows.size(); ++h) {
    if (!hours.in[h]) continue;
    e.at(h, 0) = seen < 1825 ? 300.0f : 299.9f;
    e.at(h, 1) = seen < 1824 ? 300.0f : 299.9f;
    ++seen;
  }
  std::vector<PointMetrics> points;
  const GridMetrics g = annual_metrics({&e, nullptr, nullptr, -1, &hours, nullptr}, {}, &points);
  EXPECT_EQ(g.analysis_hours, 3650u);
  EXPECT_EQ(points[0].sda_hours, 1825u);
  EXPECT_TRUE(points[0].sda_met);
  EXPECT_EQ(points[1].sda_hours, 1824u);
  EXPECT_FALSE(points[1].sda_met);
  EXPECT_DOUBLE_EQ(g.sda, 0.5);
  EXPECT_TRUE(has_note(g, "no closed-blinds illuminance")) << "the sDA without blinds must say so";
}

TEST(AnnualMetrics, SdaOverAnOddNumberOfHoursRoundsTheHalfUp) {
  // 5 hours: at least 50% is 3 hours (2.5 up).
  HourlyIlluminance two(2, 5);
  for (std::size_t h = 0; h < 5; ++h) {
    two.at(h, 0) = h < 3 ? 300.0f : 0.0f;
    two.at(h, 1) = h < 2 ? 300.0f : 0.0f;
  }
  const AnalysisHours hours = all_hours(5);
  std::vector<PointMetrics> points;
  annual_metrics({&two, nullptr, nullptr, -1, &hours, nullptr}, {}, &points);
  EXPECT_TRUE(points[0].sda_met);
  EXPECT_FALSE(points[1].sda_met);
}

TEST(AnnualMetrics, SdaFractionIsNotUndoneByRounding) {
  // 0.55 x 100 is 55.00000000000001 in doubles: 55 hours of 100 must still be 55%.
  HourlyIlluminance e(2, 100);
  for (std::size_t h = 0; h < 100; ++h) {
    e.at(h, 0) = h < 55 ? 300.0f : 0.0f;
    e.at(h, 1) = h < 54 ? 300.0f : 0.0f;
  }
  const AnalysisHours hours = all_hours(100);
  AnnualMetricsOptions options;
  options.sda_fraction = 0.55;
  std::vector<PointMetrics> points;
  annual_metrics({&e, nullptr, nullptr, -1, &hours, nullptr}, options, &points);
  EXPECT_TRUE(points[0].sda_met);
  EXPECT_FALSE(points[1].sda_met);
}

// --- ASE ------------------------------------------------------------------------------

TEST(AnnualMetrics, AseNeedsMoreThan1000LuxForMoreThan250Hours) {
  const std::size_t n_hours = 300;
  HourlyIlluminance total(4, n_hours), sun(4, n_hours);
  std::fill(total.lux.begin(), total.lux.end(), 500.0f);
  for (std::size_t h = 0; h < n_hours; ++h) {
    sun.at(h, 0) = h < 250 ? 1001.0f : 0.0f;  // exactly 250 hours above: not more than 250
    sun.at(h, 1) = h < 251 ? 1001.0f : 0.0f;  // 251: exceeded
    sun.at(h, 2) = 1000.0f;                   // exactly 1000 is not above 1000
    sun.at(h, 3) = 50000.0f;
  }
  const AnalysisHours hours = all_hours(n_hours);
  std::vector<PointMetrics> points;
  const GridMetrics g = annual_metrics({&total, &sun, nullptr, -1, &hours, nullptr}, {}, &points);
  EXPECT_TRUE(g.ase_computed);
  EXPECT_EQ(points[0].ase_hours, 250u);
  EXPECT_FALSE(points[0].ase_exceeded);
  EXPECT_EQ(points[1].ase_hours, 251u);
  EXPECT_TRUE(points[1].ase_exceeded);
  EXPECT_EQ(points[2].ase_hours, 0u);
  EXPECT_FALSE(points[2].ase_exceeded);
  EXPECT_TRUE(points[3].ase_exceeded);
  EXPECT_DOUBLE_EQ(g.ase, 0.5);
}

TEST(AnnualMetrics, AseCountsOnlyAnalysisHours) {
  HourlyIlluminance total = repeated_plane({500.0f}, 600), sun = repeated_plane({2000.0f}, 600);
  AnalysisHours hours = all_hours(600);
  for (std::size_t h = 250; h < 600; ++h) hours.in[h] = 0;  // 250 analysis hours of sun
  std::vector<PointMetrics> points;
  GridMetrics g = annual_metrics({&total, &sun, nullptr, -1, &hours, nullptr}, {}, &points);
  EXPECT_EQ(points[0].ase_hours, 250u);
  EXPECT_DOUBLE_EQ(g.ase, 0.0);
  hours.in[300] = 1;
  g = annual_metrics({&total, &sun, nullptr, -1, &hours, nullptr}, {}, &points);
  EXPECT_DOUBLE_EQ(g.ase, 1.0);
}

TEST(AnnualMetrics, WithoutDirectSunThereIsNoAseAndTheOutputSaysSo) {
  const HourlyIlluminance e = repeated_plane({500.0f}, 3);
  const AnalysisHours hours = all_hours(3);
  const GridMetrics g = annual_metrics({&e, nullptr, nullptr, -1, &hours, nullptr});
  EXPECT_FALSE(g.ase_computed);
  EXPECT_FALSE(g.blinds);
  EXPECT_TRUE(has_note(g, "ASE not computed"));
}

// --- LM-83's blinds -------------------------------------------------------------------

// 100 points at 500 lx, blinds closed 100 lx. Hour 0: direct sun >= 1000 at exactly 2
// points (2%, not more): open. Hour 1: at 3 points: closed. Hour 2: 3 points at 999 lx:
// open. Hour 3: not an analysis hour, 50 points in sun.
struct BlindsCase {
  HourlyIlluminance total = repeated_plane(std::vector<float>(100, 500.0f), 4);
  HourlyIlluminance closed = repeated_plane(std::vector<float>(100, 100.0f), 4);
  HourlyIlluminance sun{100, 4};
  AnalysisHours hours = all_hours(4);
  BlindsCase() {
    sun.at(0, 0) = sun.at(0, 1) = 1000.0f;
    sun.at(1, 0) = sun.at(1, 1) = sun.at(1, 2) = 1000.0f;
    sun.at(2, 0) = sun.at(2, 1) = sun.at(2, 2) = 999.0f;
    for (std::size_t p = 0; p < 50; ++p) sun.at(3, p) = 5000.0f;
    hours.in[3] = 0;
  }
};

TEST(AnnualMetrics, BlindsCloseWhenMoreThanTwoPercentOfPointsGetDirectSun) {
  const BlindsCase c;
  std::vector<PointMetrics> points;
  AnnualMetricsOptions options;
  options.sda_fraction = 0.75;  // needs 3 of the 3 hours (2.25 up)
  const GridMetrics g = annual_metrics({&c.total, &c.sun, &c.closed, -1, &c.hours, nullptr}, options, &points);
  EXPECT_TRUE(g.blinds);
  EXPECT_EQ(g.blinds_closed_hours, 1u);
  EXPECT_TRUE(has_note(g, "closed in 1 of 3 analysis hours")) << g.notes.back();
  for (const PointMetrics& m : points) {
    EXPECT_EQ(m.sda_hours, 2u);
    EXPECT_FALSE(m.sda_met);
    EXPECT_FLOAT_EQ(m.da, 2.0f / 3);
    EXPECT_FLOAT_EQ(m.cda, static_cast<float>((1 + 1 + 100.0 / 300) / 3));
  }
  EXPECT_DOUBLE_EQ(g.sda, 0.0);

  // A transmittance standing for the closed blinds gives the same here (500 x 0.2).
  const GridMetrics scaled = annual_metrics({&c.total, &c.sun, nullptr, 0.2, &c.hours, nullptr}, options, &points);
  EXPECT_EQ(scaled.blinds_closed_hours, 1u);
  EXPECT_EQ(points[50].sda_hours, 2u);
  EXPECT_TRUE(has_note(scaled, "scaling the illuminance by 0.2"));

  // Without closed-blinds illuminance the blinds stay open and the output says so.
  const GridMetrics open = annual_metrics({&c.total, &c.sun, nullptr, -1, &c.hours, nullptr}, options, &points);
  EXPECT_FALSE(open.blinds);
  EXPECT_EQ(open.blinds_closed_hours, 0u);
  EXPECT_DOUBLE_EQ(open.sda, 1.0);
  EXPECT_TRUE(has_note(open, "no blinds"));

  // Closed-blinds illuminance without direct sun: the rule cannot run.
  const GridMetrics no_sun = annual_metrics({&c.total, nullptr, &c.closed, -1, &c.hours, nullptr}, options);
  EXPECT_FALSE(no_sun.blinds);
  EXPECT_DOUBLE_EQ(no_sun.sda, 1.0);
  EXPECT_TRUE(has_note(no_sun, "blinds rule cannot run"));
}

TEST(AnnualMetrics, BlindsDoNotChangeAse) {
  BlindsCase c;
  for (std::size_t h = 0; h < 3; ++h) c.sun.at(h, 7) = 1200.0f;  // point 7 above 1000 in all 3 hours
  AnnualMetricsOptions options;
  options.ase_hours = 2;  // more than 2 of the 3 hours
  std::vector<PointMetrics> points;
  const GridMetrics g = annual_metrics({&c.total, &c.sun, &c.closed, -1, &c.hours, nullptr}, options, &points);
  EXPECT_EQ(points[7].ase_hours, 3u);
  EXPECT_TRUE(points[7].ase_exceeded);
  EXPECT_DOUBLE_EQ(g.ase, 0.01);
}

TEST(AnnualMetrics, BlindsThresholdFollowsThePointCount) {
  // 50 points: 2% is 1 point, so 1 sunlit point leaves the blinds open and 2 close them.
  HourlyIlluminance total = repeated_plane(std::vector<float>(50, 500.0f), 2);
  HourlyIlluminance sun(50, 2);
  sun.at(0, 10) = 1000.0f;
  sun.at(1, 10) = sun.at(1, 11) = 1000.0f;
  const AnalysisHours hours = all_hours(2);
  const GridMetrics g = annual_metrics({&total, &sun, nullptr, 0.1, &hours, nullptr});
  EXPECT_EQ(g.blinds_closed_hours, 1u);
}

TEST(AnnualMetrics, EvaluatesEn17037OverTheDaylightHoursFromTheBlindsOpenIlluminance) {
  const HourlyIlluminance e = planes({kBright, kBright, kDim});
  const HourlyIlluminance closed = planes({kDim, kDim, kDim});
  HourlyIlluminance sun(20, 3);
  std::fill(sun.lux.begin(), sun.lux.end(), 2000.0f);  // blinds closed every hour
  const AnalysisHours occupied = all_hours(3), daylight = all_hours(3);
  const GridMetrics g = annual_metrics({&e, &sun, &closed, -1, &occupied, &daylight});
  EXPECT_EQ(g.blinds_closed_hours, 3u);
  ASSERT_TRUE(g.en17037.has_value());
  EXPECT_EQ(g.en17037->achieved, "high");

  const GridMetrics without = annual_metrics({&e, nullptr, nullptr, -1, &occupied, nullptr});
  EXPECT_FALSE(without.en17037.has_value());
  EXPECT_TRUE(has_note(without, "EN 17037 not evaluated"));
}

// --- against a plain reference --------------------------------------------------------

TEST(AnnualMetrics, MatchesAStraightforwardReferenceOnAYear) {
  const std::vector<HourEnding> rows = year_hours();
  const AnalysisHours hours = occupied_hours(rows);
  const std::size_t n_points = 60;
  Lcg rng(2024);
  HourlyIlluminance total(n_points, rows.size()), sun(n_points, rows.size()), closed(n_points, rows.size());
  for (std::size_t h = 0; h < rows.size(); ++h) {
    const double day = rows[h].hour >= 7 && rows[h].hour <= 19 ? 1 : 0;
    const bool sunny = rng.uniform() < 0.4;
    for (std::size_t p = 0; p < n_points; ++p) {
      const double depth = 1.0 - static_cast<double>(p) / n_points;
      const float s = sunny && rng.uniform() < 0.05 * depth ? static_cast<float>(day * 4000 * rng.uniform()) : 0;
      sun.at(h, p) = s;
      total.at(h, p) = static_cast<float>(day * 1500 * depth * rng.uniform()) + s;
      closed.at(h, p) = 0.15f * total.at(h, p) - 0.1f * s;
      closed.at(h, p) = std::max(closed.at(h, p), 0.0f);
    }
  }
  std::vector<PointMetrics> points;
  const GridMetrics g = annual_metrics({&total, &sun, &closed, -1, &hours, nullptr}, {}, &points);

  // The reference: the list of analysis hours, the blinds per hour, then each point on
  // its own.
  std::vector<std::size_t> list;
  for (std::size_t h = 0; h < rows.size(); ++h)
    if (hours.in[h]) list.push_back(h);
  ASSERT_EQ(list.size(), 3650u);
  std::vector<bool> blinds_closed;
  std::size_t closed_hours = 0;
  for (std::size_t h : list) {
    std::size_t lit = 0;
    for (std::size_t p = 0; p < n_points; ++p) lit += sun.at(h, p) >= 1000;
    blinds_closed.push_back(100.0 * lit / n_points > 2.0);
    closed_hours += blinds_closed.back();
  }
  EXPECT_EQ(g.blinds_closed_hours, closed_hours);
  EXPECT_GT(closed_hours, 0u);
  std::size_t sda_points = 0, ase_points = 0;
  for (std::size_t p = 0; p < n_points; ++p) {
    std::uint32_t da = 0, low = 0, high = 0, ase = 0;
    double cda = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const float e = blinds_closed[i] ? closed.at(list[i], p) : total.at(list[i], p);
      da += e >= 300;
      cda += std::min(1.0, e / 300.0);
      low += e < 100;
      high += e > 3000;
      ase += sun.at(list[i], p) > 1000;
    }
    EXPECT_EQ(points[p].sda_hours, da) << p;
    EXPECT_FLOAT_EQ(points[p].da, static_cast<float>(da / 3650.0));
    EXPECT_NEAR(points[p].cda, cda / 3650, 1e-6);
    EXPECT_FLOAT_EQ(points[p].udi_low, static_cast<float>(low / 3650.0));
    EXPECT_FLOAT_EQ(points[p].udi_high, static_cast<float>(high / 3650.0));
    EXPECT_EQ(points[p].ase_hours, ase);
    sda_points += 2 * da >= 3650;
    ase_points += ase > 250;
  }
  EXPECT_DOUBLE_EQ(g.sda, static_cast<double>(sda_points) / n_points);
  EXPECT_DOUBLE_EQ(g.ase, static_cast<double>(ase_points) / n_points);
  EXPECT_GT(g.sda, 0.0);
  EXPECT_LT(g.sda, 1.0);
}

// --- errors ---------------------------------------------------------------------------

TEST(AnnualMetrics, RefusesInputsThatDisagreeOrAreNotIlluminances) {
  const HourlyIlluminance e = repeated_plane({100.0f, 200.0f}, 3);
  const AnalysisHours hours = all_hours(3);
  EXPECT_THROW(annual_metrics({nullptr, nullptr, nullptr, -1, &hours, nullptr}), std::invalid_argument);
  EXPECT_THROW(annual_metrics({&e, nullptr, nullptr, -1, nullptr, nullptr}), std::invalid_argument);
  const AnalysisHours four = all_hours(4);
  EXPECT_THROW(annual_metrics({&e, nullptr, nullptr, -1, &four, nullptr}), std::invalid_argument);
  const HourlyIlluminance other = repeated_plane({100.0f}, 3);
  EXPECT_THROW(annual_metrics({&e, &other, nullptr, -1, &hours, nullptr}), std::invalid_argument);
  AnalysisHours none = all_hours(3);
  std::fill(none.in.begin(), none.in.end(), 0);
  EXPECT_THROW(annual_metrics({&e, nullptr, nullptr, -1, &none, nullptr}), std::invalid_argument);
  AnnualMetricsOptions inverted;
  inverted.udi_low = 3000;
  inverted.udi_high = 100;
  EXPECT_THROW(annual_metrics({&e, nullptr, nullptr, -1, &hours, nullptr}, inverted), std::invalid_argument);

  HourlyIlluminance bad = e;
  bad.at(2, 1) = -5.0f;
  try {
    annual_metrics({&bad, nullptr, nullptr, -1, &hours, nullptr});
    FAIL() << "a negative illuminance was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("hour row 2, point 1"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace dynrad::rad