// `dynrad validate`'s outputs: its exit status, the JSON of every point, the HTML report.
#include "test_support.h"

#include <gtest/gtest.h>
#include <filesystem>
#include <nlohmann/json.hpp>

namespace dynrad {
namespace {

TEST(Validate, ReportsEveryPointAndWritesAReportWithAPlanPerRun) {
  test::TempDir dir;
  const auto r = test::run_dynrad("validate --case 5.3 --json '" + dir.path("v.json") + "' --html '" +
                                  dir.path("v.html") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("every case within its goal"), std::string::npos) << r.output;
  const auto runs = nlohmann::json::parse(test::read_text(dir.path("v.json")));
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0]["case"], "5.3");
  // 64 floor and 12 wall points of the lit mesh, and the work plane's 64.
  EXPECT_EQ(runs[0]["points"].size(), 140u);
  for (const auto& p : runs[0]["points"]) {
    EXPECT_GT(p["reference"].get<double>(), 0) << p;
    EXPECT_LT(p["error"].get<double>(), 0.01) << p;
  }
  const std::string html = test::read_text(dir.path("v.html"));
  EXPECT_NE(html.find("5.3 Lambertian area source in a room"), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);  // the work plane's plan
  EXPECT_NE(html.find("within"), std::string::npos);
  // One chart of the points' errors per run: 140 points, none over the goal (red).
  EXPECT_NE(html.find("<svg"), std::string::npos);
  std::size_t dots = 0;
  for (auto at = html.find("<circle"); at != std::string::npos; at = html.find("<circle", at + 1)) ++dots;
  EXPECT_EQ(dots, 140u);
  EXPECT_EQ(html.find("fill=\"#c00\""), std::string::npos);
}

// 5.6's black walls take the floor's reflection: shot to convergence (--converge) at
// high quality they are within the goal, where the defaults' stop, by a mean error the
// bright floor dominates, leaves them short (docs/validation.md). The solves must get
// the option.
TEST(Validate, ConvergePassesToEverySolve) {
  test::TempDir dir;
  const auto r = test::run_dynrad("validate --case \"5.6 reflectance 0.5\" --quality high --converge 1e-4 --keep '" +
                                  dir.path("work") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("shot until 0.01% of the light is unshot"), std::string::npos) << r.output;
  const auto report = nlohmann::json::parse(test::read_text(dir.path("work/00_5.6_reflectance_0.5/report.json")));
  EXPECT_EQ(report["stopped_by"], "converged") << report.dump();
}

// A first SIGINT ends the run after the case under way: what was done is reported and
// written, the work folder removed, and the exit status says it was interrupted.
TEST(Validate, AnInterruptedRunKeepsWhatItDidAndCleansUp) {
  test::TempDir dir;
  const auto r = test::run_dynrad_and_signal("validate --case 5.9 --json '" + dir.path("v.json") + "'", 2, "INT",
                                             "5.9 ");
  EXPECT_NE(r.output.find("exit=3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("interrupted after"), std::string::npos) << r.output;
  const auto runs = nlohmann::json::parse(test::read_text(dir.path("v.json")));
  EXPECT_GE(runs.size(), 1u);
  EXPECT_LT(runs.size(), 16u);
  const auto at = r.output.find("(work in ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string work = r.output.substr(at + 9, r.output.find(')', at) - at - 9);
  EXPECT_FALSE(std::filesystem::exists(work)) << work;
}

// A line copied from --list names its case (the title sits between id and variant there),
// and only that case: 5.4 has three variants.
TEST(Validate, ALineOfTheListNamesItsCase) {
  const auto list = test::run_dynrad("validate --list");
  ASSERT_EQ(list.exit_code, 0) << list.output;
  const auto at = list.output.find("roof opening");
  ASSERT_NE(at, std::string::npos) << list.output;
  const auto start = list.output.rfind('\n', at) + 1;
  const std::string line = list.output.substr(start, list.output.find('\n', at) - start);
  const auto r = test::run_dynrad("validate --case '" + line + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("roof opening"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("facade opening"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("point source  "), std::string::npos) << r.output;
}

TEST(Validate, AnUnknownCaseIsNamed) {
  const auto r = test::run_dynrad("validate --case 9.9");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no case matches"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace dynrad
