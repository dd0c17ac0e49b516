/* The C ABI's error paths: bad materials, positions, indices and options refused with a
 * status and a message that names the fault, and the library still usable after them. */
#include "capi_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void test_errors(void) {
  const uint32_t faces[6] = {0, 0, 0, 0, 0, 1};
  dynrad_material materials[2] = {grey(0.5, 0.0, "plaster"), grey(0.5, 10.0, "lamp")};
  Box box;
  make_box(&box, 1, 1, 1, faces);
  dynrad_scene* scene = (dynrad_scene*)&box; /* must be overwritten with NULL on failure */
  const size_t m = 2;

  materials[0].reflectance[1] = 1.0;
  expect_error(dynrad_scene_create(box.positions, 8, box.indices, box.sizes, 6, box.face_materials, materials, m,
                                   &scene),
               DYNRAD_INVALID_INPUT, "'plaster'", "reflectance 1");
  CHECK(scene == NULL, "a failed create left a handle");
  CHECK(strstr(dynrad_last_error(), "below 1") != NULL, "message '%s' does not say what to do", dynrad_last_error());
  materials[0].reflectance[1] = NAN;
  expect_error(dynrad_scene_create(box.positions, 8, box.indices, box.sizes, 6, box.face_materials, materials, m,
                                   &scene),
               DYNRAD_INVALID_INPUT, "'plaster'", "NaN reflectance");
  materials[0].reflectance[1] = 0.5;
  materials[1].emission[2] = -1;
  expect_error(dynrad_scene_create(box.positions, 8, box.indices, box.sizes, 6, box.face_materials, materials, m,
                                   &scene),
               DYNRAD_INVALID_INPUT, "'lamp'", "negative emission");
  materials[1].emission[2] = 10;

  box.positions[3 * 5 + 1] = NAN;
  expect_error(dynrad_scene_create(box.positions, 8, box.indices, box.sizes, 6, box.face_materials, materials, m,
                                   &scene),
               DYNRAD_INVALID_INPUT, "vertex 5", "NaN position");
  box.positions[3 * 5 + 1] = 0;

  box.indices[4 * 3 + 2] = 8;
  expect_error(dynrad_scene_create(box.positions, 8, box.indices, box.sizes, 6, box.face_materials, materials, m,
                                   &scene),
               DYNRAD_INVALID_INPUT, "polygon 3, corner 2: vertex index 8 is out of range", "index out of range");
  box.indices[4 * 3 + 2] = 7;

  box.face_materials[4] = 2;
  expect_error(dynrad_scene_create(box.positions, 8, box.indices, box.sizes, 6, box.face_materials, materials, m,
                                   &scene),
               DYNRAD_INVALID_INPUT, "polygon 4: material index 2", "material out of range");
  box.face_materials[4] = 0;

  box.face_materials[5] = 0;
  expect_error(dynrad_scene_create(box.positions, 8, box.indices, box.sizes, 6, box.face_materials, materials, m,
                                   &scene),
               DYNRAD_NO_EMITTER, "emits", "no emitter");
  box.face_materials[5] = 1;

  expect_error(dynrad_scene_create(box.positions, 8, box.indices, box.sizes, 6, box.face_materials, materials, m,
                                   NULL),
               DYNRAD_INVALID_ARGUMENT, "NULL", "NULL out_scene");

  dynrad_options* options = NULL;
  CHECK(dynrad_options_create(&options) == DYNRAD_OK, "%s", dynrad_last_error());
  expect_error(dynrad_options_set_method(options, "radiant"), DYNRAD_INVALID_ARGUMENT,
               "available: progressive, adaptive, dynamic", "unknown method");
  expect_error(dynrad_options_set_converge(options, 1.5), DYNRAD_INVALID_ARGUMENT, "converge", "converge 1.5");
  expect_error(dynrad_options_set_oracle(options, "oracle of delphi"), DYNRAD_INVALID_ARGUMENT, "available: pushdown, paper",
               "unknown oracle");
  expect_error(dynrad_options_set_oracle_threshold(options, "gradient", 0.1), DYNRAD_INVALID_ARGUMENT,
               "pushdown_error", "unknown threshold name");
  expect_error(dynrad_options_set_max_level(options, -1), DYNRAD_INVALID_ARGUMENT, "max_level", "level -1");
  expect_error(dynrad_options_set_overshoot(options, 2.0), DYNRAD_INVALID_ARGUMENT, "between 0 and 2", "overshoot 2");
  expect_error(dynrad_options_set_negligible_share(options, -1), DYNRAD_INVALID_ARGUMENT, "[0, 0.1]", "share -1");
  expect_error(dynrad_solve(NULL, options, NULL, NULL, NULL, NULL), DYNRAD_INVALID_ARGUMENT, "NULL", "NULL scene");

  /* After all those failures, a valid scene still works, and a short buffer is refused. */
  scene = create_box(&box, materials, m);
  CHECK(dynrad_options_set_iterations(options, 3) == DYNRAD_OK, "%s", dynrad_last_error());
  dynrad_result* result = NULL;
  CHECK(dynrad_solve(scene, options, NULL, NULL, NULL, &result) == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(strcmp(dynrad_last_error(), "") == 0, "a success left the message '%s'", dynrad_last_error());
  const size_t n = dynrad_result_vertex_count(result);
  float* b = malloc(3 * n * sizeof *b);
  expect_error(dynrad_result_radiosity(result, b, n - 1), DYNRAD_BUFFER_TOO_SMALL, "needed", "short buffer");
  dynrad_report report;
  CHECK(dynrad_result_report(result, &report) == DYNRAD_OK && report.stopped_by == DYNRAD_STOP_ITERATIONS &&
            report.shots == 3,
        "stopped_by %d after %llu shots", report.stopped_by, (unsigned long long)report.shots);
  CHECK(dynrad_result_vertex_count(NULL) == 0, "NULL result has vertices");
  free(b);
  dynrad_result_destroy(result);
  dynrad_options_destroy(options);
  dynrad_scene_destroy(scene);
  dynrad_scene_destroy(NULL);
  dynrad_result_destroy(NULL);
  dynrad_options_destroy(NULL);
}
