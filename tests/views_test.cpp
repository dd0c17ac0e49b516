// Views (radiosity/analysis/views.h, rooms.h, render.h): storeys and rooms found from geometry,
// plans cut through walls, declared cameras pointing where they say, a preview that is
// never black inside a closed building, and the HTML report's contents.
#include "mesh/core/error.h"
#include "mesh/io/io_util.h"
#include "radiosity/analysis/render.h"
#include "radiosity/analysis/rooms.h"
#include "radiosity/analysis/views.h"
#include "test_support.h"

#include <boost/archive/iterators/base64_from_binary.hpp>
#include <boost/archive/iterators/transform_width.hpp>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>

namespace dynrad {
namespace {

using Value = std::function<Rgb(const Vec3d&)>;

// A lit scene written by hand: quads with their own corners, so each carries its own
// radiosity (a function of position).
class LitBuilder {
 public:
  // The rectangle corner, corner + u, corner + u + v, corner + v, wound to face `normal`.
  void quad(const Vec3d& corner, Vec3d u, Vec3d v, const Vec3d& normal, const Value& value, Rgb emission = Rgb()) {
    if (OpenMesh::dot(OpenMesh::cross(u, v), normal) < 0) std::swap(u, v);
    const auto base = static_cast<std::uint32_t>(scene.positions.size());
    for (const Vec3d& p : {corner, corner + u, corner + u + v, corner + v}) {
      scene.positions.push_back(p);
      scene.radiosity.push_back(value(p));
    }
    scene.triangles.push_back({base, base + 1, base + 2});
    scene.triangles.push_back({base, base + 2, base + 3});
    scene.emission.push_back(emission);
    scene.emission.push_back(emission);
  }
  // An axis-aligned box, faces outward (a solid) or inward (a room).
  void box(const Vec3d& lo, const Vec3d& hi, bool inward, const Value& value) {
    const Vec3d e = hi - lo;
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        Vec3d corner = lo, u(0.0), v(0.0), n(0.0);
        corner[a] = side ? hi[a] : lo[a];
        u[b] = e[b];
        v[c] = e[c];
        n[a] = (side ? 1.0 : -1.0) * (inward ? -1.0 : 1.0);
        quad(corner, u, v, n, value);
      }
  }
  rad::LitScene& done() {
    scene.prepare();
    return scene;
  }
  rad::LitScene scene;
};

Value constant(double b) {
  return [b](const Vec3d&) { return Rgb(b); };
}

// A 10 x 6 m storey, 2.7 m high, cut in two by a 0.2 m wall at x = 5 with a door of
// `door` width from y = 2.5, 2.1 m high.
void two_rooms(LitBuilder& b, double door) {
  b.box(Vec3d(0, 0, 0), Vec3d(10, 6, 2.7), true, constant(1));
  b.box(Vec3d(4.9, 0, 0), Vec3d(5.1, 2.5, 2.7), false, constant(0.5));
  b.box(Vec3d(4.9, 2.5 + door, 0), Vec3d(5.1, 6, 2.7), false, constant(0.5));
  b.box(Vec3d(4.9, 2.5, 2.1), Vec3d(5.1, 2.5 + door, 2.7), false, constant(0.5));
}

TEST(Views, UpIsAgainstTheEmittersFacing) {
  LitBuilder b;
  b.box(Vec3d(0, 0, 0), Vec3d(4, 3, 5), true, constant(1));
  b.quad(Vec3d(1, 2.9, 1), Vec3d(1, 0, 0), Vec3d(0, 0, 1), Vec3d(0, -1, 0), constant(10), Rgb(10));
  EXPECT_EQ(rad::up_axis(b.done()), 1);
  LitBuilder plain;
  plain.box(Vec3d(0, 0, 0), Vec3d(4, 3, 5), true, constant(1));
  EXPECT_EQ(rad::up_axis(plain.done()), 2);  // nothing says otherwise: z
}

TEST(Views, FindsTwoStoreysAndNeitherTheRoofNorATable) {
  LitBuilder b;
  b.box(Vec3d(0, 0, 0), Vec3d(10, 8, 2.7), true, constant(1));        // ground floor room
  b.box(Vec3d(0, 0, 3.0), Vec3d(10, 8, 5.7), true, constant(1));      // first floor room
  b.box(Vec3d(-1, -1, 5.8), Vec3d(11, 9, 6.1), false, constant(0.2));  // roof slab: sky above
  b.box(Vec3d(2, 2, 0), Vec3d(4, 3, 0.75), false, constant(1));       // a table
  const std::vector<rad::Storey> storeys = rad::find_storeys(b.done(), 2);
  ASSERT_EQ(storeys.size(), 2u);
  EXPECT_NEAR(storeys[0].floor, 0.0, 1e-9);
  EXPECT_NEAR(storeys[1].floor, 3.0, 1e-9);
  for (const rad::Storey& s : storeys) {
    EXPECT_NEAR(s.height, 2.7, 1e-4);  // Embree's single precision
    EXPECT_NEAR(s.lo[0], 0, 1e-9);
    EXPECT_NEAR(s.hi[0], 10, 1e-9);
    EXPECT_NEAR(s.lo[1], 0, 1e-9);
    EXPECT_NEAR(s.hi[1], 8, 1e-9);
  }
}

TEST(Views, ADoorwaySeparatesRoomsAWideOpeningDoesNot) {
  LitBuilder narrow;
  two_rooms(narrow, 0.9);
  const rad::LitScene& scene = narrow.done();
  const auto storeys = rad::find_storeys(scene, 2);
  ASSERT_EQ(storeys.size(), 1u);
  const std::vector<rad::Room> rooms = rad::find_rooms(scene, 2, storeys[0]);
  ASSERT_EQ(rooms.size(), 2u);
  for (const rad::Room& r : rooms) {
    const bool west = r.middle[0] < 5;
    EXPECT_NEAR(r.middle[0], west ? 2.45 : 7.55, 0.15);
    EXPECT_NEAR(r.middle[1], 3.0, 0.15);
    EXPECT_NEAR(r.area, 4.9 * 6, 0.1 * 4.9 * 6);
    // The camera's corner is in the same room, clear of its walls.
    EXPECT_EQ(r.corner[0] < 5, west);
    EXPECT_GT(std::min({r.corner[0] - (west ? 0 : 5.1), (west ? 4.9 : 10) - r.corner[0], r.corner[1], 6 - r.corner[1]}),
              0.4);
  }
  LitBuilder wide;
  two_rooms(wide, 1.6);
  const rad::LitScene& open = wide.done();
  EXPECT_EQ(rad::find_rooms(open, 2, rad::find_storeys(open, 2)[0]).size(), 1u);
}

// The pixel of a plan (orthographic, looking down -z, x to the right) over (x, y).
std::size_t plan_pixel(const rad::View& v, double x, double y) {
  const rad::Camera& c = v.camera;
  const double aspect = static_cast<double>(v.width) / v.height, half = 0.5 * c.view_height;
  const int px = static_cast<int>(((x - c.eye[0]) / (half * aspect) + 1) / 2 * v.width);
  const int py = static_cast<int>((1 - (y - c.eye[1]) / half) / 2 * v.height);
  return static_cast<std::size_t>(py) * v.width + px;
}

TEST(Views, PlanCutsThroughWallsAndShowsTheFloor) {
  LitBuilder b;
  two_rooms(b, 0.9);
  const rad::LitScene& scene = b.done();
  const std::vector<rad::View> views = rad::automatic_views(scene, {});
  ASSERT_EQ(views.size(), 3u);  // a plan and two rooms
  const rad::View& plan = views[0];
  ASSERT_EQ(plan.kind, rad::View::Kind::plan);
  EXPECT_EQ(plan.name, "plan_storey1");
  EXPECT_NEAR(plan.camera.eye[2], 0.45 * 2.7, 1e-4);  // the cut
  const rad::RenderedView r = rad::render_view(scene, plan.camera, plan.width, plan.height);
  EXPECT_EQ(r.kind[plan_pixel(plan, 5.0, 1.0)], rad::PixelKind::back);    // the wall, cut
  EXPECT_EQ(r.kind[plan_pixel(plan, 5.0, 2.95)], rad::PixelKind::front);  // the doorway's floor
  EXPECT_EQ(r.kind[plan_pixel(plan, 2.0, 1.0)], rad::PixelKind::front);   // the floor
  EXPECT_EQ(r.kind[plan_pixel(plan, 7.0, 5.0)], rad::PixelKind::front);
  EXPECT_NEAR(r.radiosity[plan_pixel(plan, 2.0, 1.0)].r, 1.0, 1e-9);
  // The room views stand in their rooms and look at the middle.
  for (int k = 1; k < 3; ++k) {
    EXPECT_EQ(views[k].kind, rad::View::Kind::room);
    EXPECT_NEAR(views[k].camera.eye[2], 0.6 * 2.7, 1e-4);
    EXPECT_EQ(views[k].camera.eye[0] < 5, views[k].camera.target[0] < 5);
  }
}

TEST(Views, RoomsTakeTheirGridsNames) {
  LitBuilder b;
  two_rooms(b, 0.9);
  rad::GridSpec office;
  office.name = "office";
  office.polygon = {{5.1, 0}, {10, 0}, {10, 6}, {5.1, 6}};
  const std::vector<rad::View> views = rad::automatic_views(b.done(), {office});
  std::vector<std::string> names;
  for (const rad::View& v : views) names.push_back(v.name);
  EXPECT_NE(std::find(names.begin(), names.end(), "room_office"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "storey1_room1"), names.end());
}

TEST(Views, RoomCameraStandsWhereItSeesTheMostLitSurface) {
  // A 6 x 4 x 2.7 m room whose light falls off along x, from 0.5 at x = 0 to 0 at x = 6.
  // At an exposure that counts 0.25 and up as lit (1% of display white 0.9 / 0.036), the
  // lit half is x < 3: a camera in a corner of the dark half looks into it, one in the
  // lit half looks away from it. Without an exposure the camera stands in the farthest
  // corner, as before. A 0.3 m column against the wall at y = 0 in the lit half moves
  // the room's middle towards +x and +y, so that the corner at (0.54, 0.54) is the
  // farthest by a clear margin: in an empty room the four corners tie, and which one
  // wins would be rounding's choice.
  LitBuilder b;
  const Value falling = [](const Vec3d& p) { return Rgb(0.5 * (1 - p[0] / 6)); };
  b.box(Vec3d(0, 0, 0), Vec3d(6, 4, 2.7), true, falling);
  b.box(Vec3d(1.2, 0, 0), Vec3d(1.5, 0.3, 2.7), false, falling);
  const rad::LitScene& scene = b.done();
  rad::ViewOptions options;
  options.plans = false;
  options.exposure = 0.009 / 0.25;
  const std::vector<rad::View> chosen = rad::automatic_views(scene, {}, options);
  ASSERT_EQ(chosen.size(), 1u);
  EXPECT_GT(chosen[0].camera.eye[0], 3.0);
  EXPECT_LT(chosen[0].camera.target[0] - chosen[0].camera.eye[0], 0.0);  // looking towards the light

  const std::vector<rad::Room> rooms = rad::find_rooms(scene, 2, rad::find_storeys(scene, 2).at(0));
  ASSERT_EQ(rooms.size(), 1u);
  ASSERT_EQ(rooms[0].corners.size(), 4u);  // one in each quarter around the middle
  for (const auto& c : rooms[0].corners) {
    // 0.54 m in from the walls (the erosion), to within two raster cells.
    EXPECT_NEAR(std::min(c[0], 6 - c[0]), 0.54, 0.15);
    EXPECT_NEAR(std::min(c[1], 4 - c[1]), 0.54, 0.15);
  }
  options.exposure = 0;
  const std::vector<rad::View> farthest = rad::automatic_views(scene, {}, options);
  ASSERT_EQ(farthest.size(), 1u);
  // (The farthest corner lies in the lit half, so the choice above is the score's.)
  EXPECT_NEAR(rooms[0].corner[0], 0.54, 0.15);
  EXPECT_NEAR(rooms[0].corner[1], 0.54, 0.15);
  EXPECT_NEAR(farthest[0].camera.eye[0], rooms[0].corner[0], 1e-12);
  EXPECT_NEAR(farthest[0].camera.eye[1], rooms[0].corner[1], 1e-12);
}

TEST(Views, DeclaredCameraLooksWhereItSays) {
  // The -x wall of a room brightens upwards (z) and along +y: a camera looking at it
  // along -x with z up has +y to its right, so its picture brightens up and right.
  LitBuilder b;
  b.box(Vec3d(0, 0, 0), Vec3d(6, 4, 3), true, constant(0.1));
  b.quad(Vec3d(0.01, 0, 0), Vec3d(0, 4, 0), Vec3d(0, 0, 3), Vec3d(1, 0, 0),
         [](const Vec3d& p) { return Rgb(0.2 + 0.1 * p[2] + 0.05 * p[1]); });
  test::TempDir dir;
  const std::string path =
      dir.write("cams.json", R"({"cameras": [{"name": "wall", "position": [5, 2, 1.5], "look_at": [0, 2, 1.5],
                                   "fov": 40, "width": 64, "height": 48}]})");
  const std::vector<rad::View> cameras = rad::read_cameras(path);
  ASSERT_EQ(cameras.size(), 1u);
  const rad::View& v = cameras[0];
  EXPECT_EQ(v.name, "wall");
  EXPECT_EQ(v.width, 64);
  EXPECT_EQ(v.height, 48);
  const rad::RenderedView r = rad::render_view(b.done(), v.camera, v.width, v.height);
  auto at = [&](int x, int y) { return r.radiosity[static_cast<std::size_t>(y) * v.width + x].r; };
  // The middle pixel sees the wall's middle: 0.2 + 0.15 + 0.1.
  EXPECT_NEAR(0.5 * (at(31, 23) + at(32, 24)), 0.45, 0.01);
  // Rows 10 and 37 see the wall 1 m above and below the middle, columns 10 and 53 1.6 m
  // to either side (the picture's edges see the floor, ceiling and side walls).
  const double row10_height = 13.5 / 24 * std::tan(20 * M_PI / 180) * 4.99;  // above the middle
  EXPECT_NEAR(at(32, 10), 0.45 + 0.1 * row10_height, 0.01);                  // up is up
  EXPECT_GT(at(32, 10), at(32, 37) + 0.15);
  EXPECT_GT(at(53, 24), at(10, 24) + 0.1);  // +y is to the right
  EXPECT_NEAR(r.luminance(static_cast<std::size_t>(24) * v.width + 32), at(32, 24) / M_PI, 1e-12);
}

