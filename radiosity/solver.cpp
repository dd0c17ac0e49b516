// State and helpers of the solver; the loop itself is in shoot.cpp.
#include "radiosity/solver.h"

#include "radiosity/daylight.h"

#include "radiosity/form_factor.h"
#include "radiosity/parallel.h"
#include "radiosity/random.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <unistd.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <thread>
#include <unordered_map>

namespace dynrad::rad {

namespace {


double sum(const Rgb& c) { return c.r + c.g + c.b; }
double magnitude(const Rgb& c) { return std::abs(c.r) + std::abs(c.g) + std::abs(c.b); }

}  // namespace

Method parse_method(const std::string& name) {
  if (name == "progressive") return Method::progressive;
  if (name == "adaptive") return Method::adaptive;
  if (name == "dynamic") return Method::dynamic;
  throw std::invalid_argument("'" + name + "' is not a method; available: progressive, adaptive, dynamic");
}

const char* method_name(Method method) {
  switch (method) {
    case Method::progressive: return "progressive";
    case Method::adaptive: return "adaptive";
    case Method::dynamic: return "dynamic";
  }
  return "?";
}

Solver::Solver(SceneMesh& scene, ElementHierarchy& hierarchy, SolveOptions options, RefineSettings refine,
               std::vector<Luminaire> luminaires)
    : scene_(scene),
      hierarchy_(hierarchy),
      options_(std::move(options)),
      refine_(refine),
      luminaires_(std::move(luminaires)) {
  shot_max_rays_ = options_.max_rays;
  visibility_ = std::make_unique<Visibility>(scene_);
  patches_.resize(hierarchy_.patch_count());
  std::vector<ElementId> leaves;
  for (std::uint32_t p = 0; p < patches_.size(); ++p) {
    const ElementId root = hierarchy_.patch_root(p);
    const Element& el = hierarchy_.element(root);
    Patch& patch = patches_[p];
    for (int k = 0; k < 3; ++k) patch.corners[k] = hierarchy_.position(el.corners[k]);
    patch.normal = hierarchy_.normal(root);
    patch.area = el.area;
    patch.centre = (patch.corners[0] + patch.corners[1] + patch.corners[2]) / 3.0;
    for (const Vec3d& c : patch.corners) patch.radius = std::max(patch.radius, (c - patch.centre).norm());
    leaves.clear();
    hierarchy_.leaves(root, leaves);
    const Material& m = scene_.material(hierarchy_.element(leaves.front()).face);
    patch.reflectance = Rgb(std::max(m.reflectance.r, options_.min_reflectance),
                            std::max(m.reflectance.g, options_.min_reflectance),
                            std::max(m.reflectance.b, options_.min_reflectance));
    patch.emission = m.emission * options_.emission_scale;
    patch.unshot = patch.emission;
    report_.energy.emitted += patch.emission * patch.area;
    total_area_ += patch.area;
    reflectance_area_ += patch.reflectance * patch.area;
  }
  for (Luminaire& l : luminaires_)
    if (l.directional()) l.daylight_flux = daylight_flux(l);
  for (const Luminaire& l : luminaires_) {
    const double flux = l.flux();
    if (!(flux >= 0) || !std::isfinite(flux)) throw std::invalid_argument("luminaire " + l.name + " has no valid flux");
    luminaire_flux_.push_back(flux);
    luminaire_unshot_ += l.colour * flux;
  }
  luminaire_lost_.assign(luminaires_.size(), -1.0);
  luminaire_escaped_.assign(luminaires_.size(), 0.0);
  report_.energy.emitted += luminaire_unshot_;
  emitted_total_ = sum(report_.energy.emitted);
  unshot_magnitude_ = emitted_total_;
  if (!(options_.overshoot > 0 && options_.overshoot < 2))
    throw std::invalid_argument("overshoot must lie between 0 and 2 (1: none)");
  if (!(emitted_total_ > 0)) throw std::invalid_argument("nothing emits light (no emitting surface, no luminaire)");
  // Facing classes: normals equal to about 1e-9.
  std::map<std::array<long long, 3>, std::uint32_t> planes;
  for (Patch& patch : patches_) {
    const std::array<long long, 3> k{std::llround(patch.normal[0] * 1e9), std::llround(patch.normal[1] * 1e9),
                                     std::llround(patch.normal[2] * 1e9)};
    patch.plane = planes.emplace(k, static_cast<std::uint32_t>(planes.size())).first->second;
  }
  double largest = 0;
  for (const Patch& patch : patches_) largest = std::max(largest, patch.area);
  patch_area_ = std::min(refine_.patch_area, largest);
  build_clusters();
  build_groups();
  if (refine_.method == Method::dynamic && refine_.patch_area > 0) {
    const std::vector<double> facet = facet_areas(hierarchy_);
    for (std::uint32_t p = 0; p < patches_.size(); ++p)
      patches_[p].detail = facet[p] < kDetailFacet * patch_area_;
  }
  build_tree();
  indexed_.assign(patches_.size(), 0);
  survey_patches();
  // Every existing element starts at its patch's emission.
  value_.resize(hierarchy_.element_count());
  for (ElementId e = 0; e < hierarchy_.element_count(); ++e) {
    const Rgb emission = patches_[hierarchy_.element(e).patch].emission;
    value_[e] = {emission, emission, emission};
  }
  initialised_ = hierarchy_.element_count();
  register_receivers(0);
  pending_.resize(initialised_);
  gathered_in_.assign(initialised_, 0);
  report_.method = method_name(refine_.method);
  report_.patches = patches_.size();
  report_.luminaires = luminaires_.size();
}

Solver::~Solver() = default;

Solver::Survey Solver::join(Survey left, const Survey& right) {
  left.unshot += right.unshot;
  left.staying += right.staying;
  left.magnitude += right.magnitude;
  if (right.best_power > left.best_power) {
    left.best = right.best;
    left.best_power = right.best_power;
  }
  return left;
}

std::uint32_t Solver::unit_of_sender(std::uint32_t id) const {
  return is_cluster(id) ? static_cast<std::uint32_t>(groups_.groups.size()) + cluster_index(id) : groups_.group_of[id];
}

std::uint32_t Solver::unit_of_receiver(std::uint32_t patch) const {
  const std::uint32_t part = clusters_.part_of_patch.empty() ? FaceClusters::kNone : clusters_.part_of_patch[patch];
  return part != FaceClusters::kNone ? static_cast<std::uint32_t>(groups_.groups.size()) + clusters_.parts[part].cluster
                                     : groups_.group_of[patch];
}

void Solver::mark_surveyed(std::uint32_t unit) {
  if (unit >= survey_marked_.size() || survey_marked_[unit]) return;
  survey_marked_[unit] = 1;
  survey_dirty_.push_back(unit);
}

Solver::Survey Solver::survey_unit(std::size_t n, bool open) const {
  Survey s;
  Rgb power;
  double lost = -1;
  const std::size_t standalone = groups_.groups.size();
  if (n < standalone) {
    const PlaneGroups::Group& g = groups_.groups[n];
    s.best = groups_.members[g.first];
    double area = 0;
    for (std::uint32_t m = g.first; m < g.first + g.count; ++m) {
      const Patch& patch = patches_[groups_.members[m]];
      power += patch.unshot * patch.area;
      s.magnitude += magnitude(patch.unshot) * patch.area;
      area += patch.area;
    }
    const Patch& leader = patches_[s.best];
    lost = leader.lost >= 0 ? leader.lost : leader.rough_lost;
    // (SolveOptions::whole_patch_senders: a small sender is chosen as a whole patch, or
    // as twice its size if that is less)
    s.best_power = s.magnitude;
    if (options_.whole_patch_senders && !leader.detail && area > 0 && area < patch_area_)
      s.best_power *= std::min(patch_area_ / area, 2.0);
  } else {
    const std::uint32_t c = static_cast<std::uint32_t>(n - standalone);
    const auto& cl = clusters_.clusters[c];
    for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) {
      power += part_unshot_[k];
      s.magnitude += magnitude(part_unshot_[k]);
    }
    s.best = cluster_sender(c);
    lost = cluster_state_[c].lost >= 0 ? cluster_state_[c].lost : cluster_state_[c].rough_lost;
    s.best_power = s.magnitude;
  }
  s.unshot = power;
  s.staying = power * (open && lost >= 0 ? 1 - lost : 1.0);
  return s;
}

