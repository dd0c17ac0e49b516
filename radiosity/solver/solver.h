// The radiosity solver: progressive refinement (Cohen et al. 1988) with no refinement,
// with Adaptive Subdivision (Cohen et al. 1986; the paper's Figure 2) or with Dynamic
// Subdivision (Dubuis & Bieri; Figures 5 and 6). The loop is in shoot.cpp, the oracles
// in oracle.cpp; this class holds the state they share.
//
// State. Every element of the hierarchy, interior ones included, keeps the cumulated
// radiosity at its three corners. New elements interpolate their parent's corner values
// (linear across the flat parent, so a midpoint gets the mean of its edge's ends).
// Patches keep their unshot radiosity (its mean; each shot gives it a shape from a
// quarter grid of points on the patch, see SenderShape). Receivers are the element
// corners; a corner's form factor to the sender is Lambert's closed form at the corner times the
// fraction of rays that reach the sender, evaluated once per shot for each vertex and
// patch.
#pragma once

#include "mesh/core/face_clusters.h"
#include "mesh/core/plane_groups.h"
#include "mesh/core/refinement.h"
#include "mesh/core/sphere_index.h"
#include "mesh/core/vertex_split.h"
#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/grow_array.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/sources/shadow_outlines.h"
#include "radiosity/solver/coefficient_channels.h"
#include "radiosity/solver/oracle.h"
#include "radiosity/solver/patch_state.h"
#include "radiosity/solver/refine_settings.h"
#include "radiosity/solver/sender_shape.h"
#include "radiosity/solver/shot_walk.h"
#include "radiosity/transfer/process_memory.h"
#include "radiosity/transfer/receiver_tree.h"
#include "radiosity/solver/solve_types.h"
#include "radiosity/solver/solver_output.h"
#include "radiosity/transfer/vertex_plane_map.h"
#include "radiosity/transfer/visibility.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace dynrad::rad {

class Solver {
 public:
  // Refines `scene` through `hierarchy` as it goes; both must outlive the solver.
  // Luminaires (luminaire.h) shoot first, each once, in the order given, into the same
  // walk as the patches: their "form factor" at a receiver is the illuminance they give
  // it, I cos(theta) / d^2 times the fraction of the luminaire it sees, per unit of
  // their colour. Throws std::invalid_argument when nothing emits.
  Solver(SceneMesh& scene, ElementHierarchy& hierarchy, SolveOptions options, RefineSettings refine = {},
         std::vector<Luminaire> luminaires = {});
  ~Solver();

  SolveReport run();
  bool shoot_once();  // one shot from the brightest patch; false when nothing is left

  using Output = SolverOutput;  // solver_output.h
  Output output() { return output(options_.ambient_display); }
  Output output(bool ambient_display);  // with or without the ambient term, whatever the options
  // Frees what only the shots and output() use, per element and per receiver (the
  // values, the push-down, the form factors, the receivers, their direct light, the
  // ray scene), keeping the patches, the luminaires, the report and the coefficient
  // channels. For a host that has taken output() and goes on to the lit scene and
  // the written mesh (the pipeline): on one office storey that is about 1 GB of its
  // peak. Nothing may shoot, estimate or output after it.
  void release_elements();

  // The estimated mean relative error of what output() writes now: per leaf element,
  // area-weighted, over surfaces that reflect, relative to their mean radiosity.
  //   unshot: the light not yet shot reaches each element as its reflectance times
  //     Cohen et al.'s ambient radiosity. Written without the ambient term, all of it
  //     is missing (on the 1990 room at 2% unshot: 3.2% estimated, 3.3% measured);
  //     with it (SolveOptions::ambient_display), a quarter of it is counted: the term
  //     is right on average and wrong in its distribution, and on the 1990 room it
  //     removes 80-90% of the unshot light's error (bench/results/bench_time_to_accuracy.md).
  //   discretisation: at every leaf below a patch, the hierarchical surplus at the
  //     corner its parent's split made: the leaf's value there minus the parent's
  //     linear interpolation, halved: bisection halves the interpolation error (it
  //     goes with the element's area), so what is left at the leaf is about the
  //     surplus there, and the mean of a linear interpolation's error over an element
  //     is about half its value at an edge's midpoint (2/3 along a parabola). Leaves
  //     that are whole patches have no surplus: no refinement was asked for there.
  //   shadows: per leaf, what two thirds of its direct gap (direct_gap.cpp) adds above
  //     that (mesh_error() takes the larger): a shadow inside an element whose corners
  //     are lit, which linear interpolation misses and the surplus does not show. The
  //     solve stops by the other two (ErrorEstimate::stop_measure()).
  // Measured against the path-traced reference in tests/error_estimate_test.cpp.
  // Without `shadows` that part is left at 0 and not computed: the solve's looks stop by
  // the other two (ErrorEstimate::stop_measure()), so only the last estimate needs it.
  ErrorEstimate estimate_error(bool shadows = true);
  // The part of the estimate that is the unshot light, per unit reflectance (see
  // estimate_error()).
  Rgb unshot_error_radiosity() const;
  // An element's hierarchical surplus: at the corner its parent's split made, |value -
  // the parent's linear interpolation| (luminance); 0 for a patch's root.
  double surplus(ElementId e) const;
  // A leaf's estimated mean error from its mesh: the larger of half its surplus and
  // its direct gap (direct_gap.cpp) times kDirectGapWeight, both luminance.
  double mesh_error(ElementId e) const;
  const EnergyBalance& energy() const { return report_.energy; }
  double unshot_fraction() const;
  const SolveReport& report() const { return report_; }
  // The shadow outlines drawn after the shots (SolveOptions::outline_patch_size).
  const ShadowOutlineReport& outline_report() const { return outline_report_; }
  // The sources as solved: daylight's flux (what reached the surfaces) filled in.
  const std::vector<Luminaire>& luminaires() const { return luminaires_; }
  // For benchmarks: see Visibility::record_rays (single thread only).
  void record_rays(std::vector<RTCRay>* sink) { visibility_->record_rays(sink); }
  // For benchmarks: see Visibility::time_calls.
  void time_visibility(bool on) { visibility_->time_calls(on); }
  double seconds_in_embree() const { return visibility_->seconds_in_embree(); }

