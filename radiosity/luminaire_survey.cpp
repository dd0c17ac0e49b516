// Where luminaires' light goes first (survey_luminaire), and the placement warnings
// built on it.
#include "radiosity/luminaire.h"
#include "radiosity/visibility.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <set>

namespace dynrad::rad {

namespace {

// SplitMix64 (as the solver's): each row of directions draws from its own seed.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double uniform(std::uint64_t& state) {
  state = mix(state);
  return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
}

}  // namespace

LuminaireSurvey survey_luminaire(const Visibility& visibility, const Luminaire& l, int side, std::uint64_t seed) {
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

}  // namespace dynrad::rad
