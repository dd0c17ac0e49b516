// Hidden parts: the pieces that imprinting cut off and that no light can reach (cleanup,
// after imprinting). They leave the mesh: they would never receive light, and their dark
// corners would be interpolated into the visible surface beside them.
//
// A piece is a connected part of one facet between imprinted lines. A part of a surface
// is hidden when
//   1. enclosed: the point just in front of it is inside a closed solid of the model
//      as given (a winding number of one: the floor under a wall or a closed cupboard,
//      a wall's part inside a slab), or at least `enclosed_fraction` of the rays
//      leaving its front (cosine-distributed, a fixed set) first hit the back of a
//      surface or the front of a piece already found enclosed (the floor under a box
//      without a bottom). An open box's floor sees out through its opening;
//   2. face to face with a hidden part: two surfaces in one plane, facing each other
//      (a cupboard's bottom on a floor): where one is hidden, so is the other. Two
//      sheets back to back where neither is hidden (a wall drawn as two faces with no
//      thickness) both stay;
//   3. covered: two surfaces in one plane facing the same way (a lamp drawn on a
//      ceiling, a rug on a floor): where they overlap the smaller facet stays, the
//      other goes, as the detail drawn on a surface is meant to be seen.
// Rule 1 decides per piece; rules 2 and 3 per triangle, where the facets' triangles
// overlap (imprinting has cut each along the other's outline, so a triangle lies wholly
// inside the other facet or outside it).
#pragma once

#include "mesh/repair/imprint.h"

#include <cstddef>
#include <vector>

namespace dynrad {

struct HiddenOptions {
  int rays = 16;                   // per piece, from a fixed cosine-distributed set
  double enclosed_fraction = 0.9;  // share of rays that must hit a back for "enclosed"
};

struct HiddenReport {
  std::size_t pieces_tested = 0;
  std::size_t inside_solid_pieces = 0;  // rule 1, by winding number
  std::size_t enclosed_pieces = 0;      // rule 1, by rays
  std::size_t face_to_face_pieces = 0;  // rule 2
  std::size_t covered_pieces = 0;       // rule 3
  double hidden_area = 0;               // model units squared
};

// A closed surface of the model as given: its triangles, each as three corners.
using ClosedSurface = std::vector<std::array<Vec3d, 3>>;

struct HiddenInput {
  const std::vector<ClosedSurface>& solids;  // closed surfaces facing out (others count nothing)
  const std::vector<Vec3d>& points;
  const std::vector<Triangle>& triangles;
  const std::vector<std::uint32_t>& facet_of;  // per triangle
  const std::vector<char>& touched;            // per facet: only these are tested
  const std::vector<Imprints::Overlap>& overlaps;
  const std::vector<double>& facet_area;  // per facet, for rule 3
  double tolerance;                       // as for imprinting
};

// Per triangle: 1 where it is hidden.
std::vector<char> find_hidden_triangles(const HiddenInput& input, const HiddenOptions& options, HiddenReport& report);

}  // namespace dynrad
