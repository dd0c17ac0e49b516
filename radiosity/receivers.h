// Receiver nodes: the points where radiosity is computed, one per vertex and surface.
// They are exactly the vertices written to the output (see mesh/vertex_split.h): a
// vertex where a wall meets the floor is two nodes, one with the wall's normal and
// reflectance and one with the floor's. Each node's normal is the area-weighted mean
// of its faces' normals, so a tessellated sphere is shaded smoothly.
#pragma once

#include "mesh/scene_mesh.h"
#include "mesh/vertex_split.h"

#include <vector>

namespace dynrad::rad {

struct Receivers {
  VertexSplit split;  // face corner -> node, node -> mesh vertex
  std::vector<Vec3d> position;
  std::vector<Vec3d> normal;
  // Where form factors and visibility are evaluated: the node moved a little into its
  // own faces. A vertex where the floor meets a wall lies in the wall's plane, where
  // the wall is seen edge-on (form factor 0, not the 0.5 the floor's radiosity tends
  // to there), and rays from it would start in the wall and see through it into the
  // next room (the light leak lightmapper users complain about most).
  std::vector<Vec3d> sample_point;
  std::vector<std::uint32_t> material;

  std::size_t size() const { return position.size(); }
  std::uint32_t node(FaceHandle f, int corner) const { return split.corner[3 * f.idx() + corner]; }
};

Receivers make_receivers(const SceneMesh& scene, double crease_angle_degrees);

}  // namespace dynrad::rad
