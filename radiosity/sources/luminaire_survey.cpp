// Where luminaires' light goes first (survey_luminaire), the placement warnings built
// on it, and the illuminance a luminaire gives a point (luminaire_illuminance).
#include "radiosity/sources/luminaire.h"

#include "radiosity/sources/daylight.h"
#include "radiosity/transfer/random.h"
#include "radiosity/transfer/visibility.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <set>

namespace dynrad::rad {

LuminaireSurvey survey_luminaire(const Visibility& visibility, const Luminaire& l, int side, std::uint64_t seed) {
  if (l.directional()) {  // its flux is defined as what reaches the model's surfaces
    LuminaireSurvey all;
    all.front = 1;
    return all;
  }
  std::vector<std::array<double, 4>> rows(static_cast<std::size_t>(side));  // weight, escaped, back, front
  tbb::parallel_for(0, side, [&](int a) {
    std::uint64_t state = mix(seed ^ mix(static_cast<std::uint64_t>(a) + 1));
    std::array<double, 4> row{0, 0, 0, 0};
    for (int b = 0; b < side; ++b) {
      const double z = 1 - 2 * (a + uniform(state)) / side, phi = 2 * M_PI * (b + uniform(state)) / side;
      const double s = std::sqrt(std::max(0.0, 1 - z * z));
      const Vec3d dir = l.nadir * z + l.c0 * (s * std::cos(phi)) + l.c90 * (s * std::sin(phi));
      const double w = l.intensity_towards(dir);
      if (!(w > 0)) continue;
      row[0] += w;
      switch (visibility.trace(l.position, dir, dir)) {
        case Visibility::Hit::nothing: row[1] += w; break;
        case Visibility::Hit::back: row[2] += w; break;
        case Visibility::Hit::front: row[3] += w; break;
      }
    }
    rows[static_cast<std::size_t>(a)] = row;
  });
  std::array<double, 4> total{0, 0, 0, 0};
  for (const auto& row : rows)  // in order: the same sums for any number of threads
    for (int k = 0; k < 4; ++k) total[k] += row[k];
  LuminaireSurvey out;
  if (total[0] > 0) {
    out.escaped = total[1] / total[0];
    out.back = total[2] / total[0];
    out.front = total[3] / total[0];
  }
  return out;
}

std::vector<std::string> luminaire_warnings(const Visibility& visibility, const std::vector<Luminaire>& luminaires) {
  std::vector<std::string> out;
  // The photometric files' own warnings, once per file.
  std::set<const Photometry*> files;
  for (const Luminaire& l : luminaires)
    if (l.photometry && files.insert(l.photometry.get()).second)
      out.insert(out.end(), l.photometry->warnings.begin(), l.photometry->warnings.end());
  for (const Luminaire& l : luminaires) {
    if (l.directional()) continue;  // the sky and the sun: nothing to place
    if (!(l.flux() > 0)) {
      out.push_back(fmt::format("luminaire {} sends no light (its flux is 0).", l.name));
      continue;
    }
    const LuminaireSurvey s = survey_luminaire(visibility, l, 32, 0x5EED);
    if (s.back > 0.5)
      out.push_back(fmt::format(
          "luminaire {} at ({:.4g}, {:.4g}, {:.4g}) is inside a solid or behind a surface: {:.0f}% of its flux meets "
          "the back of a face. Move it into the room (a ceiling luminaire: just below the ceiling).",
          l.name, l.position[0], l.position[1], l.position[2], 100 * s.back));
    else if (s.escaped > 0.75)
      out.push_back(fmt::format(
          "luminaire {} is aimed at nothing: {:.0f}% of its flux leaves the model. Check its \"aim\" (where its "
          "nadir points) and position.",
          l.name, 100 * s.escaped));
  }
  return out;
}

double luminaire_illuminance(const Visibility* visibility, const Luminaire& l, const Vec3d& x, const Vec3d& n,
                             std::uint64_t seed, double* unoccluded) {
  if (l.directional()) return daylight_illuminance(visibility, l, x, n, unoccluded);
  const bool rays = visibility != nullptr;
  const double length = l.opening_length(), width = l.opening_width();
  const double distance = (x - l.position).norm();
  // Far (the opening below a fifth of the distance, the usual far-field rule): a point.
  const bool near = std::max(length, width) > 0.2 * distance;
  const int side = near ? kLuminaireOpeningSide : 1;
  const double share = 1.0 / (side * side);
  std::uint64_t state = seed;
  double open = 0, seen = 0;
  for (int a = 0; a < side; ++a)
    for (int b = 0; b < side; ++b) {
      Vec3d p = l.position;
      if (near) {
        const double u = (a + (rays ? uniform(state) : 0.5)) / side, w = (b + (rays ? uniform(state) : 0.5)) / side;
        if (l.round_opening()) {  // a disc of diameter `length`, equal-area polar strata
          const double r = 0.5 * length * std::sqrt(u), phi = 2 * M_PI * w;
          p += l.c0 * (r * std::cos(phi)) + l.c90 * (r * std::sin(phi));
        } else {
          p += l.c0 * ((u - 0.5) * length) + l.c90 * ((w - 0.5) * width);
        }
      }
      Vec3d d = x - p;
      const double r2 = d.sqrnorm();
      if (!(r2 > 0)) continue;
      d /= std::sqrt(r2);
      const double cos_receiver = -OpenMesh::dot(n, d);
      if (cos_receiver <= 0) continue;
      const double e = share * l.intensity_towards(d) * cos_receiver / r2;
      if (!(e > 0)) continue;
      open += e;
      if (rays && !visibility->occluded(x, n, p, d)) seen += e;
    }
  if (unoccluded) *unoccluded = open;
  return rays ? seen : open;
}

}  // namespace dynrad::rad
