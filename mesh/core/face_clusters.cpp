#include "mesh/core/face_clusters.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dynrad {
namespace {

struct Candidate {
  std::uint32_t patch;
  Vec3d centroid;
  Bounds bounds;  // of its corners
};

class Builder {
 public:
  Builder(const ElementHierarchy& h, const FaceClusterOptions& o) : h_(h), o_(o) {
    out_.part_of_patch.assign(h.patch_count(), FaceClusters::kNone);
    in_cluster_.assign(h.patch_count(), 0);
    assigned_.assign(h.patch_count(), 0);
    cos_part_ = std::cos(o.part_angle * M_PI / 180);
  }

  FaceClusters run(std::vector<Candidate> candidates) {
    items_ = std::move(candidates);
    if (!items_.empty()) split(0, items_.size(), false);
    return std::move(out_);
  }

 private:
  // Cuts items_[begin, end) until each piece fits a cluster (radius, members, parts).
  void split(std::size_t begin, std::size_t end, bool must_cut) {
    Bounds box, centroids;
    for (std::size_t i = begin; i < end; ++i) {
      box.extend(items_[i].bounds.lo);
      box.extend(items_[i].bounds.hi);
      centroids.extend(items_[i].centroid);
    }
    const std::size_t count = end - begin;
    const Vec3d spread = centroids.extent();
    const bool can_cut = count > 1 && spread.max() > 0;
    const bool fits = 0.5 * box.diagonal() <= o_.max_radius && count <= o_.max_members;
    if (!can_cut || (fits && !must_cut)) {
      if (!make_cluster(begin, end, box) && can_cut) split(begin, end, true);
      return;
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (spread[a] > spread[axis]) axis = a;
    const std::size_t middle = begin + count / 2;
    std::nth_element(items_.begin() + static_cast<std::ptrdiff_t>(begin),
                     items_.begin() + static_cast<std::ptrdiff_t>(middle),
                     items_.begin() + static_cast<std::ptrdiff_t>(end), [axis](const Candidate& a, const Candidate& b) {
                       return a.centroid[axis] < b.centroid[axis] ||
                              (a.centroid[axis] == b.centroid[axis] && a.patch < b.patch);
                     });
    split(begin, middle, false);
    split(middle, end, false);
  }

  // Makes items_[begin, end) a cluster with its parts; false (and nothing made) when it
  // would have too many parts.
  bool make_cluster(std::size_t begin, std::size_t end, const Bounds& box) {
    std::vector<std::uint32_t> members;
    for (std::size_t i = begin; i < end; ++i) members.push_back(items_[i].patch);
    std::sort(members.begin(), members.end());
    const auto cluster = static_cast<std::uint32_t>(out_.clusters.size());
    // Parts: grown from each member not yet in one, over shared edges, to members of
    // this cluster facing within the angle of the seed.
    for (std::uint32_t p : members) in_cluster_[p] = cluster + 1;
    std::vector<std::vector<std::uint32_t>> parts;
    std::vector<std::uint32_t> stack;
    const TriMesh& mesh = h_.scene().mesh();
    for (std::uint32_t seed : members) {
      if (assigned_[seed] == cluster + 1) continue;
      const Vec3d n0 = h_.normal(h_.patch_root(seed));
      parts.emplace_back();
      stack.assign(1, seed);
      assigned_[seed] = cluster + 1;
      while (!stack.empty()) {
        const std::uint32_t p = stack.back();
        stack.pop_back();
        parts.back().push_back(p);
        const FaceHandle f = h_.element(h_.patch_root(p)).face;
        for (auto he : mesh.fh_range(f)) {
          const FaceHandle g = mesh.opposite_face_handle(he);
          if (!g.is_valid()) continue;
          const std::uint32_t q = h_.element(h_.element_of(g)).patch;
          if (in_cluster_[q] != cluster + 1 || assigned_[q] == cluster + 1) continue;
          if (OpenMesh::dot(h_.normal(h_.patch_root(q)), n0) < cos_part_) continue;
          assigned_[q] = cluster + 1;
          stack.push_back(q);
        }
      }
    }
    if (parts.size() > o_.max_parts && members.size() > 1) {
      // Undo the marks: the pieces are numbered again as clusters of their own.
      for (std::uint32_t p : members) in_cluster_[p] = assigned_[p] = 0;
      return false;
    }
    FaceClusters::Cluster c;
    c.centre = (box.lo + box.hi) * 0.5;
    c.radius = 0.5 * box.diagonal();
    c.first_member = static_cast<std::uint32_t>(out_.members.size());
    c.member_count = static_cast<std::uint32_t>(members.size());
    c.first_part = static_cast<std::uint32_t>(out_.parts.size());
    c.part_count = static_cast<std::uint32_t>(parts.size());
    for (auto& part : parts) {
      std::sort(part.begin(), part.end());
      FaceClusters::Part made;
      made.cluster = cluster;
      Vec3d normal(0, 0, 0), centroid(0, 0, 0);
      for (std::uint32_t p : part) {
        const ElementId root = h_.patch_root(p);
        const double a = h_.element(root).area;
        made.area += a;
        normal += h_.normal(root) * a;
        centroid += h_.centroid(root) * a;
      }
      const double n = normal.norm();
      made.normal = n > 0 ? normal / n : h_.normal(h_.patch_root(part.front()));
      if (made.area > 0) centroid /= made.area;
      double best = -1;
      for (std::uint32_t p : part) {
        const double d = (h_.centroid(h_.patch_root(p)) - centroid).sqrnorm();
        if (best < 0 || d < best) {
          best = d;
          made.patch = p;
        }
      }
      made.point = h_.centroid(h_.patch_root(made.patch));
      const auto id = static_cast<std::uint32_t>(out_.parts.size());
      for (std::uint32_t p : part) out_.part_of_patch[p] = id;
      c.area += made.area;
      out_.parts.push_back(made);
    }
    out_.members.insert(out_.members.end(), members.begin(), members.end());
    out_.clusters.push_back(c);
    return true;
  }

  const ElementHierarchy& h_;
  const FaceClusterOptions& o_;
  double cos_part_ = 1;
  std::vector<Candidate> items_;
  FaceClusters out_;
  std::vector<std::uint32_t> in_cluster_, assigned_;  // per patch: cluster + 1 while building
};

}  // namespace

std::vector<double> facet_areas(const ElementHierarchy& h) {
  const TriMesh& mesh = h.scene().mesh();
  std::vector<double> area(h.patch_count(), 0.0);
  std::vector<std::uint32_t> facet(h.patch_count(), UINT32_MAX), stack, members;
  for (std::uint32_t seed = 0; seed < h.patch_count(); ++seed) {
    if (facet[seed] != UINT32_MAX) continue;
    const Vec3d n = h.normal(h.patch_root(seed));
    members.clear();
    stack.assign(1, seed);
    facet[seed] = seed;
    double total = 0;
    while (!stack.empty()) {
      const std::uint32_t p = stack.back();
      stack.pop_back();
      members.push_back(p);
      const Element& el = h.element(h.patch_root(p));
      total += el.area;
      if (!el.is_leaf()) continue;
      for (auto he : mesh.fh_range(el.face)) {
        const FaceHandle g = mesh.opposite_face_handle(he);
        if (!g.is_valid()) continue;
        const std::uint32_t q = h.element(h.element_of(g)).patch;
        if (facet[q] != UINT32_MAX || OpenMesh::dot(h.normal(h.patch_root(q)), n) < 1 - 1e-9) continue;
        facet[q] = seed;
        stack.push_back(q);
      }
    }
    for (std::uint32_t p : members) area[p] = total;
  }
  return area;
}


FaceClusters build_face_clusters(const ElementHierarchy& hierarchy, const FaceClusterOptions& options,
                                 const std::function<bool(std::uint32_t)>& eligible) {
  std::vector<Candidate> candidates;
  if (options.small_area > 0 && options.max_radius > 0) {
    const std::vector<double> facet = facet_areas(hierarchy);
    for (std::uint32_t p = 0; p < hierarchy.patch_count(); ++p) {
      const ElementId root = hierarchy.patch_root(p);
      const Element& el = hierarchy.element(root);
      if (!el.is_leaf() || !(facet[p] < options.small_area) || (eligible && !eligible(p))) continue;
      Candidate c{p, hierarchy.centroid(root), {}};
      double reach = 0;
      for (VertexHandle v : el.corners) {
        c.bounds.extend(hierarchy.position(v));
        reach = std::max(reach, (hierarchy.position(v) - c.centroid).norm());
      }
      // A long sliver is small in area but not in extent: it stays a patch of its own.
      if (reach > 0.5 * options.max_radius) continue;
      candidates.push_back(c);
    }
  }
  Builder builder(hierarchy, options);
  return builder.run(std::move(candidates));
}

}  // namespace dynrad
