// Which receivers a shot visits (Solver::receiving_patches): the receiver tree's ray
// tests cull what the sender cannot see (receiver_tree.h), face clusters are received
// as one or opened (solver_clusters.cpp), and each patch left is culled exactly
// (behind the sender, or the sender behind it) or for a negligible share, or kept:
// then the form factors at its corners are computed at once, the walk's first level.
#include "radiosity/solver/solver.h"

#include "radiosity/sources/daylight.h"
#include "radiosity/transfer/random.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

void Solver::build_tree() {
  // Items: the patches on their own (four points each: their centroid and halfway from
  // it to each corner), then the clusters (their parts' points).
  std::vector<ReceiverTree::Item> items(standalone_.size() + clusters_.clusters.size());
  for (std::size_t n = 0; n < standalone_.size(); ++n) {
    const Patch& p = patches_[standalone_[n]];
    ReceiverTree::Item& item = items[n];
    for (const Vec3d& c : p.corners) item.bounds.extend(c);
    item.pieces.push_back({p.centre, p.normal, p.area / 4});
    for (const Vec3d& c : p.corners) item.pieces.push_back({(p.centre + c) * 0.5, p.normal, p.area / 4});
  }
  for (std::size_t c = 0; c < clusters_.clusters.size(); ++c) {
    const FaceClusters::Cluster& cl = clusters_.clusters[c];
    ReceiverTree::Item& item = items[standalone_.size() + c];
    item.bounds.extend(cl.centre - Vec3d(cl.radius));
    item.bounds.extend(cl.centre + Vec3d(cl.radius));
    for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) {
      const FaceClusters::Part& part = clusters_.parts[k];
      item.pieces.push_back({part.point, part.normal, part.area});
    }
  }
  tree_ = ReceiverTree(items);
}

bool Solver::sender_near(const Bounds& box) const {
  Vec3d centre;
  double radius = 0;
  if (is_luminaire(sender_)) {
    const Luminaire& l = luminaire(sender_);
    centre = l.position;
    radius = 0.5 * std::hypot(l.opening_length(), l.opening_width());
  } else if (is_cluster(sender_)) {
    centre = sender_cluster_centre_;
    radius = sender_cluster_radius_;
  } else {
    centre = sender_centre_;
    radius = sender_radius_;
  }
  // Distance from the sphere's centre to the box, against its radius and a margin of a
  // tenth of the box (a sender at a node's edge sees it at grazing angles).
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double below = box.lo[a] - centre[a], above = centre[a] - box.hi[a];
    const double out = std::max({below, above, 0.0});
    d2 += out * out;
  }
  const double margin = radius + 0.1 * box.diagonal();
  return d2 <= margin * margin;
}

ReceiverTree::Seen Solver::test_node(std::uint32_t node) const {
  const ReceiverTree::Node& n = tree_.node(node);
  if (options_.cull && !is_luminaire(sender_) && !is_cluster(sender_)) {
    // Exact, as receiving_patches() culls one patch: the whole box behind or on the
    // sending patch's plane (a group's patches share it). Without it, the storeys above
    // a ceiling were opened down to their leaves, their samples all facing away (too
    // few to say), and every patch there judged one by one: a cost per shot that grew
    // with the building (the 4-storey office: 38,000 patches a shot).
    const Patch& p = patches_[sender_];
    bool in_front = false;
    for (int corner = 0; corner < 8 && !in_front; ++corner) {
      const Vec3d c((corner & 1) ? n.bounds.hi[0] : n.bounds.lo[0], (corner & 2) ? n.bounds.hi[1] : n.bounds.lo[1],
                    (corner & 4) ? n.bounds.hi[2] : n.bounds.lo[2]);
      in_front = OpenMesh::dot(p.normal, c - p.corners[0]) > 0;
    }
    if (!in_front) return ReceiverTree::Seen::hidden;
  }
  std::uint64_t state = mix(options_.seed ^ mix(0x7EE5000000000ull + node) ^ mix(report_.iterations + 1));
  int facing = 0, visible = 0;
  for (std::uint32_t s = n.first_sample; s < n.first_sample + n.sample_count; ++s) {
    const ReceiverTree::Piece& at = tree_.sample(s);
    Vec3d to, to_normal;
    if (is_luminaire(sender_)) {
      to = luminaire(sender_).position;
      to_normal = at.point - to;
      const double d = to_normal.norm();
      if (!(d > 0)) continue;
      to_normal /= d;
    } else if (is_cluster(sender_)) {
      // a part of the sender, drawn by its share of the power
      double target = uniform(state), running = 0;
      std::size_t k = 0;
      for (; k + 1 < sender_parts_.size(); ++k) {
        running += sender_parts_[k].share;
        if (running > target) break;
      }
      if (sender_parts_.empty()) return ReceiverTree::Seen::untested;
      to = sender_parts_[k].point;
      to_normal = sender_parts_[k].normal;
    } else {
      const Patch& p = patches_[sender_];
      const double u = uniform(state), v = uniform(state);
      to = sender_members_.empty() ? point_on_triangle(p.corners, u, v) : group_sender_point(uniform(state), u, v);
      to_normal = p.normal;
    }
    // Facing each other: the point in front of the sender and the sender in front of it.
    if (OpenMesh::dot(at.normal, to - at.point) <= 0 || OpenMesh::dot(to_normal, at.point - to) <= 0) continue;
    ++facing;
    visible += !visibility_->occluded(at.point, at.normal, to, to_normal);
  }
  // Too few facing points to say: the children are tested instead.
  if (facing < 4) return ReceiverTree::Seen::partly;
  return visible == 0 ? ReceiverTree::Seen::hidden : visible == facing ? ReceiverTree::Seen::wholly
                                                                       : ReceiverTree::Seen::partly;
}

