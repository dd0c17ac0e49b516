/* Boxes solved through the C ABI and checked against closed forms and energy facts: the
 * furnace (B = E / (1 - rho) everywhere) with the default options, the ambient term
 * and overshooting, shaped against flat senders, and a lit room's energy balance. */
#include "capi_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Every surface emits E and reflects rho: B = E / (1 - rho) at every vertex, and the
 * display colours, one exposure for a uniform field, are all equal. */
void test_furnace(void) {
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

/* No options at all, as `dynrad solve` without any: dynamic subdivision stopped by the
 * normal quality's error target (1%), which the report's estimate meets; the furnace's
 * mean is then within it. A quality that does not exist is refused by name. */
void test_defaults(void) {
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

/* Ten shots of the furnace: without the ambient term the values are far too dark;
 * with it their mean is close to E / (1 - rho) = 2. Overshooting gives the same answer
 * at convergence. */
void test_ambient_and_overshoot(void) {
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

/* Shaped senders (the default) against even ones (dynrad_options_set_shaped_senders(o, 0),
 * `--flat-senders`): in a room lit by its ceiling the walls' light is uneven, so the two
 * differ, but both are the same room's light: within a few percent at every vertex. */
void test_shaped_senders(void) {
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

/* A closed room lit by its ceiling, rho = 0.6 everywhere: sum of B x area over the
 * refined mesh = emitted power / (1 - rho). Checks positions, triangles and values
 * together. The same scene solved twice gives the same answer. */
void test_lit_room_energy(void) {
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
