// Glass whose transmittance falls with the angle of incidence (radiosity/sources/glass.h).
#include "radiosity/sources/glass.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dynrad::rad {
namespace {

constexpr double kR0 = (1.52 - 1) * (1.52 - 1) / ((1.52 + 1) * (1.52 + 1));  // 0.0426, face on

TEST(Glass, FaceOnItPassesWhatItIsGiven) {
  for (double t : {0.0, 0.1, 0.5, 0.7, 0.88, 0.9}) EXPECT_NEAR(GlassPane(t).transmittance(1), t, 1e-12) << t;
  // Two clean surfaces and no absorption: (1 - R0) / (1 + R0), light going back and
  // forth between them.
  const GlassPane clear((1 - kR0) / (1 + kR0));
  EXPECT_NEAR(clear.internal(), 1, 1e-12);
  EXPECT_NEAR(clear.reflectance(1), 2 * kR0 / (1 + kR0), 1e-12);
  // Above what two surfaces allow: scaled, still the given value face on.
  EXPECT_NEAR(GlassPane(0.95).transmittance(1), 0.95, 1e-12);
}

TEST(Glass, ItPassesLessTheMoreObliqueTheLight) {
  for (double t : {0.5, 0.88}) {
    const GlassPane pane(t);
    double before = pane.transmittance(1);
    for (int degrees = 5; degrees <= 89; degrees += 4) {
      const double now = pane.transmittance(std::cos(degrees * M_PI / 180));
      EXPECT_LT(now, before + 1e-12) << t << " at " << degrees;
      EXPECT_GE(now, 0);
      before = now;
    }
    EXPECT_NEAR(pane.transmittance(0), 0, 1e-12);  // grazing: all reflected
    EXPECT_NEAR(pane.reflectance(0), 1, 1e-12);
  }
}

TEST(Glass, AtBrewstersAngleOnlyTheSPolarisationIsReflected) {
  // No absorption; at tan(angle) = 1.52 the p polarisation passes whole, and the s
  // polarisation's surface reflectance is sin^2(i - t) / sin^2(i + t).
  const GlassPane clear((1 - kR0) / (1 + kR0));
  const double i = std::atan(1.52), t = std::asin(std::sin(i) / 1.52);
  const double rs = std::pow(std::sin(i - t) / std::sin(i + t), 2);
  EXPECT_NEAR(clear.transmittance(std::cos(i)), 0.5 * (1 + (1 - rs) / (1 + rs)), 1e-12);
}

TEST(Glass, AbsorptionGrowsWithThePathInside) {
  // One pass keeps a^(1 / cos(refracted)): at 60 degrees the refracted angle is 34.7,
  // so the pane absorbs 1.216 times as much in logarithm as face on.
  const GlassPane pane(0.7);
  const double a = pane.internal();
  EXPECT_GT(a, 0.7);
  EXPECT_LT(a, 1);
  const double t = std::asin(std::sin(M_PI / 3) / 1.52);
  const double a60 = std::pow(a, 1 / std::cos(t));
  // Between the bounds a single pass through each surface gives (no inter-reflection)
  // and the full sum: 0.5 ((1 - rs)^2 + (1 - rp)^2) a60 <= T <= that / (1 - r^2 a60^2).
  const double i = M_PI / 3, c = std::cos(i), ct = std::cos(t);
  const double rs = std::pow((c - 1.52 * ct) / (c + 1.52 * ct), 2), rp = std::pow((1.52 * c - ct) / (1.52 * c + ct), 2);
  const double single = 0.5 * ((1 - rs) * (1 - rs) + (1 - rp) * (1 - rp)) * a60;
  EXPECT_GT(pane.transmittance(c), single);
  EXPECT_LT(pane.transmittance(c), single * 1.01);
}

}  // namespace
}  // namespace dynrad::rad
