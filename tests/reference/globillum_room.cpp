#include "reference/globillum_room.h"

namespace dynrad_test::reference {

BoxScene globillum_room(bool obstructed) {
  BoxScene scene;
  const int room = scene.add_room({0, 0, 0}, {10, 6, 3}, Reflectances::walls_floor_ceiling(0.5, 0.3, 0.7));
  scene.add_emitter(room, Face::plus_z, {4.75, 2.75, 3}, {5.25, 3.25, 3}, 31.416);
  if (obstructed) {
    scene.add_solid({2.95, 3, 0}, {3.05, 6, 3}, Reflectances::uniform(0.5));
    scene.add_solid({6.95, 0, 0}, {7.05, 3, 3}, Reflectances::uniform(0.5));
  }
  return scene;
}

std::vector<ReferencePoint> globillum_points() {
  std::vector<ReferencePoint> points;
  for (const bool ceiling : {false, true})
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 20; ++i) {
        const Vec3 p{0.25 + 0.5 * i, 0.25 + 0.5 * j, ceiling ? 3.0 : 0.0};
        points.push_back({ceiling ? "ceiling" : "floor", {p, {0, 0, ceiling ? -1.0 : 1.0}}});
      }
  return points;
}

std::vector<ReferencePoint> globillum_wall_points() {
  std::vector<ReferencePoint> points;
  for (const double y : {0.0, 6.0})
    for (int k = 0; k < 6; ++k)
      for (int i = 0; i < 20; ++i)
        points.push_back({y == 0 ? "wall_y0" : "wall_y6",
                          {{0.25 + 0.5 * i, y, 0.25 + 0.5 * k}, {0, y == 0 ? 1.0 : -1.0, 0}}});
  for (const double x : {0.0, 10.0})
    for (int k = 0; k < 6; ++k)
      for (int j = 0; j < 12; ++j)
        points.push_back({x == 0 ? "wall_x0" : "wall_x10",
                          {{x, 0.25 + 0.5 * j, 0.25 + 0.5 * k}, {x == 0 ? 1.0 : -1.0, 0, 0}}});
  return points;
}

}  // namespace dynrad_test::reference
