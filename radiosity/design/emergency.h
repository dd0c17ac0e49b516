// Emergency escape lighting, EN 1838:2013, checked by its conventions: the horizontal
// illuminance on the floor (here 1 cm above it) from the luminaires marked
// "emergency", each at its flux on emergency supply, direct light only (no
// reflections, which the standard leaves out so that the result does not depend on
// surfaces' soiling).
//
// Escape routes (up to 2 m wide): along the centre line at least 1 lx, with Emax / Emin
//   at most 40; the central band of half the width at least 0.5 lx. Points every 0.1 m
//   along the line, and across the band at 0, +-w/8 and +-w/4 from it.
// Open (anti-panic) areas: at least 0.5 lx over the floor less a 0.5 m border, with
//   Emax / Emin at most 40. Points on the automatic grid spacing (grid.h), at most 0.5 m.
//
// The scene file's top-level "routes" and "open_areas" (see emergency_scene.cpp).
#pragma once

#include "mesh/core/default_seed.h"
#include "radiosity/design/check.h"
#include "radiosity/analysis/lit_scene.h"

#include <array>
#include <string>
#include <vector>

namespace dynrad::rad {

struct EmergencyArea {
  enum class Kind { route, open_area };
  Kind kind = Kind::route;
  std::string name;
  // A route's centre line, or an open area's outline, in the plan's axes.
  std::vector<std::array<double, 2>> points;
  double width = 2;    // route only, model units
  double floor = 0;    // the floor's height along up
  int up = 2;
  // The standard's minima; routes: centre line and central band.
  double e_min = 1, band_min = 0.5, max_ratio = 40;
};

struct EmergencyResult {
  std::string name;
  EmergencyArea::Kind kind = EmergencyArea::Kind::route;
  std::size_t points = 0;
  double e_min = 0, e_max = 0, band_min = 0;  // centre line (routes) or area; the band (routes)
  double length = 0;                          // routes: of the centre line
  std::vector<Check> checks;
  std::vector<std::string> luminaires;        // the emergency luminaires that light it
  bool met() const { return all_met(checks); }
};

// Throws InputError naming the scene file and the entry. Empty when the scene has none.
std::vector<EmergencyArea> read_emergency_areas(const std::string& scene_path);

// `scene`'s luminaires with emergency > 0 (Luminaire::emergency), at that share of their
// flux. Seeded: the same answer for any thread count.
EmergencyResult check_emergency(const LitScene& scene, const EmergencyArea& area, std::uint64_t seed = default_seed());

}  // namespace dynrad::rad
