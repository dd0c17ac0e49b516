// Options and results shared by the solvers.
#pragma once

#include "mesh/core/default_seed.h"
#include "mesh/core/types.h"

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace dynrad::rad {

// Photometric solves: lumens per watt of the emission of faces (given in W/m^2) and
// of RGB white, Radiance's convention for equal-energy white light over the visible
// range. Luminance of an RGB value: Rec. 709 / sRGB weights (Rgb::luminance), which
// sum to 1, so a white of value v has luminance v.
constexpr double kLumensPerWatt = 179.0;

struct SolveOptions {
  double converge = 0.01;         // stop when unshot power is this fraction of emitted power
  std::size_t max_iterations = 0;  // stop after this many shots (0: no limit)
  double time_limit = 0;           // stop after this many seconds (0: no limit)
  // Visibility rays per receiver and sender, first pass (stratified over the sender: 2
  // as 2 x 1 strata, n as sqrt(n) x sqrt(n)); where they disagree, max_rays more. On the
  // IFC house two first rays instead of four cut the solve by 14% (129 M rays to 72 M),
  // and its values moved by 0.76% rms, as much as changing the seed moves them (0.73%
  // with four, 0.78% with two); the 1990 rooms, open and obstructed, and the furnace
  // gave the same errors against their references (bench/results/bench_house.md).
  int min_rays = 2;
  int max_rays = 16;               // added when the first pass finds the sender partly hidden
  // The same in the first shot of a primary emitting patch (a small area light; see
  // RefineSettings::sharp_primary_patches): its penumbrae are the sharpest light a patch
  // casts and most of a vertex's value there, and that shot's finer elements put many
  // vertices in them. With 16 the Cornell demo kept 31-46 vertices more than 2% off
  // their rings, the worst 6-8% (tests/pictures_test.cpp, seeds 1-5); with 64, at most
  // 2, the worst 2.9%. The obstructed 1990 room's mean error: 0.93% (16), 0.89% (64).
  int primary_rays = 64;
  int escape_rays = 1024;          // rays per sender to measure the power it loses to the outside
  std::uint64_t seed = default_seed();  // all sampling is seeded: same input, same answer
  int threads = 0;                 // 0: all cores
  double crease_angle = 30;        // degrees; see mesh/core/vertex_split.h
  // Output only: add Cohen et al.'s (1988) ambient estimate of the light not yet shot,
  // reflectance x ambient, to every vertex. It does not touch the solve or
  // its energy balance; it makes an early stop (a time limit, Ctrl-C) look like the
  // converged picture rather than a darker one. It vanishes as the solve converges.
  bool ambient_display = false;
  // With the ambient term: the patches within half a patch size of a vertex are taken at
  // the unshot radiosity each holds rather than the scene's mean (their first bounce;
  // see radiosity/solver/near_unshot.cpp). At a concave edge the ambient term's mean is wrong:
  // there half the view is a few patches of the other surface.
  bool near_unshot = true;
  // Count in the estimate (ErrorEstimate::shadows, and the PLY's per-vertex `error`)
  // what linear interpolation gets wrong of the primary sources' shadows at each leaf's
  // centroid (radiosity/solver/direct_gap.cpp): a shadow inside an element whose corners are
  // lit, which the hierarchical surplus does not see. False: the surplus alone.
  bool direct_check = true;
  // Above 0: the outlines of hard shadows (radiosity/sources/shadow_outlines.h, with its
  // options for patches of this size) are drawn into the mesh after the shots, before
  // its refinement for display, through the element hierarchy (RefineSettings::
  // exact_direct and the dynamic method only). Drawn before the solve instead, their
  // pieces became patches of their own: one storey of the generated office went from
  // 229,000 patches to 1.58 million. 0: none (the host may have drawn them before).
  double outline_patch_size = 0;
  // Over-relaxation of each shot (Gortler, Cohen & Slusallek 1993; Feda & Purgathofer
  // 1992 call it overshooting): the sender shoots `overshoot` times its unshot
  // radiosity and keeps the rest, 1 - overshoot of it, which is negative for values
  // above 1 and is shot back later. It anticipates the light that will come back to the
  // sender and cuts the number of shots to a given accuracy. 1 is the paper's (and
  // Cohen et al. 1988's) progressive refinement. Convergence is then measured on the
  // magnitude of unshot power.
  double overshoot = 1.0;
  // Receiver culling, per shot, before any form factor or ray (see Solver::receiving_patches):
  // patches that cannot exchange light with the sender (behind its plane, or with the
  // sender behind theirs) are skipped exactly; then patches whose unoccluded share of
  // the shot is bounded below negligible_share / (number of patches) are skipped too,
  // so that all those skipped in one shot carry at most `negligible_share` of its power
  // (the normalisation of each shot hands it to the receivers that remain). 0 turns the
  // second rule off; `cull` false turns both off (for tests and measurements).
  bool cull = true;
  double negligible_share = 1e-4;
  // Shaped senders: a patch's unshot radiosity is one mean, but the light it has
  // received is not even across it. Each shot gives the mean a shape from what a
  // quarter grid of points on the sender gained since it last shot, with the same
  // power; receivers near the sender see it (on 2 m patches of the 1990 room the error
  // the senders leave falls from 0.80% to 0.23%: bench/results/bench_time_to_accuracy.md). The shape is
  // measured on luminance and given to all three channels. False: every patch shoots
  // evenly, as Cohen et al. 1988 and the paper do.
  bool shaped_senders = true;
  // Choosing the brightest sender (its unshot power, Cohen et al. 1988), a patch of less
  // area than a whole patch (RefineSettings::patch_area) counts as a whole patch, or as
  // twice its own area if that is less, unless it is detail (Solver::Patch::detail).
  // By power alone, a patch of half a whole patch's area (a sliver along a box's edge)
  // shoots only when its unshot radiosity is twice its neighbours': the small patches
  // hold the most unshot radiosity when the solve stops, and a vertex beside them sees
  // them most (an edge vertex takes half its light from the patches along the other
  // side of the edge). The ambient term, one area-weighted mean, cannot give that back:
  // a 1 x 1 x 3 furnace at the defaults kept an edge vertex 5.7% dark, 1.2% with this
  // rule in as many shots, 0.8% with near_unshot too (bench/results/concave_edges.md). Without the cap
  // at twice, the much smaller patches of imprinted lines shot far more often: the IFC
  // house took 14% more shots (25% with detail counted too); with it, as many (4,338).
  // False: power alone.
  bool whole_patch_senders = true;
  // Face clusters (mesh/core/face_clusters.h): patches whose facet (the patches that touch
  // in one plane) has less area than cluster_area and that emit nothing are grouped, within spheres of radius cluster_radius, into clusters
  // that send and receive light as one: a cluster far from a sender (kClusterFar of its
  // radii) receives at one point per part, and it shoots the light its patches
  // reflected as one sender (see Solver). 0 (either): no clusters, every patch on its
  // own. `dynrad solve` sets them from the patch size (radiosity/solver/settings.h); the
  // adaptive method never uses them (it gathers every earlier shot into new elements).
  double cluster_area = 0;
  double cluster_radius = 0;
  // Sender groups (mesh/core/plane_groups.h): the patches that are in no face cluster are
  // grouped, with the neighbours that lie in their plane and have their material,
  // within spheres of this radius (at most 16 patches a group); a group sends its
  // patches' light in one shot (see Solver). 0: every patch sends on its own. `dynrad
  // solve` sets it with the clusters (three quarters of the patch size).
  double group_radius = 0;
  // Stop when the estimated mean relative error of the written values
  // (Solver::estimate_error) falls below this (0: off). `converge` still applies as a
  // floor; when only the mesh's own error is left above the target (the unshot part is
  // below a tenth of the target, or below a quarter of the mesh's part), the solve
  // stops too: shooting on would buy little (stopped_by "error floor").
  double error_target = 0;
  // Photometric solves (luminaires, or --units photometric) work in lumens: emitting
  // faces' emission, given in W/m^2, is multiplied by this (179 lm/W, Radiance's
  // efficacy of equal-energy white light, in photometric solves; 1 otherwise).
  double emission_scale = 1;
  // Reflectance channels below this are raised to it. Illuminance is recovered from
  // radiosity as (B - emission) / reflectance, which a black surface would lose; a
  // floor of 1e-4 (photometric solves) keeps it at a cost of 1e-4 of the light.
  double min_reflectance = 0;
  // Called at every shot boundary; returning true stops the solve there (signals).
  std::function<bool()> should_stop;
  // Called after every shot.
  std::function<void(std::size_t iteration, double unshot_fraction)> on_shot;
  // Called during the passes after the shots (the display's refinement, the receivers'
  // direct light, the near-unshot correction), at most every 2 s and when each ends,
  // from any thread: the pass's name, how much of it is done and of how much (units of
  // its own) and its seconds. Such a pass took minutes on a building and said nothing.
  // should_stop cuts the display's refinement and the near-unshot correction short.
  std::function<void(const char* pass, std::size_t done, std::size_t total, double seconds)> on_pass;
  // Called during a shot, at most every 2 s, from any thread: how many receiving points
  // the shot has computed so far and its seconds. A sky's first shot on a building can
  // take minutes (about a thousand rays per point); this is its sign of life. A stop
  // (should_stop) still waits for the shot's end, so that the solution stays whole.
  std::function<void(std::size_t points, double seconds)> on_busy;
};

// Power bookkeeping in W per channel (when lengths are metres). After every shot,
// emitted = absorbed + escaped + unshot, up to rounding.
struct EnergyBalance {
  Rgb emitted, absorbed, escaped, unshot;
};

// The estimated mean relative error of the written values, area-weighted over the
// surfaces that reflect (see Solver::estimate_error for how).
struct ErrorEstimate {
  double unshot = 0;          // light not yet shot (what the ambient term leaves)
  double discretisation = 0;  // the mesh: how much the values still bend at the finest elements
  // The mesh again, where a shadow's edge inside an element makes its linear
  // interpolation wrong and the bending above does not show it (SolveOptions::direct_check).
  double shadows = 0;
  double total() const { return unshot + discretisation + shadows; }
  // What the solve stops by (SolveOptions::error_target): shooting on changes neither
  // the shadows' part (the mesh under a primary source is made by its first shot) nor,
  // much, the surplus once the shots are small.
  double stop_measure() const { return unshot + discretisation; }
};

// Why a solve stopped. Reports write it as its name (to_string); parse_stop_reason reads
// the name back.
enum class StopReason {
  converged,     // the unshot fraction fell to SolveOptions::converge
  error_target,  // the estimated error fell to SolveOptions::error_target
  error_floor,   // only the mesh's error was left above the target (not reached)
  iterations,    // SolveOptions::max_iterations shots
  time_limit,    // SolveOptions::time_limit seconds
  interrupted,   // SolveOptions::should_stop said so
};
// "converged", "error target", "error floor", "iterations", "time limit", "interrupted".
const char* to_string(StopReason reason);
// The reason of that name; false when there is none.
bool parse_stop_reason(std::string_view name, StopReason* reason);
// Whether the solve reached what it was asked for (converged or its error target).
inline bool reached_target(StopReason reason) {
  return reason == StopReason::converged || reason == StopReason::error_target;
}

struct SolveReport {
  std::string method;
  std::size_t iterations = 0;
  std::uint64_t energy_transfers = 0;         // shoot(i, q): sender i to receiving element q
  std::uint64_t patch_element_transfers = 0;  // the same, to elements below patch level
  std::uint64_t visibility_rays = 0;
  std::size_t elements = 0;
  std::size_t patches = 0;
  std::size_t luminaires = 0;
  std::size_t receivers = 0;
  double unshot_fraction = 1;
  double seconds = 0;
  StopReason stopped_by = StopReason::converged;
  std::vector<double> unshot_history;  // after each shot
  std::vector<std::uint64_t> transfers_history;  // energy transfers so far, after each shot
  double form_factor_sum_error = 0;    // mean |1 - sum of receiver form factors| before normalisation
  // Empty, or why refinement stopped before the solve did ("max elements", "memory
  // budget") and at which shot.
  std::string refinement_stopped;
  std::size_t refinement_stopped_at = 0;
  // Parts of `seconds`, each with the process's resident and peak memory (bytes) when it
  // ended: the luminaires' (and the sun's) shots, the shots after them, the refinement
  // for display after the shots (RefineSettings::exact_direct) and the estimate.
  struct Part {
    double seconds = 0;
    std::size_t resident = 0, peak = 0;
  };
  Part luminaire_shots, later_shots, display;
  std::size_t peak_resident_memory = 0;  // bytes: the process's peak (VmHWM) when the solve ended, where known
  std::uint64_t culled_receivers = 0;    // patches skipped by a shot, summed over shots (see SolveOptions::cull)
  std::uint64_t negligible_receivers = 0;  // of those, skipped for a negligible bound
  std::size_t clusters = 0, clustered_patches = 0, cluster_parts = 0;  // see SolveOptions::cluster_area
  std::size_t sender_groups = 0, grouped_patches = 0;  // groups of more than one patch, and their patches
  std::uint64_t cluster_receptions = 0;  // clusters that received a shot as one, summed over shots
  std::uint64_t cluster_openings = 0;    // clusters whose patches received a shot one by one
  // Receivers (patches on their own and clusters) that a shot's tree tests found hidden
  // from its sender (radiosity/transfer/receiver_tree.h), summed over shots, and the tests.
  std::uint64_t hidden_receivers = 0, visibility_tests = 0;
  double negligible_share_max = 0;       // the largest bound on the power skipped in one shot
  EnergyBalance energy;
  ErrorEstimate estimated_error;  // when the solve ended
  double error_target = 0;        // SolveOptions::error_target
};

}  // namespace dynrad::rad
