/* Results for lighting design through the C ABI: per-vertex illuminance, the HTML
 * report written from a result, and the false-colour scale. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "capi_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h> /* access */

/* A room lit by the downlight sample (IES), with a work plane: per-vertex illuminance,
 * the HTML report and the report's false-colour scale. */
void test_illuminance_and_report(void) {
  char dir[] = "/tmp/capi_reportXXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  char obj[512], path[512], html[512], picture[512], command[1024];
  /* 4 x 4 x 3 m, every face's front inside. */
  write_file(dir, "room.obj",
             "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 0 0 3\nv 4 0 3\nv 4 4 3\nv 0 4 3\n"
             "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n",
             obj, sizeof obj);
  write_file(dir, "room.json",
             "{\"meshes\": [{\"file\": \"room.obj\", \"material\": \"wall\"}],\n"
             " \"materials\": {\"wall\": {\"reflectance\": 0.5}},\n"
             " \"luminaires\": [{\"name\": \"D1\", \"photometry\": \"" DYNRAD_SAMPLES_DIR "/downlight.ies\",\n"
             "                 \"position\": [2, 2, 2.9]}],\n"
             " \"grids\": [{\"name\": \"work\", \"rectangle\": [0, 0, 4, 4], \"height\": 0.8, \"spacing\": 0.5,\n"
             "            \"border\": 0.5}]}\n",
             path, sizeof path);
  dynrad_scene* scene = NULL;
  dynrad_status s = dynrad_scene_load(path, &scene);
  CHECK(s == DYNRAD_OK, "dynrad_scene_load: %s: %s", dynrad_status_name(s), dynrad_last_error());
  dynrad_options* options = NULL;
  CHECK(dynrad_options_create(&options) == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_quality(options, "draft") == DYNRAD_OK, "%s", dynrad_last_error());
  dynrad_result* result = NULL;
  if (scene) s = dynrad_solve(scene, options, NULL, NULL, NULL, &result);
  CHECK(result && s == DYNRAD_OK, "solve: %s: %s", dynrad_status_name(s), dynrad_last_error());
  if (result) {
    /* A closed room absorbs all the luminaire emits: integrated from the vertices'
     * illuminance over the triangles, (1 - rho) E dA with rho 0.5 everywhere is the
     * emitted flux (lm; the values hold the ambient estimate of light not yet shot, so
     * the sum is the whole flux, not the report's `absorbed` so far). */
    const size_t n = dynrad_result_vertex_count(result), t = dynrad_result_triangle_count(result);
    float* lux = malloc((n ? n : 1) * sizeof(float));
    double* xyz = malloc(3 * (n ? n : 1) * sizeof(double));
    uint32_t* tri = malloc(3 * (t ? t : 1) * sizeof(uint32_t));
    CHECK(dynrad_result_illuminance(result, lux, n ? n - 1 : 0) == DYNRAD_BUFFER_TOO_SMALL, "a short buffer");
    CHECK(dynrad_result_illuminance(result, lux, n) == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(dynrad_result_positions(result, xyz, n) == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(dynrad_result_triangles(result, tri, t) == DYNRAD_OK, "%s", dynrad_last_error());
    double absorbed = 0, brightest = 0;
    for (size_t v = 0; v < n; ++v) {
      CHECK(isfinite(lux[v]) && lux[v] >= 0, "vertex %zu: %g lx", v, lux[v]);
      brightest = lux[v] > brightest ? lux[v] : brightest;
    }
    for (size_t k = 0; k < t; ++k) {
      const double* a = xyz + 3 * tri[3 * k];
      const double* b = xyz + 3 * tri[3 * k + 1];
      const double* c = xyz + 3 * tri[3 * k + 2];
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double cross[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      const double area = 0.5 * sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
      absorbed += 0.5 * area * (lux[tri[3 * k]] + lux[tri[3 * k + 1]] + lux[tri[3 * k + 2]]) / 3;
    }
    dynrad_report report;
    CHECK(dynrad_result_report(result, &report) == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(fabs(absorbed - report.emitted[1]) <= 0.03 * report.emitted[1],
          "absorbed from the illuminance %g lm, emitted %g lm", absorbed, report.emitted[1]);
    CHECK(brightest > 100, "the floor under the downlight has %g lx", brightest);
    free(lux);
    free(xyz);
    free(tri);

    /* The report: the page, its grid plan beside it, the grid's Eavg as the JSON has it. */
    snprintf(html, sizeof html, "%s/lighting.html", dir);
    s = dynrad_result_write_report(result, html);
    CHECK(s == DYNRAD_OK, "dynrad_result_write_report: %s: %s", dynrad_status_name(s), dynrad_last_error());
    snprintf(picture, sizeof picture, "%s/lighting_grid_work.png", dir);
    FILE* png = fopen(picture, "rb");
    CHECK(png != NULL, "no grid picture %s", picture);
    if (png) fclose(png);
    FILE* f = fopen(html, "r");
    CHECK(f != NULL, "no report %s", html);
    const char* eavg = strstr(dynrad_result_report_json(result), "\"Eavg\": ");
    CHECK(eavg != NULL, "no Eavg in the JSON report");
    if (f && eavg) {
      static char page[1 << 23];
      const size_t size = fread(page, 1, sizeof page - 1, f);
      page[size] = 0;
      char cell[64];
      snprintf(cell, sizeof cell, "<td class=\"n\">%.1f</td>", strtod(eavg + 8, NULL));
      CHECK(strstr(page, "<td>work</td>") != NULL, "the page does not name the grid");
      CHECK(strstr(page, cell) != NULL, "the page has no %s", cell);
      CHECK(strstr(page, "<td>D1</td>") != NULL, "the page does not list the luminaire");
      CHECK(strstr(page, "data:image/png;base64,") != NULL, "the page embeds no picture");
    }
    if (f) fclose(f);
    /* A directory that is not there: the file named, nothing written. */
    snprintf(path, sizeof path, "%s/missing/lighting.html", dir);
    expect_error(dynrad_result_write_report(result, path), DYNRAD_OUTPUT_ERROR, "missing", "a report without its folder");
    snprintf(path, sizeof path, "%s/missing", dir);
    CHECK(access(path, F_OK) != 0, "a failed report made %s", path);
    expect_error(dynrad_result_write_report(result, NULL), DYNRAD_INVALID_ARGUMENT, "path", "a NULL path");
    dynrad_result_destroy(result);
  }
  /* The false-colour scale's ends, and what it refuses. */
  uint8_t rgb[3] = {0, 0, 0};
  CHECK(dynrad_false_colour(1.0, rgb) == DYNRAD_OK && rgb[0] > 200 && rgb[1] < 60 && rgb[2] < 60,
        "the top is red: %d %d %d", rgb[0], rgb[1], rgb[2]);
  CHECK(dynrad_false_colour(-3.0, rgb) == DYNRAD_OK && rgb[2] > rgb[0] && rgb[2] > rgb[1],
        "below the bottom is blue: %d %d %d", rgb[0], rgb[1], rgb[2]);
  expect_error(dynrad_false_colour(NAN, rgb), DYNRAD_INVALID_ARGUMENT, "finite", "a NaN");
  dynrad_options_destroy(options);
  dynrad_scene_destroy(scene);
  snprintf(command, sizeof command, "rm -rf '%s'", dir);
  CHECK(system(command) == 0, "%s", command);
}