void Solver::sender_ray_hits(std::vector<std::uint32_t>& positions) const {
  // Rows of strata, each with a seed of its own (the same hits for any thread count).
  const int side = kSenderRaySide;
  std::vector<std::vector<std::uint32_t>> rows(side);
  const bool luminaire_sender = is_luminaire(sender_);
  const std::uint64_t seed = mix(options_.seed ^ mix(0x5EE5000000000ull + sender_) ^ mix(report_.iterations + 1));
  const double offset = 1e-6 * scene_.bounds().diagonal();
  tbb::parallel_for(0, side, [&](int i) {
    Rng rng{mix(seed ^ mix(static_cast<std::uint64_t>(i) + 1))};
    for (int j = 0; j < side; ++j) {
      const double u1 = (i + rng.uniform()) / side, u2 = (j + rng.uniform()) / side;
      Vec3d from, dir;
      if (luminaire_sender) {
        // Directions stratified over the sphere; the dark ones are skipped.
        const Luminaire& l = luminaire(sender_);
        const double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * M_PI * u2;
        dir = l.nadir * z + l.c0 * (r * std::cos(phi)) + l.c90 * (r * std::sin(phi));
        if (!(l.intensity_towards(dir) > 0)) continue;
        from = l.position;
      } else {
        Vec3d n;
        if (is_cluster(sender_)) {
          if (sender_parts_.empty()) return;
          const double target = rng.uniform();
          const std::size_t k = pick_by_weight(sender_parts_.size(), target,
                                               [&](std::size_t m) { return std::abs(sender_parts_[m].share); });
          from = sender_parts_[k].point;
          n = sender_parts_[k].normal;
        } else {
          const double a = rng.uniform(), b = rng.uniform();
          from = sender_members_.empty() ? point_on_triangle(patches_[sender_].corners, a, b)
                                         : group_sender_point(rng.uniform(), a, b);
          n = patches_[sender_].normal;
        }
        dir = cosine_direction(n, u1, u2);
        from += n * offset;
      }
      const Visibility::Intersection hit = visibility_->intersect(from, dir);
      if (!hit.hit || !hit.front) continue;
      const std::uint32_t p = hierarchy_.element(hierarchy_.element_of(FaceHandle(hit.face))).patch;
      const std::uint32_t cluster = clusters_.clusters.empty() ? FaceClusters::kNone : clusters_.cluster_of(p);
      std::uint32_t item;
      if (cluster != FaceClusters::kNone) {
        item = static_cast<std::uint32_t>(standalone_.size()) + cluster;
      } else {
        const auto at = std::lower_bound(standalone_.begin(), standalone_.end(), p);
        if (at == standalone_.end() || *at != p) continue;
        item = static_cast<std::uint32_t>(at - standalone_.begin());
      }
      rows[i].push_back(tree_.position(item));
    }
  });
  positions.clear();
  for (const auto& row : rows) positions.insert(positions.end(), row.begin(), row.end());
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
}

