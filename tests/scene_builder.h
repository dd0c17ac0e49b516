// Polygon soups built in code for tests: quads and boxes as architects' models have
// them (closed solids facing outward, rooms facing inward, sheets).
#pragma once

#include "mesh/core/soup.h"

#include <array>
#include <string>

namespace dynrad::test {

class SceneBuilder {
 public:
  SceneBuilder();
  // Adds (or finds) a material; returns its index.
  std::uint32_t material(const std::string& name, double reflectance, double emission = 0);
  // Starts a new group (element); later faces belong to it.
  void group(const std::string& name);
  // A quad a-b-c-d, counter-clockwise seen from its front.
  void quad(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d, std::uint32_t material);
  // An axis-aligned box [lo, hi]: faces outward (a solid) or inward (a room). Faces in
  // the order -x, +x, -y, +y, -z, +z; `skip[k]` leaves face k out.
  enum Facing { outward, inward };
  void box(const Vec3d& lo, const Vec3d& hi, std::uint32_t material, Facing facing = outward,
           std::array<bool, 6> skip = {});
  // A horizontal rectangle at height z facing up (+1) or down (-1).
  void rectangle(double x0, double y0, double x1, double y1, double z, int facing, std::uint32_t material);

  // The same scene turned about the axis (1, 2, 3) by `degrees` and moved by `shift`.
  PolygonSoup transformed(double degrees, const Vec3d& shift) const;
  const PolygonSoup& soup() const { return soup_; }

 private:
  PolygonSoup soup_;
  std::uint32_t current_group_ = 0;
};

}  // namespace dynrad::test
