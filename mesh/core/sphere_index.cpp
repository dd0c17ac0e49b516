#include "mesh/core/sphere_index.h"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <boost/iterator/function_output_iterator.hpp>

#include <algorithm>
#include <iterator>

namespace dynrad {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

using Point = bg::model::point<double, 3, bg::cs::cartesian>;
using Box = bg::model::box<Point>;
using Value = std::pair<Box, std::uint32_t>;

struct SphereIndex::Tree {
  bgi::rtree<Value, bgi::quadratic<16>> tree;
};

namespace {
Box box_around(const Vec3d& c, double r) {
  return Box(Point(c[0] - r, c[1] - r, c[2] - r), Point(c[0] + r, c[1] + r, c[2] + r));
}
}  // namespace

SphereIndex::SphereIndex() : tree_(std::make_unique<Tree>()) {}

SphereIndex::~SphereIndex() = default;
SphereIndex::SphereIndex(SphereIndex&&) noexcept = default;
SphereIndex& SphereIndex::operator=(SphereIndex&&) noexcept = default;

void SphereIndex::insert(std::uint32_t id, const Ball& ball) {
  if (balls_.size() <= id) balls_.resize(static_cast<std::size_t>(id) + 1);
  balls_[id] = ball;
  tree_->tree.insert(Value(box_around(ball.centre, ball.radius), id));
}

std::size_t SphereIndex::size() const { return tree_->tree.size(); }

void SphereIndex::near(const Vec3d& x, double distance, std::vector<std::uint32_t>& out) const {
  const std::size_t start = out.size();
  tree_->tree.query(bgi::intersects(box_around(x, distance)),
                    boost::make_function_output_iterator([&](const Value& v) {
                      const Ball& b = balls_[v.second];
                      if ((b.centre - x).norm() < b.radius + distance) out.push_back(v.second);
                    }));
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(start), out.end());
}

}  // namespace dynrad
