// How much of a sender's light leaves the scene (openings, an open model): measured
// with rays, once per patch (Solver::lost_fraction).
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/parallel.h"
#include "radiosity/transfer/random.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

namespace {

// Rays for a rough lost fraction (Solver::rough_lost_fraction).
constexpr int kRoughEscapeRays = 64;

}  // namespace

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
        const Vec3d dir = cosine_direction(n, u1, u2);
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

}  // namespace dynrad::rad
