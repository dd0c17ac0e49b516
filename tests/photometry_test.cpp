// IES LM-63 and EULUMDAT readers (radiosity/sources/photometry.h): closed-form fluxes, the
// symmetries of both formats giving the same distribution, interpolation that is exact
// at the file's angles and makes no new extremes, and every kind of bad file refused
// with its name, line and what to do. Every file is written here.
// The refusals are in photometry_errors_test.cpp.
#include "photometry_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace dynrad::rad {
namespace {

using namespace photometry_test;

// ---------------------------------------------------------------------------
// Closed forms.

TEST(PhotometryIes, IsotropicAxialFileGivesFourPiI) {
  Ies ies;  // 100 cd everywhere, one horizontal angle
  const Photometry p = read_text_as("iso.ies", ies.text());
  EXPECT_EQ(p.format, "IES LM-63-2002");
  EXPECT_EQ(p.symmetry, "axial");
  EXPECT_EQ(p.name, "Test downlight");
  EXPECT_TRUE(p.warnings.empty());
  EXPECT_EQ(p.lamp_flux, 0);  // absolute photometry
  EXPECT_NEAR(p.flux, 4 * kPi * 100, 1e-4 * 4 * kPi * 100);
  for (const double c : {0.0, 33.0, 190.0, 359.9})
    for (const double g : {0.0, 7.0, 90.0, 135.5, 180.0}) EXPECT_DOUBLE_EQ(p.intensity(c, g), 100) << c << " " << g;
}

TEST(PhotometryIes, CosineLawGivesPiI0) {
  Ies ies;
  ies.vertical = steps(0, 90, 5);
  ies.candela = [](double, double g) { return g == 90 ? 0.0 : 1000 * std::cos(g * kDeg); };
  const Photometry p = read_text_as("cos.ies", ies.text());
  EXPECT_NEAR(p.flux, kPi * 1000, 1e-3 * kPi * 1000);
  EXPECT_NEAR(integrate_flux(p), p.flux, 1e-12 * p.flux);
  EXPECT_EQ(p.intensity(0, 95), 0);  // a downlight: nothing above the horizontal
  EXPECT_EQ(p.intensity(0, 180), 0);
  EXPECT_NEAR(p.intensity(45, 42.5), 1000 * std::cos(42.5 * kDeg), 1);  // between nodes: close to the cosine
}

TEST(PhotometryIes, UpwardOnlyFileGivesNothingDownward) {
  Ies ies;
  ies.vertical = steps(90, 180, 10);
  ies.candela = [](double, double g) { return g == 90 ? 0.0 : -50 * std::cos(g * kDeg); };
  const Photometry p = read_text_as("up.ies", ies.text());
  EXPECT_EQ(p.intensity(0, 0), 0);
  EXPECT_EQ(p.intensity(0, 89.9), 0);
  EXPECT_DOUBLE_EQ(p.intensity(0, 180), 50);
  EXPECT_NEAR(p.flux, kPi * 50, 1e-3 * kPi * 50);
}

// ---------------------------------------------------------------------------
// Symmetries.

// A distribution that changes with C in every quadrant differently unless mirrored.
double lumpy(double c, double g) { return 200 + 120 * std::sin(g * kDeg) * (1 + c / 90) + 30 * std::cos(3 * g * kDeg); }

TEST(PhotometryIes, QuadrantFileIsMirroredIntoEveryQuadrant) {
  Ies ies;
  ies.horizontal = steps(0, 90, 22.5);
  ies.candela = lumpy;
  const Photometry p = read_text_as("quad.ies", ies.text());
  EXPECT_EQ(p.symmetry, "quadrant");
  EXPECT_EQ(p.c_angles.size(), 16u);
  for (const double c : {0.0, 10.0, 22.5, 37.0, 67.5, 80.0, 90.0})
    for (const double g : {0.0, 15.0, 42.0, 90.0, 133.0, 180.0}) {
      const double v = p.intensity(c, g);
      EXPECT_NEAR(p.intensity(180 - c, g), v, 1e-9 * v) << c << " " << g;
      EXPECT_NEAR(p.intensity(180 + c, g), v, 1e-9 * v) << c << " " << g;
      EXPECT_NEAR(p.intensity(360 - c, g), v, 1e-9 * v) << c << " " << g;
      EXPECT_NEAR(p.intensity(-c, g), v, 1e-9 * v) << c << " " << g;
    }
  // Exact at the file's angles, in every quadrant.
  EXPECT_NEAR(p.intensity(22.5, 40), lumpy(22.5, 40), 1e-12 * lumpy(22.5, 40));
  EXPECT_NEAR(p.intensity(157.5, 40), lumpy(22.5, 40), 1e-12 * lumpy(22.5, 40));
  EXPECT_NEAR(p.intensity(337.5, 40), lumpy(22.5, 40), 1e-12 * lumpy(22.5, 40));
  EXPECT_NE(p.intensity(22.5, 40), p.intensity(67.5, 40));  // and really asymmetric within a quadrant
}

TEST(PhotometryIes, BilateralFileIsMirroredInTheC0C180Plane) {
  Ies ies;
  ies.horizontal = steps(0, 180, 15);
  ies.candela = lumpy;
  const Photometry p = read_text_as("bilateral.ies", ies.text());
  EXPECT_EQ(p.symmetry, "bilateral");
  EXPECT_EQ(p.c_angles.size(), 24u);
  for (const double c : {0.0, 15.0, 50.0, 100.0, 165.0, 180.0})
    for (const double g : {5.0, 60.0, 120.0}) {
      const double v = p.intensity(c, g);
      EXPECT_NEAR(p.intensity(360 - c, g), v, 1e-9 * v) << c << " " << g;
    }
  EXPECT_NEAR(p.intensity(345, 60), lumpy(15, 60), 1e-12 * lumpy(15, 60));
  EXPECT_NE(p.intensity(15, 60), p.intensity(165, 60));
}

TEST(PhotometryIes, C90C270FileIsMirroredInTheC90C270Plane) {
  Ies ies;
  ies.horizontal = steps(90, 270, 15);
  ies.candela = lumpy;
  const Photometry p = read_text_as("c90.ies", ies.text());
  EXPECT_EQ(p.symmetry, "bilateral (C90-C270 plane)");
  EXPECT_EQ(p.c_angles.size(), 24u);
  for (const double c : {90.0, 100.0, 135.0, 180.0, 222.0, 270.0})
    for (const double g : {5.0, 60.0, 120.0}) {
      const double v = p.intensity(c, g);
      EXPECT_NEAR(p.intensity(180 - c, g), v, 1e-9 * v) << c << " " << g;
    }
  EXPECT_NEAR(p.intensity(0, 60), lumpy(180, 60), 1e-12 * lumpy(180, 60));
  EXPECT_NEAR(p.intensity(30, 60), lumpy(150, 60), 1e-12 * lumpy(150, 60));
  EXPECT_NEAR(p.intensity(300, 60), lumpy(240, 60), 1e-12 * lumpy(240, 60));
}

TEST(PhotometryIes, FullFileDropsThe360PlaneAndIsPeriodic) {
  Ies ies;
  ies.horizontal = steps(0, 360, 30);
  ies.candela = [](double c, double g) { return 100 + 50 * std::cos(c * kDeg) * std::sin(g * kDeg); };
  const Photometry p = read_text_as("full.ies", ies.text());
  EXPECT_EQ(p.symmetry, "none");
  EXPECT_EQ(p.c_angles.size(), 12u);
  EXPECT_EQ(p.c_angles.back(), 330);
  EXPECT_NEAR(p.intensity(359.999, 90), p.intensity(0, 90), 1e-2);
  EXPECT_NEAR(p.intensity(-15, 70), p.intensity(345, 70), 1e-12);
  // cos C integrates to 0 round the circle: flux of the constant part, 4 pi 100.
  EXPECT_NEAR(p.flux, 4 * kPi * 100, 1e-3 * 4 * kPi * 100);
}

// ---------------------------------------------------------------------------
// Header details.

TEST(PhotometryIes, TiltIncludeIsReadAndInterpolated) {
  Ies ies;
  ies.tilt = "TILT=INCLUDE";
  ies.tilt_data = "1\n7\n0 15 30 45\n60 75 90\n1.0 0.95 0.9 0.85 0.8 0.75 0.7\n";
  const Photometry p = read_text_as("tilt.ies", ies.text());
  ASSERT_EQ(p.tilt_angles.size(), 7u);
  EXPECT_EQ(p.tilt_factors[3], 0.85);
  EXPECT_DOUBLE_EQ(p.tilt_factor(0), 1.0);
  EXPECT_DOUBLE_EQ(p.tilt_factor(22.5), 0.925);
  EXPECT_DOUBLE_EQ(p.tilt_factor(80), 0.75 - 0.05 / 3);
  EXPECT_DOUBLE_EQ(p.tilt_factor(-10), 1.0);  // clamped at the ends
  EXPECT_DOUBLE_EQ(p.tilt_factor(120), 0.7);
  EXPECT_EQ(read_text_as("no_tilt.ies", Ies{}.text()).tilt_factor(30), 1.0);
}

TEST(PhotometryIes, FactorsUnitsOpeningAndVersions) {
  Ies ies;
  ies.version = "IESNA:LM-63-1995";
  ies.multiplier = 2;
  ies.ballast = 0.5;
  ies.second = 0.9;  // 1995: the ballast-lamp photometric factor, applied
  ies.units = 1;     // feet
  ies.width = -0.5;  // round, 0.5 ft across
  ies.length = -0.5;
  ies.height = 0.25;
  ies.lamps = 2;
  ies.lumens = 1000;
  const Photometry p = read_text_as("old.ies", ies.text());
  EXPECT_EQ(p.format, "IES LM-63-1995");
  EXPECT_DOUBLE_EQ(p.intensity(0, 0), 100 * 2 * 0.5 * 0.9);
  EXPECT_TRUE(p.round);
  EXPECT_DOUBLE_EQ(p.length, 0.5 * 0.3048);
  EXPECT_DOUBLE_EQ(p.height, 0.25 * 0.3048);
  EXPECT_EQ(p.lamp_flux, 2000);

  ies.version = "IESNA:LM-63-2002";  // 2002: the second value is for future use, ignored
  EXPECT_DOUBLE_EQ(read_text_as("new.ies", ies.text()).intensity(0, 0), 100 * 2 * 0.5);
  ies.version = "IES:LM-63-2019";
  EXPECT_EQ(read_text_as("2019.ies", ies.text()).format, "IES LM-63-2019");
  ies.version = "IESNA91";
  EXPECT_EQ(read_text_as("1991.ies", ies.text()).format, "IES LM-63-1991");

  ies.version = "";  // 1986: no version line, keywords free text
  ies.keywords = {"ACME downlight", "[LUMCAT] D-100"};
  const Photometry old = read_text_as("1986.ies", ies.text());
  EXPECT_EQ(old.format, "IES LM-63-1986");
  EXPECT_EQ(old.name, "D-100");
  ASSERT_FALSE(old.warnings.empty());
  EXPECT_NE(old.warnings[0].find("1986.ies: has no version line"), std::string::npos) << old.warnings[0];
}

TEST(PhotometryIes, CommasWrappingCrlfAndTrailingValues) {
  Ies ies;
  ies.horizontal = steps(0, 90, 30);
  ies.candela = lumpy;
  const Photometry plain = read_text_as("plain.ies", ies.text());
  ies.separator = ", ";
  ies.per_line = 3;
  ies.trailer = "0 0\n";
  std::string text = ies.text();
  std::string crlf;
  for (const char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  TempDir dir;
  const std::string path = dir.write("commas.ies", crlf);
  const Photometry p = read_ies(path);
  EXPECT_EQ(p.candela, plain.candela);
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_NE(p.warnings[0].find(path + ":"), std::string::npos);
  EXPECT_NE(p.warnings[0].find("2 more values after the candela table"), std::string::npos) << p.warnings[0];
}

// ---------------------------------------------------------------------------
// EULUMDAT: each symmetry gives the distribution of the IES file that lists it all.

// Distributions with exactly the symmetry each Isym declares.
Distribution with_symmetry(int isym) {
  const auto g_part = [](double g) { return 1 + std::sin(g * kDeg) + 0.3 * std::cos(2 * g * kDeg); };
  switch (isym) {
    case 0:
      return [=](double c, double g) { return 100 * g_part(g) * (2 + std::cos(c * kDeg) + 0.5 * std::sin(c * kDeg)); };
    case 1:
      return [=](double, double g) { return 100 * g_part(g); };
    case 2:
      return
          [=](double c, double g) { return 100 * g_part(g) * (2 + std::cos(c * kDeg) + 0.3 * std::cos(2 * c * kDeg)); };
    case 3:
      return
          [=](double c, double g) { return 100 * g_part(g) * (2 + std::sin(c * kDeg) + 0.3 * std::cos(2 * c * kDeg)); };
    default:
      return [=](double c, double g) { return 100 * g_part(g) * (2 + std::cos(2 * c * kDeg)); };
  }
}

TEST(PhotometryEulumdat, EverySymmetryMatchesTheIesFile) {
  for (int isym = 0; isym <= 4; ++isym) {
    SCOPED_TRACE("Isym " + std::to_string(isym));
    Ldt ldt;
    ldt.isym = isym;
    ldt.candela = with_symmetry(isym);
    const Photometry from_ldt = read_text_as("lum.ldt", ldt.text());
    EXPECT_EQ(from_ldt.format, "EULUMDAT");
    EXPECT_EQ(from_ldt.name, "Test luminaire");

    Ies full;  // every plane, 0 to 360 every 15 degrees
    full.horizontal = steps(0, 360, 15);
    full.candela = ldt.candela;
    const Photometry from_ies = read_text_as("lum.ies", full.text());

    Ies own;  // the IES file with the same symmetry
    own.candela = ldt.candela;
    own.horizontal = isym == 0   ? steps(0, 360, 15)
                     : isym == 1 ? std::vector<double>{0}
                     : isym == 2 ? steps(0, 180, 15)
                     : isym == 3 ? steps(90, 270, 15)
                                 : steps(0, 90, 15);
    const Photometry from_own = read_text_as("own.ies", own.text());

    if (isym != 1) {
      EXPECT_EQ(from_ldt.c_angles, from_ies.c_angles);
    }
    for (double c = 0; c < 360; c += 7.3)
      for (double g = 0; g <= 180; g += 6.1) {
        const double v = from_ies.intensity(c, g);
        EXPECT_NEAR(from_ldt.intensity(c, g), v, 1e-9 * v) << c << " " << g;
        EXPECT_NEAR(from_own.intensity(c, g), v, 1e-9 * v) << c << " " << g;
      }
    for (double c = 0; c < 360; c += 15) EXPECT_DOUBLE_EQ(from_ldt.intensity(c, 40), ldt.candela(c, 40)) << c;
    EXPECT_NEAR(from_ldt.flux, from_ies.flux, 1e-9 * from_ies.flux);
    EXPECT_EQ(from_ldt.lamp_flux, 2000);
  }
}

TEST(PhotometryEulumdat, DecimalCommasAndCrlfReadAlike) {
  Ldt ldt;
  ldt.isym = 4;
  ldt.candela = with_symmetry(4);
  ldt.lamp_flux = 1234.5;
  ldt.conversion = 0.5;
  const Photometry dots = read_text_as("dots.ldt", ldt.text());
  ldt.decimal_comma = true;
  ldt.eol = "\r\n";
  const Photometry commas = read_text_as("commas.ldt", ldt.text());
  ASSERT_EQ(dots.candela.size(), commas.candela.size());
  for (std::size_t i = 0; i < dots.candela.size(); ++i) EXPECT_DOUBLE_EQ(commas.candela[i], dots.candela[i]);
  EXPECT_DOUBLE_EQ(commas.intensity(30, 50), ldt.candela(30, 50));  // conversion factor and flux applied
}

TEST(PhotometryEulumdat, OpeningAndNegativeLampCount) {
  Ldt ldt;
  ldt.lamps = -1;  // absolute photometry in some writers' files: read the same way
  const Photometry p = read_text_as("led.ldt", ldt.text());
  EXPECT_DOUBLE_EQ(p.intensity(10, 10), 100);
  EXPECT_DOUBLE_EQ(p.length, 0.5);
  EXPECT_DOUBLE_EQ(p.width, 0.5);
  EXPECT_FALSE(p.round);
  EXPECT_EQ(p.symmetry, "none");
}

// ---------------------------------------------------------------------------
// Interpolation.

TEST(PhotometryInterpolation, ExactAtNodesAndWithinEachCell) {
  std::mt19937 random(17);
  std::uniform_real_distribution<double> uniform(0, 1);
  Ies ies;
  ies.horizontal = steps(0, 360, 20);
  ies.vertical = {0, 5, 10, 20, 25, 40, 60, 61, 90, 120, 150, 180};
  std::vector<double> table;  // spiky, with zeros: where unbounded cubics overshoot
  for (std::size_t i = 0; i < ies.horizontal.size() * ies.vertical.size(); ++i)
    table.push_back(uniform(random) < 0.3 ? 0.0 : std::round(1000 * uniform(random)));
  for (std::size_t g = 0; g < ies.vertical.size(); ++g)  // the 360 plane repeats the 0 plane
    table[(ies.horizontal.size() - 1) * ies.vertical.size() + g] = table[g];
  const auto at = [&](std::size_t ci, std::size_t gi) { return table[ci * ies.vertical.size() + gi]; };
  ies.candela = [&](double c, double g) {
    const auto ci = static_cast<std::size_t>(std::lround(c / 20));
    const auto gi =
        static_cast<std::size_t>(std::find(ies.vertical.begin(), ies.vertical.end(), g) - ies.vertical.begin());
    return at(ci, gi);
  };
  const Photometry p = read_text_as("spiky.ies", ies.text());
  for (std::size_t ci = 0; ci < ies.horizontal.size(); ++ci)
    for (std::size_t gi = 0; gi < ies.vertical.size(); ++gi)
      ASSERT_EQ(p.intensity(ies.horizontal[ci], ies.vertical[gi]), at(ci, gi)) << ci << " " << gi;
  for (int n = 0; n < 20000; ++n) {
    const double c = 360 * uniform(random), g = 180 * uniform(random);
    const auto ci = static_cast<std::size_t>(c / 20);
    const auto gi = static_cast<std::size_t>(std::upper_bound(ies.vertical.begin(), ies.vertical.end(), g) -
                                             ies.vertical.begin() - 1);
    const double corners[4] = {at(ci, gi), at(ci + 1, gi), at(ci, gi + 1), at(ci + 1, gi + 1)};
    const double v = p.intensity(c, g);
    ASSERT_GE(v, *std::min_element(corners, corners + 4)) << c << " " << g;
    ASSERT_LE(v, *std::max_element(corners, corners + 4)) << c << " " << g;
  }
}

// ---------------------------------------------------------------------------
// Warnings about the flux.

TEST(PhotometryWarnings, FluxThatDisagreesWithTheFileIsReported) {
  Ldt ldt;  // I = I0 cos(gamma) downward: flux pi I0 = 800 lm from 1000 lm lamps
  ldt.lamp_flux = 1000;
  ldt.gamma = steps(0, 90, 5);
  ldt.candela = [](double, double g) { return g == 90 ? 0.0 : 800 / kPi * std::cos(g * kDeg); };
  ldt.lorl = 80;
  const Photometry good = read_text_as("good.ldt", ldt.text());
  EXPECT_NEAR(good.flux, 800, 0.8);
  EXPECT_DOUBLE_EQ(good.stated_flux, 800);
  EXPECT_TRUE(good.warnings.empty());

  ldt.lorl = 60;
  TempDir dir;
  const std::string path = dir.write("bad.ldt", ldt.text());
  const Photometry bad = read_eulumdat(path);
  ASSERT_EQ(bad.warnings.size(), 1u);
  EXPECT_NE(bad.warnings[0].find(path + ": the intensities integrate to "), std::string::npos) << bad.warnings[0];
  EXPECT_NE(bad.warnings[0].find("states a luminaire flux of 600 lm"), std::string::npos) << bad.warnings[0];

  Ies ies;  // 4 pi 100 = 1257 lm from a 1000 lm lamp
  ies.lumens = 1000;
  const std::string ies_path = dir.write("bright.ies", ies.text());
  const Photometry bright = read_ies(ies_path);
  ASSERT_EQ(bright.warnings.size(), 1u);
  EXPECT_NE(bright.warnings[0].find(ies_path + ": "), std::string::npos);
  EXPECT_NE(bright.warnings[0].find("more than the lamps' 1000 lm"), std::string::npos) << bright.warnings[0];
}
}  // namespace
}  // namespace dynrad::rad