  // Coefficient channels (coefficient_channels.h, solver_coefficients.cpp): the light
  // of each part of the sky carried beside the colours.
  using CoefficientChannels = ::dynrad::rad::CoefficientChannels;
  void carry_coefficients(CoefficientChannels channels);  // before run()
  // Patch p's mean radiosity per channel, reflected light only (count values).
  const float* patch_coefficients(std::uint32_t p) const { return coefficient_total_.data() + p * coefficients_.count; }
  std::size_t coefficient_count() const { return coefficients_.count; }
  // The absolute channels' (CoefficientChannels::relative on) part of
  // patch_coefficients(p) that they brought straight from the sky's shot (count -
  // relative values): a sun's direct light, reflected. The rest is interreflection.
  const float* patch_direct_coefficients(std::uint32_t p) const {
    return coefficient_direct_.data() + p * (coefficients_.count - absolute_from());
  }
  std::size_t absolute_from() const { return std::min(coefficients_.count, coefficients_.relative); }

 private:
  // Coefficient channels (see carry_coefficients; all empty when count is 0).
  CoefficientChannels coefficients_;
  std::vector<float> coefficient_unshot_;       // per patch, radiosity not yet shot
  std::vector<float> coefficient_total_;        // per patch, radiosity received and reflected
  std::vector<float> coefficient_direct_;       // per patch, the absolute channels' first booking
  std::vector<float> coefficient_part_unshot_;  // per cluster part, power not yet shot
  std::vector<float> coefficient_shot_;         // the current sender's shot (as current_shot_)
  std::vector<float> coefficient_mix_;          // the sky's shot: per receiver in coefficient_slot_
  std::vector<std::uint32_t> coefficient_slot_;  // per patch, then per part: its mix's slot (or ~0)
  std::vector<char> coefficient_booked_;         // per slot: its absolute channels taken
  // A patch sender: `factor` of its unshot channels into the shot (adding `weight` x
  // that), 1 - factor left.
  void shoot_coefficients(std::uint32_t p, double factor, double weight);
  // The sky's shot: the mix of every receiver it reached (coefficient_slot_).
  void mix_sky(const std::vector<ElementId>& terminals, const std::vector<double>& reach);
  // What a receiver of the sky's shot takes per unit area: channel j of the mix at
  // `slot` times `factor` (the steering sky's light there), to `out`.
  // The absolute channels (CoefficientChannels::relative) are taken at the first
  // booking of a slot only (coefficient_booked_).
  void incident_coefficients(std::uint32_t slot, double factor, float* out);
  // Books a patch's reception (see account_transfers): `incident` times `factor` per
  // unit area.
  // `from_sky`: the sky's shot (its absolute channels also go to coefficient_direct_).
  void book_coefficients(std::uint32_t patch, const float* incident, float factor, bool from_sky);
  void book_part_coefficients(std::uint32_t part, const float* incident, float factor, bool from_sky);
  void book_direct(std::uint32_t patch, const float* incident, float reflected);
  // A sign of life during a long shot (SolveOptions::on_busy): counts the receiving points
  // computed and calls on_busy when 2 s have passed since the last call.
  void beat();
  // The progress of a pass after the shots (SolveOptions::on_pass): add() from any
  // thread; the call comes at most every 2 s from one of them, and once at the end.
  class PassProgress {
   public:
    PassProgress(const SolveOptions& options, const char* name, std::size_t total);
    ~PassProgress();
    void add(std::size_t done);
    void grow(std::size_t more) { total_ += more; }  // the pass found more to do
    // should_stop, read at most every 50 ms (a signal handler's flag is cheap to read,
    // a host's callback need not be).
    bool stop();

   private:
    const SolveOptions& options_;
    const char* name_;
    std::atomic<std::size_t> done_{0}, total_;
    std::chrono::steady_clock::time_point start_;
    std::atomic<std::int64_t> next_{0}, next_stop_check_{0};
    std::atomic<bool> stopped_{false};
  };
  std::atomic<std::size_t> shot_points_{0};
  std::chrono::steady_clock::time_point shot_start_;
  std::atomic<std::int64_t> next_beat_{0};  // steady clock, nanoseconds

