#include "radiosity/analysis/tonemap.h"

#include <algorithm>
#include <cmath>

namespace dynrad::rad {

std::uint8_t encode_srgb(double linear) {
  if (!(linear > 0)) return 0;  // also maps NaN to black
  if (linear >= 1) return 255;
  const double encoded = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(encoded * 255.0));
}

double auto_exposure(const std::vector<Rgb>& linear, const std::vector<char>& include,
                     const std::vector<double>& area) {
  std::vector<std::pair<double, double>> luminance;  // and weight
  double total = 0;
  for (std::size_t i = 0; i < linear.size(); ++i)
    if (i >= include.size() || include[i]) {
      const double w = area.empty() ? 1.0 : area[i];
      luminance.emplace_back(linear[i].luminance(), w);
      total += w;
    }
  if (luminance.empty()) return 1.0;
  double reference = 0;
  if (area.empty()) {
    const std::size_t k = std::min(luminance.size() - 1, static_cast<std::size_t>(0.99 * luminance.size()));
    std::nth_element(luminance.begin(), luminance.begin() + static_cast<std::ptrdiff_t>(k), luminance.end());
    reference = luminance[k].first;
  } else {
    std::sort(luminance.begin(), luminance.end());
    double below = 0;
    for (const auto& [value, w] : luminance) {
      reference = value;
      below += w;
      if (below >= 0.99 * total) break;
    }
  }
  return reference > 0 ? 0.9 / reference : 1.0;
}

std::vector<double> vertex_areas(const std::vector<Vec3d>& positions,
                                 const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  std::vector<double> area(positions.size(), 0.0);
  for (const auto& t : triangles) {
    const double a = 0.5 * OpenMesh::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]).norm();
    for (std::uint32_t v : t) area[v] += a / 3;
  }
  return area;
}

VertexValues tone_map(std::vector<Rgb> linear, double exposure, const std::string& name) {
  VertexValues out;
  out.name = name;
  out.display.reserve(linear.size());
  out.quality.reserve(linear.size());
  for (const Rgb& c : linear) {
    out.display.push_back({encode_srgb(c.r * exposure), encode_srgb(c.g * exposure), encode_srgb(c.b * exposure)});
    out.quality.push_back(static_cast<float>(c.luminance()));
  }
  out.linear = std::move(linear);
  return out;
}

}  // namespace dynrad::rad
