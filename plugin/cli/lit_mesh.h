// A mesh lit by `dynrad solve`, read back from its PLY, and the model it was lit from:
// what `probe` and `grid` read.
#pragma once

#include "mesh/core/scene_mesh.h"
#include "radiosity/transfer/visibility.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace dynrad::cli {

// The lit mesh as plain triangles with per-vertex radiosity, and the triangles around
// each place: vertices split where surfaces meet (a lamp in a ceiling) share their
// place, place[v]; its triangles are around[around_start[place] .. around_start[place
// + 1]), in number order.
struct LitMesh {
  std::vector<Vec3d> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Rgb> radiosity;
  // Photometric solves (a scene with luminaires) also write illuminance (lx) and
  // luminance (cd/m^2) per vertex; probe then reads those.
  bool photometric = false;
  std::vector<double> illuminance, luminance;
  std::vector<std::uint32_t> place, around_start, around;
  double diagonal = 0;
};

// Throws InputError when the file is not a PLY written by dynrad solve.
LitMesh read_lit(const std::string& path);

// Throws InputError naming both files when `model`, as read, does not span the lit
// mesh's box (each corner within 1% of the lit mesh's diagonal): the PLY was lit from
// another model, or from this one read with another --up or --scale (--model-up,
// --model-scale).
void check_model_matches(const LitMesh& lit, const std::string& lit_path, const SceneMesh& model,
                         const std::string& model_path);

// The material of the model face at `point` facing along `normal`. A short ray from a
// hair above the point (along the normal) finds a face within twice that hair; then,
// as a search of every face would, the faces around its corners that face within 30
// degrees of the normal, pass within the hair of the point and hold it, in number
// order, the nearest plane winning (the later face on a tie). So a point on a lamp's
// edge gets the same face every time, whichever of the two Embree's tree reports.
const Material* material_at(const SceneMesh& model, const rad::Visibility& index, const Vec3d& point,
                            const Vec3d& normal);

}  // namespace dynrad::cli
