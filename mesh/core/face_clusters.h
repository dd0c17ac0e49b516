// Face clusters: small patches grouped by place into clusters that can stand for all
// their patches at once (Willmott, Heckbert & Garland 1999 build clusters from a mesh's
// faces for hierarchical radiosity; these are flat groups of the patches of
// ElementHierarchy, built once before any refinement).
//
// Architects' models are made of small parts: window frames, railings, handles, chair
// legs. Each is a handful of small triangles, and each triangle is a patch. A cluster
// gathers the small patches within a sphere of a given radius; inside a cluster, the
// patches that touch (share an edge) and face the same way to within an angle form a
// part. A part is represented by one point on its surface (the centroid of the patch
// nearest to the part's centroid) and its area-weighted normal, so a cluster of a
// thousand triangles may be a few dozen parts.
//
// Parts never join across a gap: the handle on each side of a door, the skirting on
// each side of a wall are parts of their own, even when one cluster holds both, so that
// what one side receives is not given to the other.
#pragma once

#include "mesh/core/refinement.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace dynrad {

struct FaceClusterOptions {
  // Patches whose facet (the patches that touch and lie in one plane) has less area
  // join clusters (0: none does). A wall that CAD cut into strips is one big facet and
  // stays a set of patches of its own; a frame's profile or a chair's leg is small.
  double small_area = 0;
  // A cluster's bounding sphere has at most this radius (model units).
  double max_radius = 0;
  // A cluster holds at most this many patches and this many parts; a bigger group is cut.
  std::size_t max_members = 256;
  std::size_t max_parts = 64;
  // Degrees: a part's patches face within this angle of its first patch's normal.
  double part_angle = 20;
};

struct FaceClusters {
  static constexpr std::uint32_t kNone = UINT32_MAX;
  struct Part {
    Vec3d point;   // on the surface: the centroid of patch `patch`
    Vec3d normal;  // area-weighted mean of its patches' normals, unit
    double area = 0;
    std::uint32_t cluster = 0;
    std::uint32_t patch = 0;  // the patch `point` lies on
  };
  struct Cluster {
    Vec3d centre{0, 0, 0};
    double radius = 0;  // of a sphere about `centre` holding every corner of its patches
    double area = 0;
    std::uint32_t first_member = 0, member_count = 0;  // into `members`
    std::uint32_t first_part = 0, part_count = 0;      // into `parts`
  };
  std::vector<Cluster> clusters;
  std::vector<Part> parts;
  std::vector<std::uint32_t> members;        // patch ids, cluster after cluster
  std::vector<std::uint32_t> part_of_patch;  // per patch: its part, or kNone (the patch stands alone)

  bool clustered(std::uint32_t patch) const { return part_of_patch[patch] != kNone; }
  std::uint32_t cluster_of(std::uint32_t patch) const {
    const std::uint32_t p = part_of_patch[patch];
    return p == kNone ? kNone : parts[p].cluster;
  }
};

// Per patch of `hierarchy` (not refined yet), the area of its facet: the patches
// reached from it over shared edges between patches facing the same way (normals equal
// to 1e-9). A wall that CAD cut into strips is one facet; a chair leg's side is another.
std::vector<double> facet_areas(const ElementHierarchy& hierarchy);

// Clusters of the patches of `hierarchy` whose facets are smaller than
// options.small_area and for which `eligible` holds (all, when it is empty). The hierarchy must not have been
// refined yet (every patch is one face). Deterministic: the same input gives the same
// clusters, numbered in the same order.
FaceClusters build_face_clusters(const ElementHierarchy& hierarchy, const FaceClusterOptions& options,
                                 const std::function<bool(std::uint32_t)>& eligible = {});

}  // namespace dynrad
