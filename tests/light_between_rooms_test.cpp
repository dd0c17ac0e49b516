// Light between rooms, against the independent mesh tracer (tests/reference/mesh_tracer.h,
// which shares no code with the solver): two rooms joined by a door, a lamp in one. The
// other room is lit only through the door; its work plane must come out as the path
// tracer has it (the whole-buildings issue: within 3% at its work plane).
#include "radiosity/pipeline/pipeline.h"
#include "test_support.h"
#include "reference/mesh_tracer.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace dynrad {
namespace {

namespace tracer = dynrad_test::mesh_tracer;

// A rectangle: corners counter-clockwise seen from the front, and its reflectance.
struct Quad {
  std::array<Vec3d, 4> corners;
  double reflectance = 0;
  std::string material;
};

// Two rooms of 4 x 4 x 2.7 m side by side along x, parted by a 0.1 m wall at x = 4 with a
// 0.9 x 2.1 m door in its middle (y 1.55 to 2.45), every face seen from inside.
std::vector<Quad> two_rooms() {
  const double h = 2.7, x0 = 3.95, x1 = 4.05, d0 = 1.55, d1 = 2.45, top = 2.1;
  std::vector<Quad> q;
  auto add = [&](Vec3d a, Vec3d b, Vec3d c, Vec3d d, double rho, const char* m) { q.push_back({{a, b, c, d}, rho, m}); };
  add({0, 0, 0}, {8, 0, 0}, {8, 4, 0}, {0, 4, 0}, 0.3, "floor");
  add({0, 0, h}, {0, 4, h}, {8, 4, h}, {8, 0, h}, 0.8, "ceiling");
  add({0, 0, 0}, {0, 0, h}, {8, 0, h}, {8, 0, 0}, 0.7, "wall");  // y = 0, facing +y
  add({0, 4, 0}, {8, 4, 0}, {8, 4, h}, {0, 4, h}, 0.7, "wall");  // y = 4, facing -y
  add({0, 0, 0}, {0, 4, 0}, {0, 4, h}, {0, 0, h}, 0.7, "wall");  // x = 0, facing +x
  add({8, 0, 0}, {8, 0, h}, {8, 4, h}, {8, 4, 0}, 0.7, "wall");  // x = 8, facing -x
  // The partition's two sides, each three rectangles round the door.
  for (const double x : {x0, x1}) {
    const bool west = x == x0;  // facing -x
    auto side = [&](double ya, double yb, double za, double zb) {
      if (west)
        add({x, ya, za}, {x, ya, zb}, {x, yb, zb}, {x, yb, za}, 0.7, "wall");
      else
        add({x, ya, za}, {x, yb, za}, {x, yb, zb}, {x, ya, zb}, 0.7, "wall");
    };
    side(0, d0, 0, h);
    side(d1, 4, 0, h);
    side(d0, d1, top, h);
  }
  // Stools in both rooms, 0.3 m cubes 0.45 m high on a 0.7 m raster: their many small
  // faces fill the receiver tree with nodes worth testing, as furniture does.
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 5; ++j) {
      const double x = 0.45 + 0.7 * i + (i >= 5 ? 0.25 : 0.0), y = 0.45 + 0.7 * j, s = 0.3, t = 0.45;
      add({x, y, t}, {x + s, y, t}, {x + s, y + s, t}, {x, y + s, t}, 0.5, "stool");              // top
      add({x, y, 0}, {x + s, y, 0}, {x + s, y, t}, {x, y, t}, 0.5, "stool");                      // -y
      add({x, y + s, 0}, {x, y + s, t}, {x + s, y + s, t}, {x + s, y + s, 0}, 0.5, "stool");      // +y
      add({x, y, 0}, {x, y, t}, {x, y + s, t}, {x, y + s, 0}, 0.5, "stool");                      // -x
      add({x + s, y, 0}, {x + s, y + s, 0}, {x + s, y + s, t}, {x + s, y, t}, 0.5, "stool");      // +x
    }
  // The door's reveal: its two jambs and its head.
  add({x0, d0, 0}, {x1, d0, 0}, {x1, d0, top}, {x0, d0, top}, 0.7, "wall");  // facing +y
  add({x0, d1, 0}, {x0, d1, top}, {x1, d1, top}, {x1, d1, 0}, 0.7, "wall");  // facing -y
  add({x0, d0, top}, {x1, d0, top}, {x1, d1, top}, {x0, d1, top}, 0.7, "wall");  // facing -z
  return q;
}

