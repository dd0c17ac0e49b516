// Openings: the holes of a model that light from outside comes in through, found as
// the mesh's planar boundary loops that are not the border of a flat surface (a window
// hole in a wall without thickness, a door cut down to the floor, the missing ceiling of
// a box open at the top). Daylight samples the sky through them (radiosity/daylight.h):
// a point close beside a small opening sees it in a sliver of directions that a fixed
// set of directions over the whole hemisphere can miss.
#pragma once

#include "mesh/scene_mesh.h"

#include <array>
#include <vector>

namespace dynrad {

// Each opening triangulated in its plane. A loop counts when its corners lie within
// 1e-4 of its size of one plane, and it is not the outline of faces in that plane
// (the border of a plate or of a wall standing alone runs the other way round than a
// hole in it does). Holes through thick walls, whose reveals close the mesh, have no
// boundary and are not found (their glass, if any, is).
std::vector<std::array<Vec3d, 3>> find_openings(const TriMesh& mesh);

}  // namespace dynrad
