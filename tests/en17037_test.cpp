// EN 17037 daylight levels (radiosity/climate/annual_metrics.h) on hand-built planes and
// years: every level at its edges, the daylight hours, the median diffuse illuminance.
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

// The bright and dim planes: annual_metrics_support.h.

TEST(En17037, EveryLevelAtItsEdges) {
  const HourlyIlluminance e = planes({kBright});
  const En17037Result r = en17037_daylight_provision(e, all_hours(1));
  EXPECT_EQ(r.achieved, "high");
  for (const En17037LevelResult& l : r.levels) {
    EXPECT_TRUE(l.met()) << l.level;
    EXPECT_DOUBLE_EQ(l.target_hours, 1.0);
  }
  EXPECT_EQ(hourly_illuminance_reached(e, all_hours(1), 0.5), std::vector<float>{750.0f});
  EXPECT_EQ(hourly_illuminance_reached(e, all_hours(1), 0.95), std::vector<float>{500.0f});

  // One point less at 750: the high target is reached over 45% only.
  std::vector<float> short_of_high = kBright;
  short_of_high[9] = 749.0f;
  const En17037Result below = en17037_daylight_provision(planes({short_of_high}), all_hours(1));
  EXPECT_EQ(below.achieved, "medium");
  EXPECT_FALSE(below.levels[2].target_met);
  EXPECT_TRUE(below.levels[2].minimum_met);
}

TEST(En17037, HalfTheDaylightHoursPassesAndLessFails) {
  // Two bright and two dim hours: every level reached for exactly 50% of the hours.
  const En17037Result half = en17037_daylight_provision(planes({kBright, kDim, kBright, kDim}), all_hours(4));
  EXPECT_EQ(half.achieved, "high");
  EXPECT_DOUBLE_EQ(half.levels[2].target_hours, 0.5);
  EXPECT_DOUBLE_EQ(half.levels[0].target_hours, 1.0);

  // Two bright of five: 40% for medium and high; the minimum level every hour.
  const En17037Result less = en17037_daylight_provision(planes({kBright, kDim, kBright, kDim, kDim}), all_hours(5));
  EXPECT_EQ(less.achieved, "minimum");
  EXPECT_TRUE(less.levels[0].met());
  EXPECT_FALSE(less.levels[1].met());
  EXPECT_DOUBLE_EQ(less.levels[1].target_hours, 0.4);
  EXPECT_DOUBLE_EQ(less.levels[1].minimum_hours, 0.4);
  EXPECT_EQ(hourly_illuminance_reached(planes({kBright, kDim}), all_hours(2), 0.5),
            (std::vector<float>{750.0f, 300.0f}));

  // Hours outside the daylight hours do not count: leave out two dim ones.
  AnalysisHours daylight = all_hours(5);
  daylight.in[3] = daylight.in[4] = 0;
  const En17037Result counted = en17037_daylight_provision(planes({kBright, kDim, kBright, kDim, kDim}), daylight);
  EXPECT_EQ(counted.daylight_hours, 3u);
  EXPECT_EQ(counted.achieved, "high");
}

TEST(En17037, TargetWithoutTheMinimumIsNotALevel) {
  // Half the plane bright, half dark: the target over 50% is met, the minimum over 95%
  // is not.
  const En17037Result r = en17037_daylight_provision(planes({plane({{10, 1000.0f}, {10, 50.0f}})}), all_hours(1));
  EXPECT_EQ(r.achieved, "none");
  EXPECT_TRUE(r.levels[0].target_met);
  EXPECT_FALSE(r.levels[0].minimum_met);
  EXPECT_FALSE(r.levels[0].met());
}

