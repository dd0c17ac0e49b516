#include "radiosity/analysis/lit_scene.h"

namespace dynrad::rad {

LitScene lit_scene(const SceneMesh& mesh, const VertexSplit& split, const std::vector<Rgb>& radiosity,
                   std::vector<Luminaire> luminaires, double emission_scale, bool photometric) {
  LitScene lit;
  lit.positions.reserve(split.size());
  for (VertexHandle v : split.source) lit.positions.push_back(mesh.mesh().point(v));
  lit.radiosity = radiosity;
  for (auto f : mesh.mesh().faces()) {
    lit.triangles.push_back({split.corner[3 * f.idx()], split.corner[3 * f.idx() + 1], split.corner[3 * f.idx() + 2]});
    lit.emission.push_back(mesh.material(f).emission * emission_scale);
  }
  lit.luminaires = std::move(luminaires);
  lit.photometric = photometric;
  lit.prepare();
  return lit;
}

void LitScene::prepare() {
  visibility = std::make_unique<Visibility>(positions, triangles);
  Bounds bounds;
  for (const Vec3d& p : positions) bounds.extend(p);
  diagonal = bounds.diagonal();
  emitting.clear();
  for (std::size_t f = 0; f < emission.size(); ++f)
    if (!emission[f].is_zero()) emitting.push_back(static_cast<std::uint32_t>(f));
}

}  // namespace dynrad::rad
