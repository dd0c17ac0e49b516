#include "plugin/report/grid_output.h"

#include "mesh/io/atomic_file.h"
#include "plugin/report/grid_picture.h"
#include "plugin/report/png.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace dynrad::report {

void check_grid_outputs(const std::string& prefix, const std::vector<rad::GridSpec>& grids) {
  if (grids.empty()) return;
  check_output_writable(prefix + "_grids.json");
  for (const rad::GridSpec& g : grids) {
    check_output_writable(prefix + "_grid_" + g.name + ".csv");
    check_output_writable(prefix + "_grid_" + g.name + ".png");
  }
}

nlohmann::json grid_target_json(const rad::GridSpec& g) {
  nlohmann::json t = nlohmann::json::object();
  if (g.target_eavg > 0) t["Eavg"] = g.target_eavg;
  if (g.target_u0 > 0) t["U0"] = g.target_u0;
  return t;
}

nlohmann::json write_grid_results(const std::string& prefix, const std::string& input,
                                  const std::vector<rad::GridResult>& grids, bool photometric) {
  nlohmann::json results = nlohmann::json::array();
  const char* unit = photometric ? "lx" : "W/m2";
  for (const rad::GridResult& r : grids) {
    const rad::GridSpec& g = r.spec;
    const std::string csv = prefix + "_grid_" + g.name + ".csv";
    AtomicFile file(csv, std::ios::out);
    const bool df = r.outside > 0;
    file.stream() << fmt::format("x,y,z,illuminance_{0},direct_{0},indirect_{0},masked{1}\n", unit,
                                 df ? ",daylight_factor_percent,sky_component_percent,externally_reflected_percent,"
                                      "internally_reflected_percent"
                                    : "");
    for (const rad::GridPointResult& p : r.points) {
      file.stream() << fmt::format("{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{}", p.position[0], p.position[1],
                                   p.position[2], p.illuminance, p.direct, p.indirect, p.masked ? 1 : 0);
      if (df)
        file.stream() << fmt::format(",{:.5g},{:.5g},{:.5g},{:.5g}", 100 * p.illuminance / r.outside,
                                     100 * p.sky / r.outside, 100 * p.ground / r.outside, 100 * p.indirect / r.outside);
      file.stream() << "\n";
    }
    file.commit();
    const std::string png = prefix + "_grid_" + g.name + ".png";
    write_png(png, grid_picture(r, unit));
    nlohmann::json daylight = nullptr;
    if (r.outside > 0)
      daylight = {{"outside_horizontal_illuminance", r.outside},
                  {"DFavg", r.df_avg},
                  {"DFmin", r.df_min},
                  {"DFmax", r.df_max},
                  {"sky_component", r.sky_component},
                  {"externally_reflected_component", r.externally_reflected},
                  {"internally_reflected_component", r.internally_reflected}};
    results.push_back({{"name", g.name},
                       {"daylight_factor", daylight},
                       {"units", unit},
                       {"height", g.height},
                       {"spacing", r.spacing},
                       {"border", g.border},
                       {"count", r.count},
                       {"masked", r.masked},
                       {"Eavg", r.e_avg},
                       {"Emin", r.e_min},
                       {"Emax", r.e_max},
                       {"U0", r.u0},
                       {"Emin/Emax", r.min_over_max},
                       {"indirect_rays_per_point", r.indirect_rays},
                       {"target", grid_target_json(g)},
                       {"meets_target", r.meets_target()},
                       {"csv", csv},
                       {"picture", png}});
    spdlog::info("grid {}: {} points ({} inside solids, left out) at {:.3g} spacing, height {:.3g}: Eavg {:.4g} {}, "
                 "Emin {:.4g}, Emax {:.4g}, U0 {:.3f}, Emin/Emax {:.3f}{}; wrote {} and {}",
                 g.name, r.count, r.masked, r.spacing, g.height, r.e_avg, unit, r.e_min, r.e_max, r.u0,
                 r.min_over_max, r.spec.target_eavg > 0 || r.spec.target_u0 > 0 ? "; " + target_text(r, unit) : "", csv, png);
    if (r.outside > 0)
      spdlog::info("grid {}: daylight factor average {:.2f}% (sky component {:.2f}%, externally reflected {:.2f}%, "
                   "internally reflected {:.2f}%), minimum {:.2f}%, maximum {:.2f}%, outside {:.4g} lx",
                   g.name, r.df_avg, r.sky_component, r.externally_reflected, r.internally_reflected, r.df_min,
                   r.df_max, r.outside);
  }
  AtomicFile file(prefix + "_grids.json", std::ios::out);
  file.stream() << nlohmann::json({{"input", input}, {"grids", results}}).dump(2) << "\n";
  file.commit();
  return results;
}

}  // namespace dynrad::report
