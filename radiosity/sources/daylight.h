// Daylight: the sky and the sun as light sources of the same walk as luminaires (they
// are Luminaire kinds `sky` and `sun`, shot first), reaching surfaces through openings
// and glazing.
//
// Glazing. Faces of a material with a transmittance are windows (mesh/load.h keeps
// them out of the lit mesh). Light from outside crossing them is scaled by their
// transmittance (its luminance: tinted glass is not resolved by channel): the given
// value face on, less at oblique incidence as a pane of index 1.52 passes less
// (radiosity/sources/glass.h; 6 mm clear glass of 0.88 face on passes 0.87 at 40 degrees,
// 0.80 at 60, 0.42 at 80). Light from inside leaves through them and is booked as
// escaped. Their reflection is not modelled: light from outside that the pane reflects
// is lost (which is right), and light from inside leaves instead of the 8% (face on)
// to 100% (grazing) that the pane sends back into the room, so a glazed room's
// internally reflected light is somewhat low.
//
// The sun at a point x facing n: E = E_n cos(theta) if the ray from x towards the sun
// leaves the model, times the transmittance of the glass it crosses: exact shadows of
// a point source at infinity.
// The sky at x: E = integral over the hemisphere of n of L(d) T(d) cos(theta) d(omega),
// L the sky model's luminance (the ground's below the horizon), T the transmittance
// along d (0 where d meets a surface of the model). In two parts that share no
// direction:
// - Through the portals: the panes (glass, and the openings of mesh/core/openings.h) that
//   cover at least one stratum's share of x's sky. Each is integrated over its own solid
//   angle (Arvo's map of a spherical triangle, stratum centres), a direction counting
//   for the first pane it crosses. A point beside a wall sees an opening in that wall as
//   a sliver along the wall's plane, which the hemisphere's directions below missed:
//   27-52% low 0.125-0.25 m from a facade (CIE 171 test 5.11's room, tests/daylight_test.cpp).
//   Strata a mask's edge crosses take sub-strata; a pane seen only through a thin gap
//   past a mask (or only at a corner) is integrated again on finer strata where it could
//   matter to x (CIE 171 test 5.13's floor under an overhang).
// - The rest of the hemisphere: side x side strata of cosine-weighted directions, E = pi x
//   their mean, each stratum by its centre, except those where a neighbour sees
//   otherwise (the edge of a surface against the open sky, of a small pane), which take
//   the mean of 8 x 8 sub-strata.
// The directions are the same for every point, so the solution carries no
// point-to-point noise for refinement to chase.
#pragma once

#include "radiosity/sources/glass.h"
#include "radiosity/sources/sky.h"

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

namespace dynrad {
class RayCaster;
struct GlazingTriangle;
}  // namespace dynrad

namespace dynrad::rad {

class Visibility;
struct Luminaire;

// The windows, for rays from inside to outside: the glass, and the openings
// (mesh/core/openings.h) as panes that pass everything. The sky is sampled through each of
// them as a portal (daylight_illuminance).
class Glazing {
 public:
  // Openings that glass covers (a pane in a hole of a wall without thickness) are left
  // out: the glass is their portal.
  explicit Glazing(const std::vector<GlazingTriangle>& triangles,
                   const std::vector<std::array<Vec3d, 3>>& openings = {});
  ~Glazing();
  Glazing(const Glazing&) = delete;
  Glazing& operator=(const Glazing&) = delete;
  // The product of the transmittances of the glass a ray from `origin` along `direction`
  // crosses (1 when none).
  double along(const Vec3d& origin, const Vec3d& direction) const;
  std::size_t size() const { return corners_.size(); }
  // The pane a ray from `origin` along `direction` crosses first, or -1.
  long first(const Vec3d& origin, const Vec3d& direction) const;
  const std::array<Vec3d, 3>& pane(std::size_t i) const { return corners_[i]; }
  const Vec3d& normal(std::size_t i) const { return normals_[i]; }
  // A sphere around pane i: its corners' mean and the farthest corner's distance.
  const Vec3d& centre(std::size_t i) const { return centres_[i]; }
  double radius(std::size_t i) const { return radii_[i]; }
  std::size_t glass_count() const { return glass_panes_.size(); }

