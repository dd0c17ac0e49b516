// `dynrad annual`'s lit meshes and vertex coefficients (see annual_meshes.h).
#include "plugin/cli/annual_meshes.h"

#include "mesh/core/error.h"
#include "mesh/io/export.h"
#include "mesh/core/scene_mesh.h"
#include "plugin/cli/npy.h"
#include "radiosity/analysis/tonemap.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace dynrad::cli {

AnnualHour parse_annual_hour(const std::string& text, const std::vector<rad::HourEnding>& rows) {
  int month = 0, day = 0, hour = 0;
  char a = 0, b = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c%d%c", &month, &a, &day, &b, &hour, &extra) != 5 || a != '-' || b != '-')
    throw InputError("--hour", 0, "'" + text + "' is not MM-DD-HH; write the date and the hour the weather row ends, "
                                              "e.g. 03-21-12 for 11:00 to 12:00 standard time on 21 March.");
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (rows[r].month == month && rows[r].day == day && rows[r].hour == hour) return {text, r};
  throw InputError("--hour", 0, "'" + text + "': the weather file has no such row (months 1-12, days of the month, "
                                             "hours 1-24 ending at HH:00 standard time).");
}

namespace {

std::string hour_file(const std::string& prefix, const rad::HourEnding& h) {
  return fmt::format("{}_hour_{:02d}{:02d}_{:02d}.ply", prefix, h.month, h.day, h.hour);
}

// A grey lit PLY from luminance radiosity per vertex: display colours at the values'
// own exposure, illuminance (B / reflectance) and luminance (B / pi).
VertexValues lit_values(const rad::VertexCoefficients& c, const std::vector<double>& radiosity,
                        const std::vector<double>& area) {
  std::vector<Rgb> linear(radiosity.size());
  std::vector<float> illuminance(radiosity.size()), luminance(radiosity.size());
  for (std::size_t v = 0; v < radiosity.size(); ++v) {
    linear[v] = Rgb(radiosity[v]);
    illuminance[v] = c.reflectance[v] > 0 ? static_cast<float>(radiosity[v] / c.reflectance[v]) : 0.0f;
    luminance[v] = static_cast<float>(radiosity[v] / M_PI);
  }
  const double exposure = rad::auto_exposure(linear, std::vector<char>(linear.size(), 1), area);
  VertexValues values = rad::tone_map(linear, exposure, "radiosity");
  values.quality = illuminance;
  values.scalars.emplace_back("illuminance", std::move(illuminance));
  values.scalars.emplace_back("luminance", std::move(luminance));
  return values;
}

}  // namespace

std::vector<std::string> annual_mesh_files(const std::string& prefix, const std::vector<AnnualHour>& hours,
                                           const std::vector<rad::HourEnding>& rows, bool coefficients) {
  std::vector<std::string> files;
  for (const AnnualHour& h : hours) files.push_back(hour_file(prefix, rows[h.row]));
  if (coefficients) {
    files.push_back(prefix + "_vertex_coefficients.npy");
    files.push_back(prefix + "_vertices.ply");
  }
  return files;
}

void annual_mesh_outputs(const std::string& prefix, const SceneMesh& mesh, const VertexSplit& split,
                         const rad::VertexCoefficients& vertices, const rad::YearSky& year,
                         const std::vector<AnnualHour>& hours, bool coefficients, const rad::Visibility& visibility,
                         const rad::Glazing* glazing, const rad::SkyPatches& indirect,
                         std::vector<std::function<void()>>& writes, nlohmann::json& report) {
  auto area = std::make_shared<const std::vector<double>>(split_vertex_areas(mesh, split));
  for (const AnnualHour& h : hours) {
    const rad::HourEnding& when = year.rows[h.row];
    const std::string path = hour_file(prefix, when);
    std::vector<double> radiosity(vertices.size(), 0.0);
    const bool dark = year.dark[h.row];
    if (!dark) radiosity = rad::vertex_hour(vertices, year.hours[h.row], visibility, glazing);
    if (dark) spdlog::warn("--hour {}: the sun is down or the sky dark at that hour; its mesh is black", h.text);
    double lit = 0, sum = 0;
    for (std::size_t v = 0; v < radiosity.size(); ++v) {
      sum += (*area)[v] * radiosity[v];
      lit += (*area)[v];
    }
    report["hours"].push_back({{"hour", fmt::format("{:02d}-{:02d}-{:02d}", when.month, when.day, when.hour)},
                               {"file", path},
                               {"dark", dark},
                               {"sun", !dark && year.hours[h.row].direct_normal > 0},
                               {"mean_luminance", lit > 0 ? sum / lit / M_PI : 0.0}});
    writes.push_back([&mesh, &split, &vertices, area, path, radiosity = std::move(radiosity)] {
      write_mesh_with_values(path, mesh, split, lit_values(vertices, radiosity, *area));
    });
  }
  if (!coefficients) return;
  nlohmann::json suns = nlohmann::json::array();
  for (const Vec3d& s : year.suns) {
    const auto [altitude, azimuth] = indirect.altitude_azimuth(s);
    const double degrees = 180 / M_PI, east_of_north = azimuth < 0 ? azimuth + 2 * M_PI : azimuth;
    suns.push_back({std::round(altitude * degrees * 1e3) / 1e3, std::round(east_of_north * degrees * 1e3) / 1e3});
  }
  report["vertex_coefficients"] = {
      {"file", prefix + "_vertex_coefficients.npy"},
      {"mesh", prefix + "_vertices.ply"},
      {"shape", {vertices.size(), vertices.count}},
      {"channels",
       fmt::format("columns 0-{}: Reinhart MF:{} sky patches (rows from the horizon up, each clockwise from north), "
                   "radiosity per cd/m^2 of the patch's luminance; column {}: the ground, per cd/m^2; columns {}-{}: "
                   "sun positions (sun_positions: altitude, azimuth in degrees), interreflected light per lx of "
                   "direct normal illuminance, the sun's direct light not included (a shadow ray per hour)",
                   indirect.size() - 1, indirect.subdivision(), indirect.size(), indirect.size() + 1,
                   vertices.count - 1)},
      {"sun_positions", suns}};
  writes.push_back([&vertices, path = prefix + "_vertex_coefficients.npy"] {
    write_npy(path, vertices.values, vertices.size(), vertices.count);
  });
  // The mesh the rows belong to, lit by a uniform sky of luminance 1 and a black ground.
  writes.push_back([&mesh, &split, &vertices, area, path = prefix + "_vertices.ply"] {
    std::vector<double> radiosity(vertices.size());
    for (std::size_t v = 0; v < vertices.size(); ++v)
      radiosity[v] = rad::steering_light(vertices.at(v), vertices.sky_count, 0.0);
    write_mesh_with_values(path, mesh, split, lit_values(vertices, radiosity, *area));
  });
}

}  // namespace dynrad::cli
