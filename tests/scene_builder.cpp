#include "scene_builder.h"

#include <cmath>

namespace dynrad::test {

SceneBuilder::SceneBuilder() {
  soup_.files.push_back("generated");
  soup_.group_names.push_back("scene");
}

std::uint32_t SceneBuilder::material(const std::string& name, double reflectance, double emission) {
  const int found = soup_.find_material(name);
  if (found >= 0) return static_cast<std::uint32_t>(found);
  soup_.materials.push_back(Material{name, Rgb(reflectance), Rgb(emission), "test", true});
  return static_cast<std::uint32_t>(soup_.materials.size() - 1);
}

void SceneBuilder::group(const std::string& name) { current_group_ = soup_.find_or_add_group(name); }

void SceneBuilder::quad(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d, std::uint32_t material) {
  std::vector<std::uint32_t> loop;
  for (const Vec3d& p : {a, b, c, d}) {
    soup_.points.push_back(p);
    loop.push_back(static_cast<std::uint32_t>(soup_.points.size() - 1));
  }
  soup_.polygons.push_back(loop);
  soup_.material.push_back(material);
  soup_.group.push_back(current_group_);
  soup_.origin.push_back(SourceRef{0, 0, static_cast<std::uint32_t>(soup_.polygons.size() - 1)});
}

void SceneBuilder::box(const Vec3d& lo, const Vec3d& hi, std::uint32_t material, Facing facing,
                       std::array<bool, 6> skip) {
  auto p = [&](int i, int j, int k) { return Vec3d(i ? hi[0] : lo[0], j ? hi[1] : lo[1], k ? hi[2] : lo[2]); };
  // Counter-clockwise seen from outside.
  const std::array<std::array<Vec3d, 4>, 6> faces = {{
      {p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0)},  // -x
      {p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)},  // +x
      {p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)},  // -y
      {p(0, 1, 0), p(0, 1, 1), p(1, 1, 1), p(1, 1, 0)},  // +y
      {p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0)},  // -z
      {p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)},  // +z
  }};
  for (int k = 0; k < 6; ++k) {
    if (skip[k]) continue;
    const auto& f = faces[k];
    if (facing == outward)
      quad(f[0], f[1], f[2], f[3], material);
    else
      quad(f[3], f[2], f[1], f[0], material);
  }
}

void SceneBuilder::rectangle(double x0, double y0, double x1, double y1, double z, int facing, std::uint32_t material) {
  const Vec3d a(x0, y0, z), b(x1, y0, z), c(x1, y1, z), d(x0, y1, z);
  if (facing > 0)
    quad(a, b, c, d, material);
  else
    quad(d, c, b, a, material);
}

PolygonSoup SceneBuilder::transformed(double degrees, const Vec3d& shift) const {
  PolygonSoup soup = soup_;
  const Vec3d axis = Vec3d(1, 2, 3).normalized();
  const double angle = degrees * M_PI / 180, c = std::cos(angle), s = std::sin(angle);
  for (Vec3d& p : soup.points) {  // Rodrigues' rotation
    p = p * c + OpenMesh::cross(axis, p) * s + axis * (OpenMesh::dot(axis, p) * (1 - c)) + shift;
  }
  return soup;
}

}  // namespace dynrad::test
