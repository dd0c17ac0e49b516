#include "mesh/core/soup.h"

#include <unordered_map>

namespace dynrad {

Bounds PolygonSoup::bounds() const {
  Bounds b;
  for (const auto& poly : polygons)
    for (auto v : poly) b.extend(points[v]);
  return b;
}

std::uint32_t PolygonSoup::find_or_add_group(const std::string& name) {
  for (std::size_t i = 0; i < group_names.size(); ++i)
    if (group_names[i] == name) return static_cast<std::uint32_t>(i);
  group_names.push_back(name);
  return static_cast<std::uint32_t>(group_names.size() - 1);
}

int PolygonSoup::find_material(const std::string& name) const {
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == name) return static_cast<int>(i);
  return -1;
}

void PolygonSoup::append(const PolygonSoup& other) {
  const auto point_base = static_cast<std::uint32_t>(points.size());
  const auto file_base = static_cast<std::uint32_t>(files.size());
  points.insert(points.end(), other.points.begin(), other.points.end());
  files.insert(files.end(), other.files.begin(), other.files.end());
  warnings.insert(warnings.end(), other.warnings.begin(), other.warnings.end());

  // By name through hash maps: a model may bring 10^5 materials or groups.
  std::unordered_map<std::string, std::uint32_t> material_index;
  for (std::size_t m = materials.size(); m-- > 0;) material_index[materials[m].name] = static_cast<std::uint32_t>(m);
  std::vector<std::uint32_t> material_map(other.materials.size());
  for (std::size_t m = 0; m < other.materials.size(); ++m) {
    const auto [it, added] =
        material_index.emplace(other.materials[m].name, static_cast<std::uint32_t>(materials.size()));
    if (added) materials.push_back(other.materials[m]);
    // A name one file uses without defining it is defined by the next file that does.
    if (!added && !materials[it->second].defined && other.materials[m].defined)
      materials[it->second] = other.materials[m];
    material_map[m] = it->second;
  }
  std::unordered_map<std::string, std::uint32_t> group_index;
  for (std::size_t g = group_names.size(); g-- > 0;) group_index[group_names[g]] = static_cast<std::uint32_t>(g);
  std::vector<std::uint32_t> group_map(other.group_names.size());
  for (std::size_t g = 0; g < other.group_names.size(); ++g) {
    const auto [it, added] = group_index.emplace(other.group_names[g], static_cast<std::uint32_t>(group_names.size()));
    if (added) group_names.push_back(other.group_names[g]);
    group_map[g] = it->second;
  }

  for (std::size_t i = 0; i < other.polygons.size(); ++i) {
    auto poly = other.polygons[i];
    for (auto& v : poly) v += point_base;
    polygons.push_back(std::move(poly));
    material.push_back(material_map[other.material[i]]);
    group.push_back(group_map[other.group[i]]);
    SourceRef ref = other.origin[i];
    ref.file += file_base;
    origin.push_back(ref);
  }
}

std::string PolygonSoup::where(std::size_t i) const {
  const SourceRef& ref = origin.at(i);
  std::string file = ref.file < files.size() ? files[ref.file] : std::string("<input>");
  if (ref.line > 0) return file + ":" + std::to_string(ref.line);
  return file + " face " + std::to_string(ref.face);
}

}  // namespace dynrad