  // Sender ids: patches are 0 .. P - 1, luminaires P .. P + L - 1, clusters P + L ..
  // P + L + C - 1.
  bool is_luminaire(std::uint32_t id) const {
    return id >= patches_.size() && id < patches_.size() + luminaires_.size();
  }
  const Luminaire& luminaire(std::uint32_t id) const { return luminaires_[id - patches_.size()]; }
  bool is_cluster(std::uint32_t id) const { return id >= patches_.size() + luminaires_.size(); }
  std::uint32_t cluster_sender(std::uint32_t cluster) const {
    return static_cast<std::uint32_t>(patches_.size() + luminaires_.size()) + cluster;
  }
  std::uint32_t cluster_index(std::uint32_t id) const {
    return id - static_cast<std::uint32_t>(patches_.size() + luminaires_.size());
  }
  // The flux a sky or sun luminaire sends onto the patches (see solver.cpp).
  double daylight_flux(const Luminaire& l) const;
  // Illuminance at x (normal n) from luminaire `id` per unit of its colour: see
  // rad::luminaire_illuminance (rays: with the solver's visibility).
  double luminaire_illuminance(const Vec3d& x, const Vec3d& n, std::uint32_t id, std::uint64_t seed, bool rays,
                               double* unoccluded) const;
  using Patch = PatchState;  // radiosity/solver/patch_state.h

