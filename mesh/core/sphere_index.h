// Which of a growing set of balls come within a distance of a point: a bounding-volume
// tree (Boost.Geometry's R-tree) over the balls' boxes.
#pragma once

#include "mesh/core/types.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace dynrad {

class SphereIndex {
 public:
  struct Ball {
    Vec3d centre;
    double radius = 0;
  };
  SphereIndex();
  ~SphereIndex();
  SphereIndex(SphereIndex&&) noexcept;
  SphereIndex& operator=(SphereIndex&&) noexcept;

  // Adds a ball, numbered `id` (ids need not be dense: `near` returns them).
  void insert(std::uint32_t id, const Ball& ball);
  std::size_t size() const;

  // Appends to `out` the index of every ball whose surface comes within `distance` of
  // `x` (its centre is closer than radius + distance), in increasing order.
  void near(const Vec3d& x, double distance, std::vector<std::uint32_t>& out) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
  std::vector<Ball> balls_;  // by id
};

}  // namespace dynrad
