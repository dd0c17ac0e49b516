// The mean free path of a model: how far, on average, a cosine-distributed ray leaving
// the front of a surface travels before it meets another. In a closed room it is the
// mean chord 4V/S (V the volume, S the surface area; 3.33 m in a 10 x 6 x 3 room), the
// length that sets how fast light changes across a surface, and so a natural scale for
// patches in a model of any size or unit: a house's rooms, not its outline.
#pragma once

#include "mesh/core/default_seed.h"
#include "mesh/core/scene_mesh.h"

#include <cstdint>

namespace dynrad {

struct MeanFreePathOptions {
  int rays = 4096;          // from area-weighted points on the fronts of all faces
  std::uint64_t seed = default_seed();  // the same model gives the same figure
};

struct MeanFreePath {
  double length = 0;        // mean distance to the first hit, over the rays that hit; 0 when none did
  double escaped = 0;       // fraction of the rays that left the model
  double met = 0;           // fraction of the rays that met another face: those `length` is the mean of
  int rays = 0;
};

MeanFreePath mean_free_path(const SceneMesh& scene, const MeanFreePathOptions& options = {});

}  // namespace dynrad
