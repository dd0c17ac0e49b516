#include "mesh/core/plane_groups.h"

#include <algorithm>
#include <numeric>

namespace dynrad {

PlaneGroups build_plane_groups(const ElementHierarchy& hierarchy, const PlaneGroupOptions& options,
                               const std::function<bool(std::uint32_t)>& eligible) {
  const std::uint32_t count = static_cast<std::uint32_t>(hierarchy.patch_count());
  const TriMesh& mesh = hierarchy.scene().mesh();
  PlaneGroups out;
  out.group_of.assign(count, PlaneGroups::kNone);
  std::vector<std::uint32_t> order;
  for (std::uint32_t p = 0; p < count; ++p)
    if (!eligible || eligible(p)) order.push_back(p);
  auto area = [&](std::uint32_t p) { return hierarchy.element(hierarchy.patch_root(p)).area; };
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return area(a) > area(b); });
  std::vector<char> taken(count, 0);
  for (std::uint32_t p : order) taken[p] = 1;  // 1: eligible and free; 2: in a group
  std::vector<std::uint32_t> members, queue;
  for (std::uint32_t seed : order) {
    if (taken[seed] != 1) continue;
    const ElementId seed_root = hierarchy.patch_root(seed);
    const Vec3d normal = hierarchy.normal(seed_root);
    const FaceHandle seed_face = hierarchy.element(seed_root).face;
    const std::uint32_t material = hierarchy.scene().material_id(seed_face);
    Bounds box;
    for (VertexHandle v : hierarchy.element(seed_root).corners) box.extend(hierarchy.position(v));
    members.assign(1, seed);
    taken[seed] = 2;
    if (options.max_radius > 0) {
      queue.assign(1, seed);
      for (std::size_t next = 0; next < queue.size() && members.size() < options.max_members; ++next) {
        const FaceHandle f = hierarchy.element(hierarchy.patch_root(queue[next])).face;
        for (auto he : mesh.fh_range(f)) {
          if (members.size() >= options.max_members) break;
          const FaceHandle g = mesh.opposite_face_handle(he);
          if (!g.is_valid()) continue;
          const std::uint32_t q = hierarchy.element(hierarchy.element_of(g)).patch;
          if (taken[q] != 1 || hierarchy.scene().material_id(g) != material) continue;
          if (options.small_area > 0 && !(area(q) < options.small_area)) continue;
          const ElementId root = hierarchy.patch_root(q);
          if (OpenMesh::dot(hierarchy.normal(root), normal) < 1 - options.normal_tolerance) continue;
          Bounds grown = box;
          for (VertexHandle v : hierarchy.element(root).corners) grown.extend(hierarchy.position(v));
          if (0.5 * grown.diagonal() > options.max_radius) continue;
          box = grown;
          taken[q] = 2;
          members.push_back(q);
          queue.push_back(q);
        }
      }
    }
    std::sort(members.begin(), members.end());
    PlaneGroups::Group group;
    group.first = static_cast<std::uint32_t>(out.members.size());
    group.count = static_cast<std::uint32_t>(members.size());
    group.centre = (box.lo + box.hi) * 0.5;
    group.radius = 0.5 * box.diagonal();
    for (std::uint32_t m : members) {
      group.area += area(m);
      out.group_of[m] = static_cast<std::uint32_t>(out.groups.size());
    }
    out.members.insert(out.members.end(), members.begin(), members.end());
    out.groups.push_back(group);
  }
  // Numbered by their first (lowest) patch id, as the patches are.
  std::vector<std::uint32_t> by_leader(out.groups.size());
  std::iota(by_leader.begin(), by_leader.end(), 0u);
  std::sort(by_leader.begin(), by_leader.end(), [&](std::uint32_t a, std::uint32_t b) {
    return out.members[out.groups[a].first] < out.members[out.groups[b].first];
  });
  PlaneGroups sorted;
  sorted.group_of.assign(count, PlaneGroups::kNone);
  for (std::uint32_t g : by_leader) {
    PlaneGroups::Group group = out.groups[g];
    const auto first = out.members.begin() + group.first;
    group.first = static_cast<std::uint32_t>(sorted.members.size());
    sorted.members.insert(sorted.members.end(), first, first + group.count);
    for (std::uint32_t n = group.first; n < group.first + group.count; ++n)
      sorted.group_of[sorted.members[n]] = static_cast<std::uint32_t>(sorted.groups.size());
    sorted.groups.push_back(group);
  }
  return sorted;
}

}  // namespace dynrad