  std::uint32_t brightest_patch() const { return brightest_; }
  // After each shot (and before the first): the unshot totals and the brightest sender,
  // which the next shot sends from. Only the senders the shot changed are looked at
  // again (mark_surveyed()); see "Survey" below.
  void survey_patches();
  // The patches sender i's shot must visit: all others but those SolveOptions::cull
  // rules out. Appends their roots to `roots`; counts in the report.
  // The form factors at their roots' corners are computed on the way (the walk's first
  // level), so that the sender's first level costs no parallel region of its own.
  void receiving_patches(std::uint32_t i, std::vector<ElementId>& roots);
  // False once a limit of RefineSettings is reached; says so in the report, once.
  bool refinement_allowed();
  double lost_fraction(std::uint32_t patch);
  // The shares of cosine-weighted rays (SolveOptions::escape_rays of them, stratified)
  // that meet nothing and that meet nothing or a back face, from the points and
  // normals `origin` draws (from the random state it is given), seeded by `seed`.
  using EscapeOrigin = std::function<void(std::uint64_t& state, Vec3d& origin, Vec3d& normal)>;
  // `rays` of them (the first pass is for SolveOptions::escape_rays only).
  std::array<double, 2> escape_counts(std::uint64_t seed, const EscapeOrigin& origin, int rays) const;
  std::array<double, 2> patch_escape_counts(std::uint32_t patch, int rays) const;
  std::array<double, 2> cluster_escape_counts(std::uint32_t cluster, int rays) const;
  // A rough lost fraction (kRoughEscapeRays) for a patch or cluster sender that holds
  // unshot light but has not shot yet: survey_patches() needs only an idea of it.
  void rough_lost_fraction(std::uint32_t id);
  // Form factors at the corners of `elements` for the current sender, computed in
  // parallel for every receiver not yet known this shot.
  void compute_form_factors(const std::vector<ElementId>& elements);
  // One element's: on return, all three are known (see solver.cpp).
  void compute_corner_form_factors(ElementId e);
  // After compute_form_factors(elements), when settles_visibility(): a corner whose few
  // first rays all agreed (RayVerdict::seen or hidden) is cast again with the full count
  // when another corner of one of its elements found the sender partly hidden or had
  // the opposite verdict, and the sender's unoccluded light there is at least
  // kSettleShare of what the corner holds. Two rays that happen to agree inside a
  // penumbra otherwise make a lone dark or bright vertex (tests/pictures_test.cpp).
  void settle_visibility(const std::vector<ElementId>& elements);
  // For shots from patches, emitting or reflecting (not luminaires: their rays give no
  // verdict). Two first rays that agree are kept as the whole answer, and that pulls
  // the fraction seen towards 0 or 1: a sender seen by a fifth of it counts as seen
  // with p^2, hidden with (1 - p)^2, so 10% instead of 20% on average. Behind the
  // obstructed 1990 room's partition ends, where the floor's bright patches are seen
  // in part, that made the ceiling and floor up to 8% too bright (mean 0.80%; settled:
  // 0.71%, largest 6-7%, at seeds 1-3). For reflected light only where it is at least
  // kSettleShareReflected of the corner's value: on the IFC house that costs 7% more
  // rays (at kSettleShare's 0.05, 12%, for the room no better).
  bool settles_visibility() const { return sender_ < patches_.size(); }
  // The share of patch p that point x (normal n) sees, by kNearRays rays: to its
  // centroid and halfway to each corner. For the near-field corrections, where a
  // closed form stands for the light of a patch a few decimetres off, which a
  // partition or a wall's thickness may hide (near_field_start, near_unshot).
  double near_seen_share(const Vec3d& x, const Vec3d& n, const Patch& p) const;
  double form_factor(ElementId e, int corner) const;
  // Receivers: one per (vertex, facing) that an element's corner is, numbered as the
  // elements appear (in id order: the same for any thread count), for elements from
  // `first` on. A receiver is evaluated at a point a hundredth of the way from its
  // vertex to the centroid of the first element that has it, fixed for the whole solve:
  // at a vertex that is also a sender's corner, F depends on the direction one comes
  // from, and the shares of all senders sum to the right total only if every shot uses
  // the same point.
  void register_receivers(ElementId first);
  // F from evaluation point x (of vertex v, on a surface with normal n) to patch
  // `sender`: Lambert's closed form times the fraction of seeded rays that arrive.
  double point_form_factor(VertexHandle v, const Vec3d& x, const Vec3d& n, std::uint32_t sender,
                           double* unoccluded, const RayPlan& plan = {}) const;
  // Adaptive subdivision: new elements' corner values gathered from every patch that
  // has shot, this shot included (the paper: their values "must be recalculated"). They
  // are stamped so that the walk, if it reaches them in this shot, does not add this
  // shot again.
  void gather_new_elements(std::size_t first);
  double element_form_factor(ElementId e) const;
  // Lambert's closed form from point x (normal n) to the current sender, with the
  // sender's shape (SolveOptions::shaped_senders) where it has one.
  double sender_closed_form(const Vec3d& x, const Vec3d& n) const;
  SenderShape shape_;  // the current sender's (sender_shape.h)
  void shape_sender();
  // The shape of patch `patch`'s unshot radiosity for a shot of mean luminance m (see
  // SenderShape); moves the patch's shot_at_nodes on to this shot.
  SenderShape shape_of(std::uint32_t patch, double m);
  // The shape of all that patch `patch` has shot so far (Patch::shot_at_nodes against
  // its mean, Patch::shot), for gathering to new elements (gather_new_elements).
  SenderShape shipped_shape(std::uint32_t patch) const;
  // Luminance of the cumulated radiosity at point p of patch `root`'s surface: the
  // leaf's corner values interpolated, plus what its ancestors still hold to push down.
  double luminance_at(ElementId root, const Vec3d& p) const;
  // OracleInputs::pushdown_error and current_peak for element q and this shot's dB at
  // its corners.
  // Returns the mean over q's edge midpoints of the visible form factor (the rule
  // exact for quadratics: q's mean form factor), or -1 when it did not estimate.
  // `mid` gets midpoint_form_factors() on the way.
  double estimate_pushdown_error(ElementId q, const Rgb& reflectance, OracleInputs& in,
                                 std::array<double, 3>& mid) const;
  // Corner values for elements created since the last call, from their parents.
  void initialise_new_elements();
  // Elements from `first` on whose nearest older ancestor is one of this shot's
  // `terminals` were split after the shot had stopped there (a neighbour's refinement,
  // kept conforming, reached it): they took this shot's dB as a line between that
  // ancestor's corners, which misses how F bends (beside a neighbouring wall, by a tenth
  // of B). Their new corners take it from the sender's closed form instead, times the
  // visible fraction interpolated from that ancestor's corners. What they then hold is
  // kept (held_), for their own children should the refinement reach them again later
  // in the shot: a floor vertex 19 cm from a wall, born two splits below a terminal
  // of the wall's first shot, took a line between corners 0.75 m apart and stayed 2.2%
  // dark in a converged furnace (bench/defaults.cpp, the 4 x 3 x 1.5 box).
  void restart_split_terminals(std::size_t first, std::vector<ElementId> terminals, const Rgb& shot);
  // This shot's dB at an element's corners and the fractions of the sender they see,
  // for elements split from a terminal after the walk had passed (cleared every shot).
  struct HeldShot {
    std::array<Rgb, 3> dB;
    std::array<double, 3> seen{};
  };
  std::unordered_map<ElementId, HeldShot> held_;
  // Values of elements first to count - 1, each from its nearest ancestor before first.
  void initialise_values(ElementId first, std::size_t count);
  // Push-down: dB given at q's corners and edge midpoints reaches every element below
  // q, interpolated by the quadratic through those six values (RefineSettings::
  // quadratic_pushdown; linear from the corners otherwise: the midpoints are then the
  // corners' means). It is lazy (exact, since a quadratic restricted to a child is the
  // quadratic through the child's six nodes): q keeps the sum as pending, and flush(q)
  // hands it to q's children when the walk enters them.
  void push_down(ElementId q, const std::array<Rgb, 6>& delta);
  void flush(ElementId q);
  void flush_all();
  Rgb interpolate(ElementId e, const std::array<Rgb, 3>& at_corners, const Vec3d& point) const;
  std::array<double, 3> barycentric(ElementId e, const Vec3d& point) const;
  // The quadratic through six node values (corners, then edge midpoints) at barycentric point l.
  static Rgb quadratic(const std::array<Rgb, 6>& nodes, const std::array<double, 3>& l);
  // This shot's visible form factor at q's three edge midpoints (edge k runs from corner
  // k to k + 1): Lambert's closed form there times the mean visible fraction of the
  // edge's ends (no rays), or, far from the sender, the corners' mean plus the far-field
  // form's second difference.
  void midpoint_form_factors(ElementId q, std::array<double, 3>& mid) const;
  // A_q times the mean form factor over q: the share of the sender's power (per unit
  // of its area) that q would receive, before account_transfers() normalises it.
  double element_reach(ElementId q) const;
  // `reach` holds element_reach() of each terminal element, computed where the walk
  // stopped.
  void account_transfers(const std::vector<ElementId>& terminals, const std::vector<double>& reach,
                         std::uint32_t sender, const Rgb& shot_radiosity);

