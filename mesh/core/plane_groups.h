// Plane groups: neighbouring patches of one flat surface, grouped so that something can
// treat them as one piece of that surface.
//
// Cleanup cuts a building's walls, floors and ceilings wherever another element meets
// them (imprinting), and CAD exports cut them into fans of long thin triangles around
// every opening; each piece becomes a patch. On the IFC house of Debian's
// assimp-testmodels, 18,600 of 32,000 such patches hold less than a 64th of a whole
// patch's area each (13.5 m^2 of 1,600). A group gathers a patch and the small patches
// around it: those that touch it over shared edges (or touch one that joined), lie in
// its plane (facing the same way), have its material, and fit with it in a sphere of a
// given radius.
//
// Groups are grown from the largest patches first (ties: the lower id), each taking its
// neighbours in breadth-first order as long as the group still fits; so the same input
// gives the same groups, numbered in the same order. Every eligible patch is in exactly
// one group (a patch no group could take is a group of its own).
#pragma once

#include "mesh/core/refinement.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace dynrad {

struct PlaneGroupOptions {
  // A group's patches fit in a sphere of this radius (model units) around the middle of
  // their corners' bounding box (0: no grouping, every patch alone).
  double max_radius = 0;
  // Only patches of less area join another's group (model units squared; the patch a
  // group grows from may be of any size): two big patches stay senders of their own,
  // and what is grouped is the slivers and small pieces around them. 0: no limit.
  double small_area = 0;
  // At most this many patches in a group.
  std::size_t max_members = 16;
  // Normals closer than this (1 - cos of the angle) count as facing the same way.
  double normal_tolerance = 1e-9;
};

struct PlaneGroups {
  static constexpr std::uint32_t kNone = UINT32_MAX;
  struct Group {
    std::uint32_t first = 0, count = 0;  // into `members`, in id order
    Vec3d centre{0, 0, 0};               // of the bounding box of its patches' corners
    double radius = 0;                   // of a sphere about `centre` holding every corner
    double area = 0;
  };
  std::vector<Group> groups;
  std::vector<std::uint32_t> members;   // patch ids, group after group
  std::vector<std::uint32_t> group_of;  // per patch: its group, or kNone (not eligible)
};

// Groups of the patches of `hierarchy` for which `eligible` holds (all, when it is
// empty). The hierarchy must not have been refined yet (every patch is one face).
PlaneGroups build_plane_groups(const ElementHierarchy& hierarchy, const PlaneGroupOptions& options,
                               const std::function<bool(std::uint32_t)>& eligible = {});

}  // namespace dynrad