void Solver::survey_patches() {
  const bool open = sum(report_.energy.escaped) > 0;
  const std::size_t standalone = groups_.groups.size();
  const std::size_t count = standalone + clusters_.clusters.size();
  if (!survey_built_ || open != survey_open_) {
    // Every unit: the first survey, and when light first leaves (each unit's staying
    // share changes).
    survey_leaves_ = 1;
    while (survey_leaves_ < count) survey_leaves_ *= 2;
    survey_tree_.assign(2 * survey_leaves_, Survey{});
    survey_marked_.assign(count, 1);
    survey_dirty_.resize(count);
    for (std::size_t n = 0; n < count; ++n) survey_dirty_[n] = static_cast<std::uint32_t>(n);
    survey_built_ = true;
  }
  survey_open_ = open;
  std::sort(survey_dirty_.begin(), survey_dirty_.end());
  // An open scene (some light has left it): the senders holding unshot light need an
  // idea of what share of it will leave too, so that ambient() does not count light
  // that is on its way out. A rough one does (rough_lost_fraction(), 64 rays): the
  // ambient term is a sum over thousands of senders, and a sender's exact share
  // (lost_fraction(), 1,024 rays) is measured when it shoots. Measuring it exactly for
  // every sender that merely received light cost the IFC house 15% of its solve. A
  // sender gets light only in a shot that marks it, so the marked ones are all to ask.
  if (open) {
    std::vector<std::uint32_t> unknown;
    for (std::uint32_t n : survey_dirty_) {
      if (n < standalone) {
        const PlaneGroups::Group& g = groups_.groups[n];
        const std::uint32_t leader = groups_.members[g.first];
        if (patches_[leader].lost >= 0 || patches_[leader].rough_lost >= 0) continue;
        bool holds = false;
        for (std::uint32_t m = g.first; m < g.first + g.count && !holds; ++m)
          holds = !patches_[groups_.members[m]].unshot.is_zero();
        if (holds) unknown.push_back(leader);
      } else {
        const std::uint32_t c = static_cast<std::uint32_t>(n - standalone);
        if (cluster_state_[c].lost >= 0 || cluster_state_[c].rough_lost >= 0) continue;
        const auto& cl = clusters_.clusters[c];
        bool holds = false;
        for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count && !holds; ++k)
          holds = !part_unshot_[k].is_zero();
        if (holds) unknown.push_back(cluster_sender(c));
      }
    }
    tbb::parallel_for(std::size_t(0), unknown.size(), [&](std::size_t n) { rough_lost_fraction(unknown[n]); });
  }
  // The marked leaves, then their ancestors level by level (each parent once).
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, survey_dirty_.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k < range.end(); ++k) {
                        const std::uint32_t n = survey_dirty_[k];
                        survey_tree_[survey_leaves_ + n] = survey_unit(n, open);
                        survey_marked_[n] = 0;
                      }
                    });
  std::vector<std::size_t> level(survey_dirty_.size());
  for (std::size_t k = 0; k < survey_dirty_.size(); ++k) level[k] = survey_leaves_ + survey_dirty_[k];
  survey_dirty_.clear();
  while (!level.empty() && level.front() > 1) {
    std::size_t kept = 0;
    for (std::size_t node : level)
      if (kept == 0 || level[kept - 1] != node / 2) level[kept++] = node / 2;
    level.resize(kept);
    for (std::size_t node : level) survey_tree_[node] = join(survey_tree_[2 * node], survey_tree_[2 * node + 1]);
  }
  const Survey& total = survey_tree_[1];
#ifndef NDEBUG
  {  // the tree against a pass over every unit
    Survey all;
    for (std::size_t n = 0; n < count; ++n) all = join(all, survey_unit(n, open));
    assert(all.best == total.best && all.best_power == total.best_power);
    assert(std::abs(all.magnitude - total.magnitude) <= 1e-9 * std::max(1.0, all.magnitude));
  }
#endif
  report_.energy.unshot = total.unshot + luminaire_unshot_;
  unshot_staying_ = total.staying + luminaire_unshot_;
  unshot_magnitude_ = total.magnitude + magnitude(luminaire_unshot_);
  brightest_ = total.best;
}

std::size_t resident_memory() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long size = 0, resident = 0;
  const int read = std::fscanf(f, "%lu %lu", &size, &resident);
  std::fclose(f);
  return read == 2 ? static_cast<std::size_t>(resident) * static_cast<std::size_t>(sysconf(_SC_PAGESIZE)) : 0;
}

std::size_t peak_resident_memory() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  std::size_t kib = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmHWM: %zu kB", &kib) == 1) break;
  std::fclose(f);
  return kib * 1024;
}

bool Solver::refinement_allowed() {
  if (!report_.refinement_stopped.empty()) return false;
  if (refine_.max_elements > 0 && hierarchy_.element_count() >= refine_.max_elements) {
    report_.refinement_stopped = "max elements";
  } else if (refine_.memory_budget > 0 && hierarchy_.element_count() >= memory_checked_at_ + 4096) {
    memory_checked_at_ = hierarchy_.element_count();  // /proc is read every 4096 new elements
    const std::size_t resident = resident_memory();
    report_.peak_resident_memory = std::max(report_.peak_resident_memory, resident);
    if (resident >= refine_.memory_budget) report_.refinement_stopped = "memory budget";
  }
  if (report_.refinement_stopped.empty()) return true;
  report_.refinement_stopped_at = report_.iterations + 1;
  return false;
}

Rgb Solver::ambient() const {
  // Unshot power, less what the patches holding it will lose to the outside (see
  // survey_patches()); kept current by survey_patches() and shoot_once().
  const Rgb unshot = unshot_staying_;
  const double area = total_area_;
  if (!(area > 0)) return Rgb();
  const Rgb mean_reflectance = reflectance_area_ * (1.0 / area);
  // In an open scene (a floor under the sky, a facade) part of every bounce leaves.
  // The unshot power U above is what will land; of its reflection, the share e that
  // the shots so far lost to the outside is taken to leave too: U lands, rho (1 - e)
  // U lands again, and so on: the factor 1 / (1 - rho (1 - e)), which is Cohen et
  // al.'s 1 / (1 - rho) in a closed scene (e = 0).
  const double shot_so_far = sum(report_.energy.absorbed) + sum(report_.energy.escaped);
  const double escape = shot_so_far > 0 ? std::clamp(sum(report_.energy.escaped) / shot_so_far, 0.0, 1.0) : 0.0;
  const double stays = 1 - escape;
  auto factor = [stays](double rho) { return rho * stays < 1 ? 1 / (1 - rho * stays) : 0.0; };
  return Rgb(unshot.r / area * factor(mean_reflectance.r), unshot.g / area * factor(mean_reflectance.g),
             unshot.b / area * factor(mean_reflectance.b));
}

double Solver::unshot_fraction() const { return unshot_magnitude_ / emitted_total_; }

// Fraction of the power patch `id` shoots that reaches no front face (it leaves the
// scene or meets a black back side): cosine-weighted rays from points on the patch,
// stratified over the hemisphere, once per patch. Exactly 0 in a closed room.
// A first pass with a quarter of the rays settles most senders: where none of them is
// lost (a closed room), the answer is 0 and the full pass is skipped; otherwise the full
// pass alone gives it. (An opening below about 1/256 of a sender's cosine-weighted view
// can go unseen by the first pass, as one below 1/1024 can by the full one.)
double Solver::lost_fraction(std::uint32_t id) {
  if (is_luminaire(id)) {  // see survey_luminaire
    const std::size_t k = id - patches_.size();
    if (luminaire_lost_[k] < 0) {
      const int side = std::max(8, static_cast<int>(std::sqrt(4.0 * options_.escape_rays)));
      const LuminaireSurvey s = survey_luminaire(*visibility_, luminaires_[k], side, mix(options_.seed ^ mix(id)));
      luminaire_escaped_[k] = s.escaped;
      luminaire_lost_[k] = s.escaped + s.back;
    }
    return luminaire_lost_[k];
  }
  if (is_cluster(id)) return cluster_lost_fraction(cluster_index(id));
  Patch& p = patches_[id];
  if (p.lost >= 0) return p.lost;
  const auto counts = patch_escape_counts(id, options_.escape_rays);
  p.escaped = counts[0];
  p.lost = counts[1];
  return p.lost;
}

std::array<double, 2> Solver::patch_escape_counts(std::uint32_t id, int rays) const {
  const Patch& p = patches_[id];
  // The rough count draws from another stream than the exact one.
  const std::uint64_t seed = options_.seed ^ mix(0xE5CA9E000000ull + id) ^ (rays == options_.escape_rays ? 0 : 0x5106ull);
  if (is_group(id)) {
    // From points on the group's patches, each drawn in proportion to its area.
    const PlaneGroups::Group& g = group_of(id);
    return escape_counts(
        seed,
        [this, &g](std::uint64_t& state, Vec3d& origin, Vec3d& normal) {
          double target = uniform(state) * g.area, running = 0;
          std::uint32_t n = g.first;
          for (; n + 1 < g.first + g.count; ++n) {
            running += patches_[groups_.members[n]].area;
            if (running > target) break;
          }
          const Patch& member = patches_[groups_.members[n]];
          const double u = uniform(state), v = uniform(state);
          origin = point_on_triangle(member.corners, u, v);
          normal = member.normal;
        },
        rays);
  }
  return escape_counts(
      seed,
      [&p](std::uint64_t& state, Vec3d& origin, Vec3d& normal) {
        const double u = uniform(state), v = uniform(state);
        origin = point_on_triangle(p.corners, u, v);
        normal = p.normal;
      },
      rays);
}

void Solver::rough_lost_fraction(std::uint32_t id) {
  if (is_cluster(id)) {
    ClusterState& state = cluster_state_[cluster_index(id)];
    state.rough_lost = cluster_escape_counts(cluster_index(id), kRoughEscapeRays)[1];
  } else {
    patches_[id].rough_lost = patch_escape_counts(id, kRoughEscapeRays)[1];
  }
}

