// Daylight coefficients: the illuminance at a point per unit luminance of each sky
// patch (climate/sky_patches.h), so that any hour's illuminance is the product of its
// sky vector (each patch's mean luminance) with them.
//
// The direct part at a point comes from the same integral as one sky's
// (daylight_illuminance: the hemisphere's directions and the windows as portals, with
// the glass's transmittance), each direction's weight binned to the patch it lies in
// (the ground below the horizon is one more patch). The coefficients hold the model's
// geometry exactly as a direct computation does; what they cannot hold is the sky's
// variation inside a patch, which is why the sky is split finer for the points than
// for the interreflection (DaylightCoefficientOptions).
//
// The sun is not a patch: its direct light at a point is a shadow ray per hour
// (sun_illuminance), as sharp as the sun of a single solve.
#pragma once

#include "mesh/core/types.h"
#include "radiosity/climate/sky_patches.h"

#include <cstdint>
#include <vector>

namespace dynrad::rad {

class Visibility;
class Glazing;
struct Luminaire;

// A point's coefficients, sparse: the patches it sees (ascending) and lx per cd/m^2.
struct SkyCoefficients {
  std::vector<std::uint32_t> patch;
  std::vector<float> value;
  // lx under a sky vector (sky_vector(): one luminance per patch, the ground's last).
  double illuminance(const std::vector<double>& sky) const;
};

// The direct coefficients at x facing n. `sky` is a sky luminaire of the scene (its
// glazing and directions are used, not its luminance, but for deciding where an edge
// of what x sees needs finer directions); `side` as daylight_illuminance's.
SkyCoefficients direct_sky_coefficients(const Visibility& visibility, const Luminaire& sky,
                                        const SkyPatches& patches, const Vec3d& x, const Vec3d& n, int side = 0);

// The sun's direct illuminance at x facing n (lx) for a direct normal illuminance
// `direct_normal` from unit direction `sun`: 0 in shadow, scaled by the glass crossed.
double sun_illuminance(const Visibility& visibility, const Glazing* glazing, const Vec3d& x, const Vec3d& n,
                       const Vec3d& sun, double direct_normal);

}  // namespace dynrad::rad
