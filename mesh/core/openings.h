// Openings: the holes of a model that light from outside comes in through (a window
// hole, a door, the missing ceiling of a box open at the top, the inner outline of a
// window's reveal). Daylight samples the sky through them (radiosity/sources/daylight.h): a
// point close beside a small opening sees it in a sliver of directions that a fixed set
// of directions over the whole hemisphere can miss.
#pragma once

#include "mesh/core/scene_mesh.h"

#include <array>
#include <vector>

namespace dynrad {

// Each opening triangulated in its plane. Two kinds:
// - Loops of the mesh's boundary whose corners lie within 1e-4 of their size of one
//   plane and that are not the outline of faces in that plane (the border of a plate
//   or of a wall standing alone runs the other way round than a hole in it does).
// - Holes in a flat region that faces behind the region close, in part or wholly,
//   and none in front: a window hole whose head an overhang meets from outside or
//   whose sides fins meet, the inner outline of a reveal in a wall with thickness.
//   (A hole that something in front closes, a column standing on a floor, is none.)
std::vector<std::array<Vec3d, 3>> find_openings(const TriMesh& mesh);

}  // namespace dynrad
