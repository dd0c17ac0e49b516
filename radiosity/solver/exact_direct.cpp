// Direct light where it is seen (RefineSettings::exact_direct).
//
// A luminaire's light on the surfaces is known in closed form at any point (its
// intensity towards the point, the cosine, the distance, a shadow ray), and the sun's
// likewise (daylight.h). Refining the element hierarchy until linear interpolation
// between corners draws each pool of light and each shadow made every luminaire refine
// the whole room under it, and every later shot, error estimate and output pass carried
// those elements. So the direct senders (luminaires and the sun; the sky, which is
// soft, stays a sender of the hierarchy) shoot into the walk only to the patches
// (shoot.cpp): a patch books the power it receives, its first bounce, into its unshot
// light, keeps its mean as Patch::direct and notes who lit it. The element values then
// hold the light between surfaces alone.
//
// The direct light itself is evaluated exactly at the receivers (a vertex and a facing,
// at the receiver's point): from the luminaires that lit the patches around the vertex,
// so that no pass loops over every luminaire of a building for every vertex. Once the
// shots are done (refine_for_display), the mesh is refined for display where that light
// bends between corners more than the luminaires' push-down error allows, or a shadow's
// edge crosses an element, to the luminaires' levels: the pools and shadows are drawn
// in the written mesh, but only once, at the end. What linear interpolation still
// misses at each leaf is kept as its display gap, the mesh error's part for direct
// light.
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/parallel.h"
#include "radiosity/transfer/random.h"

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

namespace {

// A shadow's edge crosses an element when its corners see fractions of the direct light
// that differ by more than this (as Solver::shadow_crosses for a shot).
constexpr double kShadowCrossing = 0.25;
// An element is small enough for a point source's shadow when its longest edge is below
// this share of its distance from the source (as Solver::shadow_resolved).
constexpr double kShadowResolution = 0.02;
// Where an evaluation point sits: this share of the way from an edge's midpoint towards
// the element's centroid (as receivers sit inside their element).
constexpr double kInside = 1e-2;
// The display gap's weight in the mesh error: the mean error of a linear interpolation
// over an element is about two thirds of its error at an edge's midpoint (a parabola's).
constexpr double kGapWeight = 2.0 / 3;

}  // namespace

double Solver::direct_reach(ElementId q) const {
  // The mean over kReachSide^2 points, one in the middle of each stratum of the patch,
  // with rays: a table's shadow inside a patch whose corners are lit takes its share
  // off, and the pool under a lamp is summed where it bends, not from the corners.
  const Element& el = hierarchy_.element(q);
  const std::array<Vec3d, 3> c{hierarchy_.position(el.corners[0]), hierarchy_.position(el.corners[1]),
                               hierarchy_.position(el.corners[2])};
  const Vec3d& n = hierarchy_.normal(q);
  double sum = 0;
  for (int i = 0; i < kReachSide; ++i)
    for (int j = 0; j < kReachSide; ++j) {
      const Vec3d x = point_on_triangle(c, (i + 0.5) / kReachSide, (j + 0.5) / kReachSide);
      const std::uint64_t key = (std::uint64_t{5} << 33) + kReachSide * kReachSide * std::uint64_t{q} + i * kReachSide + j;
      sum += luminaire_illuminance(x, n, sender_, mix(options_.seed ^ mix(key)), true, nullptr);
    }
  return el.area * sum / (kReachSide * kReachSide);
}

void Solver::note_direct(std::uint32_t patch, const Rgb& radiosity) {
  patches_[patch].direct += radiosity;
  lit_by_.emplace_back(patch, sender_ - static_cast<std::uint32_t>(patches_.size()));
}

void Solver::build_direct_lists() {
  if (direct_lists_built_) return;
  direct_lists_built_ = true;
  std::sort(lit_by_.begin(), lit_by_.end());
  lit_by_.erase(std::unique(lit_by_.begin(), lit_by_.end()), lit_by_.end());
  lit_first_.assign(patches_.size() + 1, 0);
  for (const auto& [patch, luminaire] : lit_by_) ++lit_first_[patch + 1];
  for (std::size_t p = 0; p < patches_.size(); ++p) lit_first_[p + 1] += lit_first_[p];
  lit_luminaires_.resize(lit_by_.size());
  for (std::size_t k = 0; k < lit_by_.size(); ++k) lit_luminaires_[k] = lit_by_[k].second;
  lit_by_.clear();
  lit_by_.shrink_to_fit();
}

