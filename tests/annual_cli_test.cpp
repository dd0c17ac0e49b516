// `dynrad annual` (plugin/cli/cmd_annual.cpp): a synthetic clear year on the daylit
// room sample gives metrics that agree with its own files and with what the geometry
// implies, and bad input is refused before any work, leaving no output.
#include "synthetic_weather.h"
#include "test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace dynrad {
namespace {

std::string sample(const std::string& name) { return std::string(DYNRAD_SAMPLES_DIR) + "/" + name; }

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AnnualCli, AClearYearOnTheDaylitRoom) {
  test::TempDir dir;
  test::SyntheticYear clear;  // a site near London, every day clear
  const test::TempWeatherFile weather(clear);
  const auto run = test::run_dynrad("annual '" + sample("daylight_overcast.json") + "' --weather '" + weather.path() +
                                    "' -o '" + dir.path("room") + "' --hour 06-21-13 --hour 01-01-01 "
                                    "--vertex-coefficients");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto j = nlohmann::json::parse(read(dir.path("room_annual.json")));
  ASSERT_EQ(j["grids"].size(), 1u);
  const auto& g = j["grids"][0];
  const std::size_t points = g["points"].get<std::size_t>() + g["masked"].get<std::size_t>();
  EXPECT_EQ(points, 240u);  // 6 x 4 m less a 0.5 m border, every 0.25 m
  EXPECT_EQ(j["weather"]["hours"].get<int>(), 8760);
  // Every day clear, and a south window of 2.4 x 1.4 m: some points get direct sun over
  // 1000 lx for more than 250 of the occupied hours, and most reach 300 lx for half of them.
  EXPECT_GT(g["ASE1000_250h"].get<double>(), 5);
  EXPECT_GT(g["sDA300_50"].get<double>(), 50);
  const double udi = g["UDI_below_100"].get<double>() + g["UDI_100_3000"].get<double>() + g["UDI_above_3000"].get<double>();
  EXPECT_NEAR(udi, 100, 1e-6);
  EXPECT_EQ(g["EN17037"]["daylight_hours"].get<int>(), 4380);

  // The hourly file: NumPy's format, (8760, 240) float32; dark at midnight, lit at noon
  // in June everywhere, brightest near the south window (y = 0.625) at noon.
  const std::string npy = read(dir.path("room_room_hourly.npy"));
  ASSERT_GE(npy.size(), 10u);
  EXPECT_EQ(npy.substr(0, 6), "\x93NUMPY");
  const std::size_t header = 10 + (static_cast<unsigned char>(npy[8]) | static_cast<unsigned char>(npy[9]) << 8);
  EXPECT_EQ(header % 64, 0u);
  EXPECT_NE(npy.find("'shape': (8760, 240)"), std::string::npos);
  ASSERT_EQ(npy.size(), header + 8760u * 240 * 4);
  auto lux = [&](std::size_t row, std::size_t point) {
    float v;
    std::memcpy(&v, npy.data() + header + (row * 240 + point) * 4, 4);
    return v;
  };
  const std::size_t june_noon = (31 + 28 + 31 + 30 + 31 + 20) * 24 + 12;  // 21 June, 12:00-13:00
  double midnight = 0, noon_min = 1e30;
  for (std::size_t k = 0; k < 240; ++k) {
    midnight += lux(june_noon - 12, k);
    noon_min = std::min<double>(noon_min, lux(june_noon, k));
  }
  EXPECT_EQ(midnight, 0);
  EXPECT_GT(noon_min, 100);

  // The points file: each point's column in the hourly file, and the mean of its DA
  // column is the JSON's mean DA.
  std::istringstream csv(read(dir.path("room_room_points.csv")));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.substr(0, 18), "point,x,y,z,DA300,");
  double sum = 0;
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    std::istringstream fields(line);
    std::string index, x, y, z, da;
    std::getline(fields, index, ',');
    EXPECT_EQ(std::stoul(index), rows);  // no point of this room is masked: columns in order
    std::getline(fields, x, ',');
    std::getline(fields, y, ',');
    std::getline(fields, z, ',');
    std::getline(fields, da, ',');
    sum += std::stod(da);
    ++rows;
  }
  EXPECT_EQ(rows, g["points"].get<std::size_t>());
  EXPECT_NEAR(100 * sum / static_cast<double>(rows), g["DA300_mean"].get<double>(), 0.01);
  for (const char* plan : {"DA300", "cDA300", "UDI", "ASE"})
    EXPECT_TRUE(std::filesystem::exists(dir.path(std::string("room_room_") + plan + ".png"))) << plan;
  // The HTML report: the figures of the JSON, EN 17037's table and the four plans embedded.
  const std::string html = read(dir.path("room_annual.html"));
  EXPECT_NE(html.find(fmt::format("{:.1f}%", g["sDA300_50"].get<double>())), std::string::npos);
  EXPECT_NE(html.find("level achieved <strong>" + g["EN17037"]["achieved"].get<std::string>()), std::string::npos);
  std::size_t images = 0;
  for (std::size_t at = html.find("data:image/png;base64,"); at != std::string::npos;
       at = html.find("data:image/png;base64,", at + 1))
    ++images;
  EXPECT_EQ(images, 4u);

  // The model at 12:00-13:00 on 21 June: a sun patch on the floor (a floor of
  // reflectance 0.3 to 0.6 in tens of thousands of lux); at midnight, black.
  ASSERT_EQ(j["hours"].size(), 2u);
  EXPECT_TRUE(j["hours"][0]["sun"].get<bool>());
  EXPECT_GT(j["hours"][0]["mean_luminance"].get<double>(), 10);
  EXPECT_TRUE(j["hours"][1]["dark"].get<bool>());
  EXPECT_EQ(j["hours"][1]["mean_luminance"].get<double>(), 0);
  auto ply_vertices = [](const std::string& ply, std::size_t* data) {
    const std::size_t at = ply.find("element vertex "), end = ply.find("end_header\n");
    if (at == std::string::npos || end == std::string::npos) return std::size_t(0);
    *data = end + 11;
    return static_cast<std::size_t>(std::stoul(ply.substr(at + 15)));
  };
  const std::string june = read(dir.path("room_hour_0621_13.ply"));
  std::size_t data = 0;
  const std::size_t vertices = ply_vertices(june, &data);
  ASSERT_GT(vertices, 100u);
  ASSERT_NE(june.find("property float illuminance"), std::string::npos);
  float brightest = 0;
  for (std::size_t v = 0; v < vertices; ++v) {  // x y z, r g b, radiosity r g b, quality: 27 bytes in
    float quality;
    std::memcpy(&quality, june.data() + data + v * 39 + 27, 4);
    brightest = std::max(brightest, quality);
  }
  EXPECT_GT(brightest, 20000);
  EXPECT_TRUE(std::filesystem::exists(dir.path("room_hour_0101_01.ply")));
  // Every vertex's coefficients: a row per vertex of the mesh beside them, a column per
  // channel of the solve.
  const std::string coefficients = read(dir.path("room_vertex_coefficients.npy"));
  EXPECT_NE(coefficients.find(fmt::format("'shape': ({}, {})", vertices, j["solve"]["channels"].get<int>())),
            std::string::npos);
  std::size_t mesh_data = 0;
  EXPECT_EQ(ply_vertices(read(dir.path("room_vertices.ply")), &mesh_data), vertices);
  EXPECT_EQ(j["vertex_coefficients"]["sun_positions"].size(), j["solve"]["channels"].get<std::size_t>() - 578);
}

