// Inserting a straight line into the mesh as a chain of edges, before patching.
//
// Where shading jumps along a known line (the outline of a hard shadow), a mesh whose
// edges run across the line can only show it as a staircase of elements. Made into
// edges, the line stays straight at any refinement: bisection never removes an edge.
//
// The walk. From the line's first point p, inserted as a vertex (a face split 1 -> 3,
// or an edge split where p is on an edge), the line leaves the current vertex v into
// one face of v's fan and crosses that face's edge opposite v. Splitting that edge at
// the crossing (2 -> 4, as every split of refinement.h) connects the new vertex to v,
// so the piece of line just crossed is an edge; the walk goes on from the new vertex.
// Where the line runs along an existing edge it follows it, and where it ends inside a
// face, the face is split at the end. Only faces in the plane of the first one are
// walked: the line stops where that flat region ends. Every step is a split, so the
// mesh is conforming throughout.
//
// Crossings within `snap` of a vertex go through the vertex instead, so that a line
// passing near a corner bends by less than `snap` rather than leaving a sliver.
#pragma once

#include "mesh/core/refinement.h"
#include "mesh/core/scene_mesh.h"

#include <cstddef>
#include <functional>

namespace dynrad {

struct LineOptions {
  // Distance within which the line passes through an existing vertex (and its ends
  // snap to one), model units. 0: only exact hits.
  double snap = 0;
  // Recorded on the line's edges (SceneMesh::line_width): the width of the strip the
  // line bounds. Must be above 0.
  float width = 1;
  // Faces searched, from the start face across the flat region, for the one holding p.
  std::size_t search_limit = 4096;
  // How an edge is split at a point on it (default: split_edge). An element hierarchy
  // that must follow every split (ElementHierarchy::split_at) passes its own; a point
  // inside a face is then made by two edge splits (through the corner opposite the
  // face's longest edge, then along the new edge), not by a 1 -> 3 split of the face.
  std::function<EdgeSplit(OpenMesh::EdgeHandle, const Vec3d&)> split;
};

struct InsertedLine {
  bool started = false;      // p was found in the start face's flat region
  bool reached_end = false;  // the line got to q (false: the flat region ended first)
  std::size_t vertices_added = 0;
  std::size_t edges = 0;  // edges now on the line
};

// Inserts the segment p -> q into the flat region (faces in one plane, joined by edges)
// that holds `start`, a face at or near p (found by walking out from `start`). p and q
// must lie in that plane to within `snap`.
InsertedLine insert_line(SceneMesh& scene, FaceHandle start, const Vec3d& p, const Vec3d& q,
                         const LineOptions& options);

// Edge-splitting insertion leaves long thin triangles beside the lines (each split
// joins the crossing to a far corner). This flips edges towards a Delaunay
// triangulation of each flat region, lines kept (Lawson's flips, constrained: an edge
// on a line, on a border, between two planes or between faces of different material,
// group or source polygon is never flipped). Starts from the edges at the vertices of
// lines; returns the flips made.
std::size_t flip_beside_lines(SceneMesh& scene);

}  // namespace dynrad
