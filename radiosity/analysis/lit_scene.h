// A solved scene as plain triangles with per-vertex radiosity, per-triangle emission and
// the luminaires: what calculation grids gather from and views render, whether it comes
// from a solve in this process or from a lit PLY read back with its model.
#pragma once

#include "mesh/core/scene_mesh.h"
#include "mesh/core/vertex_split.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/transfer/visibility.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace dynrad::rad {

// A solved scene to gather from: the lit output mesh (per-vertex radiosity, per-triangle
// emission, both in the solve's units) and the light sources.
struct LitScene {
  std::vector<Vec3d> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Rgb> radiosity;  // per position
  std::vector<Rgb> emission;   // per triangle (its exitance; 0 for most)
  std::vector<Luminaire> luminaires;
  bool photometric = false;    // lx and cd/m^2 (else W/m^2)
  // Built by prepare() from the triangles.
  std::unique_ptr<Visibility> visibility;
  double diagonal = 0;
  std::vector<std::uint32_t> emitting;  // the triangles whose emission is not zero
  void prepare();
};

// The lit scene of a solve: the output mesh (split vertices) and radiosity, each
// triangle's emission times `emission_scale` (SolveOptions::emission_scale), the
// luminaires. Prepared (visibility built).
LitScene lit_scene(const SceneMesh& mesh, const VertexSplit& split, const std::vector<Rgb>& radiosity,
                   std::vector<Luminaire> luminaires, double emission_scale, bool photometric);

}  // namespace dynrad::rad
