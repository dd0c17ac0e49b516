// Progressive refinement radiosity on the initial patches, the paper's Figure 1:
//
//   while (not converged) {
//     pick brightest patch: i;          brightest_patch(): most unshot power
//     for every patch j  shoot(i, j);   form factors at every receiver node, then the
//                                       power each element receives
//     update(i);                        the sender's unshot radiosity becomes zero
//   }
//
// Quantities (per colour channel unless said otherwise):
//   B(x)      radiosity at receiver node x (W/m^2), starts at the emission E(x);
//   dB_i      unshot radiosity of patch i: what it has received (or emits) but not yet
//             shot; the sender's power this shot is dB_i * A_i;
//   F(x, i)   point-to-patch form factor: Lambert's closed form for the unoccluded
//             part times the fraction of rays from x to points on i that arrive
//             (Wallace et al. 1989: receivers are the vertices, so no aliasing of the
//             sender's shape, and the values are exactly what is exported);
//   element q receives power dB_i * A_q * mean of F over q's three corners; a fraction
//             rho_q of it is reflected and joins the unshot radiosity of q's patch,
//             weighted by A_q / A_patch (the paper's eq. 3); the rest is absorbed;
//   B(x) += rho(x) * F(x, i) * dB_i.
//
// Normalisation. Averaging point form factors over an element's three corners does
// not integrate F exactly, so the power elements receive does not sum exactly to what
// the sender can reach. Each shot's element powers are scaled so that they sum to the
// sender's power times (1 - lost_i), where lost_i is the fraction of the sender's
// cosine-weighted hemisphere that leaves the scene or meets a back face, measured once
// per patch with stratified rays (exactly 0 in a closed room). The scale's distance
// from 1 is reported as form_factor_sum_error. With it, emitted = absorbed + escaped +
// unshot holds after every shot, which catches bookkeeping bugs at once. Node values
// use the unscaled point form factors (exact at a point).
#include "radiosity/progressive.h"

#include "radiosity/form_factor.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace dynrad::rad {

namespace {

// SplitMix64: a tiny, well-mixed hash for seeding per-pair sampling, so each receiver
// and sender pair gets the same samples whatever thread computes it.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

struct Rng {
  std::uint64_t state;
  double uniform() {
    state = mix(state);
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  }
};

// Uniform in the triangle for (u, v) uniform in the unit square, kept a hundredth of
// the way off the edges: a point on an edge lies in the neighbouring face's plane, and a
// ray from there slips out through the seam (see Receivers::sample_point).
Vec3d point_on_triangle(const std::array<Vec3d, 3>& c, double u, double v) {
  const double s = std::sqrt(u);
  const Vec3d p = c[0] * (1 - s) + c[1] * (s * (1 - v)) + c[2] * (s * v);
  const Vec3d centroid = (c[0] + c[1] + c[2]) / 3.0;
  return p + (centroid - p) * 1e-2;
}

double sum(const Rgb& c) { return c.r + c.g + c.b; }

}  // namespace

struct ProgressiveSolver::Patch {
  std::array<Vec3d, 3> corners;
  Vec3d normal;
  double area = 0;
  Rgb reflectance, emission, unshot;
  double lost = -1;     // fraction of shot power reaching no front face (-1: not measured yet)
  double escaped = 0;   // the part of `lost` that leaves the scene
};

ProgressiveSolver::ProgressiveSolver(const SceneMesh& scene, const ElementHierarchy& hierarchy, SolveOptions options)
    : scene_(scene), hierarchy_(hierarchy), options_(std::move(options)) {
  receivers_ = make_receivers(scene_, options_.crease_angle);
  visibility_ = std::make_unique<Visibility>(scene_);
  patches_.resize(hierarchy_.patch_count());
  std::vector<ElementId> leaves;
  for (std::uint32_t p = 0; p < patches_.size(); ++p) {
    const Element& root = hierarchy_.element(hierarchy_.patch_root(p));
    Patch& patch = patches_[p];
    for (int k = 0; k < 3; ++k) patch.corners[k] = hierarchy_.position(root.corners[k]);
    patch.normal = hierarchy_.normal(hierarchy_.patch_root(p));
    patch.area = root.area;
    leaves.clear();
    hierarchy_.leaves(hierarchy_.patch_root(p), leaves);
    const Material& m = scene_.material(hierarchy_.element(leaves.front()).face);
    patch.reflectance = m.reflectance;
    patch.emission = m.emission;
    patch.unshot = m.emission;
    report_.energy.emitted += m.emission * patch.area;
  }
  emitted_total_ = sum(report_.energy.emitted);
  if (!(emitted_total_ > 0)) throw std::invalid_argument("no surface emits light");
  report_.energy.unshot = report_.energy.emitted;
  node_radiosity_.resize(receivers_.size());
  for (std::size_t x = 0; x < receivers_.size(); ++x)
    node_radiosity_[x] = scene_.materials()[receivers_.material[x]].emission;
  node_form_factor_.resize(receivers_.size());
  report_.method = "progressive";
  report_.patches = patches_.size();
  report_.receivers = receivers_.size();
}