TEST(En17037, CountingAgreesWithTheIlluminanceReachedByTheFraction) {
  Lcg rng(5);
  const std::size_t n_points = 37, n_hours = 200;
  HourlyIlluminance e(n_points, n_hours);
  for (float& v : e.lux) v = static_cast<float>(std::floor(1200 * rng.uniform()));  // ties on purpose
  const AnalysisHours hours = all_hours(n_hours);
  const std::vector<float> e50 = hourly_illuminance_reached(e, hours, 0.5);
  const std::vector<float> e95 = hourly_illuminance_reached(e, hours, 0.95);
  const En17037Result r = en17037_daylight_provision(e, hours);
  for (std::size_t l = 0; l < 3; ++l) {
    std::size_t target = 0, minimum = 0;
    for (std::size_t h = 0; h < n_hours; ++h) {
      target += e50[h] >= kEn17037Levels[l].target_lux;
      minimum += e95[h] >= kEn17037Levels[l].minimum_lux;
    }
    EXPECT_DOUBLE_EQ(r.levels[l].target_hours, static_cast<double>(target) / n_hours);
    EXPECT_DOUBLE_EQ(r.levels[l].minimum_hours, static_cast<double>(minimum) / n_hours);
  }
}

TEST(En17037, DaylightHoursAndMedianDiffuseOfAConstructedYear) {
  // Every value 0 to 8759 once, scattered over the year (7919 is prime to 8760).
  std::vector<double> diffuse(8760);
  for (std::size_t i = 0; i < diffuse.size(); ++i) diffuse[i] = static_cast<double>((i * 7919) % 8760);
  const AnalysisHours daylight = en17037_daylight_hours(diffuse);
  EXPECT_EQ(daylight.count(), 4380u);
  for (std::size_t i = 0; i < diffuse.size(); ++i) EXPECT_EQ(daylight.in[i] != 0, diffuse[i] >= 4380) << i;
  // The median of 4380..8759 is between 6569 and 6570, the year's 75th percentile.
  EXPECT_DOUBLE_EQ(median_diffuse_illuminance(diffuse), 6569.5);
  EXPECT_DOUBLE_EQ(median_diffuse_illuminance(diffuse, &daylight), 6569.5);

  // Given hours: the median over them, odd count.
  AnalysisHours three;
  three.in.assign(8760, 0);
  three.in[0] = three.in[1] = three.in[2] = 1;  // values 0, 7919, 7078
  EXPECT_DOUBLE_EQ(median_diffuse_illuminance(diffuse, &three), 7078.0);

  // Ties (a dark year) go to the earlier rows.
  const AnalysisHours dark = en17037_daylight_hours(std::vector<double>(8760, 0.0));
  EXPECT_EQ(dark.count(), 4380u);
  EXPECT_TRUE(dark.in[4379]);
  EXPECT_FALSE(dark.in[4380]);
}

TEST(En17037, AMissingDiffuseHourIsRefused) {
  std::vector<double> diffuse(8760, 100.0);
  diffuse[4000] = std::nan("");
  EXPECT_THROW(en17037_daylight_hours(diffuse), std::invalid_argument);
  EXPECT_THROW(median_diffuse_illuminance(diffuse), std::invalid_argument);
  diffuse[4000] = -1;
  EXPECT_THROW(en17037_daylight_hours(diffuse), std::invalid_argument);
}

TEST(En17037, DaylightFactorTargetsFollowTheMedianDiffuse) {
  EXPECT_DOUBLE_EQ(daylight_factor_target(300, 15000), 2.0);
  EXPECT_DOUBLE_EQ(daylight_factor_target(750, 15000), 5.0);
  EXPECT_THROW(daylight_factor_target(300, 0), std::invalid_argument);

  // 20 points at Ev,d,med 15 000 lx: minimum D_T 2%, D_TM 0.667%; medium 3.33% and 2%;
  // high 5% and 3.33%. 10 points at 3.4%, 9 at 2.0%, 1 at 0.1%: minimum and medium met.
  const std::vector<float> df = plane({{10, 3.4f}, {9, 2.0f}, {1, 0.1f}});
  const auto r = en17037_daylight_factor(df, 15000);
  EXPECT_NEAR(r[0].minimum_df, 100.0 / 150, 1e-12);
  EXPECT_NEAR(r[1].target_df, 500.0 / 150, 1e-12);
  EXPECT_TRUE(r[0].met);
  EXPECT_TRUE(r[1].met);
  EXPECT_FALSE(r[2].met);
  EXPECT_DOUBLE_EQ(r[2].target_share, 0.0);
  EXPECT_DOUBLE_EQ(r[1].minimum_share, 0.95);
}

}  // namespace
}  // namespace dynrad::rad