TEST(Views, CameraEntriesAreCheckedAndNamed) {
  test::TempDir dir;
  auto message = [&](const std::string& cameras) {
    const std::string path = dir.write("c.json", "{\"cameras\": " + cameras + "}");
    try {
      rad::read_cameras(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"([{"position": [0, 0, 1]}])").find("cameras[0] (\"camera1\") needs \"position\" and \"look_at\""),
            std::string::npos);
  EXPECT_NE(message(R"([{"name": "a", "position": [0, 0, 1], "look_at": [0, 0, 1]}])").find("the camera's own position"),
            std::string::npos);
  EXPECT_NE(message(R"([{"name": "a", "position": [0, 0, 1], "look_at": [0, 0, 0]}])").find("looks along its \"up\""),
            std::string::npos);
  EXPECT_NE(message(R"([{"name": "a", "position": [0, 0, 1], "look_at": [1, 0, 1], "fov": 180}])").find(".fov"),
            std::string::npos);
  EXPECT_NE(message(R"([{"name": "a", "position": [0, 0, 1], "look_at": [1, 0, 1], "zoom": 2}])")
                .find("unknown key \"zoom\" in cameras[0]"),
            std::string::npos);
  EXPECT_NE(message(R"([{"name": "a", "position": [0, 0, 1], "look_at": [1, 0, 1]},
                        {"name": "a", "position": [0, 0, 1], "look_at": [1, 0, 1]}])")
                .find("two cameras are named \"a\""),
            std::string::npos);
  EXPECT_NE(message(R"([{"name": "../x", "position": [0, 0, 1], "look_at": [1, 0, 1]}])").find("must not hold '/'"),
            std::string::npos);
}