ProgressiveSolver::~ProgressiveSolver() = default;

std::uint32_t ProgressiveSolver::brightest_patch() const {
  std::uint32_t best = 0;
  double best_power = -1;
  for (std::uint32_t p = 0; p < patches_.size(); ++p) {
    const double power = sum(patches_[p].unshot) * patches_[p].area;
    if (power > best_power) {
      best = p;
      best_power = power;
    }
  }
  return best;
}

double ProgressiveSolver::unshot_fraction() const { return sum(report_.energy.unshot) / emitted_total_; }

// Fraction of the power patch `id` shoots that reaches no front face: cosine-weighted
// directions from points on the patch, stratified over the hemisphere.
double ProgressiveSolver::lost_fraction(std::uint32_t id) {
  Patch& p = patches_[id];
  if (p.lost >= 0) return p.lost;
  const Vec3d n = p.normal;
  const Vec3d t = OpenMesh::cross(std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0), n).normalized();
  const Vec3d b = OpenMesh::cross(n, t);
  const int side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(options_.escape_rays))));
  Rng rng{mix(options_.seed ^ mix(0xE5CA9E000000ull + id))};
  int escaped = 0, back = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const double u1 = (i + rng.uniform()) / side, u2 = (j + rng.uniform()) / side;
      const double r = std::sqrt(u1), phi = 2 * M_PI * u2;
      const Vec3d dir = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - u1));
      const Vec3d origin = point_on_triangle(p.corners, rng.uniform(), rng.uniform());
      const auto hit = visibility_->trace(origin, n, dir);
      escaped += hit == Visibility::Hit::nothing;
      back += hit == Visibility::Hit::back;
    }
  const double total = static_cast<double>(side) * side;
  p.escaped = escaped / total;
  p.lost = (escaped + back) / total;
  return p.lost;
}

// Fraction of rays from node x to stratified points on the sender that arrive: a few
// rays first; more only when those disagree (the sender is partly hidden).
double ProgressiveSolver::visible_fraction(std::uint32_t x, const Patch& sender, std::uint32_t sender_id) const {
  Rng rng{mix(options_.seed ^ mix((static_cast<std::uint64_t>(x) << 32) ^ sender_id))};
  const Vec3d& from = receivers_.sample_point[x];
  const Vec3d& normal = receivers_.normal[x];
  int visible = 0, cast = 0;
  auto pass = [&](int count) {
    const int side = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(count)))));
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        const Vec3d target = point_on_triangle(sender.corners, (i + rng.uniform()) / side, (j + rng.uniform()) / side);
        visible += !visibility_->occluded(from, normal, target, sender.normal);
        ++cast;
      }
  };
  pass(options_.min_rays);
  if (visible != 0 && visible != cast) pass(options_.max_rays);
  return static_cast<double>(visible) / cast;
}

