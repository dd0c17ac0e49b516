// The polygon soup: what importers produce and cleanup consumes. No connectivity is
// assumed; polygons are index loops into `points` with per-polygon attributes.
#pragma once

#include "mesh/core/types.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace dynrad {

// Surface properties. Emission is radiant exitance in W/m^2 leaving the front side;
// reflectance is the diffuse (Lambertian) albedo per channel, in [0, 1).
struct Material {
  std::string name;
  Rgb reflectance{0.5};
  Rgb emission{0.0};
  std::string origin;  // "file:line" where it was defined, for messages
  bool defined = true;  // false: referenced (usemtl) but not defined anywhere yet
  // Glazing: the share of light passing straight through (0: opaque). Faces of a
  // material with a transmittance are windows: they are not lit, and light crosses
  // them scaled by it (mesh/load.h keeps them apart as LoadedScene::glazing).
  Rgb transmittance{0.0};

  bool emits() const { return emission.max_channel() > 0; }
  bool transmits() const { return transmittance.max_channel() > 0; }
};

// Where a polygon came from, for messages that point at the user's file.
struct SourceRef {
  std::uint32_t file = 0;  // index into PolygonSoup::files
  std::uint32_t line = 0;  // 1-based line, 0 when the format has no lines
  std::uint32_t face = 0;  // 0-based face index within that file
};

struct PolygonSoup {
  std::vector<Vec3d> points;
  std::vector<std::vector<std::uint32_t>> polygons;
  std::vector<std::uint32_t> material;  // per polygon, index into materials
  std::vector<std::uint32_t> group;     // per polygon, index into group_names
  std::vector<SourceRef> origin;        // per polygon
  std::vector<Material> materials;
  std::vector<std::string> group_names;
  std::vector<std::string> files;
  std::vector<std::string> warnings;  // things the user should know; not fatal

  std::size_t polygon_count() const { return polygons.size(); }
  Bounds bounds() const;
  // Appends `other`, re-indexing points, materials (merged by name: the first
  // definition wins; a name used but not defined takes a later definition), groups and
  // files.
  void append(const PolygonSoup& other);
  std::uint32_t find_or_add_group(const std::string& name);
  // Index of the material with this name, or -1.
  int find_material(const std::string& name) const;
  // Human-readable location of polygon `i` ("room.obj:17" or "room.ply face 3").
  std::string where(std::size_t i) const;
};

// The cleaned result: triangles only, consistent with the input's facing, every
// undirected edge shared by at most two triangles of opposite orientation.
struct TriangleSoup {
  std::vector<Vec3d> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> material;  // per triangle
  std::vector<std::uint32_t> group;     // per triangle
  std::vector<SourceRef> origin;        // per triangle
  std::vector<Material> materials;
  std::vector<std::string> group_names;
  std::vector<std::string> files;
  std::vector<std::string> warnings;
};

}  // namespace dynrad