  std::vector<WalkChunk> walk_chunks_;  // shot_walk.h
  void start_heartbeat();
  // Picks the sender (sender_) and starts its shot: its light leaves its unshot
  // radiosity, its shape is set. False when nothing is left to shoot.
  bool pick_sender(Rgb& shot);
  ShotRules shot_rules(std::uint32_t sender);  // also sets shot_max_rays_
  // shoot(i, q) and the oracle for every element of walk.level.
  void shoot_level(ShotWalk& walk, const ShotRules& rules, const Rgb& shot);
  void shoot_element(ElementId q, const ShotRules& rules, const Rgb& shot,
                     const std::vector<ElementId>& complete_split, WalkChunk& out);
  void subdivide(ShotWalk& walk, const Rgb& shot);   // splits walk.subdivide; new elements start from their parent
  void next_level(ShotWalk& walk, const Rgb& shot);  // the passed elements take dB; their children are the next level
  void update(std::uint32_t sender, const Rgb& shot);  // the sender's shot is booked; the shot counted
  // RefineSettings::patch_area, but no more than the largest patch: patches given
  // larger than the model's faces (a box of 2 m faces at patch size 10) still refine.
  double patch_area_ = 0;

  // Sender groups (SolveOptions::group_radius; mesh/core/plane_groups.h; solver_groups.cpp).
  // The patches on their own (not in a face cluster) are grouped with their neighbours
  // in one plane: a group sends what all its patches hold in one shot, from its first
  // patch's id (its leader), and each patch keeps receiving on its own. The light a
  // group sends is exact: F to the group is the sum over its patches of Lambert's closed
  // form times the patch's weight, its unshot radiosity over the group's mean
  // (luminance), and its rays go to points on the patches drawn by those weights and
  // areas. A group of one patch is that patch, shaped as before (shape_sender()).
  // The group's lost fraction is kept in its leader's Patch::lost, escaped and
  // rough_lost, measured from points on all its patches.
  PlaneGroups groups_;
  bool is_group(std::uint32_t id) const {
    return id < patches_.size() && groups_.groups[groups_.group_of[id]].count > 1;
  }
  const PlaneGroups::Group& group_of(std::uint32_t patch) const { return groups_.groups[groups_.group_of[patch]]; }
  void build_groups();
  // Makes group `leader`'s the current sender: its mean unshot radiosity (what the shot
  // carries per unit of its area), the weights; the patches keep what overshoot leaves.
  Rgb start_group_shot(std::uint32_t leader);
  struct SenderMember {
    std::array<Vec3d, 3> corners;
    Vec3d centroid;
    double radius = 0;  // of a sphere about the centroid holding its corners
    double area = 0, weight = 0;
    double cumulated = 0;  // of |weight| x area, up to and with this one, over the total
    SenderShape shape;     // of its own unshot radiosity (shaped senders)
  };
  std::vector<SenderMember> sender_members_;  // the current group sender's (empty: none)
  std::vector<Rgb> sender_member_unshot_;     // what each held before the shot
  Vec3d sender_centre_;                       // the current patch or group sender's sphere
  double sender_radius_ = 0;
  // A point on the current group sender for uniform numbers u (which member, by weight
  // and area) and v, w (where in it).
  Vec3d group_sender_point(double u, double v, double w) const;
  // F from x (normal n) to the current group sender with rays (seeded by `key`): each
  // patch's term of group_closed_form() times the fraction of its rays that arrive, the
  // rays drawn among the patches in proportion to their terms at x (so a point that
  // sees one patch of the group and not the other gets that patch's light, however
  // their areas compare).
  double group_form_factor(std::uint64_t key, const Vec3d& x, const Vec3d& n, double* unoccluded,
                           const RayPlan& plan) const;
  // Lambert's closed form from x (normal n) to the current group sender, weighted (each
  // patch's term in `terms`, when given, sender_members_.size() of them); a
  // patch at least kMemberFar of its radii away, wholly above x's horizon, counts by the
  // point-to-area form A cos cos / (pi r^2) instead (relative error about 0.25%, 0.5% at
  // 8 radii: measured against numerical integration over a right triangle).
  double group_closed_form(const Vec3d& x, const Vec3d& n, double* terms = nullptr) const;

