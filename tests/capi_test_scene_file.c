/* Scene files through the C ABI: the daylit room sample solved, its grid against the
 * report and against `dynrad solve`, then what a scene file can get wrong. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "capi_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A scene file, as `dynrad solve` reads it: the daylit room sample (a CIE sky, the sun
 * through a window, a grid). Its grid comes back per point and in the JSON report, whose
 * Eavg is the mean of the points; the sun's patch on the work plane is far above the
 * rest. Then what a scene file can get wrong. */
void test_scene_file(void) {
  dynrad_scene* scene = NULL;
  dynrad_status s = dynrad_scene_load(DYNRAD_SAMPLES_DIR "/daylight_clear.json", &scene);
  CHECK(s == DYNRAD_OK, "dynrad_scene_load: %s: %s", dynrad_status_name(s), dynrad_last_error());
  if (!scene) return;
  dynrad_options* options = NULL;
  CHECK(dynrad_options_create(&options) == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_quality(options, "draft") == DYNRAD_OK, "%s", dynrad_last_error());
  dynrad_result* result = NULL;
  s = dynrad_solve(scene, options, NULL, NULL, NULL, &result);
  CHECK(s == DYNRAD_OK, "solve: %s: %s", dynrad_status_name(s), dynrad_last_error());
  if (result) {
    CHECK(dynrad_result_grid_count(result) == 1, "%zu grids", dynrad_result_grid_count(result));
    CHECK(dynrad_result_grid_name(result, 0) && strcmp(dynrad_result_grid_name(result, 0), "room") == 0, "grid name");
    CHECK(dynrad_result_grid_name(result, 1) == NULL, "a grid past the last");
    const size_t n = dynrad_result_grid_point_count(result, 0);
    CHECK(n == 240, "%zu points (6 x 4 m less a 0.5 m border, every 0.25 m)", n);
    double* points = malloc(4 * (n ? n : 1) * sizeof(double));
    CHECK(dynrad_result_grid_points(result, 0, points, n ? n - 1 : 0) == DYNRAD_BUFFER_TOO_SMALL, "a short buffer");
    CHECK(dynrad_result_grid_points(result, 0, points, n) == DYNRAD_OK, "%s", dynrad_last_error());
    double sum = 0, brightest = 0;
    size_t lit = 0;
    for (size_t k = 0; k < n; ++k) {
      const double e = points[4 * k + 3];
      if (isnan(e)) continue;
      CHECK(isfinite(e) && e > 0, "point %zu: %g lx", k, e);
      CHECK(fabs(points[4 * k + 2] - 0.85) < 1e-9, "point %zu at height %g", k, points[4 * k + 2]);
      sum += e;
      brightest = e > brightest ? e : brightest;
      ++lit;
    }
    free(points);
    const char* json = dynrad_result_report_json(result);
    const char* eavg = strstr(json, "\"Eavg\": ");
    CHECK(eavg != NULL, "no Eavg in the report");
    if (eavg && lit) {
      const double reported = strtod(eavg + 8, NULL);
      CHECK(fabs(reported - sum / lit) <= 1e-6 * reported, "report Eavg %g, mean of the points %g", reported, sum / lit);
      CHECK(brightest > 3 * reported, "the sun's patch %g lx against Eavg %g", brightest, reported);
    }
    CHECK(strstr(json, "\"units\": \"photometric\"") != NULL, "a sky's solve is photometric");
    /* `dynrad solve` of the same file with the same options: the same grid, to the digit
     * (one pipeline). */
    char command[1024], report[512];
    char dir[] = "/tmp/capi_cliXXXXXX";
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    snprintf(report, sizeof report, "%s/report.json", dir);
    snprintf(command, sizeof command, "'%s' solve '%s' -o '%s/lit.ply' --quality draft --report '%s' -q", DYNRAD_EXE,
             DYNRAD_SAMPLES_DIR "/daylight_clear.json", dir, report);
    CHECK(system(command) == 0, "%s", command);
    FILE* f = fopen(report, "r");
    CHECK(f != NULL, "no report from %s", command);
    if (f && eavg) {
      static char text[1 << 20];
      const size_t size = fread(text, 1, sizeof text - 1, f);
      text[size] = 0;
      const char* grids = strstr(text, "\"grids\": [");
      const char* cli = grids ? strstr(grids, "\"Eavg\": ") : NULL;
      CHECK(cli != NULL, "no grid Eavg in the command's report");
      if (cli) CHECK(strtod(cli + 8, NULL) == strtod(eavg + 8, NULL), "dynrad solve's Eavg %.17g, the library's %.17g",
                     strtod(cli + 8, NULL), strtod(eavg + 8, NULL));
    }
    if (f) fclose(f);
    snprintf(command, sizeof command, "rm -rf '%s'", dir);
    CHECK(system(command) == 0, "%s", command);
    CHECK(strstr(json, "\"stopped_by\": ") != NULL, "no stopped_by in the report");
    dynrad_result_destroy(result);
  }
  /* Solved again: the file is read again, the same answer. */
  result = NULL;
  s = dynrad_solve(scene, options, NULL, NULL, NULL, &result);
  CHECK(s == DYNRAD_OK && result && dynrad_result_grid_count(result) == 1, "second solve: %s", dynrad_last_error());
  dynrad_result_destroy(result);
  dynrad_options_destroy(options);
  dynrad_scene_destroy(scene);

  char dir[] = "/tmp/capi_testXXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  char path[512], obj[512];
  scene = (dynrad_scene*)&failures; /* must be overwritten with NULL on failure */
  expect_error(dynrad_scene_load("/nonexistent/room.json", &scene), DYNRAD_INVALID_INPUT, "/nonexistent/room.json",
               "a missing file");
  CHECK(scene == NULL, "a failed load left a handle");
  write_file(dir, "box.obj",
             "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nv 0 0 2\nv 2 0 2\nv 2 2 2\nv 0 2 2\n"
             "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n",
             obj, sizeof obj);
  write_file(dir, "typo.json",
             "{\"meshes\": [{\"file\": \"box.obj\"}], \"luminaires\": [{\"lumen\": 1000, \"position\": [1, 1, 1.9]}]}",
             path, sizeof path);
  expect_error(dynrad_scene_load(path, &scene), DYNRAD_INVALID_INPUT, "unknown key \"lumen\"", "a misspelt key");
  write_file(dir, "dark.json", "{\"meshes\": [{\"file\": \"box.obj\"}]}", path, sizeof path);
  s = dynrad_scene_load(path, &scene);
  CHECK(s == DYNRAD_OK, "a dark scene loads: %s", dynrad_last_error());
  if (s == DYNRAD_OK) {
    result = (dynrad_result*)&failures;
    expect_error(dynrad_solve(scene, NULL, NULL, NULL, NULL, &result), DYNRAD_NO_EMITTER, "no face emits light",
                 "a scene with no light");
    CHECK(result == NULL, "a failed solve left a result");
    dynrad_scene_destroy(scene);
  }
  remove(obj);
  snprintf(path, sizeof path, "%s/typo.json", dir);
  remove(path);
  snprintf(path, sizeof path, "%s/dark.json", dir);
  remove(path);
  remove(dir);
}
