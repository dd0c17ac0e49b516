/* What the capi_test sources share: the CHECK macro and its count of failed checks,
 * the box scenes, materials and options that the tests build on, and the tests
 * themselves, which main (capi_test.c) runs in order. */
#ifndef DYNRAD_TESTS_CAPI_TEST_H
#define DYNRAD_TESTS_CAPI_TEST_H

#include <dynrad/dynrad.h>

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

extern int failures; /* checks that failed so far; main's exit status depends on it */

#define CHECK(condition, ...)                                          \
  do {                                                                 \
    if (!(condition)) {                                                \
      ++failures;                                                      \
      fprintf(stderr, "%s:%d: check failed: %s\n  ", __FILE__, __LINE__, #condition); \
      fprintf(stderr, __VA_ARGS__);                                    \
      fprintf(stderr, "\n");                                           \
    }                                                                  \
  } while (0)

/* A closed box [0, sx] x [0, sy] x [0, sz], faces pointing inward; face k gets
 * materials[k] for -x, +x, -y, +y, -z, +z. */
typedef struct Box {
  double positions[8 * 3];
  uint32_t indices[6 * 4];
  uint32_t sizes[6];
  uint32_t face_materials[6];
} Box;

/* Shared helpers (capi_test.c). */
void make_box(Box* box, double sx, double sy, double sz, const uint32_t materials[6]);
dynrad_material grey(double reflectance, double emission, const char* name);
dynrad_scene* create_box(const Box* box, const dynrad_material* materials, size_t count);
dynrad_scene* create_ceiling_lit_box(double sx, double sy, double sz, dynrad_material wall, dynrad_material lamp);
dynrad_options* options_with(double patch_size, double converge);
dynrad_scene* create_furnace_box(void);
float* solve_radiosity(dynrad_scene* scene, dynrad_options* options, const char* what, size_t* vertices,
                       size_t* triangles);
void expect_error(dynrad_status status, dynrad_status expected, const char* needle, const char* what);
void write_file(const char* dir, const char* name, const char* text, char* path, size_t size);

/* The tests, in the order main runs them, with the file that holds each. */
void test_version(void);                /* capi_test.c */
void test_imprint(void);                /* capi_test_geometry.c */
void test_furnace(void);                /* capi_test_solve.c */
void test_defaults(void);               /* capi_test_solve.c */
void test_ambient_and_overshoot(void);  /* capi_test_solve.c */
void test_simplify(void);               /* capi_test_geometry.c */
void test_shaped_senders(void);         /* capi_test_solve.c */
void test_lit_room_energy(void);        /* capi_test_solve.c */
void test_stopping(void);               /* capi_test_stopping.c */
void test_errors(void);                 /* capi_test_errors.c */
void test_scene_file(void);             /* capi_test_scene_file.c */
void test_illuminance_and_report(void); /* capi_test_report.c */

#endif
