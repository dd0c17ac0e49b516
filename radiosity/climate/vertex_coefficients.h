// Daylight coefficients at the lit mesh's vertices, from the solve that carried the
// channels (coefficient_solve.h): what lets any hour of the year be drawn on the model.
//
// At an output vertex (Solver::Output's split) the coefficients are those of the
// patches around it, averaged by area and scaled so that the steering sky through them
// gives the vertex's own steering radiosity: the shape across a patch from the refined
// mesh, the mix of skies from the patches (as point_coefficients() does for a gathered
// ray). The suns' channels hold their interreflected light only; a sun's direct light
// at a vertex is a shadow ray per hour (vertex_hour), as sharp as the mesh can show.
#pragma once

#include "radiosity/climate/coefficient_solve.h"
#include "radiosity/solver/solver.h"

#include <cstddef>
#include <vector>

namespace dynrad {
class SceneMesh;
}

namespace dynrad::rad {

class Glazing;
class Visibility;

struct VertexCoefficients {
  std::size_t count = 0;      // channels per vertex: the indirect patches, the ground, the sun positions
  std::size_t sky_count = 0;  // of which the sky's and the ground's
  // Vertex-major, count per vertex: luminance radiosity (cd/m^2 x pi) per unit of each
  // channel (sky patch and ground: per cd/m^2 of its luminance; sun position: per lx
  // of direct normal illuminance, its direct light excluded).
  std::vector<float> values;
  // Per vertex: where its sun's shadow ray starts, 1% of the way from the vertex to the
  // centroid of the first face around it (as the solver's receivers: from a vertex on
  // the line where a floor meets a wall, a ray would see past the wall), and its normal
  // (the area-weighted faces').
  std::vector<Vec3d> point, normal;
  std::vector<float> reflectance;       // per vertex, luminance reflectance (for the direct sun)

  std::size_t size() const { return point.size(); }
  const float* at(std::size_t v) const { return values.data() + v * count; }
};

// `steering` is the solve's own output (solver.output()); `ground` the steering sky's
// ground luminance.
VertexCoefficients vertex_coefficients(const SceneMesh& mesh, const Solver& solver, const Solver::Output& steering,
                                       std::size_t sky_count, double ground);

// One hour's radiosity (luminance) per vertex: the coefficients times the hour's sky
// vector and sun nodes, plus the reflected direct sun by a shadow ray from each vertex.
std::vector<double> vertex_hour(const VertexCoefficients& c, const HourSky& hour, const Visibility& visibility,
                                const Glazing* glazing);

}  // namespace dynrad::rad