std::array<double, 2> Solver::escape_counts(std::uint64_t seed, const EscapeOrigin& origin, int rays) const {
  // side x side strata; one row per task, each row with its own seed: the counts are
  // the same for any number of threads.
  auto cast = [&](int side, std::uint64_t pass) {
    std::vector<std::array<int, 2>> rows(static_cast<std::size_t>(side));
    tbb::parallel_for(0, side, [&](int i) {
      Rng rng{mix(seed ^ mix(static_cast<std::uint64_t>(i) + 1) ^ pass)};
      int escaped = 0, back = 0;
      for (int j = 0; j < side; ++j) {
        const double u1 = (i + rng.uniform()) / side, u2 = (j + rng.uniform()) / side;
        Vec3d from, n;
        origin(rng.state, from, n);
        const Vec3d t = OpenMesh::cross(std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0), n).normalized();
        const Vec3d b = OpenMesh::cross(n, t);
        const double r = std::sqrt(u1), phi = 2 * M_PI * u2;
        const Vec3d dir = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - u1));
        const auto hit = visibility_->trace(from, n, dir);
        escaped += hit == Visibility::Hit::nothing;
        back += hit == Visibility::Hit::back;
      }
      rows[static_cast<std::size_t>(i)] = {escaped, back};
    });
    std::array<int, 2> sum{0, 0};
    for (const auto& row : rows) {
      sum[0] += row[0];
      sum[1] += row[1];
    }
    return sum;
  };
  const int side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(rays))));
  if (side >= 4 && rays == options_.escape_rays) {
    const auto [escaped, back] = cast(side / 2, 0x9A55ull << 40);
    if (escaped + back == 0) return {0.0, 0.0};
  }
  const auto [escaped, back] = cast(side, 0);
  const double total = static_cast<double>(side) * side;
  return {escaped / total, (escaped + back) / total};
}

void Solver::compute_form_factors(const std::vector<ElementId>& elements) {
  parallel_for_index(elements.size(), 8, [&](std::size_t n) { compute_corner_form_factors(elements[n]); });
}

// A receiver is shared by the elements around its vertex, and elements are handled in
// parallel. Its stamp says, for this shot s, claimed (2s) or done (2s + 1): the first
// task to claim it computes it, and a task that finds it claimed by another waits for
// it (the other task is computing it and waits for nothing, so this always ends). The
// value does not depend on which task computes it. The stamps use GCC and Clang atomic
// built-ins: std::atomic_ref needs C++20.
void Solver::compute_corner_form_factors(ElementId e) {
  const std::uint64_t claimed = 2 * (report_.iterations + 1), done = claimed + 1;
  bool wait = false;
  for (std::uint32_t id : corner_receiver_[e]) {
    std::uint64_t* stamp = &form_factor_shot_[id];
    std::uint64_t seen = __atomic_load_n(stamp, __ATOMIC_ACQUIRE);
    if (seen >= claimed) {
      wait = wait || seen != done;
      continue;
    }
    if (!__atomic_compare_exchange_n(stamp, &seen, claimed, false, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
      wait = wait || seen != done;  // another task claimed it just now
      continue;
    }
    const Receiver& r = receivers_[id];
    CornerFormFactor& f = form_factor_[id];
    f.visible = point_form_factor(r.vertex, r.point, patches_[r.patch].normal, sender_, &f.unoccluded, {false, &f.verdict});
    __atomic_store_n(stamp, done, __ATOMIC_RELEASE);
    beat();
  }
  if (!wait) return;
  for (std::uint32_t id : corner_receiver_[e])
    while (__atomic_load_n(&form_factor_shot_[id], __ATOMIC_ACQUIRE) != done) std::this_thread::yield();
}

void Solver::settle_visibility(const std::vector<ElementId>& elements) {
  // Marked receivers are listed per chunk of elements and joined in order, so that the
  // list (sorted, without repeats) is the same for any number of threads.
  const std::size_t chunk = std::max<std::size_t>(64, (elements.size() + kChunks - 1) / kChunks);
  const std::size_t chunks = (elements.size() + chunk - 1) / chunk;
  std::vector<std::vector<std::uint32_t>> marked(chunks);
  parallel_for_index(chunks, 2, [&](std::size_t c) {
    for (std::size_t n = c * chunk; n < std::min(elements.size(), (c + 1) * chunk); ++n) {
      const auto& ids = corner_receiver_[elements[n]];
      bool seen = false, hidden = false, mixed = false;
      for (std::uint32_t id : ids) {
        const RayVerdict v = form_factor_[id].verdict;
        seen = seen || v == RayVerdict::seen;
        hidden = hidden || v == RayVerdict::hidden;
        mixed = mixed || v == RayVerdict::mixed;
      }
      if (!mixed && !(seen && hidden)) continue;
      // Only where a wrong verdict would show: the sender's light there, unoccluded, is at
      // least kSettleShare of what the corner holds (on the IFC house, casting again
      // wherever corners disagreed cost a fifth of the solve; with the share, a tenth).
      const ElementId e = elements[n];
      const double light = (patches_[hierarchy_.element(e).patch].reflectance * current_shot_).luminance();
      const double share = patches_[sender_].emission.is_zero() ? kSettleShareReflected : kSettleShare;
      for (int k = 0; k < 3; ++k) {
        const CornerFormFactor& f = form_factor_[ids[k]];
        if ((f.verdict == RayVerdict::seen || f.verdict == RayVerdict::hidden) &&
            light * f.unoccluded >= share * value_[e][k].luminance())
          marked[c].push_back(ids[k]);
      }
    }
  });
  std::vector<std::uint32_t> again;
  for (const auto& m : marked) again.insert(again.end(), m.begin(), m.end());
  std::sort(again.begin(), again.end());
  again.erase(std::unique(again.begin(), again.end()), again.end());
  parallel_for_index(again.size(), 8, [&](std::size_t n) {
    const Receiver& r = receivers_[again[n]];
    CornerFormFactor& f = form_factor_[again[n]];
    f.visible = point_form_factor(r.vertex, r.point, patches_[r.patch].normal, sender_, &f.unoccluded, {true, &f.verdict});
  });
}

void Solver::beat() {
  if (!options_.on_busy) return;
  // Counted on each thread and added to the shared count 64 at a time: a shared counter
  // touched at every point cost the IFC house 2.3% of its solve (the cores fought over
  // its cache line). The count is then a multiple of 64, which is enough for a sign of
  // life.
  thread_local std::size_t local = 0;
  if (++local % 64) return;
  const std::size_t points = shot_points_.fetch_add(64, std::memory_order_relaxed) + 64;
  const auto now = std::chrono::steady_clock::now();
  const std::int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count();
  std::int64_t due = next_beat_.load(std::memory_order_relaxed);
  if (now_ns < due) return;
  // One thread takes the beat; the others see the new due time.
  if (!next_beat_.compare_exchange_strong(due, now_ns + 2'000'000'000, std::memory_order_relaxed)) return;
  options_.on_busy(points, std::chrono::duration<double>(now - shot_start_).count());
}

void Solver::register_receivers(ElementId first) {
  corner_receiver_.resize(hierarchy_.element_count());
  for (ElementId e = first; e < hierarchy_.element_count(); ++e) {
    const Element& el = hierarchy_.element(e);
    for (int k = 0; k < 3; ++k) {
      const VertexHandle v = el.corners[k];
      const auto [id, added] = receiver_id_.emplace(static_cast<std::uint32_t>(v.idx()), patches_[el.patch].plane);
      if (added) {
        *id = static_cast<std::uint32_t>(receivers_.size());
        // A step into the element: at a junction, the limit from inside the surface,
        // and no ray starting in a neighbouring wall's plane.
        const Vec3d position = hierarchy_.position(v);
        receivers_.push_back({v, el.patch, position + (hierarchy_.centroid(e) - position) * 1e-2});
      }
      corner_receiver_[e][k] = *id;
    }
  }
  form_factor_.resize(receivers_.size());
  form_factor_shot_.resize(receivers_.size(), 0);
}

// What the sky or the sun sends onto the model's surfaces (lm): per patch, its area
// times the illuminance at its centroid (the sun: the mean over the centroid and the
// three points halfway to its corners, for shadow edges), summed in patch order.
double Solver::daylight_flux(const Luminaire& l) const {
  std::vector<double> power(patches_.size(), 0.0);
  tbb::parallel_for(std::size_t(0), patches_.size(), [&](std::size_t p) {
    const Patch& patch = patches_[p];
    std::vector<Vec3d> points;
    if (l.kind != Luminaire::Kind::sun) {
      points.push_back(patch.centre);
    } else {
      // A shadow ray each: 6 x 6 stratified points. (With the centre and the points
      // halfway to the corners, a south room's sun, half its window in an overhang's
      // shadow, brought 3% less than the geometry lets in, and the solve scales every
      // shot's power to this: tests/daylight_coefficients_test.cpp.)
      const int m = 6;
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) points.push_back(point_on_triangle(patch.corners, (i + 0.5) / m, (j + 0.5) / m));
    }
    double e = 0;
    for (const Vec3d& x : points) e += daylight_illuminance(visibility_.get(), l, x, patch.normal, nullptr);
    power[p] = patch.area * e / static_cast<double>(points.size());
  });
  double total = 0;
  for (double w : power) total += w;
  return total;
}

double Solver::luminaire_illuminance(const Vec3d& x, const Vec3d& n, std::uint32_t id, std::uint64_t seed,
                                     bool rays, double* unoccluded) const {
  return rad::luminaire_illuminance(rays ? visibility_.get() : nullptr, luminaire(id), x, n, seed, unoccluded);
}

double Solver::point_form_factor(VertexHandle v, const Vec3d& x, const Vec3d& normal, std::uint32_t sender_id,
                                 double* unoccluded, const RayPlan& plan) const {
  return point_form_factor_keyed(static_cast<std::uint64_t>(v.idx()), x, normal, sender_id, unoccluded, plan);
}

// Targets behind (or on) the receiver's plane are left out: the closed form has already
// clipped that part of the sender away, and counting those targets as hidden would take
// it away twice. (A floor patch that the plane of a block's side cuts was seen as much as
// a quarter darker from points near the block's foot: the spikes of the Cornell demo,
// tests/pictures_test.cpp.)
void Solver::cast_to_patch(const Patch& sender, const Vec3d& x, const Vec3d& normal, int rays, std::uint64_t& state,
                           int& visible, int& cast) const {
  Rng rng{state};
  Vec3d targets[256];
  int side = 1, columns = 1;
  strata(rays, side, columns);
  int n = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < columns; ++j) {
      const Vec3d t = point_on_triangle(sender.corners, (i + rng.uniform()) / side, (j + rng.uniform()) / columns);
      if (OpenMesh::dot(normal, t - x) > 0) targets[n++] = t;
    }
  visible += visibility_->visible_count(x, normal, targets, n, sender.normal);
  cast += n;
  state = rng.state;
}

double Solver::point_form_factor_keyed(std::uint64_t key, const Vec3d& x, const Vec3d& normal, std::uint32_t sender_id,
                                       double* unoccluded, const RayPlan& plan) const {
  if (plan.verdict) *plan.verdict = RayVerdict::none;
  if (is_luminaire(sender_id)) {
    double open = 0;
    const double seen =
        luminaire_illuminance(x, normal, sender_id, mix(options_.seed ^ mix((key << 32) ^ sender_id)), true, &open);
    if (unoccluded) *unoccluded = open;
    return seen;
  }
  if (is_cluster(sender_id)) return cluster_form_factor(x, normal, key, true, unoccluded);
  const Patch& sender = patches_[sender_id];
  // A patch sends nothing to a point that faces the way it does (in its own plane or a
  // parallel one). The closed form is undefined at a point in the sender's plane: a
  // receiver that a coplanar neighbour shares with the sender, evaluated inside the
  // sender, took F = 1.71 from it (the Cornell demo's right wall: a vertex 8-20% above
  // its ring, tests/pictures_test.cpp).
  if (OpenMesh::dot(normal, sender.normal) > 1 - 1e-9) {
    if (unoccluded) *unoccluded = 0;
    return 0.0;
  }
  if (sender_id == sender_ && !sender_members_.empty()) return group_form_factor(key, x, normal, unoccluded, plan);
  double f = sender_id == sender_ ? sender_closed_form(x, normal)
                                  : point_to_triangle(x, normal, sender.corners[0], sender.corners[1],
                                                      sender.corners[2], sender.normal);
  if (unoccluded) *unoccluded = f;
  if (f <= 0) return 0.0;
  // Visible fraction: a few rays first; more only where those disagree.
  std::uint64_t state = mix(options_.seed ^ mix((key << 32) ^ sender_id));
  int visible = 0, cast = 0;
  cast_to_patch(sender, x, normal, options_.min_rays, state, visible, cast);
  const bool agreed = visible == 0 || visible == cast;
  if (!agreed || plan.full) cast_to_patch(sender, x, normal, shot_max_rays_, state, visible, cast);
  if (cast == 0) return f;  // the sender lies (all but) behind the plane: f is about 0 anyway
  if (plan.verdict) *plan.verdict = !agreed || plan.full ? RayVerdict::mixed : visible == 0 ? RayVerdict::hidden : RayVerdict::seen;
  return f * visible / cast;
}

void Solver::gather_new_elements(std::size_t first) {
  // Earlier shots, and the current one (the sender's unshot was moved to current_shot_).
  // Luminaires that have shot (the current one included) come first, as they shot.
  std::vector<std::uint32_t> shooters;
  for (std::size_t k = 0; k < next_luminaire_; ++k) shooters.push_back(static_cast<std::uint32_t>(patches_.size() + k));
  for (std::uint32_t j = 0; j < patches_.size(); ++j)
    if (!patches_[j].shot.is_zero() || j == sender_) shooters.push_back(j);
  auto shot_of = [this](std::uint32_t j) {
    if (is_luminaire(j)) return luminaire(j).colour;
    return j == sender_ ? patches_[j].shot + current_shot_ : patches_[j].shot;
  };
  // One gather per receiver of the new elements.
  std::unordered_map<std::uint32_t, std::size_t> index;
  std::vector<std::uint32_t> todo;
  for (ElementId e = static_cast<ElementId>(first); e < hierarchy_.element_count(); ++e)
    for (std::uint32_t r : corner_receiver_[e])
      if (index.emplace(r, todo.size()).second) todo.push_back(r);
  // Geometry only (sum of F times shot radiosity) is shared by the facing; emission
  // and reflectance are each element's own (a lamp and the ceiling around it share a
  // facing and the border vertices).
  // Each patch's shots were shaped (shape_of); what they shipped in all has the shape
  // of what its nodes shipped (Patch::shot_at_nodes), which the gather gives back: a
  // new vertex then gets the light its neighbours got, not that of even senders.
  std::vector<SenderShape> shipped(shooters.size());
  if (options_.shaped_senders)
    for (std::size_t i = 0; i < shooters.size(); ++i)
      if (!is_luminaire(shooters[i]) && !is_cluster(shooters[i]) && shooters[i] != sender_)
        shipped[i] = shipped_shape(shooters[i]);
  std::vector<Rgb> gathered(todo.size());
  tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t n) {
    const Receiver& r = receivers_[todo[n]];
    const Patch& patch = patches_[r.patch];
    Rgb sum;
    for (std::size_t i = 0; i < shooters.size(); ++i) {
      const std::uint32_t j = shooters[i];
      if (j == r.patch) continue;
      double flat = 0;
      double f = point_form_factor(r.vertex, r.point, patch.normal, j, &flat);
      if (shipped[i].on && f > 0 && flat > 0) {
        const Patch& q = patches_[j];
        f *= shaped_closed_form(r.point, patch.normal, q.corners, q.centre, q.radius, q.area, q.normal, shipped[i]) /
             flat;
      }
      sum += shot_of(j) * f;
    }
    gathered[n] = sum;
  });
  for (ElementId e = static_cast<ElementId>(first); e < hierarchy_.element_count(); ++e) {
    const Element& el = hierarchy_.element(e);
    const Patch& patch = patches_[el.patch];
    for (int k = 0; k < 3; ++k)
      value_[e][k] = patch.emission + patch.reflectance * gathered[index.at(corner_receiver_[e][k])];
    gathered_in_[e] = report_.iterations + 1;
    report_.energy_transfers += shooters.size();  // shoot(j, e) for every earlier sender j
    if (el.generation > 0) report_.patch_element_transfers += shooters.size();
  }
}

