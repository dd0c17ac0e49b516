// IES LM-63 and EULUMDAT readers (radiosity/sources/photometry.h): closed-form fluxes, the
// symmetries of both formats giving the same distribution, interpolation that is exact
// at the file's angles and makes no new extremes, and every kind of bad file refused
// with its name, line and what to do. Every file is written here.
#include "radiosity/sources/photometry.h"

#include "mesh/core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace dynrad::rad {
namespace {

using test::TempDir;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180;

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> out;
  for (int i = 0; from + i * step <= to + 1e-9; ++i) out.push_back(from + i * step);
  return out;
}

std::string exact(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

using Distribution = std::function<double(double c, double gamma)>;

// An IES file; each row of numbers wraps after `per_line` values.
struct Ies {
  std::string version = "IESNA:LM-63-2002";
  std::vector<std::string> keywords = {"[TEST] dynrad photometry_test", "[LUMINAIRE] Test downlight"};
  std::string tilt = "TILT=NONE";
  std::string tilt_data;
  int lamps = 1;
  double lumens = -1, multiplier = 1;
  int type = 1, units = 2;
  double width = 0, length = 0, height = 0;
  double ballast = 1, second = 1, watts = 20;
  std::vector<double> vertical = steps(0, 180, 10), horizontal = {0};
  Distribution candela = [](double, double) { return 100.0; };
  std::size_t per_line = 7;
  std::string separator = " ";
  std::string trailer;

  std::string text() const {
    std::ostringstream out;
    if (!version.empty()) out << version << "\n";
    for (const auto& k : keywords) out << k << "\n";
    out << tilt << "\n" << tilt_data;
    out << lamps << " " << exact(lumens) << " " << exact(multiplier) << " " << vertical.size() << " "
        << horizontal.size() << " " << type << " " << units << " " << exact(width) << " " << exact(length) << " "
        << exact(height) << "\n";
    out << exact(ballast) << " " << exact(second) << " " << exact(watts) << "\n";
    row(out, vertical);
    row(out, horizontal);
    for (const double c : horizontal) {
      std::vector<double> values;
      for (const double g : vertical) values.push_back(candela(c, g));
      row(out, values);
    }
    out << trailer;
    return out.str();
  }
  void row(std::ostringstream& out, const std::vector<double>& values) const {
    for (std::size_t i = 0; i < values.size(); ++i)
      out << exact(values[i]) << ((i + 1) % per_line == 0 || i + 1 == values.size() ? "\n" : separator);
  }
};

// An EULUMDAT file with Mc equally spaced C-planes, storing the planes Isym requires.
struct Ldt {
  int isym = 0, mc = 24;
  std::vector<double> gamma = steps(0, 180, 10);
  Distribution candela = [](double, double) { return 100.0; };  // cd
  double lamp_flux = 2000, conversion = 1, lorl = 100;
  int lamps = 1;
  bool decimal_comma = false;
  std::string eol = "\n";

  std::string num(double v) const {
    std::string s = exact(v);
    if (decimal_comma) std::replace(s.begin(), s.end(), '.', ',');
    return s;
  }
  std::vector<int> stored() const {
    std::vector<int> k;
    switch (isym) {
      case 0:
        for (int i = 0; i < mc; ++i) k.push_back(i);
        break;
      case 1:
        k = {0};
        break;
      case 2:
        for (int i = 0; i <= mc / 2; ++i) k.push_back(i);
        break;
      case 3:  // C270 round through C0 to C90
        for (int i = 0; i <= mc / 2; ++i) k.push_back((3 * mc / 4 + i) % mc);
        break;
      default:
        for (int i = 0; i <= mc / 4; ++i) k.push_back(i);
    }
    return k;
  }
  std::string text() const {
    const double dc = 360.0 / mc;
    std::vector<std::string> lines = {"dynrad photometry_test",
                                      "1",
                                      std::to_string(isym),
                                      std::to_string(mc),
                                      num(dc),
                                      std::to_string(gamma.size()),
                                      num(gamma[1] - gamma[0]),
                                      "R-1",
                                      "Test luminaire",
                                      "T-1",
                                      "test.ldt",
                                      "2026-01-01 test",
                                      "600",
                                      "600",
                                      "80",
                                      "500",
                                      "500",
                                      "0",
                                      "0",
                                      "0",
                                      "0",
                                      num(100),
                                      num(lorl),
                                      num(conversion),
                                      "0",
                                      "1",
                                      std::to_string(lamps),
                                      "LED module",
                                      num(lamp_flux),
                                      "3000K",
                                      "80",
                                      num(25.5)};
    for (int i = 0; i < 10; ++i) lines.push_back(num(0.5));
    for (int i = 0; i < mc; ++i) lines.push_back(num(i * dc));
    for (const double g : gamma) lines.push_back(num(g));
    const double per_klm = 1000 / (lamp_flux * conversion);
    for (const int k : stored())
      for (const double g : gamma) lines.push_back(num(candela(k * dc, g) * per_klm));
    std::string out;
    for (const auto& l : lines) out += l + eol;
    return out;
  }
};

// Runs `read` and returns the InputError it throws (fails the test if none).
InputError refusal(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", 0, "");
}

void expect_refused(const std::string& path, const std::string& text, std::size_t line,
                    const std::vector<std::string>& words, bool ies = true) {
  TempDir dir;
  const std::string file = dir.write(path, text);
  const InputError e = refusal([&] { ies ? read_ies(file) : read_eulumdat(file); });
  EXPECT_EQ(e.file(), file);
  EXPECT_EQ(e.line(), line) << e.what();
  const std::string what = e.what();
  EXPECT_NE(what.find(file + ":" + std::to_string(line) + ": "), std::string::npos) << what;
  for (const auto& w : words) EXPECT_NE(what.find(w), std::string::npos) << "'" << w << "' not in: " << what;
}

Photometry read_text_as(const std::string& name, const std::string& text) {
  TempDir dir;
  return read_photometry(dir.write(name, text));
}

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

// ---------------------------------------------------------------------------
// Refusals: file, line and what to do.

// Line numbers below count: version, 2 keyword lines, TILT (4), header (5, 6), then
// vertical angles (19 values, 7 per line: 7-9), horizontal angles, candela.
TEST(PhotometryErrors, TruncatedIesFile) {
  const std::string text = Ies{}.text();
  const std::size_t header = text.find("1 -1 1");
  expect_refused("cut.ies", text.substr(0, header + 6), 5, {"ends where the number of vertical angles", "truncated"});
  expect_refused("cut2.ies", text.substr(0, text.size() - 10), 5, {"only", "numbers follow the header", "truncated"});
}

TEST(PhotometryErrors, CountLargerThanTheValues) {
  Ies ies;
  ies.horizontal = {0, 90};
  std::string text = ies.text();
  const std::size_t at = text.find(" 19 2 1 2");
  text.replace(at, 9, " 19 5 1 2");  // five horizontal angles declared, two given
  expect_refused("count.ies", text, 5, {"declares 19 vertical and 5 horizontal angles", "truncated"});
}

TEST(PhotometryErrors, NegativeAndNonFiniteCandela) {
  Ies ies;
  ies.candela = [](double, double g) { return g == 100 ? -5.0 : 100.0; };
  expect_refused("neg.ies", ies.text(), 12, {"candela value -5 is negative"});
  std::string text = Ies{}.text();
  const std::size_t last = text.rfind("100");
  expect_refused("nan.ies", text.replace(last, 3, "nan"), 13, {"'nan' is not a number", "candela"});
  text = Ies{}.text();
  expect_refused("inf.ies", text.replace(text.rfind("100"), 3, "1e999"), 13, {"not a finite number"});
}

TEST(PhotometryErrors, AnglesOutOfRangeOrOrder) {
  Ies ies;
  ies.vertical = {0, 45, 90, 200};
  expect_refused("g200.ies", ies.text(), 7, {"vertical angle 200 is outside 0 to 180"});
  ies.vertical = {0, 45, 30, 90};
  expect_refused("order.ies", ies.text(), 7, {"vertical angle 30 is not above the one before (45)"});
  ies.vertical = {0, 45, 90};
  ies.horizontal = {0, 45, 120};
  expect_refused("sym.ies", ies.text(), 8, {"horizontal angles run from 0 to 120", "0 to 90 (quadrant)"});
}

TEST(PhotometryErrors, TypeBAndTiltFileAndVersion) {
  Ies ies;
  ies.type = 2;
  expect_refused("typeb.ies", ies.text(), 5, {"type B", "type C only"});
  ies.type = 3;
  expect_refused("typea.ies", ies.text(), 5, {"type A"});
  ies = Ies{};
  ies.tilt = "TILT=lamp_tilt.dat";
  expect_refused("tiltfile.ies", ies.text(), 4, {"TILT=lamp_tilt.dat", "separate file", "TILT=INCLUDE"});
  ies.tilt = "TILT=INCLUDE";
  ies.tilt_data = "1 3 0 45 90 1 0.9\n";  // three angles, two factors: the rest are eaten
  ies.tilt_data = "1\n1000\n0 45 90\n";
  expect_refused("tiltshort.ies", ies.text(), 6, {"TILT=INCLUDE declares 1000 tilt angles", "truncated"});
}

TEST(PhotometryErrors, NoTiltLineOrUnknownVersion) {
  expect_refused("notilt.ies", "IESNA:LM-63-2002\n[TEST] x\n", 2, {"no TILT= line"});
  expect_refused("v.ies", "IESNA:LM-63-2008\nTILT=NONE\n", 1, {"LM-63 version dynrad does not know"});
}

TEST(PhotometryErrors, BadEulumdatFiles) {
  const std::string text = Ldt{}.text();
  // Cut after line 20: line 21 is missing.
  std::size_t at = 0;
  for (int i = 0; i < 20; ++i) at = text.find('\n', at) + 1;
  expect_refused("cut.ldt", text.substr(0, at), 20, {"ends after line 20", "line 21 should hold", "C270"}, false);
  expect_refused("short.ldt", text.substr(0, text.size() - 40), 6,
                 {"need 509 numbers after the lamp sets", "truncated"}, false);
  Ldt ldt;
  ldt.candela = [](double c, double g) { return c == 30 && g == 40 ? -100.0 : 100.0; };
  // Line: 32 header lines, 10 ratios, 24 C angles, 19 gammas, then plane 2 (C30), gamma 40.
  expect_refused("neg.ldt", ldt.text(), 32 + 10 + 24 + 19 + 2 * 19 + 5, {"intensity -50 cd/klm is negative"}, false);
  std::string sym = Ldt{}.text();
  sym.replace(sym.find("\n0\n") + 1, 1, "5");  // line 3, Isym
  expect_refused("isym.ldt", sym, 3, {"symmetry indicator Isym is 5"}, false);
  Ldt gammas;
  gammas.gamma.back() = 200;
  expect_refused("g200.ldt", gammas.text(), 32 + 10 + 24 + 19, {"gamma angle 200 is outside 0 to 180"}, false);
  Ldt nan;
  std::string nan_text = nan.text();
  nan_text.replace(nan_text.rfind("\n50\n") + 1, 2, "nan");
  expect_refused("nan.ldt", nan_text, 32 + 10 + 24 + 19 + 24 * 19, {"'nan' is not a number"}, false);
}

TEST(PhotometryRead, ChoosesTheReaderByExtensionThenContent) {
  TempDir dir;
  EXPECT_EQ(read_photometry(dir.write("a.IES", Ies{}.text())).format, "IES LM-63-2002");
  EXPECT_EQ(read_photometry(dir.write("a.LDT", Ldt{}.text())).format, "EULUMDAT");
  EXPECT_EQ(read_photometry(dir.write("a.txt", Ies{}.text())).format, "IES LM-63-2002");
  Ies old;
  old.version = "";
  EXPECT_EQ(read_photometry(dir.write("b.dat", old.text())).format, "IES LM-63-1986");
  EXPECT_EQ(read_photometry(dir.write("c.dat", Ldt{}.text())).format, "EULUMDAT");
  const InputError e = refusal([&] { read_photometry(dir.write("d.dat", "hello\nworld\n")); });
  EXPECT_NE(std::string(e.what()).find("neither an IES file"), std::string::npos) << e.what();
  const InputError missing = refusal([&] { read_photometry(dir.path("none.ies")); });
  EXPECT_EQ(missing.file(), dir.path("none.ies"));
}

}  // namespace
}  // namespace dynrad::rad

namespace dynrad::rad {
namespace {

// The fuzzers' seeds (tests/fuzz/seeds, written for dynrad) must be files the readers
// accept, or the fuzzers would start from refusals only.
TEST(PhotometrySeeds, FuzzSeedsAreReadWithoutError) {
  namespace fs = std::filesystem;
  const fs::path seeds = fs::path(DYNRAD_TEST_DATA_DIR).parent_path() / "fuzz" / "seeds";
  int files = 0;
  for (const char* format : {"ies", "ldt"})
    for (const auto& entry : fs::directory_iterator(seeds / format)) {
      SCOPED_TRACE(entry.path().string());
      const Photometry p = read_photometry(entry.path().string());
      EXPECT_GT(p.flux, 0);
      EXPECT_EQ(p.format == "EULUMDAT", std::string(format) == "ldt");
      ++files;
    }
  EXPECT_EQ(files, 10);
}

}  // namespace
}  // namespace dynrad::rad
