// The analytical cases of CIE 171:2006 section 5, rebuilt from their public
// descriptions as dynrad scenes, each with its reference (reference.h) and goal. Where
// the descriptions leave a detail open (sizes, intensities, points, sun positions),
// `choices` says what was chosen. `dynrad validate` (plugin/cli/cmd_validate.cpp) solves
// them as a user would and compares.
#pragma once

#include "mesh/core/types.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace dynrad::validate {

// A region of the lit mesh whose illuminance is integrated: the triangles whose
// centroid lies in the box [lo, hi] and that face `normal` (any facing when zero).
// Compared: the integral (lm) less `base`, against `reference` less `base` (the part
// under test: the indirect light of a cube over its direct share); when that is 0,
// against `base`.
struct AreaCheck {
  std::string label;
  Vec3d lo, hi, normal{0, 0, 0};
  double reference = 0, base = 0;
};

struct Case {
  std::string id;       // the section: "5.2"
  std::string variant;  // within it: "CIE sky 12", "reflectance 0.8"; may be empty
  std::string title, choices;
  double goal = 0.01;          // largest relative error allowed at any point (this project's)
  double cie_tolerance = 0.05;  // what CIE 171 allows (per point)
  std::vector<std::pair<std::string, std::string>> files;  // name, contents; the first is solved
  std::vector<std::string> options;                        // of `dynrad solve`
  // The reference illuminance (lx) at a point facing a direction.
  std::function<double(const Vec3d&, const Vec3d&)> reference;
  // Points of the lit mesh compared (point, normal), read with `dynrad probe`.
  std::vector<std::pair<Vec3d, Vec3d>> mesh_points;
  // The scene's grids compared (every point of each, facing up), by name.
  std::vector<std::string> grids;
  std::vector<AreaCheck> areas;
};

// Every case, in the order of the document's sections.
std::vector<Case> cie171_cases();

}  // namespace dynrad::validate
