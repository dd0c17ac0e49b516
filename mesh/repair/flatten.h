// Flattening of near-planar polygons (cleanup, before triangulation).
//
// CAD and measured models hold polygons whose corners are a little out of plane (the
// Cornell box's red wall: 0.8 mm about its best-fit plane over 550 mm). Triangulated as
// they are, their triangles get different normals, and the light computed at their
// corners jumps from triangle to triangle: blotches on a flat wall. Each polygon whose
// corners all lie within `relative_tolerance` of its width (area / diagonal of its
// bounding box: about the short side of a rectangle) from its best-fit plane is made
// exactly planar by moving its corners onto that plane. A corner shared by several such
// polygons goes to the point nearest to all their planes (the intersection line of two,
// the intersection point of three), so shared corners stay shared and the polygons
// around stay flat. Polygons farther from planar are left as they are (warped).
#pragma once

#include "mesh/core/types.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dynrad {

struct FlattenOptions {
  // Largest distance of a corner from the polygon's best-fit plane, relative to the
  // polygon's width, for the polygon to be flattened.
  double relative_tolerance = 0.01;
};

struct FlattenReport {
  std::size_t flattened_polygons = 0;  // were out of plane, are now planar
  std::size_t warped_polygons = 0;     // too far out of plane: left as they were
  double largest_move = 0;             // the longest distance a corner moved (model units)
};

// `polygons` are loops of ids into `points`; polygons with `keep[i] == 0` are ignored.
// Moves points in place.
FlattenReport flatten_polygons(std::vector<Vec3d>& points, const std::vector<std::vector<std::uint32_t>>& polygons,
                               const std::vector<char>& keep, const FlattenOptions& options = {});

}  // namespace dynrad
