// The PDF lighting report (plugin/cli/pdf_report.h): `dynrad grid --pdf` end to end on
// the storey sample, read back with poppler's pdfinfo and pdftotext, and the writer
// alone on a report without optional sections and on one with every section.
#include "plugin/cli/pdf_report.h"
#include "mesh/core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <regex>

namespace dynrad {
namespace {

using json = nlohmann::json;

bool have_poppler() { return test::run_shell("command -v pdfinfo && command -v pdftotext").exit_code == 0; }

std::string pdf_info(const std::string& pdf) { return test::run_shell("pdfinfo '" + pdf + "'").output; }

std::string pdf_text(const std::string& pdf) { return test::run_shell("pdftotext '" + pdf + "' -").output; }

int page_count(const std::string& info) {
  std::smatch m;
  return std::regex_search(info, m, std::regex(R"(Pages:\s+(\d+))")) ? std::stoi(m[1]) : -1;
}

// Three significant figures, the way the report prints illuminances: 127.58 -> "128",
// 99.03 -> "99.0", 1234 -> "1230".
std::string three_figures(double x) {
  int before_point = static_cast<int>(std::floor(std::log10(std::abs(x)))) + 1;
  if (std::round(std::abs(x) * std::pow(10.0, 3 - before_point)) >= 1000) ++before_point;
  char out[64];
  if (before_point >= 3)
    std::snprintf(out, sizeof out, "%.0f",
                  std::round(x / std::pow(10.0, before_point - 3)) * std::pow(10.0, before_point - 3));
  else
    std::snprintf(out, sizeof out, "%.*f", 3 - before_point, x);
  return out;
}

// One draft solve of the storey, shared by the tests that run `dynrad grid` on it.
class PdfGridCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<test::TempDir>();
    solved_ = test::run_dynrad("solve -q '" + test::sample("storey_luminaires.json") + "' --quality draft -o '" +
                               dir_->path("lit.ply") + "'");
  }
  static void TearDownTestSuite() { dir_.reset(); }
  void SetUp() override {
    ASSERT_EQ(solved_.exit_code, 0) << solved_.output;
    ASSERT_TRUE(have_poppler()) << "poppler-utils (pdfinfo, pdftotext) is not installed: scripts/install-deps.sh all";
  }
  static std::string grid_command(const std::string& pdf) {
    return "grid -q '" + dir_->path("lit.ply") + "' --model '" + test::sample("storey_luminaires.json") + "' -o '" +
           dir_->path("storey") + "' --pdf '" + pdf + "'";
  }
  static std::unique_ptr<test::TempDir> dir_;
  static test::CommandResult solved_;
};
std::unique_ptr<test::TempDir> PdfGridCommand::dir_;
test::CommandResult PdfGridCommand::solved_;

TEST_F(PdfGridCommand, WritesA4ReportWithEachGrid) {
  const std::string pdf = dir_->path("report.pdf");
  const auto r = test::run_dynrad(grid_command(pdf));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string info = pdf_info(pdf);
  EXPECT_NE(info.find("Page size:       595.276 x 841.89 pts (A4)"), std::string::npos) << info;
  const int pages = page_count(info);
  EXPECT_GE(pages, 2) << info;
  const std::string text = pdf_text(pdf);
  EXPECT_NE(text.find("page 1 of " + std::to_string(pages)), std::string::npos) << text;
  EXPECT_NE(text.find("page " + std::to_string(pages) + " of " + std::to_string(pages)), std::string::npos);
  EXPECT_NE(text.find("Calculation grids"), std::string::npos);
  const json grids = json::parse(test::read_text(dir_->path("storey_grids.json")))["grids"];
  ASSERT_EQ(grids.size(), 4u);
  for (const json& g : grids) {
    const std::string name = g["name"], eavg = three_figures(g["Eavg"].get<double>());
    EXPECT_NE(text.find(name), std::string::npos) << name;
    EXPECT_NE(text.find(eavg), std::string::npos) << name << " Eavg " << eavg;
  }
}

// The output's directory does not exist: refused before any work, with nothing written.
TEST_F(PdfGridCommand, UnwritableOutputIsRefused) {
  const std::string pdf = dir_->path("missing/report.pdf");
  const auto r = test::run_dynrad(grid_command(pdf));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("missing"), std::string::npos) << r.output;
  EXPECT_FALSE(test::file_exists(pdf));
}

