// Luminaires: light sources placed in the scene that are not surfaces of the model. A
// photometric luminaire carries a manufacturer's candela distribution (photometry.h);
// a point source sends the same intensity everywhere; a spot sends it within a cone.
//
// Placement. `aim` is where the luminaire's nadir (gamma 0) points. C0 is world +x
// made perpendicular to the aim (world +y when the aim is along x), turned by `spin`
// degrees counter-clockwise seen from behind the luminaire (from above, for one aimed
// down); C90 follows counter-clockwise. So a luminaire aimed straight down with spin 0
// has C0 along +x and C90 along +y.
//
// Units. Intensity in candela, flux in lumens: the solver then works in photometric
// units (radiosity in lm/m^2, see solve_types.h). Light is white: the three channels
// carry the same value, whose luminance (sRGB / Rec. 709 weights, which sum to 1) is
// that value, unless `colour` tints it (scaled to luminance 1, so the flux stays).
#pragma once

#include "mesh/core/types.h"
#include "radiosity/sources/photometry.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace dynrad::rad {

class Visibility;

struct Daylight;

struct Luminaire {
  // sky and sun: daylight (radiosity/sources/daylight.h), from infinitely far; their flux is
  // what reaches the model's surfaces (set by the solver), their colour white.
  enum class Kind { photometric, point, spot, sky, sun };
  Kind kind = Kind::point;
  std::string name;
  Vec3d position{0, 0, 0};
  // Unit frame: nadir (gamma 0), c0 and c90 (nadir x c0 ... see above).
  Vec3d nadir{0, 0, -1}, c0{1, 0, 0}, c90{0, 1, 0};
  double spin = 0;  // degrees, as given
  Rgb colour{1, 1, 1};

  // Photometric: the file's distribution times `scale` (lumens / the file's flux,
  // times the maintenance factor, times the IES tilt factor at the aim's tilt).
  std::shared_ptr<const Photometry> photometry;
  double scale = 1;
  double maintenance_factor = 1;
  double tilt = 0;  // degrees between the aim and straight down (for TILT=INCLUDE)

  // Point and spot: intensity in cd; spot: full intensity within `inner` degrees of the
  // aim, falling smoothly (smoothstep in the angle) to 0 at `outer`.
  double intensity = 0;
  double inner = 0, outer = 0;

  // For the lighting designer: the control group it belongs to (empty: none), its
  // electrical power in W (0: not given), and the share of its flux it gives on
  // emergency supply (EN 1838; 0: not an emergency luminaire, 1: its full flux).
  std::string group;
  double watts = 0;
  double emergency = 0;

  // Sky and sun.
  std::shared_ptr<const Daylight> daylight;
  double daylight_flux = 0;  // lm reaching the model's surfaces, set by the solver
  bool directional() const { return kind == Kind::sky || kind == Kind::sun; }

  // Intensity in cd towards unit direction `d` (from the luminaire).
  double intensity_towards(const Vec3d& d) const;
  // The greatest intensity in any direction (cd), for bounds.
  double peak_intensity() const;
  // Total flux, lm (maintenance and scale included).
  double flux() const;
  // The luminous opening (photometric files only): length along c0, width along c90;
  // a disc of diameter `length` when round. 0 for points.
  double opening_length() const;
  double opening_width() const;
  bool round_opening() const;
  double opening_size() const { return std::max(opening_length(), opening_width()); }
  // A description for `info`: kind, file, flux, where it points.
  std::string describe() const;
};

// Builds the frame from `aim` (need not be unit; must not be zero) and `spin`.
void aim_luminaire(Luminaire& l, const Vec3d& aim, double spin_degrees);

// The "luminaires" array of a JSON scene file (see read_luminaires in
// luminaire_scene.cpp for the keys). Photometric files are read relative to the scene
// file's directory. An empty list when the file is not a scene or has no luminaires.
// Throws InputError naming the scene file and the entry.
std::vector<Luminaire> read_luminaires(const std::string& scene_path);

// Illuminance (lx, per unit of the luminaire's colour) at point x of a surface with
// unit normal n: I(C, gamma) cos(theta) / d^2, unoccluded to *unoccluded, seen returned.
// With `visibility`: one shadow ray to a point source; over a luminous opening larger
// than a fifth of the distance (the far-field rule), one to each of
// kLuminaireOpeningSide^2 stratified samples (jittered from `seed`), each sending an
// equal share of the intensity. Without, no rays and the strata's centres: the
// unoccluded value is returned.
constexpr int kLuminaireOpeningSide = 4;
double luminaire_illuminance(const Visibility* visibility, const Luminaire& l, const Vec3d& x, const Vec3d& n,
                             std::uint64_t seed, double* unoccluded);

// Where a luminaire's light goes first, as shares of its flux: out of the model
// (`escaped`), onto the back of a face (`back`: the luminaire is inside a solid or
// behind a surface), onto the front of one. side x side directions stratified in equal
// solid angles, each weighted by the intensity; seeded, and the same for any thread
// count.
struct LuminaireSurvey {
  double escaped = 0, back = 0, front = 0;
};
LuminaireSurvey survey_luminaire(const Visibility& visibility, const Luminaire& l, int side, std::uint64_t seed);

// Warnings a user should read: each photometric file's own (once per file), then per
// luminaire, by name: inside a solid or behind a surface (more than half its flux
// meets the backs of faces), aimed at nothing (more than three quarters of it leaves
// the model: a point source over an open floor loses half), no light at all.
std::vector<std::string> luminaire_warnings(const Visibility& visibility, const std::vector<Luminaire>& luminaires);

}  // namespace dynrad::rad
