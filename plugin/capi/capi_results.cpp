// The C ABI's results (dynrad_result_*): the lit mesh, its values, the report, grids,
// the HTML report and the false-colour scale.
#include "plugin/capi/capi_internal.h"
#include "plugin/capi/capi_report.h"
#include "plugin/report/grid_picture.h"

#include <algorithm>
#include <array>

#include <cmath>
#include <string>

using namespace dynrad;
using namespace dynrad::capi;

extern "C" {

void dynrad_result_destroy(dynrad_result* result) { delete result; }

size_t dynrad_result_vertex_count(const dynrad_result* result) { return result ? result->positions.size() / 3 : 0; }

size_t dynrad_result_triangle_count(const dynrad_result* result) { return result ? result->triangles.size() / 3 : 0; }

dynrad_status dynrad_result_positions(const dynrad_result* result, double* xyz, size_t capacity) {
  return copy_out(result, &dynrad_result::positions, 3, dynrad_result_vertex_count(result), xyz, capacity,
                  "dynrad_result_positions");
}

dynrad_status dynrad_result_triangles(const dynrad_result* result, uint32_t* indices, size_t capacity) {
  return copy_out(result, &dynrad_result::triangles, 3, dynrad_result_triangle_count(result), indices, capacity,
                  "dynrad_result_triangles");
}

dynrad_status dynrad_result_triangle_materials(const dynrad_result* result, uint32_t* materials, size_t capacity) {
  return copy_out(result, &dynrad_result::triangle_materials, 1, dynrad_result_triangle_count(result), materials,
                  capacity, "dynrad_result_triangle_materials");
}

dynrad_status dynrad_result_radiosity(const dynrad_result* result, float* rgb, size_t capacity) {
  return copy_out(result, &dynrad_result::radiosity, 3, dynrad_result_vertex_count(result), rgb, capacity,
                  "dynrad_result_radiosity");
}

dynrad_status dynrad_result_display(const dynrad_result* result, uint8_t* rgb, size_t capacity) {
  return copy_out(result, &dynrad_result::display, 3, dynrad_result_vertex_count(result), rgb, capacity,
                  "dynrad_result_display");
}

dynrad_status dynrad_result_report(const dynrad_result* result, dynrad_report* report) {
  return guarded([&] {
    require(result && report, "dynrad_result_report: result or report is NULL.");
    *report = result->report;
    return DYNRAD_OK;
  });
}

const char* dynrad_result_report_json(const dynrad_result* result) { return result ? result->report_json.c_str() : ""; }

size_t dynrad_result_grid_count(const dynrad_result* result) { return result ? result->grid_names.size() : 0; }

const char* dynrad_result_grid_name(const dynrad_result* result, size_t grid) {
  return result && grid < result->grid_names.size() ? result->grid_names[grid].c_str() : nullptr;
}

size_t dynrad_result_grid_point_count(const dynrad_result* result, size_t grid) {
  return result && grid < result->grid_points.size() ? result->grid_points[grid].size() / 4 : 0;
}

dynrad_status dynrad_result_grid_points(const dynrad_result* result, size_t grid, double* xyze, size_t capacity) {
  return guarded([&] {
    require(result && xyze, "dynrad_result_grid_points: result or xyze is NULL.");
    require(grid < result->grid_points.size(), "dynrad_result_grid_points: no grid of that index.");
    const std::vector<double>& points = result->grid_points[grid];
    if (capacity < points.size() / 4)
      fail(DYNRAD_BUFFER_TOO_SMALL, "dynrad_result_grid_points: the buffer holds " + std::to_string(capacity) +
                                        " points but " + std::to_string(points.size() / 4) +
                                        " are needed; size it from dynrad_result_grid_point_count.");
    if (!points.empty()) std::memcpy(xyze, points.data(), points.size() * sizeof(double));
    return DYNRAD_OK;
  });
}

dynrad_status dynrad_result_illuminance(const dynrad_result* result, float* lux, size_t capacity) {
  return copy_out(result, &dynrad_result::illuminance, 1, dynrad_result_vertex_count(result), lux, capacity,
                  "dynrad_result_illuminance");
}

dynrad_status dynrad_result_write_report(const dynrad_result* result, const char* path) {
  return guarded([&] {
    require(result && path && *path, "dynrad_result_write_report: result is NULL, or path is NULL or empty.");
    capi::ReportInputs inputs;
    inputs.prepared = result->prepared.get();
    inputs.solved = result->solved.get();
    inputs.exposure = result->report.exposure;
    inputs.input = result->input;
    inputs.version = DYNRAD_VERSION;
    capi::write_report(path, inputs);
    return DYNRAD_OK;
  });
}

dynrad_status dynrad_false_colour(double t, uint8_t rgb[3]) {
  return guarded([&] {
    require(rgb, "dynrad_false_colour: rgb is NULL.");
    require(std::isfinite(t), "dynrad_false_colour: t is not a finite number.");
    const std::array<std::uint8_t, 3> c = report::false_colour(std::clamp(t, 0.0, 1.0));
    std::copy(c.begin(), c.end(), rgb);
    return DYNRAD_OK;
  });
}

}  // extern "C"