bool Solver::directly_lit(std::uint32_t patch) const {
  return direct_lists_built_ && lit_first_[patch + 1] > lit_first_[patch];
}

void Solver::receiver_luminaires(std::uint32_t r, std::vector<std::uint32_t>& out) const {
  out.clear();
  const Receiver& receiver = receivers_[r];
  const std::uint32_t plane = patches_[receiver.patch].plane;
  const TriMesh& mesh = scene_.mesh();
  for (const FaceHandle f : mesh.vf_range(receiver.vertex)) {
    const std::uint32_t p = hierarchy_.element(hierarchy_.element_of(f)).patch;
    if (patches_[p].plane != plane) continue;
    out.insert(out.end(), lit_luminaires_.begin() + lit_first_[p], lit_luminaires_.begin() + lit_first_[p + 1]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

Solver::DirectAt Solver::direct_at(const Vec3d& x, const Vec3d& n, const std::vector<std::uint32_t>& lights,
                                   std::uint64_t key) const {
  Rgb seen;
  double seen_luminance = 0, open_luminance = 0;
  for (const std::uint32_t k : lights) {
    const std::uint32_t id = static_cast<std::uint32_t>(patches_.size()) + k;
    double open = 0;
    const double e = luminaire_illuminance(x, n, id, mix(options_.seed ^ mix(key ^ 0xd1ec7ULL) ^ mix(k + 1)), true, &open);
    seen += luminaires_[k].colour * e;
    seen_luminance += luminaires_[k].colour.luminance() * e;
    open_luminance += luminaires_[k].colour.luminance() * open;
  }
  DirectAt out;
  out.r = static_cast<float>(seen.r);
  out.g = static_cast<float>(seen.g);
  out.b = static_cast<float>(seen.b);
  out.seen = open_luminance > 0 ? static_cast<float>(seen_luminance / open_luminance) : 1.0f;
  return out;
}

void Solver::compute_receiver_direct(std::vector<std::uint32_t> wanted) {
  if (receiver_direct_.size() < receivers_.size()) receiver_direct_.resize(receivers_.size());
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  wanted.erase(std::remove_if(wanted.begin(), wanted.end(), [&](std::uint32_t r) { return receiver_direct_[r].seen >= 0; }),
               wanted.end());
  PassProgress progress(options_, "direct light at the vertices", wanted.size());
  parallel_for_index(wanted.size(), 64, [&](std::size_t i) {
    progress.add(1);
    thread_local std::vector<std::uint32_t> lights;
    const std::uint32_t r = wanted[i];
    receiver_luminaires(r, lights);
    const Receiver& receiver = receivers_[r];
    receiver_direct_[r] = lights.empty() ? DirectAt{0, 0, 0, 1}
                                         : direct_at(receiver.point, patches_[receiver.patch].normal, lights, r);
  });
}

Rgb Solver::receiver_direct(std::uint32_t r) const {
  if (r >= receiver_direct_.size() || receiver_direct_[r].seen < 0) return Rgb();
  const DirectAt& d = receiver_direct_[r];
  return Rgb(d.r, d.g, d.b);
}

Solver::DisplayError Solver::direct_display_error(ElementId e) const {
  thread_local std::vector<std::uint32_t> lights;
  const Element& el = hierarchy_.element(e);
  const Patch& patch = patches_[el.patch];
  lights.assign(lit_luminaires_.begin() + lit_first_[el.patch], lit_luminaires_.begin() + lit_first_[el.patch + 1]);
  const auto& c = corner_receiver_[e];
  double corner[3], seen[3], corners = 0, seen_mean = 0;
  Vec3d at[3];
  for (int k = 0; k < 3; ++k) {
    corner[k] = (patch.reflectance * receiver_direct(c[k])).luminance();
    seen[k] = receiver_direct_[c[k]].seen;
    corners += corner[k] / 3;
    seen_mean += seen[k] / 3;
    at[k] = hierarchy_.position(el.corners[k]);
  }
  DisplayError out;
  out.shadow = std::max({seen[0], seen[1], seen[2]}) - std::min({seen[0], seen[1], seen[2]}) > kShadowCrossing;
  // A point source's shadow is drawn to kShadowResolution of its distance: a hard edge
  // never becomes smooth, however fine the elements.
  double longest = 0, nearest = 1e300;
  for (int k = 0; k < 3; ++k) longest = std::max(longest, (at[k] - at[(k + 1) % 3]).sqrnorm());
  const Vec3d centroid = (at[0] + at[1] + at[2]) / 3.0;
  for (const std::uint32_t k : lights)
    if (!luminaires_[k].directional()) nearest = std::min(nearest, (centroid - luminaires_[k].position).norm());
  out.resolved = nearest < 1e300 && std::sqrt(longest) < kShadowResolution * nearest;
  const Vec3d& n = patch.normal;
  // The light without occluders (closed forms, no rays) at a point, reflected.
  auto open = [&](const Vec3d& x) {
    Rgb sum;
    for (const std::uint32_t k : lights) {
      double unoccluded = 0;
      luminaire_illuminance(x, n, static_cast<std::uint32_t>(patches_.size()) + k, 0, false, &unoccluded);
      sum += luminaires_[k].colour * unoccluded;
    }
    return (patch.reflectance * sum).luminance();
  };
  // The push-down oracle's measure (estimate_pushdown_error), for this light: at each
  // edge's midpoint the closed form times the ends' mean visible share against the ends'
  // mean, plus half the ends' difference where a shadow's edge may cross between them;
  // at the centroid likewise. No rays: a shadow is found by the corners' shares.
  const double at_centroid = open(centroid) * seen_mean;
  out.peak = std::max({corner[0], corner[1], corner[2], at_centroid});
  out.error = std::abs(at_centroid - corners);
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    Vec3d mid = (at[k] + at[l]) * 0.5;
    mid += (centroid - mid) * kInside;
    const double at_mid = open(mid) * 0.5 * (seen[k] + seen[l]);
    out.peak = std::max(out.peak, at_mid);
    double error = std::abs(at_mid - 0.5 * (corner[k] + corner[l]));
    if (!out.resolved && std::abs(seen[k] - seen[l]) > 1e-6) error += 0.5 * std::abs(corner[k] - corner[l]);
    out.error = std::max(out.error, error);
  }
  // The estimate's part (the display gap): a shadow inside the element that its corners
  // do not see, found by rays at the centroid (as direct_gap.cpp does for emitting patches).
  const DirectAt here = direct_at(centroid, n, lights, (std::uint64_t{1} << 34) + std::uint64_t{e});
  out.gap = std::max(out.error, std::abs((patch.reflectance * Rgb(here.r, here.g, here.b)).luminance() - corners));
  return out;
}

void Solver::refine_for_display() {
  if (!refine_.exact_direct) return;
  build_direct_lists();
  if (lit_luminaires_.empty()) return;
  flush_all();
  // Every push-down has reached the leaves, and nothing shoots from here on: the
  // display's elements need no push-down of their own (144 bytes each; on an office
  // storey 4.4 million elements, 600 MB). A later run() makes it again (all zero).
  pending_ = {};
  display_gap_.assign(hierarchy_.element_count(), 0.0f);
  const Rgb ambient_now = options_.ambient_display ? ambient() : Rgb();
  // As a luminaire's shot refined (RefineSettings::luminaire_levels, luminaire_pushdown,
  // shadow_levels; detail_luminaire_levels and the patches' error on detail).
  const double tolerance = refine_.dynamic.pushdown * refine_.luminaire_pushdown;
  const bool refines = refine_.method == Method::dynamic;
  const int levels = refine_.max_level + refine_.luminaire_levels;
  const int detail_levels = refine_.max_level + std::min(refine_.luminaire_levels, refine_.detail_luminaire_levels);
  // The leaves of lit patches, then each round's new leaves.
  std::vector<ElementId> todo;
  for (ElementId e = 0; e < hierarchy_.element_count(); ++e) {
    const Element& el = hierarchy_.element(e);
    if (el.is_leaf() && directly_lit(el.patch)) todo.push_back(e);
  }
  auto look_at = [&](const std::vector<ElementId>& leaves) {
    std::vector<std::uint32_t> wanted;
    wanted.reserve(3 * leaves.size());
    for (const ElementId e : leaves)
      for (const std::uint32_t r : corner_receiver_[e]) wanted.push_back(r);
    compute_receiver_direct(std::move(wanted));
    display_gap_.resize(hierarchy_.element_count(), 0.0f);
  };
  std::vector<char> split;
  refining_for_display_ = true;
  struct Reset {
    bool& flag;
    ~Reset() { flag = false; }
  } reset{refining_for_display_};
  if (refines && options_.outline_patch_size > 0) {
    draw_outlines();
    todo.clear();
    for (ElementId e = 0; e < hierarchy_.element_count(); ++e) {
      const Element& el = hierarchy_.element(e);
      if (el.is_leaf() && directly_lit(el.patch)) todo.push_back(e);
    }
  }
  PassProgress progress(options_, "refining the mesh for direct light (elements looked at)", todo.size());
  while (!todo.empty()) {
    look_at(todo);
    split.assign(todo.size(), 0);
    parallel_for_index(todo.size(), 64, [&](std::size_t i) {
      progress.add(1);
      const ElementId e = todo[i];
      const Element& el = hierarchy_.element(e);
      const Patch& patch = patches_[el.patch];
      const DisplayError d = direct_display_error(e);
      display_gap_[e] = static_cast<float>(d.gap);
      if (!refines || patch.clustered || el.in_strip || (d.shadow && d.resolved)) return;
      // As the push-down oracle measures a shot (oracle.h): against the direct light's
      // own peak at the element, or the floor's share of all the light it shows.
      double bright = 0;
      const Rgb extra = patch.reflectance * ambient_now;
      for (int k = 0; k < 3; ++k)
        bright = std::max(bright, (value_[e][k] + extra + patch.reflectance * receiver_direct(corner_receiver_[e][k]))
                                      .luminance());
      const double scale = std::max(d.peak, refine_.dynamic.pushdown_floor * bright);
      const bool deeper = d.shadow && !patch.detail;
      const int generations = 2 * ((patch.detail ? detail_levels : levels) + (deeper ? refine_.shadow_levels : 0));
      const bool can_split = el.generation < generations && el.area >= std::ldexp(patch_area_, 1 - generations);
      split[i] = can_split && d.error > (patch.detail ? refine_.dynamic.pushdown : tolerance) * scale;
    });
    const std::size_t first = hierarchy_.element_count();
    bool stopped = false;
    for (std::size_t i = 0; i < todo.size() && !stopped; ++i) {
      if (!split[i]) continue;
      stopped = !refinement_allowed() || progress.stop();
      if (!stopped) hierarchy_.refine(todo[i]);
    }
    initialise_new_elements();
    todo.clear();
    for (ElementId e = static_cast<ElementId>(first); e < hierarchy_.element_count(); ++e)
      if (hierarchy_.element(e).is_leaf() && directly_lit(hierarchy_.element(e).patch)) todo.push_back(e);
    if (stopped) break;
    progress.grow(todo.size());
  }
  // Leaves a stop left not yet looked at: their gap.
  if (!todo.empty()) {
    look_at(todo);
    parallel_for_index(todo.size(), 64,
                       [&](std::size_t i) { display_gap_[todo[i]] = static_cast<float>(direct_display_error(todo[i]).gap); });
  }
}

void Solver::draw_outlines() {
  // Per luminaire, the edges of the leaves of the patches it lit (sorted, once each).
  std::vector<std::vector<OpenMesh::EdgeHandle>> edges(luminaires_.size());
  const TriMesh& mesh = scene_.mesh();
  std::vector<ElementId> leaves;
  for (std::uint32_t p = 0; p < patches_.size(); ++p) {
    if (!directly_lit(p)) continue;
    leaves.clear();
    hierarchy_.leaves(hierarchy_.patch_root(p), leaves);
    for (std::uint32_t n = lit_first_[p]; n < lit_first_[p + 1]; ++n)
      for (const ElementId e : leaves)
        for (const auto edge : mesh.fe_range(hierarchy_.element(e).face)) edges[lit_luminaires_[n]].push_back(edge);
  }
  for (auto& list : edges) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  ShadowOutlineOptions o = shadow_outline_options(options_.outline_patch_size);
  o.split = [this](OpenMesh::EdgeHandle e, const Vec3d& x) { return hierarchy_.split_at(e, x); };
  o.candidate_edges = &edges;
  outline_report_ = insert_shadow_outlines(scene_, luminaires_, o);
  initialise_new_elements();
}

double Solver::display_gap(ElementId e) const {
  return e < display_gap_.size() ? kGapWeight * display_gap_[e] : 0.0;
}

double Solver::direct_luminance_at_node(const Patch& patch, std::uint32_t p, const Vec3d& node, int k) const {
  if (!directly_lit(p)) return 0.0;
  thread_local std::vector<std::uint32_t> lights;
  lights.assign(lit_luminaires_.begin() + lit_first_[p], lit_luminaires_.begin() + lit_first_[p + 1]);
  const Vec3d x = node + (patch.centre - node) * kInside;
  const DirectAt d = direct_at(x, patch.normal, lights, (std::uint64_t{3} << 33) + 16 * std::uint64_t{p} + k);
  return (patch.reflectance * Rgb(d.r, d.g, d.b)).luminance();
}

}  // namespace dynrad::rad
