// Lossless simplification of over-tessellated flat surfaces, run on the cleaned mesh
// before patching.
//
// CAD and generated models cut flat walls, floors and boxes into many small triangles;
// every one would become a radiosity patch. This removes the vertices that carry no
// shape (inside a flat region, or in the middle of a straight crease between two
// planes) by half-edge collapses, so that the surface, every material's area, and every
// boundary are what they were, with an order of magnitude fewer triangles.
//
// What is never removed (the vertex is locked):
// - vertices on a mesh boundary: openings (windows, doors), the edges of open
//   surfaces, and the cuts cleanup made where facing disagrees;
// - vertices where the material changes, so material borders keep their shape.
// A collapse is refused unless every triangle it changes stays in its original plane
// and keeps its facing (see simplify.cpp), and it does not make a triangle worse than
// `max_aspect_ratio` (nor worse than what was there). The result is a valid half-edge
// mesh: collapses never make T-vertices.
#pragma once

#include "mesh/core/scene_mesh.h"

#include <cstddef>

namespace dynrad {

struct SimplifyOptions {
  // Off unless asked for: library callers (tests, benchmarks, the C ABI) get the cleaned
  // model as it is; `dynrad solve` and `dynrad info` turn it on.
  bool enabled = false;
  // A vertex may join a triangle only if it lies within this fraction of the
  // bounding-box diagonal of that triangle's original plane: zero up to rounding.
  double flatness = 1e-9;
  // Longest edge over its height (equilateral 1.15, half a square 2). A collapse may
  // make no triangle worse than this, unless it improves the worst one it touches.
  double max_aspect_ratio = 8.0;
};

struct SimplifyReport {
  std::size_t faces_before = 0, faces_after = 0;
  std::size_t vertices_before = 0, vertices_after = 0;
  std::size_t locked_vertices = 0;  // boundary or material border: kept as they are
  std::size_t collapses = 0;
  double worst_aspect_before = 0, worst_aspect_after = 0;  // longest edge / its height
  double seconds = 0;
};

// Simplifies `scene` in place (faces keep their material, group and origin; patch ids
// are renumbered to the new face indices). Does nothing when options.enabled is false.
SimplifyReport simplify_flat_regions(SceneMesh& scene, const SimplifyOptions& options);

// Longest edge over its height, for one triangle and the worst in the mesh.
double aspect_ratio(const TriMesh& mesh, FaceHandle f);
double worst_aspect_ratio(const TriMesh& mesh);

}  // namespace dynrad