bool ProgressiveSolver::shoot_once() {
  const std::uint32_t i = brightest_patch();
  Patch& sender = patches_[i];
  const Rgb shot_radiosity = sender.unshot;
  if (sum(shot_radiosity) <= 0) return false;
  const Rgb shot_power = shot_radiosity * sender.area;
  sender.unshot = Rgb();  // update(i)
  const double lost = lost_fraction(i);

  // shoot(i, *): form factor from every receiver node to the sender.
  const std::size_t n = receivers_.size();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t x = range.begin(); x != range.end(); ++x) {
      double f = point_to_triangle(receivers_.sample_point[x], receivers_.normal[x], sender.corners[0],
                                   sender.corners[1], sender.corners[2], sender.normal);
      if (f > 0) f *= visible_fraction(static_cast<std::uint32_t>(x), sender, i);
      node_form_factor_[x] = f;
    }
  });

  // Power per element, summed in a fixed order so any thread count gives the same sum.
  double received = 0;  // sum of A_q * mean F over elements q: the sender's area it reaches
  for (auto f : scene_.mesh().faces()) {
    if (scene_.patch(f) == i) continue;
    const double mean_ff =
        (node_form_factor_[receivers_.node(f, 0)] + node_form_factor_[receivers_.node(f, 1)] +
         node_form_factor_[receivers_.node(f, 2)]) / 3.0;
    received += scene_.area(f) * mean_ff;
  }
  const double reachable = sender.area * (1 - lost);
  double scale = 0;
  if (received > 0 && reachable > 0) {
    scale = reachable / received;
    form_factor_error_sum_ += std::abs(1 - received / reachable);
  }

  // Receivers gain rho F dB with the point form factor as computed: Lambert's formula
  // is exact at a point, so the normalisation, which corrects the averaging of F over
  // elements, does not apply. Patches gain the reflected power as unshot radiosity.
  for (std::size_t x = 0; x < n; ++x) {
    if (node_form_factor_[x] <= 0) continue;
    const Rgb& rho = scene_.materials()[receivers_.material[x]].reflectance;
    node_radiosity_[x] += rho * shot_radiosity * node_form_factor_[x];
  }
  Rgb incident_total;
  std::uint64_t transfers = 0;
  for (auto f : scene_.mesh().faces()) {
    if (scene_.patch(f) == i) continue;
    ++transfers;
    const double mean_ff =
        (node_form_factor_[receivers_.node(f, 0)] + node_form_factor_[receivers_.node(f, 1)] +
         node_form_factor_[receivers_.node(f, 2)]) / 3.0;
    if (mean_ff <= 0) continue;
    const Rgb incident = shot_radiosity * (scene_.area(f) * mean_ff * scale);
    Patch& receiver = patches_[scene_.patch(f)];
    const Rgb reflected = receiver.reflectance * incident;
    receiver.unshot += reflected * (1.0 / receiver.area);
    report_.energy.absorbed += incident - reflected;
    incident_total += incident;
  }
  // What no front face received: out of the scene, or onto black back faces.
  const Rgb not_received = shot_power - incident_total;
  // In a closed scene (lost == 0) the remainder is rounding only; book it as absorbed
  // so that "escaped" stays exactly zero there.
  const double escaped_share = lost > 0 ? sender.escaped / lost : 0.0;
  report_.energy.escaped += not_received * escaped_share;
  report_.energy.absorbed += not_received * (1 - escaped_share);

  Rgb unshot;
  for (const Patch& p : patches_) unshot += p.unshot * p.area;
  report_.energy.unshot = unshot;
  report_.energy_transfers += transfers;
  ++report_.iterations;
  report_.unshot_history.push_back(unshot_fraction());
  return true;
}

SolveReport ProgressiveSolver::run() {
  using Clock = std::chrono::steady_clock;
  std::unique_ptr<tbb::global_control> threads;
  if (options_.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                    static_cast<std::size_t>(options_.threads));
  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  report_.stopped_by = "converged";
  while (true) {
    if (unshot_fraction() <= options_.converge) break;
    if (options_.max_iterations > 0 && report_.iterations >= options_.max_iterations) {
      report_.stopped_by = "iterations";
      break;
    }
    if (options_.time_limit > 0 && elapsed() >= options_.time_limit) {
      report_.stopped_by = "time limit";
      break;
    }
    if (options_.should_stop && options_.should_stop()) {
      report_.stopped_by = "interrupted";
      break;
    }
    if (!shoot_once()) break;
    if (options_.on_shot) options_.on_shot(report_.iterations, unshot_fraction());
  }
  report_.seconds = elapsed();
  report_.unshot_fraction = unshot_fraction();
  report_.elements = hierarchy_.element_count();
  report_.visibility_rays = visibility_->rays();
  report_.form_factor_sum_error = report_.iterations ? form_factor_error_sum_ / report_.iterations : 0;
  return report_;
}

}  // namespace dynrad::rad
