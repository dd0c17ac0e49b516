// Imprinting: where one surface passes through another or touches it, the line where
// they meet becomes an edge of both (cleanup, after triangulation).
//
// Architects' models are assemblies of solids: a floor slab is one face running under
// the walls, walls pass through slabs, furniture stands on floors. Nothing in such a
// model puts an edge where a wall meets the floor, so the floor's vertices under the
// wall are dark and smear into the visible floor. This finds every such line:
//   - a facet crossing another's plane inside it (a wall through a slab),
//   - a facet's edge lying on another facet (a wall's foot on a floor),
//   - facets in one plane that overlap (a wall's bottom face on a slab's top face, a
//     lamp drawn on a ceiling): each one's outline inside the other.
// Each line is added to both facets as a segment; cleanup then triangulates the facets
// again with those segments as edges (polygon_triangulation.h).
//
// Written here rather than with CGAL's corefinement: CGAL decides exactly whether two
// triangles meet, but exported models meet only to within rounding (a wall standing on
// a slab whose top is 1e-9 m lower, a rotated plan whose faces are coplanar to 1e-12),
// where exact predicates see either a sliver crossing or a gap. Here every decision
// (on a plane, on an edge, the same point) is made to within `tolerance`, the same
// distance within which cleanup merges points. CGAL finds the candidate pairs
// (box_intersection_d) and the polygon triangulation handles crossing segments.
#pragma once

#include "mesh/core/polygon_triangulation.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dynrad {

// A flat region of surface: triangles in one plane, facing one way, joined across the
// edges they share (a polygon, or the triangles an exporter cut a face into).
struct Facet {
  std::vector<std::uint32_t> triangles;  // indices into the triangle list
  std::vector<Segment> outline;          // its boundary edges, each run as its triangle runs it
  Vec3d normal;                          // unit
  Vec3d point;                           // on its plane
};

struct Imprints {
  // Per facet: segments (point ids) where other facets cross or touch it; collinear
  // pieces found triangle by triangle are joined.
  std::vector<std::vector<Segment>> segments;
  // Per facet: it meets another facet somewhere other than along a shared edge or at a
  // shared corner (a segment, or an overlap in one plane).
  std::vector<char> touched;
  // Facet pairs that lie in one plane and share an area.
  struct Overlap {
    std::uint32_t a, b;
    bool same_facing;
  };
  std::vector<Overlap> overlaps;
  std::size_t candidate_pairs = 0;  // triangle pairs whose boxes met
};

// `triangles` triangulate the facets (triangle i lies in facet facet_of[i]). Points
// made where edges cross planes or other edges are appended to `points`.
// make_facets() finds the facets: triangles joined across edges that exactly two of
// them share, running it opposite ways, in one plane (to within `tolerance`), with the
// same `label` (material and group: a facet is triangulated again as one).
std::vector<Facet> make_facets(const std::vector<Vec3d>& points, const std::vector<Triangle>& triangles,
                               const std::vector<std::uint64_t>& label, double tolerance,
                               std::vector<std::uint32_t>& facet_of);
Imprints find_imprints(std::vector<Vec3d>& points, const std::vector<Facet>& facets,
                       const std::vector<Triangle>& triangles, const std::vector<std::uint32_t>& facet_of,
                       double tolerance);

// The outline with every segment end that lies on one of its edges (within
// `tolerance`) made a corner: the edge is split there.
std::vector<Segment> split_outline(const std::vector<Vec3d>& points, const std::vector<Segment>& outline,
                                   const std::vector<Segment>& segments, double tolerance);

}  // namespace dynrad