TEST(Views, PreviewInsideAClosedBuildingIsNotBlack) {
  // The storey sample is closed all round (walls, floor and ceiling slabs); its outside
  // is unlit. The preview must look inside.
  test::TempDir dir;
  const auto r = test::run_dynrad("solve '" + test::sample("storey.obj") + "' -o '" + dir.path("s.ply") +
                                  "' --quality draft --preview '" + dir.path("s.png") + "' --preview-width 160");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const test::Picture p = test::read_png(dir.path("s.png"));
  ASSERT_EQ(p.width, 160);
  std::size_t bright = 0;
  double sum = 0;
  for (std::size_t i = 0; i < p.rgb.size(); i += 3) {
    const double v = (p.rgb[i] + p.rgb[i + 1] + p.rgb[i + 2]) / 3.0;
    sum += v;
    bright += v > 40;
  }
  const double pixels = static_cast<double>(p.rgb.size() / 3);
  EXPECT_GT(sum / pixels, 60.0) << r.output;
  EXPECT_GT(static_cast<double>(bright) / pixels, 0.7) << r.output;
}

std::string base64_of(const std::string& bytes) {
  using namespace boost::archive::iterators;
  using Encoder = base64_from_binary<transform_width<std::string::const_iterator, 6, 8>>;
  return std::string(Encoder(bytes.begin()), Encoder(bytes.end())) + std::string((3 - bytes.size() % 3) % 3, '=');
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Views, HtmlReportHoldsTheFiguresAndEveryPicture) {
  test::TempDir dir;
  const std::string scene = dir.write(
      "room.json", R"({"meshes": [{"file": ")" + test::sample("scene_room/room.off") +
                       R"(", "material": "plaster"}, {"file": ")" + test::sample("scene_room/lamp.off") +
                       R"(", "material": "lamp", "transform": {"translate": [2, 2, 2.98]}}],
        "materials": {"plaster": {"reflectance": 0.7}, "lamp": {"reflectance": 0, "emission": 500}},
        "grids": [{"name": "desk", "rectangle": [0.5, 0.5, 3.5, 3.5], "height": 0.8, "target": {"Eavg": 1e9}}],
        "cameras": [{"name": "corner", "position": [0.5, 0.5, 1.6], "look_at": [3, 3, 1], "width": 96}]})");
  const auto r = test::run_dynrad("solve '" + scene + "' -o '" + dir.path("out.ply") + "' --quality draft --html '" +
                                  dir.path("report.html") + "' --report '" + dir.path("report.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string html = test::read_text(dir.path("report.html"));
  const nlohmann::json report = nlohmann::json::parse(test::read_text(dir.path("report.json")));
  ASSERT_EQ(report["grids"].size(), 1u);
  const nlohmann::json& grid = report["grids"][0];
  EXPECT_FALSE(grid["meets_target"].get<bool>());
  EXPECT_NE(html.find("<td class=\"n\">" + fmt::format("{:.1f}", grid["Eavg"].get<double>()) + "</td>"),
            std::string::npos);
  EXPECT_NE(html.find("not met"), std::string::npos);
  EXPECT_NE(html.find(fmt::format("{:.2f}% (unshot light", 100 * report["estimated_error"]["total"].get<double>())),
            std::string::npos);
  // The declared camera, a plan and the room: each in true and false colour, plus the grid.
  const nlohmann::json& views = report["views"];
  ASSERT_GE(views.size(), 3u);
  EXPECT_EQ(views[0]["name"], "corner");
  EXPECT_EQ(views[0]["width"], 96);
  EXPECT_EQ(views[1]["kind"], "plan");
  EXPECT_EQ(count(html, "data:image/png;base64,"), 1 + 2 * views.size());
  EXPECT_NE(html.find(base64_of(detail::read_file(grid["picture"].get<std::string>()))), std::string::npos);
  for (const auto& v : views) {
    EXPECT_NE(html.find(base64_of(detail::read_file(v["luminance_picture"].get<std::string>()))), std::string::npos);
    EXPECT_GT(v["lit_fraction"].get<double>(), 0.5) << v["name"];
  }
}

}  // namespace
}  // namespace dynrad