void Solver::visible_receivers(std::vector<std::uint32_t>& patches, std::vector<std::uint32_t>& clusters) {
  patches.clear();
  clusters.clear();
  const bool directional = is_luminaire(sender_) && luminaire(sender_).directional();
  if (!options_.cull || directional || tree_.empty()) {
    // (the sky and the sun come from everywhere, or from a direction: no point to test against)
    patches.assign(standalone_.begin(), standalone_.end());
    for (std::uint32_t c = 0; c < clusters_.clusters.size(); ++c) clusters.push_back(c);
    return;
  }
  sender_ray_hits(kept_positions_);
  const ReceiverTree::Visit visit = tree_.visit([this](const Bounds& box) { return sender_near(box); },
                                                [this](std::uint32_t node) { return test_node(node); },
                                                &kept_positions_);
  for (std::uint32_t item : visit.items) {
    if (item < standalone_.size())
      patches.push_back(standalone_[item]);
    else
      clusters.push_back(static_cast<std::uint32_t>(item - standalone_.size()));
  }
  std::sort(patches.begin(), patches.end());
  std::sort(clusters.begin(), clusters.end());
  report_.hidden_receivers += visit.culled_items;
  report_.visibility_tests += visit.tests;
}

void Solver::receiving_patches(std::uint32_t i, std::vector<ElementId>& roots) {
  const bool from_luminaire = is_luminaire(i);
  const bool from_cluster = is_cluster(i);
  const Patch& sender = patches_[from_luminaire || from_cluster ? 0 : i];
  const double per_patch = options_.negligible_share / static_cast<double>(patches_.size());
  // A luminaire: the points that emit (its position, or its opening's corners) and a
  // bound on the share of its flux a patch of area A at distance d can receive,
  // I_peak A / (d^2 flux).
  std::vector<Vec3d> source_points;
  double source_radius = 0, share_per_solid_angle = 0;
  if (from_luminaire) {
    const Luminaire& l = luminaire(i);
    source_points.push_back(l.position);
    const double hl = 0.5 * l.opening_length(), hw = 0.5 * l.opening_width();
    if (hl > 0 || hw > 0)
      for (double a : {-hl, hl})
        for (double b : {-hw, hw}) source_points.push_back(l.position + l.c0 * a + l.c90 * b);
    source_radius = std::sqrt(hl * hl + hw * hw);
    const double flux = luminaire_flux_[i - patches_.size()];
    share_per_solid_angle = flux > 0 ? l.peak_intensity() / flux : 0.0;
  }
  // Clusters first: each is culled, received as one (its parts' form factors computed
  // now), or opened, its patches then judged one by one with the patches on their own.
  std::vector<std::uint32_t>& candidates = candidates_;
  std::vector<std::uint32_t>& seen_clusters = seen_clusters_;
  visible_receivers(candidates, seen_clusters);
  whole_clusters_.clear();
  if (!seen_clusters.empty()) {
    std::vector<int>& verdict = cluster_verdict_;
    verdict.assign(seen_clusters.size(), 0);
    tbb::parallel_for(std::size_t(0), seen_clusters.size(), [&](std::size_t n) {
      const std::uint32_t c = seen_clusters[n];
      verdict[n] = cluster_verdict(c);
      if (verdict[n] == 1) receive_cluster(c);
      if (verdict[n] == 2) flush_cluster(c);  // its patches must hold what it received as one
    });
    for (std::size_t n = 0; n < seen_clusters.size(); ++n) {
      const std::uint32_t c = seen_clusters[n];
      if (verdict[n] == 1) {
        whole_clusters_.push_back(c);
        ++report_.cluster_receptions;
      } else if (verdict[n] == 2) {
        const auto& cl = clusters_.clusters[c];
        candidates.insert(candidates.end(), clusters_.members.begin() + cl.first_member,
                          clusters_.members.begin() + cl.first_member + cl.member_count);
        ++report_.cluster_openings;
      }
    }
  }
  auto in_front = [](const Patch& plane_of, const Patch& other) {
    for (const Vec3d& c : other.corners)
      if (OpenMesh::dot(plane_of.normal, c - plane_of.corners[0]) > 0) return true;
    return false;
  };
  // A group sender: in front of a receiver's plane if any of its patches is.
  auto sender_in_front_of = [&](const Patch& receiver) {
    if (sender_members_.empty()) return in_front(receiver, sender);
    for (const SenderMember& m : sender_members_)
      for (const Vec3d& c : m.corners)
        if (OpenMesh::dot(receiver.normal, c - receiver.corners[0]) > 0) return true;
    return false;
  };
  // Per candidate, in parallel: kept (-1), culled exactly (-2), or the bound it was
  // skipped for (>= 0). The roots and the sums follow in candidate order.
  // The form factors at the corners of every kept patch are computed in the same pass
  // (the walk's first level), which saves a parallel region per shot.
  std::vector<double>& verdict = cull_verdict_;
  verdict.assign(candidates.size(), -1.0);
  tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t n) {
    const std::uint32_t j = candidates[n];
    if (j == i || (!sender_members_.empty() && groups_.group_of[j] == groups_.group_of[i])) {
      verdict[n] = -3.0;  // the sender itself
      return;
    }
    if (from_luminaire && luminaire(i).directional()) {
      // The sky reaches any patch that faces some of it; the sun only those facing it.
      const Luminaire& l = luminaire(i);
      if (options_.cull && l.kind == Luminaire::Kind::sun && OpenMesh::dot(patches_[j].normal, l.daylight->sun) <= 0)
        verdict[n] = -2.0;
      if (verdict[n] == -1.0) compute_corner_form_factors(hierarchy_.patch_root(j));
      return;
    }
    if (options_.cull && from_luminaire) {
      const Patch& receiver = patches_[j];
      // Exact: every point of the source is behind or on the receiver's plane.
      bool seen = false;
      for (const Vec3d& p : source_points) seen = seen || OpenMesh::dot(receiver.normal, p - receiver.corners[0]) > 0;
      if (!seen) {
        verdict[n] = -2.0;
        return;
      }
      const double d = (receiver.centre - source_points[0]).norm() - receiver.radius - source_radius;
      // (never a patch of a shadow outline's strip: tiny, but its corners are shared
      // with the lit and the shaded elements either side, whose light they must carry)
      if (per_patch > 0 && d > 0 && !hierarchy_.element(hierarchy_.patch_root(j)).in_strip) {
        const double bound = share_per_solid_angle * receiver.area / (d * d);
        if (bound < per_patch) {
          verdict[n] = bound;
          return;
        }
      }
    } else if (options_.cull && from_cluster) {
      const Patch& receiver = patches_[j];
      // Exact: the whole cluster is behind the receiver's plane.
      if (OpenMesh::dot(receiver.normal, sender_cluster_centre_ - receiver.corners[0]) <= -sender_cluster_radius_) {
        verdict[n] = -2.0;
        return;
      }
      // Negligible: a part's term is at most its share / (pi d^2).
      const double d = (receiver.centre - sender_cluster_centre_).norm() - receiver.radius - sender_cluster_radius_;
      if (per_patch > 0 && d > 0) {
        const double bound = receiver.area / (M_PI * d * d);
        if (bound < per_patch) {
          verdict[n] = bound;
          return;
        }
      }
    } else if (options_.cull) {
      const Patch& receiver = patches_[j];
      // Exact: every point of the receiver is behind or on the sender's plane (the
      // sender sends nothing there), or the whole sender is behind or on the receiver's
      // plane (the receiver's hemisphere does not hold it). Both give F = 0 at every
      // point, which is what point_to_polygon would compute.
      if (!in_front(sender, receiver) || !sender_in_front_of(receiver)) {
        verdict[n] = -2.0;
        return;
      }
      // Negligible: at any point x of the receiver, F(x -> sender) <= A_i / (pi d^2),
      // with d no more than the distance between the two patches, so the receiver's
      // share of the shot's power, A_j F_avg / A_i, is at most A_j / (pi d^2) (times
      // the largest weight of a shaped sender's parts).
      const double d = (receiver.centre - sender_centre_).norm() - receiver.radius - sender_radius_;
      if (per_patch > 0 && d > 0) {
        const double bound = shape_.max_weight * receiver.area / (M_PI * d * d);
        if (bound < per_patch) {
          verdict[n] = bound;
          return;
        }
      }
    }
    compute_corner_form_factors(hierarchy_.patch_root(j));
  });
  double skipped_share = 0;
  for (std::size_t n = 0; n < candidates.size(); ++n) {
    if (verdict[n] == -3.0) continue;
    if (verdict[n] == -1.0) {
      roots.push_back(hierarchy_.patch_root(candidates[n]));
      continue;
    }
    ++report_.culled_receivers;
    if (verdict[n] >= 0) {
      skipped_share += verdict[n];
      ++report_.negligible_receivers;
    }
  }
  report_.negligible_share_max = std::max(report_.negligible_share_max, skipped_share);
}

}  // namespace dynrad::rad
