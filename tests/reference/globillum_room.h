// The 1990 "globillum" comparison room (Ward, Rushmeier et al.; the facts are in
// shared/reference/scenes-and-facts.md) as a box scene, and its comparison points.
#pragma once

#include "reference/box_tracer.h"

#include <string>
#include <vector>

namespace dynrad_test::reference {

// 10 x 6 x 3 m, x along the long wall, z up, origin at a corner. A 0.5 x 0.5 m source
// centred in the ceiling (x 4.75..5.25, y 2.75..3.25), exitance 31.416 W/m^2,
// reflectance 0. Reflectances: ceiling 0.70, walls 0.50, floor 0.30.
// Obstructed: two full-height partitions 0.1 m thick, centred on x = 3 (y 3..6) and on
// x = 7 (y 0..3), reflectance 0.5 (so the room is symmetric under a half turn about its
// vertical axis).
BoxScene globillum_room(bool obstructed);

struct ReferencePoint {
  std::string surface;  // "floor", "ceiling", "wall_y0", "wall_y6", "wall_x0" or "wall_x10"
  SurfacePoint at;
};

// The comparison points: the floor (z = 0, normal +z) then the ceiling (z = 3,
// normal -z), each a 0.5 m grid from 0.25 m off the walls (x 0.25..9.75, y 0.25..5.75),
// x fastest: 240 per surface. Four ceiling points, (4.75 or 5.25, 2.75 or 3.25), are
// the source's corners: its edges belong to the ceiling, so B there is the ceiling's.
std::vector<ReferencePoint> globillum_points();

// The four walls on the same 0.5 m grid, 0.25 m in from every edge (x or y fastest,
// then z): the long walls y = 0 and y = 6 (20 x 6 points each), then the short walls
// x = 0 and x = 10 (12 x 6 each), 384 in all, normals into the room. With the floor's
// and ceiling's, every point stands for 0.25 m^2 of the room's 216 m^2 (less the
// source's 0.25), so the area-weighted error over all of it can be measured.
std::vector<ReferencePoint> globillum_wall_points();

}  // namespace dynrad_test::reference
