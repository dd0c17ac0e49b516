/* A solve ended before it converges, through the C ABI: by the progress callback, by
 * the cancel flag, and by a flag already set when the solve starts. */
#include "capi_test.h"

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

void test_stopping(void) {
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
