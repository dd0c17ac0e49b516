// Face clusters in the solver (see solver.h, "Face clusters", and mesh/core/face_clusters.h):
// building them, their verdict in a shot, receiving as one, flushing to their patches,
// and shooting as one sender.
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/random.h"

#include <boost/container/small_vector.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

namespace {

// A cluster this many of its radii from the sender receives as one (solver.h, "Face clusters").
constexpr double kClusterFar = 4.0;

}  // namespace

void Solver::build_clusters() {
  standalone_.clear();
  if (options_.cluster_area > 0 && options_.cluster_radius > 0 && refine_.method != Method::adaptive) {
    FaceClusterOptions o;
    o.small_area = options_.cluster_area;
    o.max_radius = options_.cluster_radius;
    // Patches that emit stay senders of their own: their light is the scene's source.
    clusters_ = build_face_clusters(hierarchy_, o, [this](std::uint32_t p) { return patches_[p].emission.is_zero(); });
  } else {
    clusters_ = FaceClusters{};
    clusters_.part_of_patch.assign(patches_.size(), FaceClusters::kNone);
  }
  for (std::uint32_t p = 0; p < patches_.size(); ++p) {
    patches_[p].clustered = clusters_.clustered(p);
    if (!patches_[p].clustered) standalone_.push_back(p);
  }
  const std::size_t parts = clusters_.parts.size();
  part_unshot_.assign(parts, Rgb());
  part_pending_.assign(parts, Rgb());
  part_form_factor_.assign(parts, 0.0);
  part_reflectance_area_.assign(parts, Rgb());
  for (std::uint32_t p = 0; p < patches_.size(); ++p)
    if (patches_[p].clustered)
      part_reflectance_area_[clusters_.part_of_patch[p]] += patches_[p].reflectance * patches_[p].area;
  cluster_state_.assign(clusters_.clusters.size(), ClusterState{});
  report_.clusters = clusters_.clusters.size();
  report_.clustered_patches = clusters_.members.size();
  report_.cluster_parts = parts;
}

int Solver::cluster_verdict(std::uint32_t c) const {
  if (is_cluster(sender_) && cluster_index(sender_) == c) return 0;  // its own light
  const FaceClusters::Cluster& cl = clusters_.clusters[c];
  double distance = 0;  // from the sender's bounding sphere to the cluster's centre
  if (is_luminaire(sender_)) {
    const Luminaire& l = luminaire(sender_);
    if (l.directional()) return 1;  // from infinitely far
    const double hl = 0.5 * l.opening_length(), hw = 0.5 * l.opening_width();
    distance = (cl.centre - l.position).norm() - std::sqrt(hl * hl + hw * hw);
  } else if (is_cluster(sender_)) {
    distance = (cl.centre - sender_cluster_centre_).norm() - sender_cluster_radius_;
  } else {
    const Patch& sender = patches_[sender_];
    // Exact: the whole cluster is behind the sender's plane.
    if (options_.cull && OpenMesh::dot(sender.normal, cl.centre - sender.corners[0]) <= -cl.radius) return 0;
    distance = (cl.centre - sender_centre_).norm() - sender_radius_;
  }
  return distance >= kClusterFar * cl.radius ? 1 : 2;
}

void Solver::receive_cluster(std::uint32_t c) {
  const FaceClusters::Cluster& cl = clusters_.clusters[c];
  for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) {
    const FaceClusters::Part& part = clusters_.parts[k];
    // Parts have keys of their own, above any vertex index, for their rays' seeds.
    part_form_factor_[k] = point_form_factor_keyed(0x80000000ull + k, part.point, part.normal, sender_, nullptr);
    beat();
  }
}

void Solver::flush_cluster(std::uint32_t c) {
  ClusterState& state = cluster_state_[c];
  if (!state.dirty) return;
  const FaceClusters::Cluster& cl = clusters_.clusters[c];
  for (std::uint32_t n = cl.first_member; n < cl.first_member + cl.member_count; ++n) {
    const std::uint32_t p = clusters_.members[n];
    const Rgb& pending = part_pending_[clusters_.part_of_patch[p]];
    if (pending.is_zero()) continue;
    const Rgb add = patches_[p].reflectance * pending;
    const ElementId root = hierarchy_.patch_root(p);
    for (int k = 0; k < 3; ++k) value_[root][k] += add;
    // Closure may have split the patch (a bigger neighbour refined): the same to all below.
    push_down(root, {add, add, add, add, add, add});
  }
  for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) part_pending_[k] = Rgb();
  state.dirty = false;
}

void Solver::flush_clusters() {
  tbb::parallel_for(std::uint32_t(0), static_cast<std::uint32_t>(clusters_.clusters.size()),
                    [this](std::uint32_t c) { flush_cluster(c); });
}

