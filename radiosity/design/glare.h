// Discomfort glare from luminaires: the CIE Unified Glare Rating (CIE 117:1995),
//
//   UGR = 8 log10( 0.25 / Lb * sum over sources of L^2 omega / p^2 )
//
// L the luminance of a luminaire's luminous opening towards the eye (cd/m^2), omega
// the solid angle it subtends (sr), p its Guth position index, Lb the background
// luminance (cd/m^2), taken as the indirect illuminance at the eye on a vertical plane
// facing the line of sight, divided by pi.
//
// Two uses: at an observer in a solved scene (observer_glare: luminaires seen from an
// eye, Lb gathered from the solution), and the manufacturer's table for one
// photometry file (tabular_ugr: standard rooms, CIE 190:2010's layout, see
// glare.cpp for how the background is found and how it differs from CIE 190).
//
// Axes: z is up (as luminaire aims and tilts assume). The line of sight is made
// horizontal. The position index is defined only for sources in front of the eye and
// above eye level, within the field of CIE 117's Table 4.1; other luminaires are
// listed with a note and not counted.
//
// Range of the method (CIE 117, as commonly cited): sources subtending about 3e-4 to
// 1e-1 sr, UGR values from 10 to 30; CIE 147:2002 deals separately with small sources
// (projected area below about 0.005 m^2) and large ones (above about 1.5 m^2). Results
// outside these ranges carry a note; a UGR below 10 is reported as "< 10".
#pragma once

#include "radiosity/analysis/grid.h"
#include "radiosity/analysis/lit_scene.h"
#include "radiosity/sources/photometry.h"

#include <string>
#include <vector>

namespace dynrad::rad {

// Guth's position index from CIE 117's Table 4.1, bilinear between its entries:
// `h_over_r` the source's height above the eye over its distance along the line of
// sight, `t_over_r` its lateral offset (either side) over that distance. 0 outside the
// table's field (T/R above 3, H/R above 1.9, next to the void cells that stand for the
// brows, or H/R below 0: under the line of sight).
double guth_position_index(double h_over_r, double t_over_r);

// Kim, Han & Kim's closed-form fit of Guth's index (Light Res. Technol. 2009):
// ln p = (35.2 - 0.31889 tau - 1.22 exp(-2 tau / 9)) 1e-3 sigma
//        + (21 + 0.26667 tau - 0.002963 tau^2) 1e-5 sigma^2,
// tau (degrees) the angle between the vertical plane through the line of sight and
// the plane through the line of sight and the source, sigma (degrees) the angle
// between the line of sight and the source. Within about 7% of the table over most of
// its field (11% at eye level with T/R 3); dynrad uses the table, this is for
// comparison.
double kim_position_index(double tau_deg, double sigma_deg);

// How a luminaire's luminous opening appears from an eye.
struct LuminaireAppearance {
  double intensity = 0;       // cd towards the eye (scale and maintenance included)
  double projected_area = 0;  // m^2: bottom x cos(gamma) + the sides' projections
  double luminance = 0;       // cd/m^2: intensity / projected_area
  double solid_angle = 0;     // sr: projected_area / distance^2
  double distance = 0;
};
// Zero projected area (a point, a spot, a file with no opening): luminance and solid
// angle 0.
LuminaireAppearance luminaire_appearance(const Luminaire& l, const Vec3d& eye);

// The glare index of one set of sources: 8 log10(0.25 / lb * sum), the sum over
// L^2 omega / p^2. 0 when the sum or lb is not above 0 (undefined: see GlareResult).
double unified_glare_rating(double background_luminance, double sum);

struct Observer {
  std::string name;
  Vec3d eye{0, 0, 0};
  Vec3d view{0, 1, 0};  // unit, the line of sight; made horizontal for UGR
  double limit = 0;     // UGR_L to check; 0 none
};

struct GlareSource {
  std::string luminaire;
  double luminance = 0, solid_angle = 0, position_index = 0;
  double term = 0;  // L^2 omega / p^2
  bool counted = false;
  std::string note;  // why it is not counted, or what to know about it
};

struct GlareResult {
  std::string observer;
  double limit = 0;
  double ugr = 0;                    // full precision; reports round (and write "< 10" below 10)
  bool defined = false;              // a counted source with light and a background above 0
  int counted = 0;                   // sources in the sum
  double sum = 0;                    // of their terms
  double background_luminance = 0;   // Lb, cd/m^2
  double indirect_illuminance = 0;   // E_ind at the eye, vertical, facing the line of sight, lx
  std::vector<GlareSource> sources;  // one per luminaire of the scene
  std::vector<std::string> notes;
  // No limit, or the UGR within it; with no light from a counted source there is no
  // glare to limit (with light but no background, there is no bound on it).
  bool met() const {
    if (limit <= 0) return true;
    return defined ? ugr <= limit : !(sum > 0);
  }
};

// UGR at `observer` in a solved scene: every luminaire whose centre the eye sees (one
// shadow ray) and whose position the index covers; Lb from gather_point's indirect
// illuminance at the eye facing the horizontal line of sight.
GlareResult observer_glare(const LitScene& scene, const Observer& observer, const GatherOptions& gather);

// The "observers" array of a JSON scene file (keys in observer_scene.cpp). Empty when
// the file is not a scene or has none. Throws InputError naming the file and entry.
std::vector<Observer> read_observers(const std::string& scene_path);

// The tabular method (CIE 190:2010's standard table) for one luminaire type.
struct UgrRoom {
  double x = 0, y = 0;  // multiples of H: x across the line of sight, y along it
};
struct UgrReflectances {
  double ceiling = 0, walls = 0, floor = 0;
};
struct UgrTable {
  std::string luminaire;  // the file's name for it, or its path
  double flux = 0;        // lm per luminaire the table is for
  double height = 2;      // H, m: the luminaires' plane above the eye
  double spacing = 0.25;  // S / H
  std::vector<UgrRoom> rooms;
  std::vector<UgrReflectances> reflectances;
  // [room][reflectance set]; crosswise: the luminaires' C0 axis (their length) across
  // the line of sight, endwise: along it.
  std::vector<std::vector<double>> crosswise, endwise;
  bool defined = false;  // false when the file gives no luminous opening
  std::vector<std::string> notes;
};

// The standard rooms (19: 2H x 2H to 12H x 8H) and reflectance sets (5).
std::vector<UgrRoom> standard_ugr_rooms();
std::vector<UgrReflectances> standard_ugr_reflectances();

// `flux` lm per luminaire; 0: the file's own. Every value moves by 8 log10(k) when the
// flux is multiplied by k.
UgrTable tabular_ugr(const Photometry& p, double flux = 0);

}  // namespace dynrad::rad