  // Face clusters (SolveOptions::cluster_area; solver_clusters.cpp). A cluster far from
  // the sender (kClusterFar of its radii from the sender's bounding sphere, or the sky)
  // receives as one: the form factor at each part's point (its normal, the usual
  // rays), given to every patch of the part (constant over each patch, pushed down to
  // whatever closure split below it); otherwise it is opened and its patches receive
  // as any patch does. Either way, the light they reflect joins their part's unshot
  // power. A cluster sends that power as one sender: each part a disc of its area at
  // its point (Wallace et al. 1989's A cos cos / (pi r^2 + A), which stays finite near),
  // weighted by its share of the power; the fraction of seeded rays to parts picked in
  // proportion to their terms that arrive gives visibility, as a patch's rays do.
  FaceClusters clusters_;
  std::vector<std::uint32_t> standalone_;  // patches in no cluster, in id order
  struct ClusterState {
    double lost = -1, escaped = 0;  // as Patch::lost and escaped
    double rough_lost = -1;         // as Patch::rough_lost
    bool dirty = false;             // parts hold pending light for its patches
  };
  std::vector<ClusterState> cluster_state_;
  std::vector<Rgb> part_unshot_;      // power (W) its patches reflected, not yet shot
  std::vector<Rgb> part_pending_;     // shot x F received as one, not yet given to its patches
  std::vector<Rgb> part_reflectance_area_;  // sum over its patches of reflectance x area
  std::vector<double> part_form_factor_;    // this shot's, for clusters received as one
  // The current cluster sender's parts: share of its power (luminance), point, normal.
  struct SenderPart {
    Vec3d point, normal;
    double area = 0, share = 0;
  };
  std::vector<SenderPart> sender_parts_;
  double sender_cluster_radius_ = 0;
  Vec3d sender_cluster_centre_;
  // Clusters this shot receives as one, and the ones it opens.
  std::vector<std::uint32_t> whole_clusters_;
  void build_clusters();
  // Over the patches on their own and the clusters (items 0 .. S - 1: standalone_,
  // then the clusters), for culling what a sender cannot see (receiver_tree.h).
  ReceiverTree tree_;
  void build_tree();
  // The receivers the current sender may see: patches on their own (in id order) and
  // clusters (in index order), through the tree's tests.
  void visible_receivers(std::vector<std::uint32_t>& patches, std::vector<std::uint32_t>& clusters);
  ReceiverTree::Seen test_node(std::uint32_t node) const;
  // The receivers (their places in tree_.order(), sorted) that kSenderRaySide^2 of the
  // current sender's own rays meet first: cosine-weighted from points on it (a
  // luminaire: stratified over the sphere where it sends light). The tree never culls a
  // node that holds one (ReceiverTree::visit): a room seen through a door is a few
  // percent of a sender's view, which these rays see and a node's test points can miss.
  void sender_ray_hits(std::vector<std::uint32_t>& positions) const;
  static constexpr int kSenderRaySide = 16;
  std::vector<std::uint32_t> kept_positions_;
  bool sender_near(const Bounds& box) const;
  // What the cluster does in this shot: 0 culled, 1 received as one, 2 opened.
  int cluster_verdict(std::uint32_t cluster) const;
  // Form factors at the parts of cluster c for the current sender.
  void receive_cluster(std::uint32_t cluster);
  // Gives the parts' pending light to the cluster's patches.
  void flush_cluster(std::uint32_t cluster);
  void flush_clusters();
  // Makes cluster c the current sender; returns the power it shoots.
  Rgb start_cluster_shot(std::uint32_t cluster);
  // F from point x (normal n) to the current cluster sender: unoccluded closed form, and
  // with rays (seeded by `key`) when `rays`.
  double cluster_form_factor(const Vec3d& x, const Vec3d& n, std::uint64_t key, bool rays, double* unoccluded) const;
  double cluster_lost_fraction(std::uint32_t cluster);
  // Casts `rays` visibility rays from x (on a surface with unit normal n) to seeded
  // points of patch `sender`, stratified (strata()), leaving out points behind or on
  // x's plane; adds those that arrive to `visible` and those cast to `cast`. Drawn
  // from the random stream `state`.
  void cast_to_patch(const Patch& sender, const Vec3d& x, const Vec3d& n, int rays, std::uint64_t& state,
                     int& visible, int& cast) const;
  // The form factor at a point with its own seed key (a vertex's index, or a part's).
  double point_form_factor_keyed(std::uint64_t key, const Vec3d& x, const Vec3d& n, std::uint32_t sender,
                                 double* unoccluded, const RayPlan& plan = {}) const;
  static constexpr std::size_t kChunks = 256;  // per level, at most