// A stop during the solve (SIGTERM) still gives the year, from the light shot so far,
// said so in the report, with exit code 3.
TEST(AnnualCli, AStoppedSolveStillGivesTheYearFromTheLightSoFar) {
  test::TempDir dir;
  test::SyntheticYear clear;
  const test::TempWeatherFile weather(clear);
  const auto run = test::run_dynrad_and_signal("annual '" + sample("daylight_overcast.json") + "' --weather '" +
                                                   weather.path() + "' -o '" + dir.path("room") + "' --blinds 0.2",
                                               2.0, "TERM", " channels");
  ASSERT_NE(run.output.find("exit=3"), std::string::npos) << run.output;
  const auto j = nlohmann::json::parse(read(dir.path("room_annual.json")));
  EXPECT_TRUE(j["interrupted"].get<bool>());
  EXPECT_EQ(j["solve"]["stopped_by"].get<std::string>(), "interrupted");
  EXPECT_GT(j["solve"]["unshot_percent"].get<double>(), 1);
  EXPECT_TRUE(std::filesystem::exists(dir.path("room_room_hourly.npy")));
  EXPECT_GT(j["grids"][0]["DA300_mean"].get<double>(), 0);
  // LM-83's blinds: a clear year through a south window closes them in many occupied
  // hours, and the report says so.
  EXPECT_GT(j["grids"][0]["blinds_closed_hours"].get<int>(), 100);
  EXPECT_NE(j["conventions"]["blinds"].get<std::string>().find("pass 0.2"), std::string::npos);
  EXPECT_NE(j["grids"][0]["notes"].dump().find("LM-83 blinds: closed in"), std::string::npos);
}

