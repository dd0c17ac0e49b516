// Closed forms and numerical integrals for the CIE 171:2006 analytical cases, written
// apart from the solver (they share no code with radiosity/ or with its sky, form
// factors or visibility): a validation that reused the solver's own formulas would
// check nothing.
#pragma once

#include "mesh/core/types.h"

#include <array>
#include <vector>

namespace dynrad::validate {

// The configuration factor from a differential area at `x` facing `n` to the polygon
// `corners` (all on the side of x's plane that n points to), by Lambert's contour
// integral: F = 1 / (2 pi) sum over the edges of the angle they subtend at x times the
// cosine between n and the normal of the plane through x and the edge.
double polygon_factor(const Vec3d& x, const Vec3d& n, const std::vector<Vec3d>& corners);

// The CIE standard general sky (ISO 15469 / CIE S 011): luminance relative to the
// zenith's, from the gradation (a, b) and indicatrix (c, d, e) of sky `type` 1-15 and
// the sun's direction. Up is +z.
class GeneralSky {
 public:
  GeneralSky(int type, const Vec3d& sun);
  // Relative luminance towards the unit direction d (0 below the horizon).
  double relative(const Vec3d& d) const;
  // The horizontal illuminance of the whole sky at relative luminance, integrated on a
  // 1440 x 720 grid of azimuth and zenith angle.
  double horizontal() const;

 private:
  double a_, b_, c_, d_, e_;
  Vec3d sun_;
  double at_zenith_ = 1;
};

// The transmittance of a pane of clear glass of refractive index 1.52 whose
// transmittance face on is `normal`, at incidence cos_incidence: the light going back
// and forth between its two surfaces summed term by term for each polarisation
// (Fresnel's reflectances), the absorption along the refracted path found from `normal`
// by bisection.
class ClearGlass {
 public:
  explicit ClearGlass(double normal);
  double operator()(double cos_incidence) const;

 private:
  double one_pass_ = 1, scale_ = 1;  // the share one pass keeps face on; a scale above what surfaces allow
};

// An axis-aligned rectangle in space, for openings and masks: corner `origin`, edges
// `u` and `v` (perpendicular).
struct Rect {
  Vec3d origin, u, v;
};

// True when the segment from x along unit d crosses one of the rectangles.
bool blocked(const std::vector<Rect>& masks, const Vec3d& x, const Vec3d& d);

// Illuminance at x facing n from a sky of luminance L(d) = scale * sky.relative(d)
// seen through `opening` (and past `masks`), by the midpoint rule on cells of 1 cm of
// the opening; glazed with clear glass of transmittance `glass` face on when above 0.
// Below the horizon, a ground of uniform luminance `ground` (cd/m^2): the externally
// reflected component.
double sky_through(const GeneralSky& sky, double scale, const Rect& opening, const std::vector<Rect>& masks,
                   const Vec3d& x, const Vec3d& n, double glass = 0, double ground = 0);

// The same for the traditional CIE overcast sky, L = Lz (1 + 2 cos Z) / 3 with Lz such
// that the unobstructed horizontal illuminance is `horizontal` (Lz = 9 E / (7 pi)).
double overcast_through(double horizontal, const Rect& opening, const std::vector<Rect>& masks, const Vec3d& x,
                        const Vec3d& n, double glass = 0, double ground = 0);

// The illuminance on a plane facing `n` from the whole unobstructed sky above the
// horizon, on a 1440 x 720 grid of azimuth and zenith angle: the flux per area that
// enters an opening facing n.
double sky_on_plane(const GeneralSky& sky, double scale, const Vec3d& n);
double overcast_on_plane(double horizontal, const Vec3d& n);

}  // namespace dynrad::validate