  SceneMesh& scene_;
  ElementHierarchy& hierarchy_;
  SolveOptions options_;
  RefineSettings refine_;
  std::unique_ptr<Visibility> visibility_;
  std::vector<Patch> patches_;
  // Per element (GrowArray: see grow_array.h).
  GrowArray<std::array<Rgb, 3>> value_;    // cumulated radiosity at its corners
  // Push-down not yet handed to children: a quadratic on the element, its values at the
  // corners (0-2) and at the midpoints of edges (k, k + 1) (3-5).
  GrowArray<std::array<Rgb, 6>> pending_;
  // The patches that have shot, as balls (centre, radius), for
  // RefineSettings::near_field_start: on the IFC house, an index of all 62,000 patches
  // gave 125 candidates per new vertex, of which 1 in 120 had shot enough to count.
  SphereIndex patch_index_;
  std::vector<char> indexed_;  // per patch: in patch_index_
  void index_shot_patch(std::uint32_t p) {
    if (indexed_[p]) return;
    indexed_[p] = 1;
    patch_index_.insert(p, {patches_[p].centre, patches_[p].radius});
  }
  // True when an ancestor of e holds push-down that has not reached e yet (flush()).
  bool pending_above(ElementId e) const;
  // True when v is on a border or has a face in another plane than `normal`'s.
  bool on_plane_edge(VertexHandle v, const Vec3d& normal) const;
  // What patches near a new corner at `position` (of new element e, split from
  // `source`) would add to its start beyond the line across `source`
  // (RefineSettings::near_field_start).
  // `line`: the luminance the line across `source` gives there.
  Rgb near_field_start(ElementId e, ElementId source, const Vec3d& position, double line,
                       std::vector<std::uint32_t>& scratch) const;
  GrowArray<std::size_t> gathered_in_;     // shot whose transfer its gather included (+1)
  std::size_t initialised_ = 0;            // elements with values
  // This shot: sender and form factors by (vertex, patch).
  std::uint32_t sender_ = 0;
  Rgb current_shot_;  // the radiosity the sender shoots in this shot
  // Cohen et al. 1988's ambient radiosity: unshot power per area of the whole scene,
  // times the mean interreflection factor 1 / (1 - mean reflectance); in an open
  // scene, less the share the shots so far lost to the outside (see solver.cpp).
  Rgb ambient() const;
  // Per receiver (where `wanted`): the first bounce of what the patches within half a
  // patch size of it hold unshot beyond the ambient term's mean, sum of F (U_j - mean); times
  // the reflectance, what the written value adds to the ambient term (near_unshot.cpp).
  std::vector<Rgb> near_unshot(const std::vector<char>& wanted) const;
  // Exact direct light (RefineSettings::exact_direct; exact_direct.cpp). Luminaires
  // and the sun shoot to the patches only; their light at a point is evaluated there.
  bool is_direct_sender(std::uint32_t id) const {
    return refine_.exact_direct && is_luminaire(id) && luminaire(id).kind != Luminaire::Kind::sky;
  }
  // In a direct sender's shot: what element q receives of it per unit of its colour
  // (illuminance times area), by kReachSide^2 points on q with rays (account_transfers
  // scales it as every shot's reach).
  double direct_reach(ElementId q) const;
  static constexpr int kReachSide = 4;
  // In a direct sender's shot: patch p takes `radiosity` (its mean, reflected) and
  // notes the sender among those that lit it.
  void note_direct(std::uint32_t patch, const Rgb& radiosity);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> lit_by_;  // (patch, luminaire index), as booked
  // Per patch, the luminaires (indices into luminaires_) that lit it: lit_luminaires_
  // from lit_first_[p] to lit_first_[p + 1]. Built from lit_by_ once they have all shot.
  std::vector<std::uint32_t> lit_first_, lit_luminaires_;
  bool direct_lists_built_ = false;
  void build_direct_lists();
  bool directly_lit(std::uint32_t patch) const;
  // The luminaires that lit a patch around receiver r's vertex with r's facing.
  void receiver_luminaires(std::uint32_t r, std::vector<std::uint32_t>& out) const;
  // Direct illuminance (per channel, with each luminaire's colour) at a point, and the
  // share of it that arrives (luminance; 1 where none could); seen < 0: not computed.
  struct DirectAt {
    float r = 0, g = 0, b = 0;
    float seen = -1;
  };
  // At x (normal n) from `lights` (luminaire indices), with rays seeded by `key`.
  DirectAt direct_at(const Vec3d& x, const Vec3d& n, const std::vector<std::uint32_t>& lights, std::uint64_t key) const;
  std::vector<DirectAt> receiver_direct_;  // per receiver, computed when wanted
  void compute_receiver_direct(std::vector<std::uint32_t> wanted);
  // The direct light at the receivers of elements from `first` on, in lit patches (once
  // the luminaires have shot): the oracle counts it in each element's shading.
  void direct_for_new_elements(ElementId first);
  Rgb receiver_direct(std::uint32_t r) const;  // illuminance; 0 where not computed or unlit
  // Leaf e's direct light (luminance, reflected) against linear interpolation between its
  // corners (exact_direct.cpp).
  struct DisplayError {
    double error = 0;       // the push-down oracle's measure at its edge midpoints and centroid
    double gap = 0;         // that, or what rays at its centroid find, the larger
    double peak = 0;        // the largest light at its corners, midpoints and centroid
    bool shadow = false;    // its corners see shares of the light that differ by more than a quarter
    bool resolved = false;  // small enough for a point source's shadow edge
  };
  DisplayError direct_display_error(ElementId e) const;
  // After the shots: refines where direct light needs it for display (see above).
  void refine_for_display();
  std::vector<float> display_gap_;  // per element: direct_display_error() of a leaf
  // Draws hard shadows' outlines (SolveOptions::outline_patch_size) through the hierarchy,
  // each luminaire's looked for on the surfaces it lit.
  void draw_outlines();
  ShadowOutlineReport outline_report_;
  bool refining_for_display_ = false;  // new elements interpolate their parent alone
  double display_gap(ElementId e) const;  // weighted as the mesh error takes it
  // Patch p's direct light (luminance, reflected) at a node of its quarter grid, node
  // number k (for its shape, shape_of()); 0 for a patch no direct sender lit.
  double direct_luminance_at_node(const Patch& patch, std::uint32_t p, const Vec3d& node, int k) const;

