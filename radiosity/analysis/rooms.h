// Storeys and rooms found in a lit scene's geometry, for automatic views. Nothing here
// is told what a floor or a room is; it looks:
//
// Up: against the emitting triangles' area-weighted facing and the luminaires' aims,
//   when that is clearly along an axis (lights hang from ceilings); else +z.
// Storeys: triangles facing up with a surface facing down above them (a floor under a
//   ceiling; a roof has sky above it) are summed by height in bins of a thousandth of
//   the scene's extent along up. Bins holding at least a fifth of the largest are floor
//   levels; a level starts a new storey when it lies more than 0.8 of the storey below's
//   ceiling height above that storey's floor (so a bed or a table top is not a storey).
//   A storey's ceiling height is the area-weighted median distance from its floor up to
//   the surface above.
// Rooms: at 0.6 of the ceiling height above a storey's floor, points on a square raster
//   are free when a ray up meets a ceiling's front and a ray down a floor's front (so
//   not inside a wall, nor outside the building); neighbours are joined unless a
//   surface lies between them. Free space is then eroded by 0.2 of the ceiling height
//   (0.54 m in a 2.7 m storey: doors are narrower than twice that, rooms wider), which
//   cuts rooms apart at their doors; each part left of some size is a room.
#pragma once

#include "radiosity/analysis/lit_scene.h"

#include <array>
#include <vector>

namespace dynrad::rad {

int up_axis(const LitScene& scene);

// The unit vector along `axis` (0 x, 1 y, 2 z), times `sign`.
Vec3d axis_vector(int axis, double sign = 1);

// The two axes of the plan for `up`, the first to the picture's right.
std::array<int, 2> plan_axes(int up);

// The point at (x, y) in the plan's axes and `height` along `up`.
Vec3d plan_point(int up, double x, double y, double height);

struct Storey {
  double floor = 0;    // along up
  double height = 0;   // floor to ceiling
  std::array<double, 2> lo{}, hi{};  // the floor's extent in the plan axes
};

std::vector<Storey> find_storeys(const LitScene& scene, int up);

struct Room {
  std::array<double, 2> middle{};  // plan axes: the mean of its eroded raster points
  std::array<double, 2> corner{};  // its eroded point farthest from the middle
  // Its eroded points farthest from the middle in each quarter around it (up to four,
  // the farthest first; corner is the first): where a camera may stand.
  std::vector<std::array<double, 2>> corners;
  double area = 0;                 // of its free raster cells before erosion, model units squared
};

std::vector<Room> find_rooms(const LitScene& scene, int up, const Storey& storey);

}  // namespace dynrad::rad