double Solver::form_factor(ElementId e, int corner) const {
  return corner_form_factor(e, corner).visible;
}

// Mean form factor over element q, for the power it receives. The three corner values
// alone misjudge elements next to the sender's edge, where F changes fastest, the
// same way at every scale; Lambert's closed form at the centroid (no rays: scaled by
// the corners' visible fractions) gives the integral a second, interior sample.
double Solver::element_form_factor(ElementId q) const {
  double corners = 0, unoccluded = 0;
  for (int k = 0; k < 3; ++k) {
    const CornerFormFactor& f = corner_form_factor(q, k);
    corners += f.visible;
    unoccluded += f.unoccluded;
  }
  const double visible = unoccluded > 0 ? std::min(1.0, corners / unoccluded) : 0.0;
  const double centre = sender_closed_form(hierarchy_.centroid(q), hierarchy_.normal(q)) * visible;
  return (1 - kCentroidWeight) * corners / 3.0 + kCentroidWeight * centre;
}

double Solver::sender_closed_form(const Vec3d& x, const Vec3d& n) const {
  if (is_luminaire(sender_)) return luminaire_illuminance(x, n, sender_, 0, false, nullptr);
  if (is_cluster(sender_)) return cluster_form_factor(x, n, 0, false, nullptr);
  const Patch& sender = patches_[sender_];
  if (OpenMesh::dot(n, sender.normal) > 1 - 1e-9) return 0.0;  // facing the same way (see point_form_factor_keyed)
  if (!sender_members_.empty()) return group_closed_form(x, n);
  return shaped_closed_form(x, n, sender.corners, sender.centre, sender.radius, sender.area, sender.normal, shape_);
}

double Solver::luminance_at(ElementId root, const Vec3d& p) const {
  double pending = 0;
  ElementId e = root;
  for (;;) {
    const Element& el = hierarchy_.element(e);
    if (el.is_leaf()) return interpolate(e, value_[e], p).luminance() + pending;
    pending += quadratic(pending_[e], barycentric(e, p)).luminance();
    // The child whose triangle holds p (on the split line either one: values agree).
    const ElementId first = el.children[0];
    const Element& c = hierarchy_.element(first);
    const Vec3d& n = hierarchy_.normal(first);
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) {
      const Vec3d a = hierarchy_.position(c.corners[k]), b = hierarchy_.position(c.corners[(k + 1) % 3]);
      inside = OpenMesh::dot(OpenMesh::cross(b - a, p - a), n) >= -1e-12 * (b - a).sqrnorm();
    }
    e = inside ? first : el.children[1];
  }
}

void Solver::shape_sender() {
  shape_.on = false;
  shape_.max_weight = 1;
  if (!options_.shaped_senders) return;
  // (m is below 0 when the sender gives back what an overshoot sent too much; the
  // shape is then that of the excess.)
  shape_ = shape_of(sender_, current_shot_.luminance() / options_.overshoot);
}

