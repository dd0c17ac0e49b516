// How the solver refines: the method (progressive, adaptive, dynamic), its oracles'
// thresholds and the limits on the element tree; and how a point's rays are planned.
// Chosen from the model and the quality by settings.h, given to Solver (solver.h).
#pragma once

#include "radiosity/solver/oracle.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace dynrad::rad {

enum class Method { progressive, adaptive, dynamic };
// "progressive", "adaptive", "dynamic"; throws std::invalid_argument otherwise.
Method parse_method(const std::string& name);
const char* method_name(Method method);

struct RefineSettings {
  Method method = Method::progressive;
  int max_level = 3;                // paper levels (1 -> 4 splits) below a patch
  double adaptive_threshold = 0.25; // Figure 3's threshold on the cumulated gradient
  OracleThresholds dynamic;         // Figure 6's three thresholds
  // Dynamic: where new elements' cumulated radiosity comes from. "interpolate" (the
  // default) is linear across the parent from its corners; "constant" gives every
  // corner the parent's mean; "gather" recalculates them from every earlier sender as
  // adaptive does (for measurements: it costs a transfer per sender).
  enum class NewElements { interpolate, constant, gather } new_elements = NewElements::interpolate;
  // Limits (0: none). When one is reached, the solve goes on without further
  // refinement and the report says why (SolveReport::refinement_stopped). The element
  // limit may be passed by the closure of the split that reaches it (a few elements).
  std::size_t max_elements = 0;
  std::size_t memory_budget = 0;  // bytes of resident memory of the whole process
  // Dynamic: push a transfer down to the elements below where it stopped along the
  // quadratic through its values at the stopping element's corners and edge midpoints
  // (three more closed forms where elements exist below), instead of linearly from the
  // corners as the paper does. Linear push-down of a transfer that bends (near its
  // sender) overshoots at every vertex below, always on the same side, and many such
  // transfers add up: in a furnace the worst vertex was 17% off (bench/results/bench_paper_tables.md).
  bool quadratic_pushdown = true;
  // Dynamic: a new vertex starts from its parent's values (a line across the element
  // it was split from) plus, for every patch within one radius of that element that
  // has shot, what that patch's light bends away from the line: rho times the patch's
  // shot radiosity times its F at the vertex minus F interpolated from the element's
  // corners (closed forms times the share of 4 rays to the patch that arrive: a patch
  // behind a partition bends nothing). Near a junction F is far from linear (on a wall 2 cm
  // above a floor, a floor patch a little way off is seen only at grazing angles from
  // the foot and well from 4 cm up), and a vertex born between a shot from there and the
  // foot's own patch kept the difference for good: the Cornell demo's dark vertices at
  // the short block's foot (tests/pictures_test.cpp).
  bool near_field_start = true;
  // Dynamic, push-down oracle: where elements exist below q, decide by the push-down
  // error alone (OracleInputs::refined).
  bool refined_pushdown = true;
  // Dynamic: paper levels of refinement allowed beyond max_level where a shadow's edge
  // crosses an element (its corners see fractions of the sender that differ by more
  // than a quarter): shadows are where the light changes fastest, and interpolating
  // across one smears it over the element.
  int shadow_levels = 1;
  // Dynamic, shots from luminaires: paper levels allowed beyond max_level, and the
  // push-down error allowed, as a fraction of OracleThresholds::pushdown. A point
  // source's pool of light bends on the scale of its height, not of the patches. A
  // 40 m floor under a 100 cd source 2 m up (tests/luminaire_test.cpp), normal
  // quality: with the patches' own levels and error, 2.3% off the closed form at
  // worst of 50 points; with 2 more levels and a quarter of the error, 0.87% (the
  // levels bound); with 3 and a quarter, 0.29% (64,000 elements).
  int luminaire_levels = 3;
  double luminaire_pushdown = 0.25;
  // Direct light where it is seen (exact_direct.cpp): luminaires and the sun (not the
  // sky) shoot into the walk like any sender, but only to the patches: each patch
  // takes the power it receives (its first bounce, reflected into its unshot light)
  // and remembers who lit it, and no element is split for them and no corner value
  // holds their light. Their direct light is computed exactly, with shadow rays, at
  // every vertex the solve writes (and at grid points, as before), and once the shots
  // are done the mesh is refined for display where that light bends or a shadow's
  // edge crosses an element (luminaire_levels, luminaire_pushdown and shadow_levels
  // then apply to that pass). So the thousands of shots after the luminaires' walk a
  // mesh made for the light between surfaces, not for the pools under each lamp: on
  // one storey of the generated office, 3.4-4.0 M of 4.3 M elements had been the
  // luminaires' (bench/results/whole_buildings.md). Off: luminaires' shots refine the
  // hierarchy as the sharpest senders and their light lives in it.
  bool exact_direct = true;
  // Dynamic: the first shot of a primary emitting patch (Solver's direct sources: the
  // emitting patches when at most 16 hold 90% of the emitted power, a small area light
  // such as the 1990 room's 0.5 m source) refines as a luminaire's shot does, with
  // luminaire_pushdown and primary_levels: its pool of light bends on the scale of its
  // height, not of the patches. On the 1990 room at the defaults the floor below the
  // source was 1.6% dark between exact vertices 0.6 m apart (bench/results/small_area_lights.md). Later
  // shots of the same patch (light it reflects) are a patch's.
  bool sharp_primary_patches = true;
  // Levels beyond max_level for that shot: fewer than a luminaire's, since an area
  // light's penumbrae are decided by rays. With 3, the Cornell demo's floor by the red
  // wall kept a vertex 4.5% off a ring spanning 3.9% at two of five seeds
  // (tests/pictures_test.cpp; 26,000 vertices); with 2, none beyond 2.9% (12,400).
  int primary_levels = 2;
  // Dynamic, shots from luminaires onto detail (Solver's Patch::detail: facets smaller
  // than the patch size squared, such as frames, radiators, skirting boards and chair
  // parts): paper levels beyond max_level, with the patches' own push-down error and no
  // shadow levels. What the eye and the work plane see are the room's walls, floors,
  // ceilings and tables. Measured with the office building of samples/make_office.py
  // (one storey, its 36 luminaire shots) and the IFC house (solve seconds): detail
  // treated as everything else, the house 23.7 s; 3 levels and the patches' error, the
  // office 4.68 M elements and 2.84 GB, the house 24.4 s; 2 levels, 3.97 M, 2.47 GB and
  // 24.0 s; none, 3.42 M, 2.2 GB and 25.9 s (the house then needs 4,619 shots instead of
  // 4,070: the error estimate counts the coarser detail's error).
  int detail_luminaire_levels = 2;
  // The area of a whole patch (model units squared; 0: not used): no bisection the
  // oracle asks for makes an element smaller than such a patch's smallest at the levels
  // allowed. A patch smaller than that (a sliver along an imprinted line, a frame's
  // side) then refines less or not at all: the levels count from the patch size, not
  // from each patch. `dynrad solve` sets it to an eighth of the patch size squared:
  // bisecting to the patch size leaves right triangles whose longest edge lies between
  // the patch size and 1/sqrt(2) of it, so a whole patch has at least that area.
  double patch_area = 0;
};

// How a point's view of a sender was decided by rays: not at all (no rays: the sender
// lies behind the point, or its light is decided otherwise: luminaires, clusters), by
// the first few rays all arriving or all blocked, or by the full count (mixed).
enum class RayVerdict : std::uint8_t { none, seen, hidden, mixed };
// How many rays a point form factor casts: `full` casts the first pass and the full
// count whatever the first pass finds (the same first rays, so a forced count only
// adds to them); `verdict`, when given, receives how the visible part was decided.
struct RayPlan {
  bool full = false;
  RayVerdict* verdict = nullptr;
};

}  // namespace dynrad::rad
