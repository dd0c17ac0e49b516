// The sky divided into patches, for daylight coefficients.
//
// Tregenza (1987): 145 patches in seven bands of 12 degrees of altitude from the
// horizon (30, 30, 24, 24, 18, 12 and 6 patches) and a cap of 6 degrees round the
// zenith. Reinhart's subdivision MF:n splits every band into n rows and every patch of
// a row into n, keeping the cap whole: 144 n^2 + 1 patches (MF:1 145, MF:2 577, MF:4
// 2305). One more index, size(), stands for the ground below the horizon.
//
// Numbering (ours, not Radiance's): row by row from the horizon up; within a row
// clockwise from north seen from above (north, east, south, west), the first patch
// centred on north. Azimuths are measured clockwise from north in the plane
// perpendicular to `up`; east = north x up.
#pragma once

#include "mesh/core/types.h"

#include <cstddef>
#include <array>
#include <vector>

namespace dynrad::rad {

struct SkyModel;

class SkyPatches {
 public:
  // `subdivision` n >= 1 (Reinhart's MF:n; 1 is Tregenza's). `north` is made
  // perpendicular to `up`. Throws std::invalid_argument for n < 1 or n > 16.
  explicit SkyPatches(int subdivision = 1, const Vec3d& up = {0, 0, 1}, const Vec3d& north = {0, 1, 0});

  int subdivision() const { return n_; }
  // Patches above the horizon; the ground's index is size().
  std::size_t size() const { return first_.back() + 1; }
  std::size_t ground() const { return size(); }
  // The patch a unit direction lies in (ground() below the horizon).
  std::size_t index(const Vec3d& d) const;
  // Solid angle of patch i (sr; the ground's is 2 pi).
  double solid_angle(std::size_t i) const;
  // Its solid angle projected on the horizontal plane (the integral of sin(altitude)
  // over the patch): a patch of luminance L gives L times this on an unobstructed
  // horizontal plane. They sum to pi over the sky.
  double projected_solid_angle(std::size_t i) const;
  // The unit direction to the middle of patch i (in altitude and azimuth).
  Vec3d centre(std::size_t i) const;
  // Altitude and azimuth bounds of patch i (radians; the cap spans every azimuth).
  struct Bounds {
    double altitude0, altitude1, azimuth0, azimuth1;
  };
  Bounds bounds(std::size_t i) const;
  // The unit direction at altitude and azimuth (radians).
  Vec3d direction(double altitude, double azimuth) const;
  // Its inverse for a unit direction: altitude in [-pi/2, pi/2], azimuth in (-pi, pi]
  // (clockwise from north, radians).
  std::array<double, 2> altitude_azimuth(const Vec3d& d) const;

  const Vec3d& up() const { return up_; }
  const Vec3d& north() const { return north_; }

 private:
  int n_;
  Vec3d up_, north_, east_;
  double row_height_;                // radians
  std::vector<int> per_row_;         // patches per row, rows from the horizon up (the cap not included)
  std::vector<std::size_t> first_;   // index of each row's first patch; last: the cap's
};

// The mean luminance of each patch under `sky` (cd/m^2), and the ground's last: over
// side x side points per patch spread evenly in solid angle (altitude by its sine, and
// azimuth). 8 x 8 points put the mean of a smooth sky within about 1e-4.
std::vector<double> sky_vector(const SkyPatches& patches, const SkyModel& sky, int side = 8);

}  // namespace dynrad::rad
