// Repairs a polygon soup into a triangle soup that an OpenMesh half-edge mesh can hold.
// This is the only place CGAL is compiled (one translation unit: it is slow to build).
//
// Facing rule: a face's front is the side from which its vertex loop is counter-
// clockwise. Cleanup never flips a face to make orientation consistent, because in
// architectural models the side that emits and reflects is the side the modeller
// chose. Where two faces disagree across an edge, the edge is cut instead.
#pragma once

#include "mesh/soup.h"

#include <cstddef>
#include <string>

namespace dynrad {

struct CleanupOptions {
  // Points closer than this fraction of the bounding-box diagonal are merged; the same
  // distance decides when a point lies on another polygon's edge (a T-junction).
  double merge_tolerance = 1e-6;
  // Triangles whose area is below this fraction of the diagonal squared are degenerate.
  double min_area = 1e-14;
  bool snap_t_junctions = true;
};

// Every repair is counted so that `dynrad info` can report it.
struct CleanupReport {
  std::size_t input_points = 0;
  std::size_t input_polygons = 0;
  std::size_t merged_points = 0;          // points merged into a neighbour within tolerance
  std::size_t degenerate_polygons = 0;    // fewer than 3 distinct points, or no area
  std::size_t t_junctions = 0;            // points inserted into other polygons' edges
  std::size_t triangulated_polygons = 0;  // polygons with more than 3 corners
  std::size_t untriangulatable_polygons = 0;  // self-intersecting loops CGAL could not fill
  std::size_t degenerate_triangles = 0;   // zero-area triangles dropped
  std::size_t duplicate_triangles = 0;    // same corners, same facing
  std::size_t non_manifold_edges = 0;     // edges with >2 faces or disagreeing facing, cut
  std::size_t split_vertices = 0;         // vertex copies made while cutting those edges
  std::size_t unused_points = 0;          // points no face refers to, dropped
  std::size_t output_points = 0;
  std::size_t output_triangles = 0;
  std::string first_problem;  // where the first dropped polygon came from, for messages

  std::size_t repairs() const {
    return merged_points + degenerate_polygons + t_junctions + untriangulatable_polygons + degenerate_triangles +
           duplicate_triangles + non_manifold_edges + unused_points;
  }
};

CleanupReport cleanup(const PolygonSoup& input, TriangleSoup& output, const CleanupOptions& options = {});

}  // namespace dynrad
