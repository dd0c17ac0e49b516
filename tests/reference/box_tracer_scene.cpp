// Building a BoxScene (box_tracer.h): each box and emitter checked as it is added.
#include "reference/box_tracer.h"
#include "reference/box_tracer_internal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dynrad_test::reference {
using namespace detail;
namespace {

// ---------------------------------------------------------------------------------
// Building a scene.

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("box scene: " + what);
}

void check_reflectance(double rho, const std::string& what) {
  require(rho >= 0 && rho < 1, what + " reflectance " + std::to_string(rho) + " is not in [0, 1)");
}

}  // namespace

Reflectances Reflectances::uniform(double rho) { return {{rho, rho, rho, rho, rho, rho}}; }

Reflectances Reflectances::walls_floor_ceiling(double walls, double floor, double ceiling) {
  return {{walls, walls, walls, walls, floor, ceiling}};
}

int BoxScene::add_box(const Vec3& lo, const Vec3& hi, bool room, const Reflectances& reflectance) {
  const std::string name = "box " + std::to_string(boxes_.size());
  for (int c = 0; c < 3; ++c)
    require(std::isfinite(lo[c]) && std::isfinite(hi[c]) && lo[c] < hi[c],
            name + " from " + text(lo) + " to " + text(hi) + " is empty or not finite: need lo < hi on every axis");
  for (double rho : reflectance.of_face) check_reflectance(rho, name);
  boxes_.push_back({lo, hi, room, reflectance});
  return static_cast<int>(boxes_.size()) - 1;
}

int BoxScene::add_room(const Vec3& lo, const Vec3& hi, const Reflectances& reflectance) {
  return add_box(lo, hi, true, reflectance);
}

int BoxScene::add_solid(const Vec3& lo, const Vec3& hi, const Reflectances& reflectance) {
  return add_box(lo, hi, false, reflectance);
}

void BoxScene::add_emitter(int box, Face face, const Vec3& lo, const Vec3& hi, double exitance, double reflectance) {
  const std::string name = "emitter " + std::to_string(emitters_.size());
  require(box >= 0 && box < static_cast<int>(boxes_.size()),
          name + " is on box " + std::to_string(box) + ", which does not exist");
  require(std::isfinite(exitance) && exitance >= 0, name + " has exitance " + std::to_string(exitance));
  check_reflectance(reflectance, name);
  const Box& b = boxes_[box];
  const int axis = axis_of(face);
  const double plane = on_plus_side(face) ? b.hi[axis] : b.lo[axis];
  Emitter e{box, face, lo, hi, exitance, reflectance};
  for (int c = 0; c < 3; ++c) {
    e.lo[c] = std::min(lo[c], hi[c]);
    e.hi[c] = std::max(lo[c], hi[c]);
    if (c == axis) {
      require(lo[c] == plane && hi[c] == plane, name + " from " + text(lo) + " to " + text(hi) +
                                                    " is not in the plane of its face (coordinate " +
                                                    std::to_string(c) + " = " + std::to_string(plane) + ")");
    } else {
      require(e.lo[c] < e.hi[c] && b.lo[c] <= e.lo[c] && e.hi[c] <= b.hi[c],
              name + " from " + text(lo) + " to " + text(hi) + " is empty or reaches outside its face");
    }
  }
  for (const Emitter& other : emitters_) {
    if (other.box != box || other.face != face) continue;
    bool overlap = true;
    for (int c = 0; c < 3; ++c)
      if (c != axis) overlap = overlap && e.lo[c] < other.hi[c] && other.lo[c] < e.hi[c];
    require(!overlap, name + " overlaps another emitter on the same face");
  }
  emitters_.push_back(e);
}

void BoxScene::add_emitter(int box, Face face, double exitance, double reflectance) {
  require(box >= 0 && box < static_cast<int>(boxes_.size()),
          "emitter on box " + std::to_string(box) + ", which does not exist");
  const Box& b = boxes_[box];
  const int axis = axis_of(face);
  Vec3 lo = b.lo, hi = b.hi;
  lo[axis] = hi[axis] = on_plus_side(face) ? b.hi[axis] : b.lo[axis];
  add_emitter(box, face, lo, hi, exitance, reflectance);
}

}  // namespace dynrad_test::reference