Solver::SenderShape Solver::shape_of(std::uint32_t patch, double m) {
  Patch& sender = patches_[patch];
  const ElementId root = hierarchy_.patch_root(patch);
  Vec3d node[kTriangleNodes];
  triangle_nodes(sender.corners.data(), node);
  // The unshot radiosity at the nodes (the patch's own corner values at its corners,
  // read through its element tree elsewhere): everything they gained since the sender
  // last shot (its emission, before its first shot), plus what an overshoot left
  // (below 0).
  double b[kTriangleNodes];
  for (int k = 0; k < kTriangleNodes; ++k) {
    const int corner = static_cast<int>(std::find(std::begin(kGridCorners), std::end(kGridCorners), k) -
                                        std::begin(kGridCorners));
    const double now = corner < 3 ? value_[root][corner].luminance() : luminance_at(root, node[k]);
    b[k] = now - sender.shot_at_nodes[k];
  }
  // The quarter grid's nodes that are not corners or edge midpoints each lie halfway
  // between two that are (kGridHalfway); where the unshot values there are what a line
  // between those gives, the four midpoint parts carry the shape (SenderShape::fine).
  // Otherwise the bend stays unshot, for a later shot to ship when it has grown: what
  // the shots ship then sums to the sender's final values, even shapes cancel.
  double bend = 0;
  for (const auto& h : kGridHalfway) bend = std::max(bend, std::abs(b[h[0]] - 0.5 * (b[h[1]] + b[h[2]])));
  const bool fine = bend > kShapeBend * std::abs(m);
  if (!fine)
    for (const auto& h : kGridHalfway) b[h[0]] = 0.5 * (b[h[1]] + b[h[2]]);
  // What this shot ships moves shot_at_nodes on (all of it when not over-relaxed).
  for (int k = 0; k < kTriangleNodes; ++k) sender.shot_at_nodes[k] += options_.overshoot * b[k];
  return shape_from_nodes(sender.corners, b, m, fine);
}

Solver::SenderShape Solver::shipped_shape(std::uint32_t patch) const {
  const Patch& sender = patches_[patch];
  return shape_from_nodes(sender.corners, sender.shot_at_nodes.data(), sender.shot.luminance(), true);
}

Solver::SenderShape Solver::shape_from_nodes(const std::array<Vec3d, 3>& c, const double* b, double m, bool fine) {
  SenderShape shape;
  if (!(std::abs(m) > 0)) return shape;
  const auto& part_nodes = triangle_part_nodes();
  double part_mean[kTriangleParts], mean = 0;
  for (int s = 0; s < kTriangleParts; ++s) {
    part_mean[s] = (b[part_nodes[s][0]] + b[part_nodes[s][1]] + b[part_nodes[s][2]]) / 3;
    mean += part_mean[s] / kTriangleParts;
  }
  // The shape is the parts' deviation from their mean, added to the mean radiosity m
  // (from the energy the sender received, which also knows its interior). Added, not
  // scaled: over a whole solve the deviations sum to those of the sender's final
  // values, so where the answer is even (a furnace) the shapes cancel.
  double spread = 0;
  for (int s = 0; s < kTriangleParts; ++s) spread = std::max(spread, std::abs(part_mean[s] - mean));
  if (spread < 1e-3 * std::abs(m)) return shape;  // even enough: one closed form
  Vec3d node[kTriangleNodes];
  triangle_nodes(c.data(), node);
  shape.fine = fine;
  shape.centroid = (c[0] + c[1] + c[2]) / 3.0;
  shape.dipole = Vec3d(0, 0, 0);
  for (int s = 0; s < kTriangleParts; ++s) {
    shape.weight[s] = 1 + (part_mean[s] - mean) / m;
    if (fine) shape.max_weight = std::max(shape.max_weight, std::abs(shape.weight[s]));
    const Vec3d part_centroid = (node[part_nodes[s][0]] + node[part_nodes[s][1]] + node[part_nodes[s][2]]) / 3.0;
    shape.dipole += (part_centroid - shape.centroid) * ((shape.weight[s] - 1) / kTriangleParts);
  }
  // The midpoint parts' weights: the means of the small parts in them (a line's mean
  // on a triangle is the mean at its corners, so these are the corner nodes' means).
  if (!fine)
    for (int q = 0; q < 4; ++q) {
      double w = 0;
      for (int k = 0; k < 3; ++k) w += b[kMidpointParts[q][k]];
      shape.coarse[q] = 1 + (w / 3 - mean) / m;
      shape.max_weight = std::max(shape.max_weight, std::abs(shape.coarse[q]));
    }
  shape.on = true;
  return shape;
}

double Solver::shaped_closed_form(const Vec3d& x, const Vec3d& n, const std::array<Vec3d, 3>& corners,
                                  const Vec3d& centre, double radius, double area, const Vec3d& normal,
                                  const SenderShape& shape) {
  if (shape.on && (x - centre).sqrnorm() < kShapeNear * kShapeNear * radius * radius)
    return shape.fine ? point_to_parted_triangle(x, n, corners.data(), shape.weight.data(), normal)
                      : point_to_quartered_triangle(x, n, corners.data(), shape.coarse.data(), normal);
  double f = point_to_triangle(x, n, corners[0], corners[1], corners[2], normal);
  if (shape.on && f > 0) {
    // The parts' corrections (w - 1) K(c_s) with K the point-to-area form of a part
    // of the sender sum to first order to grad K(c) . dipole, the weights' mean being 1.
    const Vec3d d = shape.centroid - x;
    const double r2 = d.sqrnorm(), a = OpenMesh::dot(n, d), b = -OpenMesh::dot(normal, d);
    if (a > 0 && b > 0) {
      const double k = area / (M_PI * r2 * r2);
      const Vec3d gradient = (n * b - normal * a - d * (4 * a * b / r2)) * k;
      f = std::max(0.0, f + OpenMesh::dot(gradient, shape.dipole));
    }
  }
  return f;
}

double Solver::element_reach(ElementId q) const {
  return element_form_factor(q) * hierarchy_.element(q).area;
}

void Solver::midpoint_form_factors(ElementId q, std::array<double, 3>& mid) const {
  const Element& el = hierarchy_.element(q);
  // (the exact form costs a luminaire or a cluster no more than a far-field one; a
  // group's far field would need its weights' moments)
  if (is_luminaire(sender_) || is_cluster(sender_) || !sender_members_.empty()) {
    const Vec3d& n = hierarchy_.normal(q);
    const Vec3d centroid = hierarchy_.centroid(q);
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      const CornerFormFactor& fa = corner_form_factor(q, k);
      const CornerFormFactor& fb = corner_form_factor(q, l);
      const double unoccluded = fa.unoccluded + fb.unoccluded;
      const double visible = unoccluded > 0 ? (fa.visible + fb.visible) / unoccluded : 1.0;
      Vec3d at = (hierarchy_.position(el.corners[k]) + hierarchy_.position(el.corners[l])) * 0.5;
      at += (centroid - at) * 1e-2;
      mid[k] = visible * sender_closed_form(at, n);
    }
    return;
  }
  const Patch& sender = patches_[sender_];
  const Vec3d& n = hierarchy_.normal(q);
  const Vec3d centroid = hierarchy_.centroid(q);
  // Far from the sender, what matters is the second difference of F along each edge,
  // F(mid) - (F(a) + F(b)) / 2, and the point-to-area form A cos cos / (pi r^2) gives it
  // within a fraction (R/r)^2 of itself (R: the sender's radius), at a fraction of the
  // closed form's cost. Used when q is at least kFarField sender radii away and no part
  // of the sender is below q's horizon (nor q behind the sender), where the closed form
  // would clip.
  Vec3d pos[3];
  for (int k = 0; k < 3; ++k) pos[k] = hierarchy_.position(el.corners[k]);
  double q_radius = 0;
  for (const Vec3d& p : pos) q_radius = std::max(q_radius, (p - centroid).norm());
  bool far = (centroid - sender.centre).norm() - q_radius >= kFarField * sender.radius;
  for (int k = 0; far && k < 3; ++k)
    far = OpenMesh::dot(n, sender.corners[k] - centroid) > 0 && OpenMesh::dot(sender.normal, pos[k] - sender.corners[0]) > 0;
  auto far_form = [&](const Vec3d& x) { return point_to_area(x, n, sender.centre, sender.normal, sender.area); };
  double far_at[3] = {0, 0, 0};
  if (far)
    for (int k = 0; k < 3; ++k) far_at[k] = far_form(receivers_[corner_receiver_[q][k]].point);
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    const CornerFormFactor& fa = corner_form_factor(q, k);
    const CornerFormFactor& fb = corner_form_factor(q, l);
    const double unoccluded = fa.unoccluded + fb.unoccluded;
    const double visible = unoccluded > 0 ? (fa.visible + fb.visible) / unoccluded : 1.0;
    Vec3d at = (pos[k] + pos[l]) * 0.5;
    at += (centroid - at) * 1e-2;  // inside q, as evaluation points are
    mid[k] = far ? 0.5 * (fa.visible + fb.visible) + visible * (far_form(at) - 0.5 * (far_at[k] + far_at[l]))
                 : visible * sender_closed_form(at, n);
  }
}