  // The mesh's error on the primary sources' shadows (direct_gap.cpp): per leaf, the
  // unoccluded direct light at the centroid times the reflectance times |the share of
  // it that arrives there - the mean of the corners' shares|. Kept for the elements and
  // receivers already looked at; update_direct_gaps() computes the new ones
  // (SolveOptions::direct_check).
  void update_direct_gaps();
  double direct_gap(ElementId e) const;  // 0 where not computed
  void choose_direct_sources();
  // Every primary source (direct_sources_) has shot, but patches holding at most the
  // error target's share of the primary patches' emitted power. Until then the solve
  // does not stop by its estimate: in an open model the ambient term takes the unshot
  // light as lost in the share the shots so far lost, and a lamp of two triangles 10 m
  // above a 1 m floor stopped after one of them with half the floor's light missing
  // and 0.47% estimated.
  bool primary_sources_shot();
  // Patch i is a primary source that has not shot: its next shot carries its emission
  // (RefineSettings::sharp_primary_patches, SolveOptions::primary_rays).
  bool primary_patch_unshot(std::uint32_t i);
  // Rays added where a point's first rays disagree in the current shot: SolveOptions::
  // max_rays (set by the constructor), or primary_rays in a primary patch's first shot.
  int shot_max_rays_ = 0;
  // Direct light at x (normal n) from direct_sources_, per unit reflectance: what
  // arrives, with its own seeded rays (`key`), and what would without occluders.
  struct DirectLight {
    Rgb seen, open;
    // The share that arrives, light-weighted over the sources; 1 where none could.
    double seen_fraction() const { return open.luminance() > 0 ? seen.luminance() / open.luminance() : 1.0; }
  };
  DirectLight direct_light(const Vec3d& x, const Vec3d& n, std::uint64_t key) const;
  std::vector<std::uint32_t> direct_sources_;        // luminaires but the sky, then patches
  bool direct_sources_chosen_ = false;
  std::vector<float> direct_gap_;      // per element; < 0: not yet computed
  std::vector<float> receiver_seen_;   // per receiver, DirectLight::seen_fraction(); < 0: not yet computed
  struct CornerFormFactor {
    double visible = 0, unoccluded = 0;
    RayVerdict verdict = RayVerdict::none;  // how the visible part was decided
    // The fraction of the sender the corner sees (1 where it could see nothing anyway).
    double visible_fraction() const { return unoccluded > 0 ? visible / unoccluded : 1.0; }
  };
  // A shadow's edge crosses q: its corners see fractions of the sender that differ by
  // more than a quarter (see RefineSettings::shadow_levels).
  bool shadow_crosses(ElementId q) const;
  // A point-like luminaire's shadow edge across q is drawn finely enough: q's longest
  // edge is below kShadowResolution of its distance from the luminaire (the outline is
  // then placed to within that angle as seen from the light: 4 cm on a floor 2 m below
  // a lamp). Refining further would cut a hard edge that never becomes smooth into
  // ever smaller pieces along the whole outline of every chair leg and frame. (A
  // hundredth: the office building's 36 luminaire shots made 4.09 M elements, 2.5 GB; a
  // fiftieth: 3.42 M, 2.2 GB, the luminaire tests' closed forms unchanged.)
  bool shadow_resolved(ElementId q) const;
  struct Receiver {
    VertexHandle vertex;
    std::uint32_t patch;  // of the first element that has it (its facing is the receiver's)
    Vec3d point;          // where it is evaluated
  };
  VertexPlaneMap<std::uint32_t> receiver_id_;                // (vertex, facing) -> receiver
  std::vector<Receiver> receivers_;
  GrowArray<std::array<std::uint32_t, 3>> corner_receiver_;  // per element corner
  GrowArray<CornerFormFactor> form_factor_;                  // per receiver, this shot's...
  GrowArray<std::uint64_t> form_factor_shot_;  // ...when this is 2 (iterations + 1) + 1 (see solver.cpp)
  const CornerFormFactor& corner_form_factor(ElementId e, int corner) const {
    return form_factor_[corner_receiver_[e][corner]];
  }
  std::vector<Luminaire> luminaires_;
  std::vector<double> luminaire_flux_;             // lm, Luminaire::flux()
  std::vector<double> luminaire_lost_, luminaire_escaped_;  // as Patch::lost and escaped (-1: not yet)
  std::size_t next_luminaire_ = 0;                 // the luminaires before it have shot
  Rgb luminaire_unshot_;                           // colour x flux of those that have not
  double emitted_total_ = 0;
  std::uint32_t brightest_ = 0;  // see survey_patches()

  // Survey: what survey_patches() sums over the senders (groups of patches, then face
  // clusters; a sender's "unit" is its index in that order), kept in a segment tree
  // whose leaves are the units. A shot changes the sender and the receivers it lit, so
  // only their leaves and those leaves' ancestors are summed again: a pass over every
  // sender after every shot was a fifth of the 4-storey office building's solve, and
  // grew with the building. Each node joins its two children in one order, so the sums
  // are the same for any number of threads; ties go to the lower unit.
  struct Survey {
    Rgb unshot, staying;  // power (x area), and the part of it that will not leave
    double magnitude = 0;
    double best_power = -1;  // what the brightest is chosen by (SolveOptions::whole_patch_senders)
    std::uint32_t best = 0;  // the sender id of the unit with the largest best_power
  };
  static Survey join(Survey left, const Survey& right);
  Survey survey_unit(std::size_t unit, bool open) const;
  std::uint32_t unit_of_sender(std::uint32_t id) const;  // a patch (its group) or a cluster
  std::uint32_t unit_of_receiver(std::uint32_t patch) const;  // its group, or its cluster
  void mark_surveyed(std::uint32_t unit);  // changed: summed again at the next survey
  std::vector<Survey> survey_tree_;        // node 1 the root; leaves from survey_leaves_
  std::size_t survey_leaves_ = 0;
  std::vector<std::uint32_t> survey_dirty_;
  std::vector<char> survey_marked_;
  bool survey_built_ = false, survey_open_ = false;
  double total_area_ = 0;
  Rgb reflectance_area_;  // sum over patches of reflectance x area
  double unshot_magnitude_ = 0;
  Rgb unshot_staying_;  // unshot power that will not leave the scene (see survey_patches())  // sum over patches of |unshot| x area, all channels
  std::vector<double> cull_verdict_;  // receiving_patches(): per candidate, kept for its buffer
  std::vector<std::uint32_t> candidates_;  // receiving_patches(): patches judged one by one
  std::vector<int> cluster_verdict_;       // receiving_patches(): per cluster seen
  std::vector<std::uint32_t> seen_clusters_;  // receiving_patches(): clusters the tree kept
  std::size_t memory_checked_at_ = 0;  // element count at the last look at resident memory
  double form_factor_error_sum_ = 0;
  SolveReport report_;

};

}  // namespace dynrad::rad