TEST(PdfReport, ReportWithoutOptionalSectionsIsOnePage) {
  ASSERT_TRUE(have_poppler()) << "poppler-utils is not installed: scripts/install-deps.sh all";
  test::TempDir dir;
  const std::string pdf = dir.path("empty.pdf");
  cli::write_pdf_report(pdf, json::object());
  const std::string info = pdf_info(pdf);
  EXPECT_EQ(page_count(info), 1) << info;
  EXPECT_NE(info.find("(A4)"), std::string::npos) << info;
  EXPECT_NE(pdf_text(pdf).find("page 1 of 1"), std::string::npos);
}

TEST(PdfReport, UnwritablePathThrowsAndLeavesNoFile) {
  test::TempDir dir;
  const std::string pdf = dir.path("missing/report.pdf");
  EXPECT_THROW(cli::write_pdf_report(pdf, json::object()), OutputError);
  EXPECT_FALSE(test::file_exists(pdf));
}

// Every section from hand-made data, with odd values (nulls, a missing picture, a range
// target): nothing fails, each section's heading and figures are in the text.
TEST(PdfReport, EverySectionFromHandMadeReport) {
  ASSERT_TRUE(have_poppler()) << "poppler-utils is not installed: scripts/install-deps.sh all";
  test::TempDir dir;
  const json check_met = {{"area", "task area"}, {"quantity", "Em"}, {"value", 512.3}, {"unit", "lx"},
                          {"relation", ">="},    {"target", 500},    {"met", true},    {"margin", "+2.5%"}};
  const json check_failed = {{"area", "cylindrical"}, {"quantity", "Ez/Eh"},  {"value", nullptr}, {"unit", ""},
                             {"relation", "in"},      {"target", {0.3, 0.6}}, {"met", false}};
  const json report = {
      {"input", "office.json"},
      {"units", "photometric"},
      {"project", {{"name", "Test office"}, {"author", "Tester"}, {"date", "2024-05-01"}}},
      {"luminaires",
       {{{"name", "L1"}, {"flux", 3000.0}, {"watts", 25.0}, {"group", "A"}, {"photometry", {{"file", "a.ies"}}}},
        {{"name", "L2"}, {"flux", 3000.0}, {"watts", 25.0}, {"group", "B"}, {"photometry", {{"file", "a.ies"}}}}}},
      {"rooms", {{{"name", "Office 1"}, {"picture", dir.path("absent.png")}, {"checks", {check_met, check_failed}}}}},
      {"grids", {{{"name", "desk plane"}, {"Eavg", 512.34}, {"Emin", 301.0}, {"U0", 0.588}}}},
      {"observers", {{{"name", "desk"}, {"ugr", 18.26}, {"limit", 19}, {"met", true}, {"notes", {"a glare note"}}}}},
      {"scenes",
       {{{"name", "Evening"}, {"levels", {{"A", 0.5}}}, {"grids", {{{"name", "desk plane"}, {"Eavg", 250.0}}}}}}},
      {"emergency", {{"luminaires", {"L2"}}, {"areas", {{{"name", "Corridor"}, {"kind", "escape route"}}}}}},
      {"method", "dynamic"},
      {"iterations", 40}};
  const std::string pdf = dir.path("full.pdf");
  cli::write_pdf_report(pdf, report);
  const std::string text = pdf_text(pdf);
  for (const char* expected : {"Test office",
                               "Tester",
                               "Luminaire schedule",
                               "a.ies",
                               "6000",
                               "50.0",
                               "Rooms (EN 12464-1)",
                               "Office 1",
                               "512 lx",
                               "≥ 500 lx",
                               "+2.5%",
                               "not met",
                               "0.30 – 0.60",
                               "could not be read",
                               "desk plane",
                               "0.59",
                               "Glare (UGR)",
                               "18.3",
                               "a glare note",
                               "Light scenes",
                               "A 50%",
                               "Emergency lighting (EN 1838)",
                               "Corridor (escape route)",
                               "Solve"})
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  EXPECT_NE(text.find("page 1 of " + std::to_string(page_count(pdf_info(pdf)))), std::string::npos);
}

}  // namespace
}  // namespace dynrad
