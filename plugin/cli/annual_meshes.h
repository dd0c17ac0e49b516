// `dynrad annual`'s outputs on the model itself: the lit mesh of chosen hours
// (--hour) and every vertex's daylight coefficients (--vertex-coefficients), from
// radiosity/climate/vertex_coefficients.h.
#pragma once

#include "radiosity/climate/annual.h"
#include "radiosity/climate/vertex_coefficients.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace dynrad {
class SceneMesh;
struct VertexSplit;
}

namespace dynrad::rad {
class Glazing;
class Visibility;
}

namespace dynrad::cli {

// A weather row asked for by its date and the hour it ends, "MM-DD-HH" (03-21-12: the
// hour from 11:00 to 12:00 standard time on 21 March, its sun at 11:30).
struct AnnualHour {
  std::string text;  // as asked, for messages
  std::size_t row = 0;
};
// Throws InputError (naming the option) for text that is not MM-DD-HH or a date the
// weather file does not have.
AnnualHour parse_annual_hour(const std::string& text, const std::vector<rad::HourEnding>& rows);

// The file names the outputs will have (to check before the solve).
std::vector<std::string> annual_mesh_files(const std::string& prefix, const std::vector<AnnualHour>& hours,
                                           const std::vector<rad::HourEnding>& rows, bool coefficients);

// Adds to `writes` one lit PLY per hour, PREFIX_hour_MMDD_HH.ply (radiosity, display
// colours at the hour's own exposure, illuminance and luminance per vertex), and with
// `coefficients` PREFIX_vertex_coefficients.npy (vertices x channels) and
// PREFIX_vertices.ply (the mesh whose vertex i is the array's row i, lit by a uniform
// sky of luminance 1 over a black ground); describes them in `report`. `mesh`, `split`
// and `vertices` must outlive the writes.
void annual_mesh_outputs(const std::string& prefix, const SceneMesh& mesh, const VertexSplit& split,
                         const rad::VertexCoefficients& vertices, const rad::YearSky& year,
                         const std::vector<AnnualHour>& hours, bool coefficients, const rad::Visibility& visibility,
                         const rad::Glazing* glazing, const rad::SkyPatches& indirect,
                         std::vector<std::function<void()>>& writes, nlohmann::json& report);

}  // namespace dynrad::cli
