// The solve's JSON report (see report_json.h).
#include "radiosity/pipeline/report_json.h"

namespace dynrad::rad {

namespace {
nlohmann::json rgb_json(const Rgb& c) { return {c.r, c.g, c.b}; }
}  // namespace

nlohmann::json solve_report_json(const PreparedScene& p, const SolvedScene& s, double exposure) {
  const SolveReport& report = s.report;
  const SolveOptions& solve = p.solve;
  const RefineSettings& refine = p.refine;
  const OracleThresholds& oracle = refine.dynamic;
  const ShadowOutlineReport& outlines = p.outlines;
  const auto& e = report.energy;
  nlohmann::json j;
  j["method"] = report.method;
  j["units"] = p.photometric ? "photometric" : "radiometric";
  j["iterations"] = report.iterations;
  j["energy_transfers"] = report.energy_transfers;
  j["patch_element_transfers"] = report.patch_element_transfers;
  j["visibility_rays"] = report.visibility_rays;
  j["elements"] = report.elements;
  j["patches"] = report.patches;
  j["receivers"] = report.receivers;
  j["max_level"] = refine.max_level;
  j["unshot_fraction"] = report.unshot_fraction;
  j["seconds"] = report.seconds;
  j["imprint"] = {{"enabled", p.request.cleanup.imprint},
                  {"imprinted_edges", p.scene.cleanup.imprinted_edges},
                  {"hidden_area", p.scene.cleanup.hidden_area}};
  j["shadow_outlines"] = {{"enabled", p.request.shadow_outlines},
                          {"senders", outlines.senders},
                          {"silhouette_edges", outlines.silhouette_edges},
                          {"outlines", outlines.outlines},
                          {"lines", outlines.lines},
                          {"vertices_added", outlines.vertices_added},
                          {"flips", outlines.flips},
                          {"seconds", outlines.seconds}};
  j["stopped_by"] = to_string(report.stopped_by);
  nlohmann::json phases = nlohmann::json::array();
  for (const PhaseTime& t : p.phases.phases())
    phases.push_back({{"name", t.name},
                      {"seconds", t.seconds},
                      {"resident_mib", t.resident / 1048576.0},
                      {"peak_mib", t.peak / 1048576.0}});
  j["phases"] = phases;
  j["unshot_history"] = report.unshot_history;
  j["transfers_history"] = report.transfers_history;
  j["form_factor_sum_error"] = report.form_factor_sum_error;
  j["refinement_stopped"] = report.refinement_stopped;
  j["refinement_stopped_at"] = report.refinement_stopped_at;
  j["peak_resident_memory"] = report.peak_resident_memory;
  j["culled_receivers"] = report.culled_receivers;
  j["clusters"] = {{"clusters", report.clusters},
                   {"patches", report.clustered_patches},
                   {"parts", report.cluster_parts},
                   {"received_as_one", report.cluster_receptions},
                   {"opened", report.cluster_openings}};
  j["sender_groups"] = {{"groups", report.sender_groups}, {"patches", report.grouped_patches}};
  j["overshoot"] = solve.overshoot;
  j["hidden_receivers"] = report.hidden_receivers;
  j["visibility_tests"] = report.visibility_tests;
  j["negligible_receivers"] = report.negligible_receivers;
  j["negligible_share_max"] = report.negligible_share_max;
  j["ambient_display"] = solve.ambient_display;
  j["shaped_senders"] = solve.shaped_senders;
  j["exposure"] = exposure;
  j["patch_size"] = p.applied.patch_size;
  j["settings"] = {{"quality", quality_name(p.request.settings.quality)},
                   {"error_target", solve.error_target},
                   {"mean_free_path", p.applied.chosen.mean_free_path},
                   {"patch_size", p.applied.patch_size},
                   {"patch_size_rule", p.applied.patch_size_rule},
                   {"max_level", refine.max_level},
                   {"pushdown_error", oracle.pushdown},
                   {"pushdown_floor", oracle.pushdown_floor},
                   {"cumulated_gradient", oracle.pushdown_cumulated_gradient},
                   {"memory_budget_mib", static_cast<double>(refine.memory_budget) / (1024.0 * 1024.0)},
                   {"converge", solve.converge}};
  j["estimated_error"] = {{"total", report.estimated_error.total()},
                          {"unshot", report.estimated_error.unshot},
                          {"discretisation", report.estimated_error.discretisation},
                          {"shadows", report.estimated_error.shadows}};
  j["energy"] = {{"emitted", rgb_json(e.emitted)},
                 {"absorbed", rgb_json(e.absorbed)},
                 {"escaped", rgb_json(e.escaped)},
                 {"unshot", rgb_json(e.unshot)}};
  j["options"] = {{"converge", solve.converge},
                  {"max_elements", refine.max_elements},
                  {"memory_budget_mib", static_cast<double>(refine.memory_budget) / (1024.0 * 1024.0)},
                  {"iterations", solve.max_iterations},
                  {"time_limit", solve.time_limit},
                  {"threads", solve.threads},
                  {"seed", solve.seed}};
  return j;
}

nlohmann::json grid_summary_json(const SolvedScene& solved) {
  nlohmann::json grids = nlohmann::json::array();
  for (const GridResult& g : solved.grids) {
    nlohmann::json one = {{"name", g.spec.name}, {"points", g.count}, {"masked", g.masked}, {"Eavg", g.e_avg},
                          {"Emin", g.e_min},     {"Emax", g.e_max},   {"U0", g.u0},         {"spacing", g.spacing}};
    if (g.outside > 0) one["daylight_factor"] = {{"average", g.df_avg}, {"minimum", g.df_min}, {"maximum", g.df_max}};
    grids.push_back(one);
  }
  return grids;
}

}  // namespace dynrad::rad