TEST(AnnualCli, BadInputIsRefusedBeforeAnyWorkAndWritesNothing) {
  test::TempDir dir;
  test::SyntheticYear clear;
  clear.days = 2;  // not a whole year: refused
  const test::TempWeatherFile short_year(clear);
  test::SyntheticYear whole;
  const test::TempWeatherFile weather(whole);
  const std::string room = "'" + sample("daylight_overcast.json") + "'";
  const std::string out = " -o '" + dir.path("out") + "'";
  struct Case {
    std::string arguments, says;
  };
  dir.write("nogrid.json", "{\"meshes\": [{\"file\": \"" + sample("daylight_room.obj") + "\"}]}");
  // A closed box: no glass, no opening.
  dir.write("box.obj", "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nv 0 0 2\nv 2 0 2\nv 2 2 2\nv 0 2 2\n"
                       "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  dir.write("nowindow.json", "{\"meshes\": [{\"file\": \"box.obj\"}], \"grids\": [{\"name\": \"floor\", "
                             "\"rectangle\": [0.2, 0.2, 1.8, 1.8], \"height\": 0.8}]}");
  const std::string grid = R"(, "grids": [{"name": "g", "rectangle": [0.5, 0.5, 5.5, 3.5], "height": 0.85}])";
  dir.write("north.json", "{\"meshes\": [{\"file\": \"" + sample("daylight_room.obj") + "\"}]" + grid +
                              R"(, "sky": {"north": [0, 0]}})");
  dir.write("ground.json", "{\"meshes\": [{\"file\": \"" + sample("daylight_room.obj") + "\"}]" + grid +
                               R"(, "sky": {"ground_reflectance": 1.2}})");
  const std::vector<Case> cases = {
      {"'" + dir.path("north.json") + "' --weather '" + weather.path() + "'" + out, "sky.north"},
      {"'" + dir.path("ground.json") + "' --weather '" + weather.path() + "'" + out, "sky.ground_reflectance"},
      {room + " --weather '" + weather.path() + "' --occupied 18-8" + out, "--occupied"},
      {room + " --weather '" + weather.path() + "' --occupied 8" + out, "--occupied"},
      {room + " --weather '" + short_year.path() + "'" + out, short_year.path()},
      {room + " --weather '" + dir.path("missing.epw") + "'" + out, "missing.epw"},
      {"'" + dir.path("nogrid.json") + "' --weather '" + weather.path() + "'" + out, "grids"},
      {room + " --weather '" + weather.path() + "' -o '" + dir.path("no/such/dir/out") + "'", "no/such/dir"},
      {room + " --weather '" + weather.path() + "' --hour noon" + out, "--hour"},
      {room + " --weather '" + weather.path() + "' --blinds 1.5" + out, "--blinds"},
      {room + " --weather '" + weather.path() + "' --hour 02-30-12" + out, "no such row"},
      {room + " --weather '" + weather.path() + "' --hour 06-21-0" + out, "no such row"},
  };
  for (const Case& c : cases) {
    const auto run = test::run_dynrad("annual " + c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.output;
    EXPECT_NE(run.output.find(c.says), std::string::npos) << c.arguments << "\n" << run.output;
  }
  const auto no_window = test::run_dynrad("annual '" + dir.path("nowindow.json") + "' --weather '" + weather.path() + "'" + out);
  EXPECT_EQ(no_window.exit_code, 2) << no_window.output;
  EXPECT_NE(no_window.output.find("no windows"), std::string::npos) << no_window.output;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path("")))
    EXPECT_EQ(entry.path().filename().string().rfind("out", 0), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace dynrad
