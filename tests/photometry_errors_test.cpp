// IES LM-63 and EULUMDAT files the readers refuse, each with its name, line and what to
// do; the choice of reader; the fuzzers' seed files read without error.
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