double Solver::estimate_pushdown_error(ElementId q, const Rgb& reflectance, OracleInputs& in,
                                       std::array<double, 3>& mid) const {
  const double shot = (reflectance * current_shot_).luminance();
  in.pushdown_error = in.current_peak = 0;
  if (!(shot > 0)) return -1;
  midpoint_form_factors(q, mid);
  const bool resolved = shadow_resolved(q);
  double mid_sum = 0;
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    const CornerFormFactor& fa = corner_form_factor(q, k);
    const CornerFormFactor& fb = corner_form_factor(q, l);
    const double a = in.current[k].luminance(), b = in.current[l].luminance();
    const double at_mid = shot * mid[k];
    const bool shadow_edge = !resolved && std::abs(fa.visible_fraction() - fb.visible_fraction()) > 1e-9;
    const double error = std::abs(at_mid - 0.5 * (a + b)) + (shadow_edge ? 0.5 * std::abs(a - b) : 0.0);
    in.pushdown_error = std::max(in.pushdown_error, error);
    in.current_peak = std::max({in.current_peak, a, at_mid});
    mid_sum += mid[k];
  }
  if (is_luminaire(sender_)) {
    // A luminaire's pool of light peaks inside elements, where no edge midpoint sees
    // it (a point source straight above q): the centroid is checked too, against the
    // corners' mean, which is what q shows there if the shot stops at it (its exact
    // illuminance costs no more than a midpoint's).
    double corners = 0, unoccluded = 0, visible = 0;
    for (int k = 0; k < 3; ++k) {
      const CornerFormFactor& f = corner_form_factor(q, k);
      visible += f.visible;
      unoccluded += f.unoccluded;
      corners += in.current[k].luminance();
    }
    const double fraction = unoccluded > 0 ? visible / unoccluded : 1.0;
    const double at_centroid = shot * fraction * sender_closed_form(hierarchy_.centroid(q), hierarchy_.normal(q));
    in.pushdown_error = std::max(in.pushdown_error, std::abs(at_centroid - corners / 3));
    in.current_peak = std::max(in.current_peak, at_centroid);
  }
  return mid_sum / 3;
}

bool Solver::shadow_resolved(ElementId q) const {
  if (!is_luminaire(sender_) || luminaire(sender_).directional()) return false;
  const Element& el = hierarchy_.element(q);
  double longest = 0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (hierarchy_.position(el.corners[k]) - hierarchy_.position(el.corners[(k + 1) % 3])).sqrnorm());
  const double distance = (hierarchy_.centroid(q) - luminaire(sender_).position).norm();
  return std::sqrt(longest) < kShadowResolution * distance;
}

bool Solver::shadow_crosses(ElementId q) const {
  double lo = 2, hi = -1;
  for (int k = 0; k < 3; ++k) {
    const double fraction = corner_form_factor(q, k).visible_fraction();
    lo = std::min(lo, fraction);
    hi = std::max(hi, fraction);
  }
  return hi - lo > 0.25;
}

std::array<double, 3> Solver::barycentric(ElementId e, const Vec3d& point) const {
  const Element& el = hierarchy_.element(e);
  const Vec3d& n = hierarchy_.normal(e);
  Vec3d c[3];
  for (int k = 0; k < 3; ++k) c[k] = hierarchy_.position(el.corners[k]);
  const double area = OpenMesh::dot(OpenMesh::cross(c[1] - c[0], c[2] - c[0]), n);
  std::array<double, 3> l;
  for (int k = 0; k < 3; ++k)
    l[k] = OpenMesh::dot(OpenMesh::cross(c[(k + 1) % 3] - point, c[(k + 2) % 3] - point), n) / area;
  return l;
}

Rgb Solver::quadratic(const std::array<Rgb, 6>& nodes, const std::array<double, 3>& l) {
  Rgb out;
  for (int k = 0; k < 3; ++k) {
    out += nodes[k] * (l[k] * (2 * l[k] - 1));
    out += nodes[3 + k] * (4 * l[k] * l[(k + 1) % 3]);
  }
  return out;
}

Rgb Solver::interpolate(ElementId e, const std::array<Rgb, 3>& at_corners, const Vec3d& point) const {
  const Element& el = hierarchy_.element(e);
  const Vec3d& n = hierarchy_.normal(e);
  Vec3d c[3];
  for (int k = 0; k < 3; ++k) c[k] = hierarchy_.position(el.corners[k]);
  const double area = OpenMesh::dot(OpenMesh::cross(c[1] - c[0], c[2] - c[0]), n);
  Rgb out;
  for (int k = 0; k < 3; ++k) {
    const double w = OpenMesh::dot(OpenMesh::cross(c[(k + 1) % 3] - point, c[(k + 2) % 3] - point), n) / area;
    out += at_corners[k] * w;
  }
  return out;
}

void Solver::initialise_new_elements() {
  const std::size_t count = hierarchy_.element_count();
  const ElementId first = static_cast<ElementId>(initialised_);
  if (count == first) return;
  // The new entries are written below, in parallel (their memory is touched first there).
  value_.resize_for_overwrite(count);
  pending_.resize_for_overwrite(count);
  gathered_in_.resize_for_overwrite(count);
  if (refine_.method == Method::adaptive || refine_.new_elements == RefineSettings::NewElements::gather) {
    register_receivers(first);
    for (ElementId e = first; e < count; ++e) {
      pending_[e] = {};
      gathered_in_[e] = 0;
    }
    gather_new_elements(initialised_);
    initialised_ = count;
    return;
  }
  // In parallel. A new element's parent may be new too (a 1 -> 4 split bisects twice),
  // so each takes its values from its nearest ancestor that already had values: the
  // same as going through the new parents, since both rules reproduce a linear (or
  // constant) function on the flat ancestor.
  // Meanwhile another thread registers the new receivers (serial: a hash map); neither
  // reads what the other writes.
  if (count - first < 256) {  // too few to wake the other threads for
    register_receivers(first);
    initialise_values(first, count);
    initialised_ = count;
    return;
  }
  // Storage for the new receivers first, so that registering moves nothing the values
  // read meanwhile (near_field_start reads the source corners' receivers).
  corner_receiver_.resize(count);
  receivers_.reserve(receivers_.size() + 3 * (count - first));
  tbb::task_group registering;
  registering.run([this, first] { register_receivers(first); });
  try {
    initialise_values(first, count);
  } catch (...) {
    registering.wait();
    throw;
  }
  registering.wait();
  initialised_ = count;
}

void Solver::initialise_values(ElementId first, std::size_t count) {
  parallel_for_index(count - first, 1024, [&](std::size_t n) {
    const ElementId e = first + static_cast<ElementId>(n);
    pending_[e] = {};
    gathered_in_[e] = 0;
    const Element& el = hierarchy_.element(e);
    ElementId source = el.parent;
    while (source >= first) source = hierarchy_.element(source).parent;
    const auto& p = value_[source];
    const bool bends = refine_.near_field_start && refine_.method == Method::dynamic;
    // (see below: whether the source lacks push-down its ancestors still hold)
    const bool stale = bends && pending_above(source);
    if (refine_.new_elements == RefineSettings::NewElements::constant) {
      const Rgb mean = (p[0] + p[1] + p[2]) * (1.0 / 3);
      value_[e] = {mean, mean, mean};
    } else {
      const Element& src = hierarchy_.element(source);
      thread_local std::vector<std::uint32_t> scratch;
      for (int k = 0; k < 3; ++k) {
        const VertexHandle v = el.corners[k];
        const Vec3d position = hierarchy_.position(v);
        value_[e][k] = interpolate(source, p, position);
        const bool new_vertex = v != src.corners[0] && v != src.corners[1] && v != src.corners[2];
        // The bend is taken against the line through the source's corners, which it
        // takes to hold each nearby sender's light as F there. A source the walk did
        // not pass (the neighbour that conforming bisection splits too) may still lack
        // what its ancestors' push-down holds for it; that arrives later, interpolated
        // from the ancestor, and a bend on top of it counts the bend twice: at the
        // foot of the Cornell demo's short block one side of a new vertex started 40%
        // above the other and kept the difference, a vertex 10% above its ring. Such a
        // source bends only vertices on its plane's edge, where F jumps across the
        // edge and the ancestor's push-down cannot have it (without the bend there, a
        // furnace's edge vertex was 5% low).
        if (new_vertex && bends && (!stale || on_plane_edge(v, hierarchy_.normal(source))))
          value_[e][k] += near_field_start(e, source, position, value_[e][k].luminance(), scratch);
      }
    }
  });
}

bool Solver::pending_above(ElementId e) const {
  for (ElementId a = hierarchy_.element(e).parent; a != kNoElement; a = hierarchy_.element(a).parent)
    for (const Rgb& v : pending_[a])
      if (!v.is_zero()) return true;
  return false;
}

bool Solver::on_plane_edge(VertexHandle v, const Vec3d& normal) const {
  const TriMesh& mesh = scene_.mesh();
  if (mesh.is_boundary(v)) return true;
  for (auto f : mesh.vf_range(v))
    if (OpenMesh::dot(mesh.normal(f), normal) <= 1 - 1e-9) return true;
  return false;
}

