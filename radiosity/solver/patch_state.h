// A patch's state in the solver (Solver::Patch): its geometry and material, its
// unshot and shot radiosity, what it loses to the outside, and its place among sender
// groups and clusters.
#pragma once

#include "mesh/core/types.h"
#include "radiosity/transfer/form_factor.h"

#include <array>
#include <cstdint>

namespace dynrad::rad {

struct PatchState {
  // area and unshot first: the survey after each shot reads only these
  double area = 0;
  Rgb unshot;
  std::array<Vec3d, 3> corners;
  Vec3d normal;
  Rgb reflectance, emission;
  Rgb shot;  // radiosity shot so far, in total
  // The mean radiosity its direct light gives it, reflectance times the mean
  // illuminance from luminaires and the sun (RefineSettings::exact_direct): their light
  // is not in the element values, but is part of how bright the patch is.
  Rgb direct;
  double lost = -1, escaped = 0;  // see lost_fraction()
  double rough_lost = -1;         // see rough_lost_fraction(), until `lost` is known
  std::uint32_t plane = 0;        // patches with the same facing share form factors at a vertex
  Vec3d centre;                   // centre and radius of a sphere around the patch
  double radius = 0;
  // Luminance at the nodes of the patch's quarter grid (triangle_nodes(); see
  // shape_of()) that has been shot: the values there minus this are the shape of its
  // unshot radiosity.
  std::array<double, kTriangleNodes> shot_at_nodes{};
  // A member of a face cluster: it sends nothing of its own (its reflected light goes
  // to its part of the cluster) and is not refined.
  bool clustered = false;
  // On a facet (the patches that touch and lie in one plane) of less area than
  // kDetailFacet whole patches (RefineSettings::patch_area): a frame's profile, a
  // radiator's, a skirting board, a chair's seat. A luminaire refines it as any other
  // sender does, without its extra levels, tighter error and shadow levels: what the
  // eye and the work plane see are the room's walls, floors, ceilings and tables.
  bool detail = false;
};

}  // namespace dynrad::rad
