/* How a scene's polygons become patches, through the C ABI: a cube imprinted on the
 * floor it stands on (or not), and a floor of coplanar quads merged (or kept). */
#include "capi_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* A glowing floor 4 x 4 with a closed unit cube standing on it: imprinting (the default)
 * removes the floor under the cube and the cube's bottom, so the lit surfaces have
 * 16 - 1 + 5 = 20 m2; dynrad_options_set_imprint(o, 0) keeps them: 22 m2. */
void test_imprint(void) {
  double positions[3 * 12];
  const double corners[12][3] = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {1, 1, 0}, {2, 1, 0},
                                 {2, 2, 0}, {1, 2, 0}, {1, 1, 1}, {2, 1, 1}, {2, 2, 1}, {1, 2, 1}};
  for (int i = 0; i < 12; ++i)
    for (int c = 0; c < 3; ++c) positions[3 * i + c] = corners[i][c];
  /* the floor facing up; the cube's faces outward: bottom, top, four sides */
  const uint32_t indices[] = {0, 1, 2, 3, 4, 7, 6, 5, 8, 9, 10, 11, 4, 5, 9, 8, 5, 6, 10, 9, 6, 7, 11, 10, 7, 4, 8, 11};
  const uint32_t sizes[7] = {4, 4, 4, 4, 4, 4, 4};
  const uint32_t materials[7] = {0, 1, 1, 1, 1, 1, 1};
  const dynrad_material mats[2] = {grey(0.5, 1.0, "glow"), grey(0.5, 0.0, "box")};
  dynrad_scene* scene = NULL;
  const dynrad_status s = dynrad_scene_create(positions, 12, indices, sizes, 7, materials, mats, 2, &scene);
  CHECK(s == DYNRAD_OK, "dynrad_scene_create: %s: %s", dynrad_status_name(s), dynrad_last_error());
  if (!scene) return;
  double areas[2] = {0, 0};
  for (int run = 0; run < 2; ++run) {
    dynrad_options* options = options_with(1, 0.5);
    CHECK(dynrad_options_set_imprint(options, run == 0) == DYNRAD_OK, "%s", dynrad_last_error());
    dynrad_result* result = NULL;
    CHECK(dynrad_solve(scene, options, NULL, NULL, NULL, &result) == DYNRAD_OK, "%s", dynrad_last_error());
    if (result) {
      const size_t nv = dynrad_result_vertex_count(result), nt = dynrad_result_triangle_count(result);
      double* xyz = malloc(3 * nv * sizeof(double));
      uint32_t* tri = malloc(3 * nt * sizeof(uint32_t));
      CHECK(dynrad_result_positions(result, xyz, nv) == DYNRAD_OK, "%s", dynrad_last_error());
      CHECK(dynrad_result_triangles(result, tri, nt) == DYNRAD_OK, "%s", dynrad_last_error());
      for (size_t t = 0; t < nt; ++t) {
        const double* a = xyz + 3 * tri[3 * t];
        const double* b = xyz + 3 * tri[3 * t + 1];
        const double* c = xyz + 3 * tri[3 * t + 2];
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        areas[run] += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      }
      free(xyz);
      free(tri);
      dynrad_result_destroy(result);
    }
    dynrad_options_destroy(options);
  }
  CHECK(fabs(areas[0] - 20.0) < 1e-6, "imprinted: area %g, expected 20", areas[0]);
  CHECK(fabs(areas[1] - 22.0) < 1e-6, "not imprinted: area %g, expected 22", areas[1]);
  printf("imprint: %g m2 lit with, %g without\n", areas[0], areas[1]);
  dynrad_scene_destroy(scene);
}

/* A furnace box (every face glows 1, reflects 0.5: B = 2 everywhere) whose floor is a
 * 2 x 2 grid of coplanar quads. Simplification (the default) merges the grid; off, every
 * quad is kept. Both answer 2. */
void test_simplify(void) {
  double positions[(8 + 5) * 3];
  for (int i = 0; i < 8; ++i) {
    positions[3 * i + 0] = (i & 1) ? 2 : 0;
    positions[3 * i + 1] = (i & 2) ? 2 : 0;
    positions[3 * i + 2] = (i & 4) ? 2 : 0;
  }
  /* floor midpoints 8..11 (x = 1 edges, y = 1 edges) and centre 12, all at z = 0 */
  const double extra[5][3] = {{1, 0, 0}, {0, 1, 0}, {2, 1, 0}, {1, 2, 0}, {1, 1, 0}};
  for (int i = 0; i < 5; ++i)
    for (int c = 0; c < 3; ++c) positions[3 * (8 + i) + c] = extra[i][c];
  /* walls and ceiling as in make_box, then the floor (facing +z) as four quads */
  const uint32_t indices[] = {0, 2, 6, 4, 1, 5, 7, 3, 0, 4, 5, 1, 2, 3, 7, 6, 4, 6, 7, 5,
                              0, 8, 12, 9, 8, 1, 10, 12, 9, 12, 11, 2, 12, 10, 3, 11};
  const uint32_t sizes[9] = {4, 4, 4, 4, 4, 4, 4, 4, 4};
  const uint32_t materials[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  const dynrad_material glow = grey(0.5, 1.0, "glow");
  dynrad_scene* scene = NULL;
  const dynrad_status s = dynrad_scene_create(positions, 13, indices, sizes, 9, materials, &glow, 1, &scene);
  CHECK(s == DYNRAD_OK, "dynrad_scene_create: %s: %s", dynrad_status_name(s), dynrad_last_error());
  if (!scene) return;
  uint64_t patches[2] = {0, 0};
  for (int run = 0; run < 2; ++run) {
    dynrad_options* options = options_with(10, 1e-4); /* patches as large as the faces */
    CHECK(dynrad_options_set_simplify(options, run == 0) == DYNRAD_OK, "%s", dynrad_last_error());
    dynrad_result* result = NULL;
    const dynrad_status solved = dynrad_solve(scene, options, NULL, NULL, NULL, &result);
    CHECK(solved == DYNRAD_OK, "solve (simplify %d): %s: %s", run == 0, dynrad_status_name(solved),
          dynrad_last_error());
    if (result) {
      const size_t n = dynrad_result_vertex_count(result);
      float* b = malloc(3 * n * sizeof(float));
      CHECK(dynrad_result_radiosity(result, b, n) == DYNRAD_OK, "%s", dynrad_last_error());
      for (size_t v = 0; v < 3 * n; ++v)
        CHECK(fabs(b[v] - 2.0) < 0.02 * 2.0, "simplify %d: value %g at vertex %zu, expected 2", run == 0, b[v], v / 3);
      free(b);
      dynrad_report report;
      CHECK(dynrad_result_report(result, &report) == DYNRAD_OK, "%s", dynrad_last_error());
      patches[run] = report.patches;
      dynrad_result_destroy(result);
    }
    dynrad_options_destroy(options);
  }
  /* kept, the floor's quads (and the walls' edges split where they meet them) stay as
   * patches of their own (the written triangles may agree: refinement cuts both meshes
   * to the same smallest elements, the levels counting from the patch size) */
  CHECK(patches[0] > 0 && patches[0] < patches[1], "patches: %llu simplified, %llu not",
        (unsigned long long)patches[0], (unsigned long long)patches[1]);
  printf("simplify: %llu patches merged, %llu kept\n", (unsigned long long)patches[0], (unsigned long long)patches[1]);
  dynrad_scene_destroy(scene);
}