std::string obj_of(const std::vector<Quad>& quads) {
  std::string out = "mtllib rooms.mtl\n";
  std::string faces;
  int v = 1;
  std::string material;
  for (const Quad& q : quads) {
    for (const Vec3d& c : q.corners) out += fmt::format("v {} {} {}\n", c[0], c[1], c[2]);
    if (q.material != material) faces += "usemtl " + (material = q.material) + "\n";
    faces += fmt::format("f {} {} {} {}\n", v, v + 1, v + 2, v + 3);
    v += 4;
  }
  return out + faces;
}

tracer::Scene tracer_scene(const std::vector<Quad>& quads) {
  tracer::Scene scene;
  auto at = [](const Vec3d& p) { return tracer::Vec3{p[0], p[1], p[2]}; };
  for (const Quad& q : quads)
    for (const auto& t : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
      tracer::Triangle tri;
      tri.corners = {at(q.corners[t[0]]), at(q.corners[t[1]]), at(q.corners[t[2]])};
      tri.reflectance = {q.reflectance, q.reflectance, q.reflectance};
      scene.triangles.push_back(tri);
    }
  return scene;
}

TEST(LightBetweenRooms, ARoomLitThroughADoorMatchesThePathTracer) {
  const std::vector<Quad> quads = two_rooms();
  const test::TempDir dir;
  dir.write("rooms.obj", obj_of(quads));
  dir.write("rooms.mtl",
            "newmtl floor\nKd 0.3 0.3 0.3\nnewmtl ceiling\nKd 0.8 0.8 0.8\nnewmtl wall\nKd 0.7 0.7 0.7\n"
            "newmtl stool\nKd 0.5 0.5 0.5\n");
  // A 1000 lm isotropic lamp in the west room; a work plane in each room.
  const Vec3d lamp(2.0, 2.0, 2.4);
  const std::string scene = dir.write(
      "rooms.json",
      fmt::format(R"({{"meshes": [{{"file": "rooms.obj"}}],
  "luminaires": [{{"type": "point", "lumens": 1000, "position": [{}, {}, {}], "name": "lamp"}}],
  "grids": [{{"name": "west", "rectangle": [0.5, 0.5, 3.5, 3.5], "height": 0.8, "spacing": 0.6}},
            {{"name": "east", "rectangle": [4.5, 0.5, 7.5, 3.5], "height": 0.8, "spacing": 0.6}}]}})",
                  lamp[0], lamp[1], lamp[2]));
  rad::SceneRequest request;  // `dynrad solve`'s defaults
  request.path = scene;
  request.simplify.enabled = true;
  rad::PreparedScene prepared = rad::prepare_scene(request);
  const rad::SolvedScene solved = rad::solve_scene(prepared);
  ASSERT_EQ(solved.grids.size(), 2u);

  tracer::Scene reference_scene = tracer_scene(quads);
  reference_scene.lights.push_back({{lamp[0], lamp[1], lamp[2]}, 1000});
  const tracer::Tracer reference(std::move(reference_scene));
  tracer::TraceOptions options;
  options.target_relative_error = 0.005;
  for (const rad::GridResult& grid : solved.grids) {
    double solved_sum = 0, reference_sum = 0, reference_error2 = 0;
    for (const rad::GridPointResult& p : grid.points) {
      ASSERT_FALSE(p.masked);
      const tracer::Estimate e =
          reference.illuminance({p.position[0], p.position[1], p.position[2]}, {0, 0, 1}, options);
      solved_sum += p.illuminance;
      reference_sum += e.value;
      reference_error2 += e.std_error * e.std_error;
    }
    const double ratio = solved_sum / reference_sum;
    std::printf("%s room: Eavg %.3f lx, path tracer %.3f lx (+- %.3f), %+.2f%%\n", grid.spec.name.c_str(),
                solved_sum / grid.points.size(), reference_sum / grid.points.size(),
                std::sqrt(reference_error2) / grid.points.size(), 100 * (ratio - 1));
    // The issue's bound for a room lit through a door (3%), the same for the lit one.
    EXPECT_NEAR(ratio, 1.0, 0.03) << grid.spec.name;
  }
}

}  // namespace
}  // namespace dynrad