Rgb Solver::start_cluster_shot(std::uint32_t c) {
  const FaceClusters::Cluster& cl = clusters_.clusters[c];
  Rgb total;
  double magnitude = 0;
  for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) {
    total += part_unshot_[k];
    magnitude += part_unshot_[k].r + part_unshot_[k].g + part_unshot_[k].b;
  }
  const double luminance = total.luminance();
  sender_parts_.clear();
  for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) {
    const FaceClusters::Part& part = clusters_.parts[k];
    const Rgb& u = part_unshot_[k];
    // Shares of the power by luminance (by the sum of channels for light no eye sees).
    const double share = luminance > 0 ? u.luminance() / luminance : magnitude > 0 ? (u.r + u.g + u.b) / magnitude : 0;
    if (share > 0) sender_parts_.push_back({part.point, part.normal, part.area, share});
    part_unshot_[k] = Rgb();
  }
  // Its coefficient channels, all sent (solver_coefficients.cpp).
  const std::size_t channels = coefficients_.count;
  std::fill(coefficient_shot_.begin(), coefficient_shot_.end(), 0.0f);
  for (std::uint32_t k = cl.first_part; channels > 0 && k < cl.first_part + cl.part_count; ++k)
    for (std::size_t j = 0; j < channels; ++j) {
      coefficient_shot_[j] += coefficient_part_unshot_[k * channels + j];
      coefficient_part_unshot_[k * channels + j] = 0;
    }
  sender_cluster_centre_ = cl.centre;
  sender_cluster_radius_ = cl.radius;
  return total;
}

double Solver::cluster_form_factor(const Vec3d& x, const Vec3d& n, std::uint64_t key, bool rays,
                                   double* unoccluded) const {
  // Each part's term: share x cos cos / (pi r^2 + A).
  boost::container::small_vector<double, 64> term(sender_parts_.size());
  double total = 0;
  for (std::size_t s = 0; s < sender_parts_.size(); ++s) {
    const SenderPart& part = sender_parts_[s];
    const Vec3d d = x - part.point;
    const double r2 = d.sqrnorm();
    const double r = std::sqrt(r2);
    const double cos_part = r > 0 ? OpenMesh::dot(part.normal, d) / r : 0.0;
    const double cos_here = r > 0 ? -OpenMesh::dot(n, d) / r : 0.0;
    term[s] = cos_part > 0 && cos_here > 0 ? part.share * cos_part * cos_here / (M_PI * r2 + part.area) : 0.0;
    total += term[s];
  }
  if (unoccluded) *unoccluded = total;
  if (!rays || !(total > 0)) return total;
  // Visibility: rays to parts drawn in proportion to their terms, stratified; a few
  // first, more where those disagree (as for a patch).
  std::uint64_t state = mix(options_.seed ^ mix((key << 32) ^ sender_));
  int visible = 0, cast = 0;
  auto pass = [&](int count) {
    for (int j = 0; j < count; ++j) {
      const double target = (j + uniform(state)) / count * total;
      const SenderPart& part =
          sender_parts_[pick_by_weight(sender_parts_.size(), target, [&](std::size_t s) { return term[s]; })];
      visible += !visibility_->occluded(x, n, part.point, part.normal);
      ++cast;
    }
  };
  pass(options_.min_rays);
  if (visible != 0 && visible != cast) pass(options_.max_rays);
  return total * visible / cast;
}

double Solver::cluster_lost_fraction(std::uint32_t c) {
  ClusterState& state = cluster_state_[c];
  if (state.lost >= 0) return state.lost;
  const auto counts = cluster_escape_counts(c, options_.escape_rays);
  state.escaped = counts[0];
  state.lost = counts[1];
  return state.lost;
}

std::array<double, 2> Solver::cluster_escape_counts(std::uint32_t c, int rays) const {
  const FaceClusters::Cluster& cl = clusters_.clusters[c];
  // From the parts' points, each drawn in proportion to its area.
  const std::uint64_t seed = options_.seed ^ mix(0xC1A5000000000ull + c) ^ (rays == options_.escape_rays ? 0 : 0x5106ull);
  return escape_counts(seed, [this, &cl](std::uint64_t& random, Vec3d& origin, Vec3d& normal) {
                                      double target = uniform(random) * cl.area, running = 0;
                                      std::uint32_t k = cl.first_part;
                                      for (; k + 1 < cl.first_part + cl.part_count; ++k) {
                                        running += clusters_.parts[k].area;
                                        if (running > target) break;
                                      }
                                      origin = clusters_.parts[k].point;
                                      normal = clusters_.parts[k].normal;
                                    }, rays);
}

}  // namespace dynrad::rad
