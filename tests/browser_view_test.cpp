// `dynrad view`: the walk-through page. ViewCommand checks what the command writes and
// refuses; BrowserView opens the page in headless Chromium (Debian's chromium, software
// WebGL through SwiftShader) and looks at the picture it draws.
#include "mesh/io/read_glb.h"
#include "test_support.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

namespace dynrad {
namespace {

// tests/data/lamp_room: an 8 x 3 x 2.7 m room, its faces towards the inside, lit by an
// emitting panel (300 W/m^2) under the ceiling near its x = 0 end; its camera "wall" in
// the middle of the y = 0 side looks at the far wall (y = 3), so the end with the light is
// on the picture's left. tests/browser_walk_test.py walks through the same room.
const std::string kRoom = std::string(DYNRAD_TEST_DATA_DIR) + "/lamp_room/room.json";

// Solves the room into room.glb (and the declared camera's own pictures beside it).
void solve_room(const test::TempDir& dir) {
  const auto r = test::run_dynrad("solve '" + kRoom + "' -o '" + dir.path("room.glb") + "' --quality draft");
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The JSON chunk of a .glb.
nlohmann::json glb_json(const std::string& bytes) {
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

TEST(ViewCommand, GlbCarriesTheViewpointsAndThePageHoldsTheModel) {
  test::TempDir dir;
  solve_room(dir);
  // The viewer opens at the view that shows the most lit surface; the declared camera
  // follows it.
  const GlbSummary glb = read_glb_summary(dir.path("room.glb"));
  ASSERT_GE(glb.cameras.size(), 2u);
  EXPECT_NE(std::find(glb.cameras.begin(), glb.cameras.end(), "wall"), glb.cameras.end());
  EXPECT_EQ(glb.coloured_primitives, glb.primitives);  // no glass in the room
  EXPECT_TRUE(glb.scalars.empty());  // emission in watts: radiometric, no _LUMINANCE
  // No sky: no background for the viewer to show.
  EXPECT_FALSE(glb_json(test::read_text(dir.path("room.glb")))["scenes"][0].contains("extras"));

  const auto r = test::run_dynrad("view '" + dir.path("room.glb") + "' -o '" + dir.path("room.html") +
                                  "' --title 'Room <8 m> & co'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string html = test::read_text(dir.path("room.html"));
  // The .glb, byte for byte, as base64 (checked by its length: 4 characters per 3 bytes).
  const std::string glb_bytes = test::read_text(dir.path("room.glb"));
  const std::string start = "id=\"dynrad-model\">";
  const std::size_t from = html.find(start) + start.size(), to = html.find("</script>", from);
  ASSERT_NE(to, std::string::npos);
  EXPECT_EQ(to - from, (glb_bytes.size() + 2) / 3 * 4);
  EXPECT_EQ(html.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/=", from), to);
  // three.js r111 and its GLTFLoader are inlined, nothing is fetched.
  EXPECT_EQ(count(html, "REVISION=\"111\""), 1u);
  EXPECT_EQ(count(html, "exports.GLTFLoader = GLTFLoader"), 1u);
  EXPECT_EQ(count(html, "src=\"http"), 0u);
  EXPECT_EQ(count(html, "<script src"), 0u);
  // The title is escaped where it is shown; the configuration names the units.
  EXPECT_EQ(count(html, "Room &lt;8 m&gt; &amp; co"), 2u);
  EXPECT_EQ(count(html, "W/(m\xc2\xb2 sr)"), 1u);
}

TEST(ViewCommand, GlbCarriesTheWindowsSeeThrough) {
  // The daylit room's glass (MTL d 0.3: transmittance 0.7) is not lit, but a viewer
  // should show the windows: a "glazing" node, unlit, blended, two-sided, without vertex
  // colours, with every glazing triangle once.
  test::TempDir dir;
  const auto r = test::run_dynrad("solve '" + test::sample("daylight_overcast.json") + "' -o '" + dir.path("d.glb") +
                                  "' --quality draft");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto info = test::run_dynrad("info '" + test::sample("daylight_overcast.json") + "' --json");
  const std::size_t glazing_triangles =
      nlohmann::json::parse(info.output.substr(info.output.find('{')))["glazing_triangles"];
  ASSERT_GT(glazing_triangles, 0u);

  const nlohmann::json j = glb_json(test::read_text(dir.path("d.glb")));
  const auto& nodes = j["nodes"];
  const auto node = std::find_if(nodes.begin(), nodes.end(), [](const auto& n) { return n["name"] == "glazing"; });
  ASSERT_NE(node, nodes.end());
  const auto& mesh = j["meshes"][(*node)["mesh"].get<int>()];
  std::size_t corners = 0;
  for (const auto& primitive : mesh["primitives"]) {
    EXPECT_FALSE(primitive["attributes"].contains("COLOR_0"));
    corners += j["accessors"][primitive["attributes"]["POSITION"].get<int>()]["count"].get<std::size_t>();
    const auto& material = j["materials"][primitive["material"].get<int>()];
    EXPECT_EQ(material["alphaMode"], "BLEND");
    EXPECT_EQ(material["doubleSided"], true);
    EXPECT_TRUE(material["extensions"].contains("KHR_materials_unlit"));
    EXPECT_NEAR(material["extras"]["transmittance"][0].get<double>(), 0.7, 1e-9);
    EXPECT_NEAR(material["pbrMetallicRoughness"]["baseColorFactor"][3].get<double>(), 0.2 + 0.5 * 0.3, 1e-9);
  }
  EXPECT_EQ(corners, 3 * glazing_triangles);
  // Under the sky the background is the sky as the model's colours show it: white here
  // (its luminance near the horizon, some 1,300 cd/m^2, is far above the display white).
  const auto& extras = j["scenes"][0]["extras"];
  ASSERT_TRUE(extras.contains("background"));
  for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(extras["background"][c].get<double>(), 1.0);
  const GlbSummary summary = read_glb_summary(dir.path("d.glb"));
  EXPECT_EQ(summary.primitives, summary.coloured_primitives + mesh["primitives"].size());
  // And the page takes it.
  EXPECT_EQ(test::run_dynrad("view '" + dir.path("d.glb") + "' -o '" + dir.path("d.html") + "'").exit_code, 0);
}

TEST(ViewCommand, RefusesWhatABrowserCouldNotShowAndWritesNothing) {
  test::TempDir dir;
  auto refused = [&](const std::string& input, const std::string& output, const std::string& expected) {
    const auto r = test::run_dynrad("view '" + input + "' -o '" + output + "'");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    EXPECT_FALSE(test::file_exists(output)) << output;
  };
  const std::string page = dir.path("v.html");
  refused(dir.path("missing.glb"), page, "missing.glb");
  refused(dir.write("room.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), page, "is not binary glTF");
  refused(dir.write("short.glb", std::string("glTF\x02\0\0\0", 8) + std::string(40, '\0')), page, "cannot be read as glTF");
  // A real binary glTF whose vertices carry no colour (assimp's test box).
  refused("/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", page, "no vertex colours");

  solve_room(dir);
  const std::string glb = test::read_text(dir.path("room.glb"));
  refused(dir.write("cut.glb", glb.substr(0, glb.size() / 2)), page, "cut.glb");
  refused(dir.path("room.glb"), dir.path("v.png"), "name it NAME.html");
  refused(dir.path("room.glb"), dir.path("no/such/dir/v.html"), "v.html");
  // An existing page is left as it was when the new one is refused.
  dir.write("old.html", "keep me");
  const auto r = test::run_dynrad("view '" + dir.path("cut.glb") + "' -o '" + dir.path("old.html") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(test::read_text(dir.path("old.html")), "keep me");
}

// Headless Chromium on the page at `fragment` (the hash: view, mode), 800 x 600.
struct PageRun {
  std::string dom, log;
  test::Picture picture;
};

PageRun open_page(const test::TempDir& dir, const std::string& page, const std::string& fragment,
                  const std::string& name) {
  const std::string chromium =
      "chromium --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --hide-scrollbars "
      "--no-first-run --user-data-dir='" + dir.path("profile") + "' --window-size=800,600 --virtual-time-budget=30000 ";
  const std::string url = "'file://" + page + "#" + fragment + "'";
  PageRun run;
  const auto dom = test::run_shell(chromium + "--dump-dom " + url + " 2>/dev/null");
  EXPECT_EQ(dom.exit_code, 0) << dom.output;
  run.dom = dom.output;
  const auto shot = test::run_shell(chromium + "--enable-logging=stderr --v=0 --screenshot='" + dir.path(name) + "' " +
                                    url + " 2>&1");
  EXPECT_EQ(shot.exit_code, 0) << shot.output;
  run.log = shot.output;
  run.picture = test::read_png(dir.path(name));
  return run;
}

double mean(const test::Picture& p, int x0, int x1, int y0, int y1, int channel) {
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += channel < 0 ? (p.at(x, y)[0] + p.at(x, y)[1] + p.at(x, y)[2]) / 3.0
                                                      : p.at(x, y)[channel];
  return sum / ((x1 - x0) * (y1 - y0));
}

TEST(BrowserView, PageShowsTheLitModelAsDynradRendersIt) {
  test::TempDir dir;
  solve_room(dir);
  const auto r = test::run_dynrad("view '" + dir.path("room.glb") + "' -o '" + dir.path("room.html") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const PageRun page = open_page(dir, dir.path("room.html"), "view=wall", "page.png");
  // Loaded, drawn, and no error from any script.
  EXPECT_NE(page.dom.find("data-state=\"ready\""), std::string::npos) << page.dom.substr(0, 2000);
  EXPECT_NE(page.dom.find("data-view=\"wall\""), std::string::npos);
  EXPECT_NE(page.dom.find("data-errors=\"0\""), std::string::npos);
  EXPECT_EQ(page.log.find("Uncaught"), std::string::npos) << page.log;
  ASSERT_EQ(page.picture.width, 800) << page.log;
  ASSERT_EQ(page.picture.height, 600);

  // Not blank: the wall fills the middle of the picture with light, and the end with
  // the lamp (left) is brighter than the far end (right).
  const test::Picture& p = page.picture;
  const double left = mean(p, 40, 240, 250, 480, -1), right = mean(p, 560, 760, 250, 480, -1);
  EXPECT_GT(left, 60.0);
  EXPECT_GT(left, 1.3 * right) << "left " << left << ", right " << right;

  // The same camera rendered by dynrad itself (room_view_wall.png, 800 x 600, the same
  // exposure and sRGB curve): the page's pixels match away from its overlays (the panel
  // top left, the read-out at the bottom, the cross-hair in the middle).
  const test::Picture own = test::read_png(dir.path("room_view_wall.png"));
  ASSERT_EQ(own.width, 800);
  double difference = 0;
  int pixels = 0;
  for (int y = 0; y < 560; ++y)
    for (int x = 0; x < 800; ++x) {
      const bool panel = x < 400 && y < 190, cross = std::abs(x - 400) < 12 && std::abs(y - 300) < 12;
      if (panel || cross) continue;
      for (int c = 0; c < 3; ++c) difference += std::abs(p.at(x, y)[c] - own.at(x, y)[c]);
      pixels += 3;
    }
  std::printf("page against dynrad's own picture: %.2f of 255 per channel on average\n", difference / pixels);
  EXPECT_LT(difference / pixels, 6.0) << "mean difference per channel, of 255";
}

// Where a colour lies on the false-colour scale, t in [0, 1]: the nearest of 501 colours
// along the report's scale (plugin/report/grid_picture.cpp's stops).
double scale_position(const std::uint8_t* rgb) {
  static const double stops[6][3] = {{0.05, 0.05, 0.45}, {0.0, 0.35, 1.0}, {0.0, 0.85, 0.9},
                                     {0.2, 0.8, 0.2},    {1.0, 0.9, 0.0},  {0.9, 0.1, 0.1}};
  double best = 1e300, best_t = 0;
  for (int k = 0; k <= 500; ++k) {
    const double t = k / 500.0, u = std::min(4.999999, t * 5);
    const int s = static_cast<int>(u);
    double d = 0;
    for (int c = 0; c < 3; ++c) {
      const double v = 255 * (stops[s][c] * (1 - (u - s)) + stops[s + 1][c] * (u - s));
      d += (v - rgb[c]) * (v - rgb[c]);
    }
    if (d < best) {
      best = d;
      best_t = t;
    }
  }
  return best_t;
}

TEST(BrowserView, FalseColourRisesTowardsTheLightAsInDynradsOwnPicture) {
  test::TempDir dir;
  const auto solved = test::run_dynrad("solve '" + kRoom + "' -o '" + dir.path("room.glb") +
                                       "' --quality draft --report '" + dir.path("report.json") + "'");
  ASSERT_EQ(solved.exit_code, 0) << solved.output;
  // The scale's top of dynrad's own false-colour picture of the camera, given to the page.
  const nlohmann::json report = nlohmann::json::parse(test::read_text(dir.path("report.json")));
  ASSERT_EQ(report["views"].size(), 1u);
  const double top = report["views"][0]["luminance_legend_top"];
  ASSERT_EQ(test::run_dynrad("view '" + dir.path("room.glb") + "' -o '" + dir.path("room.html") + "'").exit_code, 0);
  const PageRun page =
      open_page(dir, dir.path("room.html"), "view=wall&mode=false&top=" + std::to_string(top), "false.png");
  EXPECT_NE(page.dom.find("data-state=\"ready\""), std::string::npos);
  EXPECT_NE(page.dom.find("data-errors=\"0\""), std::string::npos);
  ASSERT_EQ(page.picture.width, 800) << page.log;

  // Along a band of the wall below the panel and the legend, the colours lie on the
  // report's scale and climb it towards the lamp's end.
  const test::Picture& p = page.picture;
  auto position = [&](const test::Picture& picture, int x0, int dx, int dy) {
    double sum = 0;
    for (int y = 420; y < 540; ++y)
      for (int x = x0; x < x0 + 40; ++x) sum += scale_position(picture.at(x + dx, y + dy));
    return sum / (120 * 40);
  };
  const double t_left = position(p, 40, 0, 0), t_middle = position(p, 380, 0, 0), t_right = position(p, 720, 0, 0);
  std::printf("false colour along the wall: t = %.3f, %.3f, %.3f (top %g)\n", t_left, t_middle, t_right, top);
  EXPECT_GT(t_left, t_middle + 0.05);
  EXPECT_GT(t_middle, t_right + 0.02);

  // dynrad's own false-colour picture of the camera (its 800 x 600 view starts 12 pixels
  // in and 56 down, below its title) places the same points at the same t.
  const test::Picture own = test::read_png(dir.path("room_view_wall_luminance.png"));
  ASSERT_GT(own.width, 800);
  for (int x0 : {40, 380, 720}) {
    const double t_page = position(p, x0, 0, 0), t_own = position(own, x0, 12, 56);
    EXPECT_NEAR(t_page, t_own, 0.01) << "at x = " << x0;
  }
}

}  // namespace
}  // namespace dynrad
