/* The C ABI from C: boxes built from arrays, solved, checked against closed forms and
 * energy facts; a scene file with its sky and grid; the error paths; stopping early.
 * Compiled as C99 so that the header is proven usable from C. Exit status 0 when every
 * check holds.
 *
 * This file holds main, which runs the tests in order, the helpers they share and the
 * version check; the other tests are in capi_test_<topic>.c, and capi_test.h declares
 * what the files share. */
#include "capi_test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int failures = 0;

void make_box(Box* box, double sx, double sy, double sz, const uint32_t materials[6]) {
  static const uint32_t loops[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                       {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (int i = 0; i < 8; ++i) {
    box->positions[3 * i + 0] = (i & 1) ? sx : 0;
    box->positions[3 * i + 1] = (i & 2) ? sy : 0;
    box->positions[3 * i + 2] = (i & 4) ? sz : 0;
  }
  for (int k = 0; k < 6; ++k) {
    memcpy(box->indices + 4 * k, loops[k], sizeof loops[k]);
    box->sizes[k] = 4;
    box->face_materials[k] = materials[k];
  }
}

dynrad_material grey(double reflectance, double emission, const char* name) {
  dynrad_material m;
  for (int c = 0; c < 3; ++c) {
    m.reflectance[c] = reflectance;
    m.emission[c] = emission;
  }
  m.name = name;
  return m;
}

dynrad_scene* create_box(const Box* box, const dynrad_material* materials, size_t count) {
  dynrad_scene* scene = NULL;
  const dynrad_status s =
      dynrad_scene_create(box->positions, 8, box->indices, box->sizes, 6, box->face_materials, materials, count, &scene);
  CHECK(s == DYNRAD_OK, "dynrad_scene_create: %s: %s", dynrad_status_name(s), dynrad_last_error());
  return scene;
}

/* A box lit by its ceiling (the +z face): `wall` on the five others. */
dynrad_scene* create_ceiling_lit_box(double sx, double sy, double sz, dynrad_material wall,
                                     dynrad_material lamp) {
  const uint32_t faces[6] = {0, 0, 0, 0, 0, 1};
  const dynrad_material materials[2] = {wall, lamp};
  Box box;
  make_box(&box, sx, sy, sz, faces);
  return create_box(&box, materials, 2);
}

dynrad_options* options_with(double patch_size, double converge) {
  dynrad_options* options = NULL;
  CHECK(dynrad_options_create(&options) == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_patch_size(options, patch_size) == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_converge(options, converge) == DYNRAD_OK, "%s", dynrad_last_error());
  return options;
}

/* The 2 x 1 x 1 furnace box: every face emits 1 and reflects 0.5, so B = 2 everywhere. */
dynrad_scene* create_furnace_box(void) {
  const uint32_t all[6] = {0, 0, 0, 0, 0, 0};
  const dynrad_material glow = grey(0.5, 1.0, "glow");
  Box box;
  make_box(&box, 2, 1, 1, all);
  return create_box(&box, &glow, 1);
}

/* Solves and returns the per-vertex linear radiosity (3 floats per vertex; free() it),
 * or NULL after a failed check. *vertices and, if given, *triangles receive the counts. */
float* solve_radiosity(dynrad_scene* scene, dynrad_options* options, const char* what, size_t* vertices,
                       size_t* triangles) {
  dynrad_result* result = NULL;
  const dynrad_status s = dynrad_solve(scene, options, NULL, NULL, NULL, &result);
  CHECK(s == DYNRAD_OK, "solve (%s): %s: %s", what, dynrad_status_name(s), dynrad_last_error());
  *vertices = 0;
  if (!result) return NULL;
  *vertices = dynrad_result_vertex_count(result);
  if (triangles) *triangles = dynrad_result_triangle_count(result);
  float* b = malloc(3 * *vertices * sizeof(float));
  CHECK(dynrad_result_radiosity(result, b, *vertices) == DYNRAD_OK, "%s", dynrad_last_error());
  dynrad_result_destroy(result);
  return b;
}

/* Expects `status` and a message containing `needle`. */
void expect_error(dynrad_status status, dynrad_status expected, const char* needle, const char* what) {
  CHECK(status == expected, "%s: got %s, expected %s", what, dynrad_status_name(status), dynrad_status_name(expected));
  CHECK(strstr(dynrad_last_error(), needle) != NULL, "%s: message '%s' does not mention '%s'", what,
        dynrad_last_error(), needle);
}

/* Writes `text` to `dir`/`name`; the path goes to `path`. */
void write_file(const char* dir, const char* name, const char* text, char* path, size_t size) {
  snprintf(path, size, "%s/%s", dir, name);
  FILE* f = fopen(path, "w");
  CHECK(f != NULL, "cannot write %s", path);
  if (!f) return;
  fputs(text, f);
  fclose(f);
}

void test_version(void) {
  CHECK(dynrad_abi_version() == DYNRAD_ABI_VERSION, "library ABI %d, header %d", dynrad_abi_version(),
        DYNRAD_ABI_VERSION);
  CHECK(strcmp(dynrad_version(), DYNRAD_EXPECTED_VERSION) == 0, "version '%s'", dynrad_version());
  CHECK(strcmp(dynrad_status_name(DYNRAD_NO_EMITTER), "DYNRAD_NO_EMITTER") == 0, "status name");
}

int main(void) {
  test_version();
  test_imprint();
  test_furnace();
  test_defaults();
  test_ambient_and_overshoot();
  test_simplify();
  test_shaped_senders();
  test_lit_room_energy();
  test_stopping();
  test_errors();
  test_scene_file();
  test_illuminance_and_report();
  if (failures) {
    fprintf(stderr, "capi_test: %d checks failed\n", failures);
    return 1;
  }
  printf("capi_test: all checks passed\n");
  return 0;
}