Rgb Solver::near_field_start(ElementId e, ElementId source, const Vec3d& position, double line,
                             std::vector<std::uint32_t>& scratch) const {
  const Element& src = hierarchy_.element(source);
  const Patch& patch = patches_[src.patch];
  const Vec3d& n = hierarchy_.normal(source);
  const Vec3d centroid = hierarchy_.centroid(source);
  double radius = 0;
  Vec3d corner_point[3];
  for (int k = 0; k < 3; ++k) {
    radius = std::max(radius, (hierarchy_.position(src.corners[k]) - centroid).norm());
    // Where the corner's light was computed (the step into the element that registered
    // it), not a step into the source: at a patch's corner on an edge, F from that patch
    // jumps across the corner, and the bend taken from a point on the wrong side of it
    // was off by the whole jump (a furnace's edge vertex 4% too bright at high quality).
    corner_point[k] = receivers_[corner_receiver_[source][k]].point;
  }
  // The new corner's evaluation point, as register_receivers() places it.
  const Vec3d point = position + (hierarchy_.centroid(e) - position) * 1e-2;
  const std::array<double, 3> l = barycentric(source, position);
  scratch.clear();
  patch_index_.near(point, radius, scratch);  // (only patches that have shot are in it)
  // Only patches whose light could bend the start by kNearFieldShare of the value the
  // line gives (F's bend is at most 1), and only within one radius of the source: on
  // the IFC house, every patch within two radii of every new vertex cost a fifth of the
  // solve.
  Rgb add;
  for (std::uint32_t j : scratch) {
    const Patch& s = patches_[j];
    if (j == src.patch || s.plane == patch.plane) continue;
    if ((patch.reflectance * s.shot).luminance() < kNearFieldShare * line) continue;
    // F at each point times the share of the patch seen from there: a patch behind a
    // partition or a wall's thickness sends nothing, however near. (Without the rays,
    // the floor along the foot of the obstructed 1990 room's partition started each
    // new vertex with light from the back wall on the partition's lit side, and ended
    // up to 97% too bright.)
    auto f = [&](const Vec3d& x) {
      const double open = point_to_triangle(x, n, s.corners[0], s.corners[1], s.corners[2], s.normal);
      return open > 0 ? open * near_seen_share(x, n, s) : 0.0;
    };
    const double bend = f(point) - (l[0] * f(corner_point[0]) + l[1] * f(corner_point[1]) + l[2] * f(corner_point[2]));
    add += s.shot * bend;
  }
  return patch.reflectance * add;
}

double Solver::near_seen_share(const Vec3d& x, const Vec3d& n, const Patch& p) const {
  const Vec3d targets[kNearRays] = {p.centre, (p.corners[0] + p.centre) * 0.5, (p.corners[1] + p.centre) * 0.5,
                                    (p.corners[2] + p.centre) * 0.5};
  return static_cast<double>(visibility_->visible_count(x, n, targets, kNearRays, p.normal)) / kNearRays;
}

void Solver::restart_split_terminals(std::size_t first, std::vector<ElementId> terminals, const Rgb& shot) {
  const std::size_t count = hierarchy_.element_count();
  if (count == first || (terminals.empty() && held_.empty())) return;
  std::sort(terminals.begin(), terminals.end());
  auto holds = [&](ElementId s) {
    return std::binary_search(terminals.begin(), terminals.end(), s) || held_.count(s) > 0;
  };
  std::vector<ElementId> affected;
  std::vector<ElementId> source_of;
  for (ElementId e = static_cast<ElementId>(first); e < count; ++e) {
    ElementId source = hierarchy_.element(e).parent;
    while (source >= first) source = hierarchy_.element(source).parent;
    if (!holds(source)) continue;
    affected.push_back(e);
    source_of.push_back(source);
  }
  std::vector<HeldShot> now(affected.size());
  parallel_for_index(affected.size(), 64, [&](std::size_t n) {
    const ElementId e = affected[n], source = source_of[n];
    const Element& el = hierarchy_.element(e);
    const Element& src = hierarchy_.element(source);
    const Patch& patch = patches_[el.patch];
    // This shot's dB at the source's corners, as it was inherited, and the fractions of
    // the sender they see: a terminal's from its corners' form factors; an element split
    // from a terminal earlier in this shot (and split again since) as it was restarted.
    HeldShot at_source;
    if (const auto it = held_.find(source); it != held_.end()) {
      at_source = it->second;
    } else {
      for (int k = 0; k < 3; ++k) {
        at_source.dB[k] = patch.reflectance * shot * form_factor(source, k);
        at_source.seen[k] = corner_form_factor(source, k).visible_fraction();
      }
    }
    HeldShot& held = now[n];
    for (int k = 0; k < 3; ++k) {
      const VertexHandle v = el.corners[k];
      const Vec3d position = hierarchy_.position(v);
      const std::array<double, 3> l = barycentric(source, position);
      const Rgb line = interpolate(source, at_source.dB, position);
      held.seen[k] = l[0] * at_source.seen[0] + l[1] * at_source.seen[1] + l[2] * at_source.seen[2];
      held.dB[k] = line;
      if (v == src.corners[0] || v == src.corners[1] || v == src.corners[2]) continue;  // exact already
      // The sender's closed form at the new corner's evaluation point (the kernel, which
      // bends beside a neighbouring surface), times the visible fraction interpolated
      // from the source's corners (as at the push-down's midpoints: no rays, so no
      // vertex is left to two rays' say).
      const Vec3d point = receivers_[corner_receiver_[e][k]].point;
      held.dB[k] = patch.reflectance * shot * (held.seen[k] * sender_closed_form(point, hierarchy_.normal(e)));
      value_[e][k] = value_[e][k] - line + held.dB[k];
    }
  });
  for (std::size_t n = 0; n < affected.size(); ++n) held_[affected[n]] = now[n];
}

void Solver::push_down(ElementId q, const std::array<Rgb, 6>& delta) {
  if (hierarchy_.element(q).is_leaf()) return;
  for (int k = 0; k < 6; ++k) pending_[q][k] += delta[k];
}

void Solver::flush(ElementId q) {
  const Element& el = hierarchy_.element(q);
  if (el.is_leaf()) return;
  std::array<Rgb, 6>& pending = pending_[q];
  bool zero = true;
  for (const Rgb& v : pending) zero = zero && v.is_zero();
  if (zero) return;
  // A bisection: each child has the corner opposite the split edge (the parent corner
  // both children have), one end of that edge, and its midpoint. The children's nodes
  // are then known in the parent's barycentric coordinates without any geometry: a
  // corner of the parent is a unit vector, the new point is half of each end, and a
  // child's edge midpoint is the mean of its ends' coordinates.
  const Element& first = hierarchy_.element(el.children[0]);
  const Element& second = hierarchy_.element(el.children[1]);
  auto has = [](const Element& e, VertexHandle v) {
    return e.corners[0] == v || e.corners[1] == v || e.corners[2] == v;
  };
  int opposite = 0;
  while (opposite < 2 && !(has(first, el.corners[opposite]) && has(second, el.corners[opposite]))) ++opposite;
  for (ElementId c : el.children) {
    const Element& child = hierarchy_.element(c);
    std::array<std::array<double, 3>, 3> at;  // barycentric coordinates of the child's corners
    for (int k = 0; k < 3; ++k) {
      int j = 0;
      while (j < 3 && child.corners[k] != el.corners[j]) ++j;
      if (j < 3) {
        at[k] = {0, 0, 0};
        at[k][j] = 1;
      } else {  // the midpoint of the split edge
        at[k] = {0.5, 0.5, 0.5};
        at[k][opposite] = 0;
      }
    }
    std::array<Rgb, 6> delta;
    for (int k = 0; k < 3; ++k) {
      const auto& a = at[k];
      const auto& b = at[(k + 1) % 3];
      // A corner is a node of the parent: a corner's or the split edge's midpoint's.
      int j = 0;
      while (j < 3 && a[j] != 1) ++j;
      delta[k] = j < 3 ? pending[j] : pending[3 + (opposite + 1) % 3];
      delta[3 + k] = quadratic(pending, {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])});
    }
    for (int k = 0; k < 3; ++k) value_[c][k] += delta[k];
    push_down(c, delta);
  }
  pending = {};
}

void Solver::flush_all() {
  flush_clusters();
  // Each patch's tree on its own: flush() writes only below the element it flushes.
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, static_cast<std::uint32_t>(patches_.size()), 64),
                    [this](const tbb::blocked_range<std::uint32_t>& range) {
                      std::vector<ElementId> stack;
                      for (std::uint32_t p = range.begin(); p < range.end(); ++p) {
                        stack.assign(1, hierarchy_.patch_root(p));
                        while (!stack.empty()) {
                          const ElementId e = stack.back();
                          stack.pop_back();
                          const Element& el = hierarchy_.element(e);
                          if (el.is_leaf()) continue;
                          flush(e);
                          stack.push_back(el.children[0]);
                          stack.push_back(el.children[1]);
                        }
                      }
                    });
}

