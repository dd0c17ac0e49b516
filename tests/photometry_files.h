// Photometric files written by the tests (photometry_test.cpp: what the readers read;
// photometry_errors_test.cpp: what they refuse): IES LM-63 and EULUMDAT texts built from
// a distribution, and the checks of a refusal's message.
#pragma once

#include "radiosity/sources/photometry.h"

#include "mesh/core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace dynrad::rad::photometry_test {

using test::TempDir;

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDeg = kPi / 180;

inline std::vector<double> steps(double from, double to, double step) {
  std::vector<double> out;
  for (int i = 0; from + i * step <= to + 1e-9; ++i) out.push_back(from + i * step);
  return out;
}

inline std::string exact(double v) {
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
inline InputError refusal(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", 0, "");
}

inline void expect_refused(const std::string& path, const std::string& text, std::size_t line,
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

inline Photometry read_text_as(const std::string& name, const std::string& text) {
  TempDir dir;
  return read_photometry(dir.write(name, text));
}

}  // namespace dynrad::rad::photometry_test
