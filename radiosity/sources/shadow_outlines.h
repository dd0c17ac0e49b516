// Hard shadows' outlines made into mesh edges before patching (discontinuity meshing
// for the light of point-like luminaires and the sun: Heckbert 1992; Lischinski,
// Tampieri and Greenberg 1992).
//
// A luminaire small for its distance, or the sun, lights a surface with a jump where an
// occluder's edge cuts its light off. Across elements, that jump shows as a staircase
// at the element size, however deep refinement goes. Here the jump's line is found
// before lighting and inserted into the mesh (mesh/core/line_insertion.h), as two lines a
// small distance either side of it: the strip between them holds the jump, and the
// elements either side are wholly lit or wholly in shadow, so interpolating between
// their corners is right up to the strip. The strip's elements are not refined
// (Element::in_strip). Where the solver samples a luminaire's opening (near it), the
// strip spans the penumbra instead: the lines bound the umbra and the fully lit part.
//
// Finding the outlines (no exact visibility skeleton: rays, as the solver's own
// visibility). For each sender, a silhouette edge is an edge between a face turned
// towards it and one turned away, or a border edge. Rays from the sender through
// points along the edge go on past it; where they land on one plane, the landing
// points lie on one straight line, the outline (the plane cut by the wedge of the
// sender and the edge). A run of landings on one plane gives one outline; where the
// landings change plane or the edge is itself in shadow, the run's end is found by
// bisection.
#pragma once

#include "mesh/core/refinement.h"
#include "mesh/core/scene_mesh.h"
#include "radiosity/sources/luminaire.h"

#include <cstddef>
#include <functional>
#include <vector>

namespace dynrad::rad {

struct ShadowOutlineOptions {
  // Half the width of the strip a hard outline becomes, model units (the two lines lie
  // this far either side of it). `dynrad solve`: 1/500 of the patch size (1 mm for
  // 0.5 m patches). Must be above 0.
  double half_width = 0;
  // Samples along a silhouette edge are at most this far apart, model units (ends of
  // runs are then found by bisection). `dynrad solve`: a quarter of the patch size.
  double spacing = 0;
  // An outline whose penumbra is wider than this is left to refinement (a soft shadow
  // needs no edge), model units. `dynrad solve`: half the patch size.
  double widest = 0;
  // Outlines shorter than this are left to refinement (the shadow of a handle or a
  // frame's piece: a few elements), model units. `dynrad solve`: a quarter of the
  // patch size.
  double shortest = 0;
  // Bisection steps for a run's ends: each halves the gap between samples.
  int bisections = 12;
  // How the lines' edges are split (LineOptions::split): an element hierarchy that must
  // follow every split passes its own (the outlines are then drawn into a refined mesh
  // after a solve, and no edge is flipped: a flip is no split an element tree can hold).
  std::function<EdgeSplit(OpenMesh::EdgeHandle, const Vec3d&)> split;
  // Per luminaire (in the order given), the edges whose silhouettes are looked at; null:
  // every edge of the mesh for every luminaire. A solve knows which surfaces each
  // luminaire lit, and an occluder's edge in its light lies on one of them.
  const std::vector<std::vector<OpenMesh::EdgeHandle>>* candidate_edges = nullptr;
};

struct ShadowOutlineReport {
  std::size_t senders = 0;           // point-like luminaires and the sun looked at
  std::size_t silhouette_edges = 0;  // summed over the senders
  std::size_t outlines = 0;          // straight pieces of outline on a surface
  std::size_t lines = 0;             // lines inserted (up to two per outline)
  std::size_t vertices_added = 0;
  std::size_t flips = 0;  // edges flipped beside the lines (mesh/core/line_insertion.h)
  double seconds = 0;
};

// The options `dynrad solve` uses for patches of `patch_size` (see each field).
ShadowOutlineOptions shadow_outline_options(double patch_size);

// Finds the outlines of hard shadows cast by `luminaires` (all but the sky) and inserts
// them into `scene`'s mesh: before patching, on the mesh the solver will light, or after
// a solve through its element hierarchy (ShadowOutlineOptions::split). The luminaires
// are looked at in parallel; the result does not depend on the number of threads.
ShadowOutlineReport insert_shadow_outlines(SceneMesh& scene, const std::vector<Luminaire>& luminaires,
                                           const ShadowOutlineOptions& options);

}  // namespace dynrad::rad