// Energy of one shot, from the elements where it stopped. See shoot.cpp for why the
// element powers are normalised.
void Solver::account_transfers(const std::vector<ElementId>& terminals, const std::vector<double>& reach,
                               std::uint32_t sender_id, const Rgb& shot_radiosity) {
  const double lost = lost_fraction(sender_id);
  // What one unit of the shot carries: a patch's area, a luminaire's flux; a cluster
  // shoots its power itself.
  const bool from_luminaire = is_luminaire(sender_id);
  const bool from_cluster = is_cluster(sender_id);
  const double power = from_luminaire  ? luminaire_flux_[sender_id - patches_.size()]
                       : from_cluster ? 1.0
                                      : group_of(sender_id).area;
  const double escaped = from_luminaire  ? luminaire_escaped_[sender_id - patches_.size()]
                         : from_cluster ? cluster_state_[cluster_index(sender_id)].escaped
                                        : patches_[sender_id].escaped;
  double received = 0;
  for (double r : reach) received += r;  // in order: the same total for any number of threads
  for (std::uint32_t c : whole_clusters_) {
    const auto& cl = clusters_.clusters[c];
    for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k)
      received += clusters_.parts[k].area * part_form_factor_[k];
  }
  const double reachable = power * (1 - lost);
  double scale = 0;
  if (received > 0 && reachable > 0) {
    scale = reachable / received;
    form_factor_error_sum_ += std::abs(1 - received / reachable);
  }
  // Per receiving patch: a patch's terminal elements mostly come in runs (siblings have
  // neighbouring ids), so the reach of a run is summed before it is booked.
  Rgb incident_total;
  // Coefficient channels (solver_coefficients.cpp): the same transfer for each.
  const std::size_t channels = coefficients_.count;
  std::vector<float> channel_incident(channels);
  if (channels > 0 && from_luminaire) mix_sky(terminals, reach);
  const double shot_luminance = shot_radiosity.luminance();
  auto book = [&](std::uint32_t patch_id, double patch_reach) {
    if (patch_reach <= 0) return;
    Patch& receiver = patches_[patch_id];
    if (channels > 0 && from_luminaire) {
      incident_coefficients(coefficient_slot_[patch_id], shot_luminance * patch_reach * scale / receiver.area,
                            channel_incident.data());
      book_coefficients(patch_id, channel_incident.data(), 1.0f, true);
    } else if (channels > 0) {
      book_coefficients(patch_id, coefficient_shot_.data(), static_cast<float>(patch_reach * scale / receiver.area),
                        false);
    }
    mark_surveyed(unit_of_receiver(patch_id));
    const Rgb incident = shot_radiosity * (patch_reach * scale);
    const Rgb reflected = receiver.reflectance * incident;
    if (receiver.clustered)  // its cluster sends it, with its part
      part_unshot_[clusters_.part_of_patch[patch_id]] += reflected;
    else
      receiver.unshot += reflected * (1.0 / receiver.area);  // eq. 3: area-weighted pull-up
    report_.energy.absorbed += incident - reflected;
    incident_total += incident;
  };
  std::uint32_t run_patch = 0;
  double run_reach = 0;
  for (std::size_t t = 0; t < terminals.size(); ++t) {
    if (reach[t] <= 0) continue;
    const std::uint32_t patch_id = hierarchy_.element(terminals[t]).patch;
    if (patch_id != run_patch) {
      book(run_patch, run_reach);
      run_patch = patch_id;
      run_reach = 0;
    }
    run_reach += reach[t];
  }
  book(run_patch, run_reach);
  // Clusters received as one: each part takes its share; its patches get the light when
  // the cluster is flushed (flush_cluster).
  for (std::uint32_t c : whole_clusters_) {
    const auto& cl = clusters_.clusters[c];
    mark_surveyed(static_cast<std::uint32_t>(groups_.groups.size()) + c);
    for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) {
      const double f = part_form_factor_[k];
      if (!(f > 0)) continue;
      const Rgb incident = shot_radiosity * (clusters_.parts[k].area * f * scale);
      const Rgb reflected = part_reflectance_area_[k] * shot_radiosity * (f * scale);
      part_unshot_[k] += reflected;
      report_.energy.absorbed += incident - reflected;
      incident_total += incident;
      part_pending_[k] += shot_radiosity * f;
      cluster_state_[c].dirty = true;
      if (channels > 0 && from_luminaire) {
        incident_coefficients(coefficient_slot_[patches_.size() + k], shot_luminance * f * scale,
                              channel_incident.data());
        book_part_coefficients(k, channel_incident.data(), 1.0f, true);
      } else if (channels > 0) {
        book_part_coefficients(k, coefficient_shot_.data(), static_cast<float>(f * scale), false);
      }
    }
  }
  if (channels > 0 && from_luminaire) std::fill(coefficient_slot_.begin(), coefficient_slot_.end(), UINT32_MAX);
  // What no front face received: out of the scene, or onto black back faces. In a
  // closed scene only rounding is left; it is booked as absorbed.
  const Rgb not_received = shot_radiosity * power - incident_total;
  const double escaped_share = lost > 0 ? escaped / lost : 0.0;
  report_.energy.escaped += not_received * escaped_share;
  report_.energy.absorbed += not_received * (1 - escaped_share);
  if (!from_luminaire) mark_surveyed(unit_of_sender(sender_id));
  survey_patches();
}

Solver::Output Solver::output(bool ambient_display) {
  flush_all();
  update_direct_gaps();
  Output out;
  out.split = split_vertices(scene_, options_.crease_angle);
  out.radiosity.assign(out.split.size(), Rgb());
  out.emitter.assign(out.split.size(), 0);
  out.irradiance.assign(out.split.size(), Rgb());
  std::vector<double> weight(out.split.size(), 0.0);
  std::vector<double> mesh_at(out.split.size(), 0.0), unshot_at(out.split.size(), 0.0);
  const Rgb unshot_error = unshot_error_radiosity();
  auto arriving = [](const Rgb& b, const Patch& p) {
    auto channel = [](double value, double e, double rho) { return rho > 0 ? (value - e) / rho : 0.0; };
    return Rgb(channel(b.r, p.emission.r, p.reflectance.r), channel(b.g, p.emission.g, p.reflectance.g),
               channel(b.b, p.emission.b, p.reflectance.b));
  };
  const TriMesh& mesh = scene_.mesh();
  const Rgb ambient_now = ambient_display ? ambient() : Rgb();
  // Beside the ambient term, the unshot light of each vertex's near patches (near_unshot()).
  std::vector<Rgb> near;
  if (ambient_display && options_.near_unshot) {
    std::vector<char> wanted(receivers_.size(), 0);
    for (auto f : mesh.faces()) {
      const ElementId e = hierarchy_.element_of(f);
      for (int j = 0; j < 3; ++j) wanted[corner_receiver_[e][j]] = 1;
    }
    near = near_unshot(wanted);
  }
  for (auto f : mesh.faces()) {
    const ElementId e = hierarchy_.element_of(f);
    const Element& el = hierarchy_.element(e);
    const Rgb extra = patches_[el.patch].reflectance * ambient_now;
    const double mesh_here = mesh_error(e);
    const double unshot_here = (patches_[el.patch].reflectance * unshot_error).luminance();
    int k = 0;
    for (auto v : mesh.fv_range(f)) {
      const auto node = out.split.corner[3 * f.idx() + k++];
      for (int j = 0; j < 3; ++j)
        if (el.corners[j] == v) {
          const Rgb b = value_[e][j] + extra +
                        (near.empty() ? Rgb() : patches_[el.patch].reflectance * near[corner_receiver_[e][j]]);
          out.radiosity[node] += b * el.area;
          out.irradiance[node] += arriving(b, patches_[el.patch]) * el.area;
        }
      weight[node] += el.area;
      out.emitter[node] = scene_.material(f).emits();
      mesh_at[node] = std::max(mesh_at[node], mesh_here);
      unshot_at[node] = std::max(unshot_at[node], unshot_here);
    }
  }
  out.error.assign(out.split.size(), 0.0f);
  for (std::size_t i = 0; i < weight.size(); ++i)
    if (weight[i] > 0) {
      out.radiosity[i] = out.radiosity[i] * (1.0 / weight[i]);
      out.irradiance[i] = out.irradiance[i] * (1.0 / weight[i]);
      const double b = out.radiosity[i].luminance();
      if (b > 0) out.error[i] = static_cast<float>((mesh_at[i] + unshot_at[i]) / b);
    }
  return out;
}

SolveReport Solver::run() {
  using Clock = std::chrono::steady_clock;
  std::unique_ptr<tbb::global_control> threads;
  if (options_.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                    static_cast<std::size_t>(options_.threads));
  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  report_.stopped_by = StopReason::converged;
  report_.error_target = options_.error_target;
  // The error estimate costs a pass over the elements: it is taken when unshot power
  // has fallen by a fifth since the last look, or every 64 shots (at every tenth, its
  // 44 looks were about 10% of the 1990 room's solve), or, in a long solve, every 32nd
  // of the shots so far (the stop comes at most a 32nd later than it would; a look at
  // the IFC house's 530,000 elements costs about as much as two shots).
  double checked_unshot = 2;
  std::size_t checked_at = 0;
  while (true) {
    if (unshot_fraction() <= options_.converge) break;
    if (options_.error_target > 0 && report_.iterations > 0 &&
        (unshot_fraction() < 0.8 * checked_unshot || report_.iterations >= checked_at + std::max<std::size_t>(64, report_.iterations / 32))) {
      checked_unshot = unshot_fraction();
      checked_at = report_.iterations;
      report_.estimated_error = estimate_error(false);
      const ErrorEstimate& e = report_.estimated_error;
      // Not before every primary source has shot: the light of one that has not is no
      // ambient term but direct light that the surfaces under it lack altogether.
      if (primary_sources_shot()) {
        if (e.stop_measure() <= options_.error_target) {
          report_.stopped_by = StopReason::error_target;
          break;
        }
        // Only the mesh's error is left above the target: shooting on would buy little.
        if (e.unshot <= 0.1 * options_.error_target || e.unshot <= 0.25 * e.discretisation) {
          report_.stopped_by = StopReason::error_floor;
          break;
        }
      }
    }
    if (options_.max_iterations > 0 && report_.iterations >= options_.max_iterations) {
      report_.stopped_by = StopReason::iterations;
      break;
    }
    if (options_.time_limit > 0 && elapsed() >= options_.time_limit) {
      report_.stopped_by = StopReason::time_limit;
      break;
    }
    if (options_.should_stop && options_.should_stop()) {
      report_.stopped_by = StopReason::interrupted;
      break;
    }
    if (!shoot_once()) break;
    if (options_.on_shot) options_.on_shot(report_.iterations, unshot_fraction());
  }
  report_.seconds = elapsed();
  report_.estimated_error = estimate_error();
  report_.unshot_fraction = unshot_fraction();
  report_.elements = hierarchy_.element_count();
  report_.receivers = scene_.vertex_count();
  report_.visibility_rays = visibility_->rays();
  report_.form_factor_sum_error = report_.iterations ? form_factor_error_sum_ / report_.iterations : 0;
  report_.peak_resident_memory = std::max(report_.peak_resident_memory, peak_resident_memory());
  return report_;
}

}  // namespace dynrad::rad
