// The solver: construction, the loop of shots and its stopping rules (run()), the
// ambient term and the unshot fraction. One shot is shoot.cpp (Figure 5); the other
// steps are in the solver_*.cpp files, each named for its concern.
#include "radiosity/solver/solver.h"

#include "radiosity/sources/daylight.h"

#include "radiosity/transfer/form_factor.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

namespace dynrad::rad {

namespace {

constexpr double kDetailFacet = 8.0;  // 8 x patch_area: the patch size squared

}  // namespace

namespace {

double sum(const Rgb& c) { return c.r + c.g + c.b; }

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
  // (a run before may have ended with the display's refinement, which drops the
  // push-down once all of it is delivered: refine_for_display)
  pending_.resize(hierarchy_.element_count());
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
    if (next_luminaire_ == luminaires_.size() && report_.luminaire_shots.seconds == 0 && !luminaires_.empty())
      report_.luminaire_shots = {elapsed(), resident_memory(), peak_resident_memory()};
    if (options_.on_shot) options_.on_shot(report_.iterations, unshot_fraction());
  }
  // The display's refinement for direct light (exact_direct.cpp), then the estimate
  // with what it left.
  const double shots_done = elapsed();
  report_.later_shots = {shots_done - report_.luminaire_shots.seconds, resident_memory(), peak_resident_memory()};
  refine_for_display();
  report_.estimated_error = estimate_error();
  report_.seconds = elapsed();
  report_.display = {report_.seconds - shots_done, resident_memory(), peak_resident_memory()};
  report_.unshot_fraction = unshot_fraction();
  report_.elements = hierarchy_.element_count();
  report_.receivers = scene_.vertex_count();
  report_.visibility_rays = visibility_->rays();
  report_.form_factor_sum_error = report_.iterations ? form_factor_error_sum_ / report_.iterations : 0;
  report_.peak_resident_memory = std::max(report_.peak_resident_memory, peak_resident_memory());
  return report_;
}

}  // namespace dynrad::rad
