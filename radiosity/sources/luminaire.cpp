// Luminaire geometry and intensity (the scene file's entries are read in
// luminaire_scene.cpp).
#include "radiosity/sources/luminaire.h"

#include "radiosity/sources/daylight.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynrad::rad {

namespace {

constexpr double kDegree = M_PI / 180.0;

// Spot profile: 1 within `inner` degrees of the axis, 0 beyond `outer`, smoothstep
// in the angle between.
double spot_profile(double gamma_deg, double inner, double outer) {
  if (gamma_deg <= inner) return 1.0;
  if (gamma_deg >= outer) return 0.0;
  const double t = (outer - gamma_deg) / (outer - inner);
  return t * t * (3 - 2 * t);
}

}  // namespace

void aim_luminaire(Luminaire& l, const Vec3d& aim, double spin_degrees) {
  const double length = aim.norm();
  if (!(length > 0) || !std::isfinite(length)) throw std::invalid_argument("the aim must be a non-zero direction");
  l.nadir = aim / length;
  // C0: world +x made perpendicular to the nadir; +y when the nadir is (nearly) along x.
  const Vec3d reference = std::abs(l.nadir[0]) < 0.999 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  Vec3d c0 = reference - l.nadir * OpenMesh::dot(reference, l.nadir);
  c0.normalize();
  // Counter-clockwise seen from behind the luminaire, i.e. about the axis opposite to
  // the nadir ("up" for a downlight): C90 = up x C0.
  const Vec3d up = -l.nadir;
  Vec3d c90 = OpenMesh::cross(up, c0);
  const double s = std::sin(spin_degrees * kDegree), c = std::cos(spin_degrees * kDegree);
  l.c0 = c0 * c + c90 * s;
  l.c90 = OpenMesh::cross(up, l.c0);
  l.spin = spin_degrees;
  // Tilt: the angle between the aim and straight down (-z), for IES tilt factors.
  l.tilt = std::acos(std::clamp(-l.nadir[2], -1.0, 1.0)) / kDegree;
}

double Luminaire::intensity_towards(const Vec3d& d) const {
  const double cos_gamma = std::clamp(OpenMesh::dot(d, nadir), -1.0, 1.0);
  const double gamma = std::acos(cos_gamma) / kDegree;
  switch (kind) {
    case Kind::point:
      return intensity;
    case Kind::spot:
      return intensity * spot_profile(gamma, inner, outer);
    case Kind::sky:
    case Kind::sun:
      return 0;  // from infinitely far: no intensity (see daylight.h)
    case Kind::photometric: {
      double c = std::atan2(OpenMesh::dot(d, c90), OpenMesh::dot(d, c0)) / kDegree;
      if (c < 0) c += 360;
      return scale * photometry->intensity(c, gamma);
    }
  }
  return 0;
}

double Luminaire::peak_intensity() const {
  if (directional()) return 0;
  if (kind != Kind::photometric) return intensity;
  double peak = 0;
  for (double v : photometry->candela) peak = std::max(peak, v);
  return peak * scale;
}

double Luminaire::flux() const {
  switch (kind) {
    case Kind::point:
      return 4 * M_PI * intensity;
    case Kind::spot: {
      // 2 pi times the integral of I(gamma) sin(gamma) over [0, outer] (midpoint rule,
      // 2000 steps: far below 1e-6 relative for the smooth profile).
      const int steps = 2000;
      const double h = outer * kDegree / steps;
      double sum = 0;
      for (int i = 0; i < steps; ++i) {
        const double g = (i + 0.5) * h;
        sum += spot_profile(g / kDegree, inner, outer) * std::sin(g);
      }
      return 2 * M_PI * intensity * sum * h;
    }
    case Kind::photometric:
      return scale * photometry->flux;
    case Kind::sky:
    case Kind::sun:
      return daylight_flux;
  }
  return 0;
}

double Luminaire::opening_length() const { return photometry ? std::abs(photometry->length) : 0.0; }
double Luminaire::opening_width() const {
  if (!photometry) return 0.0;
  return photometry->round ? std::abs(photometry->length) : std::abs(photometry->width);
}
bool Luminaire::round_opening() const { return photometry && photometry->round; }

std::string Luminaire::describe() const {
  if (directional())
    return fmt::format("{}: {}", name, !daylight ? "daylight" : kind == Kind::sky ? daylight->sky_summary : daylight->sun_summary);
  std::string what;
  switch (kind) {
    case Kind::point:
      what = fmt::format("point source, {:.4g} cd", intensity);
      break;
    case Kind::spot:
      what = fmt::format("spot, {:.4g} cd within {:.3g} deg, none beyond {:.3g} deg", intensity, inner, outer);
      break;
    case Kind::photometric:
      what = fmt::format("{} ({}{})", photometry->file, photometry->format,
                         photometry->name.empty() ? "" : ", " + photometry->name);
      break;
    case Kind::sky:
    case Kind::sun:
      break;
  }
  std::string text = fmt::format("{}: {}, {:.5g} lm, at ({:.4g}, {:.4g}, {:.4g})", name, what, flux(), position[0],
                                 position[1], position[2]);
  if (kind != Kind::point)
    text += fmt::format(", aimed at ({:.3g}, {:.3g}, {:.3g}), spin {:.3g} deg", nadir[0], nadir[1], nadir[2], spin);
  if (maintenance_factor != 1) text += fmt::format(", maintenance factor {:.3g}", maintenance_factor);
  return text;
}

}  // namespace dynrad::rad