 private:
  std::vector<std::array<Vec3d, 3>> corners_;  // the glass first, then the openings
  std::vector<GlassPane> glass_panes_;         // per pane of glass, its transmittance by the angle
  std::vector<Vec3d> normals_, centres_;       // per pane
  std::vector<double> radii_;
  std::unique_ptr<RayCaster> caster_;
};

struct Daylight {
  SkyModel sky;
  Vec3d sun{0, 0, 1};        // unit, towards the sun
  double direct_normal = 0;  // lx, the sun's illuminance on a plane facing it
  std::shared_ptr<const Glazing> glazing;
  int side = 32;             // sky directions per point: side x side
  double horizontal_sky = 0;  // the sky's unobstructed horizontal illuminance (lx), for daylight factors
  std::string sky_summary, sun_summary;  // for logs and the report
  // The sky's unobstructed illuminance per normal (and direction count), as computed.
  mutable std::mutex cache_mutex;
  mutable std::map<std::tuple<long long, long long, long long, int>, double> unobstructed;
};

// Receives every direction a sky's illuminance at a point was summed over, with its
// weight: the illuminance is the sum of weight x the sky's luminance along the
// direction (weights hold the solid angle, the cosine and the glass's transmittance).
// Daylight coefficients bin them by sky patch (climate/daylight_coefficients.h).
using SkyDirectionSink = std::function<void(const Vec3d& direction, double weight)>;

// Illuminance (lx) at x facing n from a sky or sun luminaire; `side` overrides the
// sky's directions when above 0. With `visibility`, shadow rays; without, the
// unobstructed value (also written to *unoccluded). `ground`, when given, receives the
// part that comes from below the horizon (the externally reflected light of the ground).
// `sink` (a sky with `visibility` only) receives the directions that were not blocked.
double daylight_illuminance(const Visibility* visibility, const Luminaire& l, const Vec3d& x, const Vec3d& n,
                            double* unoccluded, int side = 0, double* ground = nullptr,
                            const SkyDirectionSink* sink = nullptr);

// The "sky" section of a JSON scene file, as luminaires (the sun first, when it has a
// direct-normal illuminance, then the sky). Keys:
//   "type"        "cie_overcast" (the default), "cie" (with "number": 1-15), "perez" or
//                 "uniform"
//   "diffuse_horizontal_irradiance", "direct_normal_irradiance" (W/m2): the hour's
//                 weather, for "perez" and required by it (with "sun"): the Perez
//                 all-weather sky and luminous efficacy (radiosity/sources/perez.h)
//   "dew_point"   (C), for "perez": its precipitable water (default 2 cm)
//   "horizontal_illuminance" or "diffuse_horizontal" (lx, from the sky alone), or
//   "zenith_luminance" (cd/m^2); default 10000 lx horizontal, for "perez" the diffuse
//   irradiance times its luminous efficacy
//   "sun"         {"latitude", "longitude", "time": "2026-06-21T12:00", "timezone",
//                  "direct_normal" (lx)} or {"altitude", "azimuth" (degrees, clockwise
//                  from north), "direct_normal"}; for "perez", direct_normal defaults to
//                  the direct irradiance times its luminous efficacy, and the date gives
//                  the Sun-Earth distance (with altitude and azimuth: the mean distance)
//   "ground_reflectance"  default 0.2
//   "north"       [x, y]: north in the plan (default [0, 1]; up is +z)
//   "rays"        sky directions per point in the solve: rays x rays (default 32)
// Throws InputError naming the scene file and the key. None when there is no "sky".
std::vector<Luminaire> read_daylight(const std::string& scene_path, const std::vector<GlazingTriangle>& glazing,
                                     const std::vector<std::array<Vec3d, 3>>& openings = {});

}  // namespace dynrad::rad
