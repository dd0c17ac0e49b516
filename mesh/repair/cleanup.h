// Repairs a polygon soup into a triangle soup that an OpenMesh half-edge mesh can hold.
// This is the only place CGAL is compiled (one translation unit: it is slow to build).
//
// Facing rule: a face's front is the side from which its vertex loop is counter-
// clockwise. Cleanup never flips a face to make orientation consistent, because in
// architectural models the side that emits and reflects is the side the modeller
// chose. Where two faces disagree across an edge, the edge is cut instead.
#pragma once

#include "mesh/repair/flatten.h"
#include "mesh/repair/hidden.h"
#include "mesh/core/soup.h"

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
  // Near-planar polygons are made planar before triangulation (flatten.h).
  bool flatten = true;
  FlattenOptions flattening;
  // Where surfaces cross or touch, the lines where they meet become edges of both, and
  // the pieces no light can reach leave the mesh (imprint.h, hidden.h). Decisions are
  // made to within the merge distance above.
  bool imprint = true;
  HiddenOptions hidden;
};

// Every repair is counted so that `dynrad info` can report it.
struct CleanupReport {
  std::size_t input_points = 0;
  std::size_t input_polygons = 0;
  std::size_t merged_points = 0;              // points merged into a neighbour within tolerance
  std::size_t degenerate_polygons = 0;        // fewer than 3 distinct points, or no area
  std::size_t t_junctions = 0;                // points inserted into other polygons' edges
  std::size_t triangulated_polygons = 0;      // polygons with more than 3 corners
  std::size_t untriangulatable_polygons = 0;  // self-intersecting loops CGAL could not fill
  std::size_t degenerate_triangles = 0;       // zero-area triangles dropped
  std::size_t duplicate_triangles = 0;        // same corners, same facing
  std::size_t non_manifold_edges = 0;         // edges with >2 faces or disagreeing facing, cut
  std::size_t split_vertices = 0;             // vertex copies made while cutting those edges
  std::size_t unused_points = 0;              // points no face refers to, dropped
  std::size_t flattened_polygons = 0;         // near-planar polygons made planar
  std::size_t warped_polygons = 0;            // too far from planar to flatten: triangulated as they are
  double largest_flattening_move = 0;         // model units
  std::size_t imprinted_edges = 0;            // lines where surfaces meet, added as edges (each once)
  std::size_t imprinted_facets = 0;           // facets triangulated again with such lines
  std::size_t imprint_failures = 0;           // facets whose lines could not be added: lit as they were
  std::string first_imprint_failure;          // where the first of those came from
  std::size_t hidden_pieces = 0;              // pieces removed because no light can reach them
  double hidden_area = 0;                     // their area, model units squared
  std::size_t output_points = 0;
  std::size_t output_triangles = 0;
  std::string first_problem;  // where the first dropped polygon came from, for messages

  std::size_t repairs() const {
    return merged_points + degenerate_polygons + t_junctions + untriangulatable_polygons + degenerate_triangles +
           duplicate_triangles + non_manifold_edges + unused_points + flattened_polygons;
  }
};

CleanupReport cleanup(const PolygonSoup& input, TriangleSoup& output, const CleanupOptions& options = {});

}  // namespace dynrad
