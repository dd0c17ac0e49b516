// The storey sample's designer checks through the command line: every section its
// scene file asks for reaches the JSON report and the PDF.
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <set>

namespace dynrad {
namespace {

TEST(DesignCli, StoreySampleReportsRoomsObserversAndTheEscapeRoute) {
  test::TempDir dir;
  const test::CommandResult run =
      test::run_dynrad("solve -q '" + test::sample("storey_luminaires.json") + "' --quality draft -o '" +
                       dir.path("s.ply") + "' --report '" + dir.path("s.json") + "' --pdf '" + dir.path("s.pdf") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json r = nlohmann::json::parse(test::read_text(dir.path("s.json")));
  EXPECT_EQ(r["project"]["name"], "Storey sample");
  EXPECT_TRUE(r["project"].contains("date"));
  // Rooms: the grids with targets, each check with its target and verdict.
  std::set<std::string> rooms;
  for (const auto& room : r["rooms"]) {
    rooms.insert(room["name"].get<std::string>());
    bool all = true;
    for (const auto& c : room["checks"]) {
      ASSERT_TRUE(c.contains("target")) << c;
      all = all && c["met"].get<bool>();
    }
    EXPECT_EQ(room["met"].get<bool>(), all) << room["name"];
  }
  EXPECT_EQ(rooms, (std::set<std::string>{"living", "kitchen", "study"}));  // the bedroom has no target
  for (const auto& room : r["rooms"]) {
    if (room["name"] != "study") continue;
    std::set<std::string> areas;
    for (const auto& c : room["checks"]) areas.insert(c["area"].get<std::string>());
    EXPECT_EQ(areas, (std::set<std::string>{"task area", "surrounding", "walls", "ceiling", "task area at 1.2 m",
                                            "observers"}));
    // Floor to ceiling: the underside of the slab the lamps sit in (samples/storey_layout.json's
    // lamps at 2.64 m).
    EXPECT_NEAR(room["ceiling"].get<double>() - room["floor"].get<double>(), 2.64, 0.01);
    // Its observers: the one at the door sees the study's downlight, the one at the desk
    // has it behind: no luminaire in view.
    EXPECT_EQ(room["observers"].size(), 2u);
  }
  ASSERT_EQ(r["observers"].size(), 3u);
  for (const auto& o : r["observers"]) {
    if (o["name"] == "study desk") {
      EXPECT_TRUE(o["ugr"].is_null()) << o;
      EXPECT_EQ(o["counted"], 0);
    } else {
      ASSERT_TRUE(o["ugr"].is_number()) << o;
      EXPECT_GT(o["counted"].get<int>(), 0);
    }
    EXPECT_GT(o["background_luminance"].get<double>(), 0);
  }
  // The escape route: lit by the three emergency luminaires at a tenth of their flux.
  const auto& e = r["emergency"];
  EXPECT_EQ(e["luminaires"], (nlohmann::json{"living", "kitchen", "study"}));
  ASSERT_EQ(e["areas"].size(), 1u);
  const auto& route = e["areas"][0];
  EXPECT_EQ(route["kind"], "escape route");
  EXPECT_NEAR(route["length"].get<double>(), 4.7 + 3.9 + 2.2, 1e-9);
  EXPECT_EQ(route["checks"].size(), 3u);
  EXPECT_GT(route["Emin"].get<double>(), 0);
  // The schedule's facts.
  for (const auto& l : r["luminaires"]) {
    EXPECT_TRUE(l.contains("group")) << l;
    EXPECT_GT(l["watts"].get<double>(), 0);
    EXPECT_EQ(l["emergency"].get<bool>(), l["name"] != "bedroom");
  }
  // The PDF holds the sections.
  const test::CommandResult text = test::run_shell("pdftotext -layout '" + dir.path("s.pdf") + "' -");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  for (const char* words : {"Storey sample", "Luminaire schedule", "EN 12464-1", "study to exit", "study desk", "UGR",
                            "EN 1838"})
    EXPECT_NE(text.output.find(words), std::string::npos) << words;
}

// A light scene combined from one solve (each group in a channel of its own) equals a
// solve of the same dimming: the storey's "evening" (day group at 0.3, night at 1)
// against the storey with its day luminaires at 0.3 of their flux, both shot until 0.1%
// of the light is unshot, so that neither solve's own stopping error hides a fault.
TEST(DesignCli, LightSceneEqualsASolveOfTheSameDimming) {
  test::TempDir dir;
  nlohmann::json scene = nlohmann::json::parse(test::read_text(test::sample("storey_luminaires.json")));
  scene["meshes"][0]["file"] = test::sample(scene["meshes"][0]["file"].get<std::string>());
  for (auto& l : scene["luminaires"]) l["photometry"] = test::sample(l["photometry"].get<std::string>());
  const std::string with = dir.write("with.json", scene.dump());
  double level = -1;
  for (const auto& s : scene["scenes"])
    if (s["name"] == "evening") {
      ASSERT_EQ(s["levels"]["night"].get<double>(), 1.0);
      level = s["levels"]["day"].get<double>();
    }
  ASSERT_GT(level, 0);
  scene.erase("scenes");
  for (auto& l : scene["luminaires"])
    if (l["group"] == "day") {
      ASSERT_FALSE(l.contains("lumens"));
      l["lumens"] = 2550.8859005908103 * level;  // samples/downlight.ies's flux (radiosity/sources/photometry.h)
    }
  const std::string without = dir.write("without.json", scene.dump());
  for (const auto& [file, name] : {std::pair{with, "a"}, std::pair{without, "b"}}) {
    const test::CommandResult run = test::run_dynrad("solve -q '" + file + "' --quality draft --converge 0.001 -o '" +
                                                     dir.path(std::string(name) + ".ply") + "' --report '" +
                                                     dir.path(std::string(name) + ".json") + "'");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  const nlohmann::json a = nlohmann::json::parse(test::read_text(dir.path("a.json")));
  const nlohmann::json b = nlohmann::json::parse(test::read_text(dir.path("b.json")));
  ASSERT_EQ(a["scenes"].size(), 3u);
  EXPECT_FALSE(b.contains("scenes"));
  // The day luminaires' flux in the direct solve is the scene's.
  for (const auto& l : b["luminaires"])
    if (l["group"] == "day") {
      EXPECT_NEAR(l["flux"].get<double>(), 2550.8859005908103 * level, 1e-6);
    }
  std::size_t compared = 0;
  for (const auto& s : a["scenes"]) {
    if (s["name"] != "evening") continue;
    for (const auto& g : s["grids"])
      for (const auto& h : b["grids"]) {
        if (h["name"] != g["name"]) continue;
        for (const char* key : {"Eavg", "Emin", "Emax"})
          EXPECT_NEAR(g[key].get<double>(), h[key].get<double>(), 0.005 * h[key].get<double>()) << g["name"] << " " << key;
        ++compared;
      }
  }
  EXPECT_EQ(compared, 4u);
  // The scene with every group at full output is the solve's own grids.
  for (const auto& s : a["scenes"]) {
    if (s["name"] != "all on") continue;
    for (std::size_t k = 0; k < s["grids"].size(); ++k)
      EXPECT_NEAR(s["grids"][k]["Eavg"].get<double>(), a["grids"][k]["Eavg"].get<double>(),
                  1e-9 * a["grids"][k]["Eavg"].get<double>());
  }
}

// An output the PDF cannot be written to stops the solve before any work, naming it, and
// writes nothing else.
TEST(DesignCli, UnwritablePdfStopsTheSolveBeforeAnyWork) {
  test::TempDir dir;
  const test::CommandResult run = test::run_dynrad("solve -q '" + test::sample("storey_luminaires.json") + "' -o '" +
                                                   dir.path("s.ply") + "' --pdf '" + dir.path("missing/s.pdf") + "'");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("missing/s.pdf"), std::string::npos) << run.output;
  EXPECT_FALSE(test::file_exists(dir.path("s.ply")));
}

}  // namespace
}  // namespace dynrad
