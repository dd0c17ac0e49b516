/* The C ABI from C: boxes built from arrays, solved, checked against closed forms and
 * energy facts; a scene file with its sky and grid; the error paths; stopping early.
 * Compiled as C99 so that the header is proven usable from C. Exit status 0 when every
 * check holds. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <dynrad/dynrad.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h> /* access */

static int failures = 0;

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

static void make_box(Box* box, double sx, double sy, double sz, const uint32_t materials[6]) {
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

static dynrad_material grey(double reflectance, double emission, const char* name) {
  dynrad_material m;
  for (int c = 0; c < 3; ++c) {
    m.reflectance[c] = reflectance;
    m.emission[c] = emission;
  }
  m.name = name;
  return m;
}

static dynrad_scene* create_box(const Box* box, const dynrad_material* materials, size_t count) {
  dynrad_scene* scene = NULL;
  const dynrad_status s =
      dynrad_scene_create(box->positions, 8, box->indices, box->sizes, 6, box->face_materials, materials, count, &scene);
  CHECK(s == DYNRAD_OK, "dynrad_scene_create: %s: %s", dynrad_status_name(s), dynrad_last_error());
  return scene;
}

/* A box lit by its ceiling (the +z face): `wall` on the five others. */
static dynrad_scene* create_ceiling_lit_box(double sx, double sy, double sz, dynrad_material wall,
                                            dynrad_material lamp) {
  const uint32_t faces[6] = {0, 0, 0, 0, 0, 1};
  const dynrad_material materials[2] = {wall, lamp};
  Box box;
  make_box(&box, sx, sy, sz, faces);
  return create_box(&box, materials, 2);
}

static dynrad_options* options_with(double patch_size, double converge) {
  dynrad_options* options = NULL;
  CHECK(dynrad_options_create(&options) == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_patch_size(options, patch_size) == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_converge(options, converge) == DYNRAD_OK, "%s", dynrad_last_error());
  return options;
}

/* The 2 x 1 x 1 furnace box: every face emits 1 and reflects 0.5, so B = 2 everywhere. */
static dynrad_scene* create_furnace_box(void) {
  const uint32_t all[6] = {0, 0, 0, 0, 0, 0};
  const dynrad_material glow = grey(0.5, 1.0, "glow");
  Box box;
  make_box(&box, 2, 1, 1, all);
  return create_box(&box, &glow, 1);
}

/* Solves and returns the per-vertex linear radiosity (3 floats per vertex; free() it),
 * or NULL after a failed check. *vertices and, if given, *triangles receive the counts. */
static float* solve_radiosity(dynrad_scene* scene, dynrad_options* options, const char* what, size_t* vertices,
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

static void test_version(void) {
  CHECK(dynrad_abi_version() == DYNRAD_ABI_VERSION, "library ABI %d, header %d", dynrad_abi_version(),
        DYNRAD_ABI_VERSION);
  CHECK(strcmp(dynrad_version(), DYNRAD_EXPECTED_VERSION) == 0, "version '%s'", dynrad_version());
  CHECK(strcmp(dynrad_status_name(DYNRAD_NO_EMITTER), "DYNRAD_NO_EMITTER") == 0, "status name");
}

/* Every surface emits E and reflects rho: B = E / (1 - rho) at every vertex, and the
 * display colours, one exposure for a uniform field, are all equal. */
static void test_furnace(void) {
  dynrad_scene* scene = create_furnace_box();
  dynrad_options* options = options_with(0.3, 1e-5);
  CHECK(dynrad_options_set_method(options, "dynamic") == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_max_level(options, 1) == DYNRAD_OK, "%s", dynrad_last_error());
  /* The push-down oracle with every transfer's error bounded (README: the defaults are
   * biased in a furnace). */
  CHECK(dynrad_options_set_oracle(options, "pushdown") == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_oracle_threshold(options, "cumulated_gradient", 0) == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_oracle_threshold(options, "pushdown_floor", 0) == DYNRAD_OK, "%s", dynrad_last_error());
  CHECK(dynrad_options_set_oracle_threshold(options, "pushdown_error", 0.02) == DYNRAD_OK, "%s", dynrad_last_error());
  dynrad_result* result = NULL;
  const dynrad_status s = dynrad_solve(scene, options, NULL, NULL, NULL, &result);
  CHECK(s == DYNRAD_OK, "solve: %s: %s", dynrad_status_name(s), dynrad_last_error());
  if (result) {
    const size_t n = dynrad_result_vertex_count(result);
    CHECK(n >= 8, "%zu vertices", n);
    float* b = malloc(3 * n * sizeof *b);
    uint8_t* display = malloc(3 * n);
    CHECK(dynrad_result_radiosity(result, b, n) == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(dynrad_result_display(result, display, n) == DYNRAD_OK, "%s", dynrad_last_error());
    int off = 0;
    for (size_t i = 0; i < 3 * n; ++i)
      if (fabs(b[i] - 2.0) > 0.01 * 2.0) ++off;
    CHECK(off == 0, "%d of %zu channel values differ from E/(1-rho) = 2 by more than 1%%", off, 3 * n);
    for (size_t i = 1; i < n; ++i)
      if (abs(display[3 * i] - display[0]) > 1) ++off;
    CHECK(off == 0, "display colours of a uniform field differ");
    dynrad_report report;
    CHECK(dynrad_result_report(result, &report) == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(report.stopped_by == DYNRAD_STOP_CONVERGED, "stopped_by %d", report.stopped_by);
    CHECK(report.unshot_fraction <= 1e-5, "unshot %g", report.unshot_fraction);
    CHECK(report.shots > 0 && report.energy_transfers >= report.shots && report.visibility_rays > 0,
          "shots %llu, transfers %llu, rays %llu", (unsigned long long)report.shots,
          (unsigned long long)report.energy_transfers, (unsigned long long)report.visibility_rays);
    CHECK(fabs(report.patch_size - 0.3) < 1e-12, "patch size %g", report.patch_size);
    CHECK(report.escaped[1] <= 1e-9 * report.emitted[1], "a closed box lets %g escape", report.escaped[1]);
    /* Emitted power = E x total area = 1 x (2 x 1 + 2 x 1 + 1 x 1) x 2 = 10 */
    CHECK(fabs(report.emitted[0] - 10.0) < 1e-9, "emitted %g, expected 10", report.emitted[0]);
    free(b);
    free(display);
  }
  dynrad_result_destroy(result);
  dynrad_options_destroy(options);
  dynrad_scene_destroy(scene);
}

/* A closed room lit by its ceiling, rho = 0.6 everywhere: sum of B x area over the
 * refined mesh = emitted power / (1 - rho). Checks positions, triangles and values
 * together. The same scene solved twice gives the same answer. */
/* Ten shots of the furnace: without the ambient term the values are far too dark;
 * with it their mean is close to E / (1 - rho) = 2. Overshooting gives the same answer
 * at convergence. */
static void test_ambient_and_overshoot(void) {
  dynrad_scene* scene = create_furnace_box();
  double means[3] = {0, 0, 0};
  for (int run = 0; run < 3; ++run) {
    dynrad_options* options = options_with(0.3, run == 2 ? 1e-5 : 0);
    if (run < 2) CHECK(dynrad_options_set_iterations(options, 10) == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(dynrad_options_set_ambient(options, run == 1) == DYNRAD_OK, "%s", dynrad_last_error());
    if (run == 2) CHECK(dynrad_options_set_overshoot(options, 1.3) == DYNRAD_OK, "%s", dynrad_last_error());
    size_t n = 0;
    float* b = solve_radiosity(scene, options, run == 0 ? "10 shots" : run == 1 ? "ambient" : "overshoot", &n, NULL);
    for (size_t v = 0; b && v < n; ++v) means[run] += b[3 * v + 1] / (double)n;
    free(b);
    dynrad_options_destroy(options);
  }
  CHECK(means[0] < 0.9 * 2.0, "10 shots without ambient: mean %g, expected well below 2", means[0]);
  CHECK(fabs(means[1] - 2.0) < 0.05 * 2.0, "10 shots with ambient: mean %g, expected about 2", means[1]);
  CHECK(fabs(means[2] - 2.0) < 0.01 * 2.0, "overshoot 1.3, converged: mean %g, expected 2", means[2]);
  dynrad_scene_destroy(scene);
}

/* A furnace box (every face glows 1, reflects 0.5: B = 2 everywhere) whose floor is a
 * 2 x 2 grid of coplanar quads. Simplification (the default) merges the grid; off, every
 * quad is kept. Both answer 2. */
static void test_simplify(void) {
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

/* Shaped senders (the default) against even ones (dynrad_options_set_shaped_senders(o, 0),
 * `--flat-senders`): in a room lit by its ceiling the walls' light is uneven, so the two
 * differ, but both are the same room's light: within a few percent at every vertex. */
static void test_shaped_senders(void) {
  dynrad_scene* scene = create_ceiling_lit_box(3, 2, 1.5, grey(0.6, 0.0, "wall"), grey(0.0, 10.0, "ceiling"));
  float* b[2] = {NULL, NULL};
  size_t n[2] = {0, 0};
  for (int shaped = 0; shaped < 2; ++shaped) {
    dynrad_options* options = options_with(0.6, 1e-3);
    /* the same mesh for both: no refinement, which would differ between them */
    CHECK(dynrad_options_set_method(options, "progressive") == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(dynrad_options_set_shaped_senders(options, shaped) == DYNRAD_OK, "%s", dynrad_last_error());
    b[shaped] = solve_radiosity(scene, options, shaped ? "shaped senders" : "flat senders", &n[shaped], NULL);
    dynrad_options_destroy(options);
  }
  CHECK(n[0] == n[1] && n[0] > 0, "vertices: %zu flat, %zu shaped", n[0], n[1]);
  double largest = 0;
  for (size_t v = 0; b[0] && b[1] && n[0] == n[1] && v < 3 * n[0]; ++v)
    if (b[0][v] > 0) largest = fmax(largest, fabs(b[1][v] - b[0][v]) / b[0][v]);
  CHECK(largest > 1e-4 && largest < 0.1, "largest relative difference, shaped against flat senders: %g", largest);
  printf("shaped senders: largest difference from flat ones %.2f%%\n", 100 * largest);
  free(b[0]);
  free(b[1]);
  dynrad_scene_destroy(scene);
}

static void test_lit_room_energy(void) {
  dynrad_scene* scene = create_ceiling_lit_box(3, 2, 1.5, grey(0.6, 0.0, "wall"), grey(0.6, 10.0, "ceiling"));
  dynrad_options* options = options_with(0.6, 1e-4);
  double totals[2] = {0, 0};
  for (int run = 0; run < 2; ++run) {
    dynrad_result* result = NULL;
    const dynrad_status s = dynrad_solve(scene, options, NULL, NULL, NULL, &result);
    CHECK(s == DYNRAD_OK, "solve %d: %s: %s", run, dynrad_status_name(s), dynrad_last_error());
    if (!result) continue;
    const size_t n = dynrad_result_vertex_count(result), t = dynrad_result_triangle_count(result);
    double* xyz = malloc(3 * n * sizeof *xyz);
    uint32_t* tri = malloc(3 * t * sizeof *tri);
    uint32_t* material = malloc(t * sizeof *material);
    float* b = malloc(3 * n * sizeof *b);
    CHECK(dynrad_result_positions(result, xyz, n) == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(dynrad_result_triangles(result, tri, t) == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(dynrad_result_triangle_materials(result, material, t) == DYNRAD_OK, "%s", dynrad_last_error());
    CHECK(dynrad_result_radiosity(result, b, n) == DYNRAD_OK, "%s", dynrad_last_error());
    double area_sum = 0, ceiling_area = 0;
    for (size_t f = 0; f < t; ++f) {
      const double* p[3];
      double mean = 0;
      for (int k = 0; k < 3; ++k) {
        CHECK(tri[3 * f + k] < n, "triangle %zu corner %d: index %u", f, k, tri[3 * f + k]);
        if (tri[3 * f + k] >= n) return;
        p[k] = xyz + 3 * tri[3 * f + k];
        mean += b[3 * tri[3 * f + k] + 1] / 3.0;
      }
      const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
      const double v[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
      const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
      const double area = 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
      area_sum += area;
      totals[run] += mean * area;
      if (material[f] == 1) {
        ceiling_area += area;
        CHECK(fabs(p[0][2] - 1.5) < 1e-12 && cz < 0, "a ceiling triangle is not at z = 1.5 facing down");
      }
    }
    CHECK(fabs(area_sum - 2 * (3 * 2 + 3 * 1.5 + 2 * 1.5)) < 1e-9, "mesh area %g, expected 27", area_sum);
    CHECK(fabs(ceiling_area - 6.0) < 1e-9, "ceiling area %g, expected 6", ceiling_area);
    const double emitted = 10.0 * 6.0;
    CHECK(fabs(totals[run] - emitted / (1 - 0.6)) < 0.01 * emitted / (1 - 0.6),
          "sum B A = %g, expected %g within 1%%", totals[run], emitted / (1 - 0.6));
    dynrad_report report;
    dynrad_result_report(result, &report);
    CHECK(fabs(report.emitted[1] - emitted) < 1e-9, "emitted %g", report.emitted[1]);
    CHECK(fabs(report.absorbed[1] - emitted) < 1e-4 * emitted, "absorbed %g of %g", report.absorbed[1], emitted);
    free(xyz);
    free(tri);
    free(material);
    free(b);
    dynrad_result_destroy(result);
  }
  CHECK(totals[0] == totals[1], "two solves of one scene differ: %.17g and %.17g", totals[0], totals[1]);
  dynrad_options_destroy(options);
  dynrad_scene_destroy(scene);
}

/* Stopping early: the progress callback's return value, and a cancel flag. */
typedef struct Progress {
  uint64_t calls, last_shot, stop_at;
  double last_unshot;
  volatile int* cancel; /* set at stop_at instead of returning non-zero, when not NULL */
} Progress;

static int on_progress(uint64_t shot, double unshot_fraction, void* user) {
  Progress* p = (Progress*)user;
  ++p->calls;
  if (unshot_fraction > p->last_unshot + 1e-12) p->last_unshot = 2; /* marks a rise: checked below */
  else p->last_unshot = unshot_fraction;
  p->last_shot = shot;
  if (shot < p->stop_at) return 0;
  if (p->cancel) {
    *p->cancel = 1;
    return 0;
  }
  return 1;
}

static void test_stopping(void) {
  dynrad_scene* scene = create_ceiling_lit_box(2, 2, 2, grey(0.7, 0.0, "wall"), grey(0.5, 5.0, "lamp"));
  dynrad_options* options = options_with(0.25, 1e-9);
  volatile int cancel = 0;
  for (int by_flag = 0; by_flag < 2; ++by_flag) {
    Progress progress = {0, 0, 5, 1.0, by_flag ? &cancel : NULL};
    dynrad_result* result = NULL;
    const dynrad_status s = dynrad_solve(scene, options, on_progress, &progress, &cancel, &result);
    CHECK(s == DYNRAD_STOPPED, "%s: %s, %s", by_flag ? "flag" : "callback", dynrad_status_name(s),
          dynrad_last_error());
    CHECK(progress.calls == 5 && progress.last_shot == 5, "%llu calls, last shot %llu",
          (unsigned long long)progress.calls, (unsigned long long)progress.last_shot);
    CHECK(progress.last_unshot <= 1.0, "unshot fraction rose during the solve");
    dynrad_report report;
    CHECK(dynrad_result_report(result, &report) == DYNRAD_OK, "no report after a stop: %s", dynrad_last_error());
    CHECK(report.shots == 5 && report.stopped_by == DYNRAD_STOP_CANCELLED, "shots %llu, stopped_by %d",
          (unsigned long long)report.shots, report.stopped_by);
    CHECK(report.unshot_fraction > 1e-3, "unshot %g after 5 shots", report.unshot_fraction);
    CHECK(dynrad_result_vertex_count(result) > 0, "a stopped solve has no vertices");
    dynrad_result_destroy(result);
  }
  /* A flag already set: no shot at all, and the (dark) solution so far all the same. */
  dynrad_result* result = NULL;
  CHECK(cancel == 1, "the callback did not set the flag");
  CHECK(dynrad_solve(scene, options, NULL, NULL, &cancel, &result) == DYNRAD_STOPPED, "%s", dynrad_last_error());
  dynrad_report report;
  CHECK(dynrad_result_report(result, &report) == DYNRAD_OK && report.shots == 0, "shots %llu",
        (unsigned long long)report.shots);
  dynrad_result_destroy(result);
  dynrad_options_destroy(options);
  dynrad_scene_destroy(scene);
}

/* Expects `status` and a message containing `needle`. */
static void expect_error(dynrad_status status, dynrad_status expected, const char* needle, const char* what) {
  CHECK(status == expected, "%s: got %s, expected %s", what, dynrad_status_name(status), dynrad_status_name(expected));
  CHECK(strstr(dynrad_last_error(), needle) != NULL, "%s: message '%s' does not mention '%s'", what,
        dynrad_last_error(), needle);
}

static void test_errors(void) {
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

/* A glowing floor 4 x 4 with a closed unit cube standing on it: imprinting (the default)
 * removes the floor under the cube and the cube's bottom, so the lit surfaces have
 * 16 - 1 + 5 = 20 m2; dynrad_options_set_imprint(o, 0) keeps them: 22 m2. */
static void test_imprint(void) {
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

/* No options at all, as `dynrad solve` without any: dynamic subdivision stopped by the
 * normal quality's error target (1%), which the report's estimate meets; the furnace's
 * mean is then within it. A quality that does not exist is refused by name. */
static void test_defaults(void) {
  dynrad_scene* scene = create_furnace_box();
  dynrad_options* options = NULL;
  CHECK(dynrad_options_create(&options) == DYNRAD_OK, "%s", dynrad_last_error());
  expect_error(dynrad_options_set_quality(options, "best"), DYNRAD_INVALID_ARGUMENT, "best", "quality 'best'");
  for (int q = 0; q < 2; ++q) {
    CHECK(dynrad_options_set_quality(options, q == 0 ? "normal" : "draft") == DYNRAD_OK, "%s", dynrad_last_error());
    dynrad_result* result = NULL;
    const dynrad_status s = dynrad_solve(scene, options, NULL, NULL, NULL, &result);
    CHECK(s == DYNRAD_OK, "solve: %s: %s", dynrad_status_name(s), dynrad_last_error());
    if (!result) continue;
    dynrad_report report;
    CHECK(dynrad_result_report(result, &report) == DYNRAD_OK, "%s", dynrad_last_error());
    const double target = q == 0 ? 0.01 : 0.03;
    CHECK(report.stopped_by == DYNRAD_STOP_ERROR_TARGET, "stopped_by %d", report.stopped_by);
    CHECK(report.estimated_error > 0 && report.estimated_error <= target, "estimated error %g, target %g",
          report.estimated_error, target);
    const size_t n = dynrad_result_vertex_count(result);
    float* b = malloc(3 * n * sizeof *b);
    CHECK(dynrad_result_radiosity(result, b, n) == DYNRAD_OK, "%s", dynrad_last_error());
    double mean = 0;
    for (size_t i = 0; i < n; ++i) mean += fabs(b[3 * i + 1] - 2.0) / 2.0 / (double)n;
    CHECK(mean <= report.estimated_error, "mean error %g above the estimate %g", mean, report.estimated_error);
    printf("defaults (%s): estimated error %.3f%%, measured %.3f%%\n", q == 0 ? "normal" : "draft",
           100 * report.estimated_error, 100 * mean);
    free(b);
    dynrad_result_destroy(result);
  }
  dynrad_options_destroy(options);
  dynrad_scene_destroy(scene);
}

/* Writes `text` to `dir`/`name`; the path goes to `path`. */
static void write_file(const char* dir, const char* name, const char* text, char* path, size_t size) {
  snprintf(path, size, "%s/%s", dir, name);
  FILE* f = fopen(path, "w");
  CHECK(f != NULL, "cannot write %s", path);
  if (!f) return;
  fputs(text, f);
  fclose(f);
}

/* A scene file, as `dynrad solve` reads it: the daylit room sample (a CIE sky, the sun
 * through a window, a grid). Its grid comes back per point and in the JSON report, whose
 * Eavg is the mean of the points; the sun's patch on the work plane is far above the
 * rest. Then what a scene file can get wrong. */
static void test_scene_file(void) {
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

/* A room lit by the downlight sample (IES), with a work plane: per-vertex illuminance,
 * the HTML report and the report's false-colour scale. */
static void test_illuminance_and_report(void) {
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
