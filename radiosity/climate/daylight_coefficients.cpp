// Daylight coefficients at points (see daylight_coefficients.h).
#include "radiosity/climate/daylight_coefficients.h"

#include "radiosity/sources/daylight.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/transfer/visibility.h"

namespace dynrad::rad {

double SkyCoefficients::illuminance(const std::vector<double>& sky) const {
  double sum = 0;
  for (std::size_t k = 0; k < patch.size(); ++k) sum += value[k] * sky[patch[k]];
  return sum;
}

SkyCoefficients direct_sky_coefficients(const Visibility& visibility, const Luminaire& sky,
                                        const SkyPatches& patches, const Vec3d& x, const Vec3d& n, int side) {
  std::vector<double> bins(patches.size() + 1, 0.0);
  const SkyDirectionSink sink = [&](const Vec3d& d, double weight) { bins[patches.index(d)] += weight; };
  daylight_illuminance(&visibility, sky, x, n, nullptr, side, nullptr, &sink);
  SkyCoefficients out;
  for (std::size_t i = 0; i < bins.size(); ++i)
    if (bins[i] > 0) {
      out.patch.push_back(static_cast<std::uint32_t>(i));
      out.value.push_back(static_cast<float>(bins[i]));
    }
  return out;
}

double sun_illuminance(const Visibility& visibility, const Glazing* glazing, const Vec3d& x, const Vec3d& n,
                       const Vec3d& sun, double direct_normal) {
  const double c = OpenMesh::dot(n, sun);
  if (!(c > 0) || !(direct_normal > 0)) return 0;
  if (visibility.trace(x, n, sun) != Visibility::Hit::nothing) return 0;
  return direct_normal * c * (glazing ? glazing->along(x, sun) : 1.0);
}

}  // namespace dynrad::rad
