#include "plugin/report/report_document.h"

#include "plugin/report/design_output.h"
#include "radiosity/pipeline/report_json.h"

namespace dynrad::report {

nlohmann::json report_document(const rad::PreparedScene& prepared, const rad::SolvedScene& solved, double exposure,
                               const ReportHost& host) {
  nlohmann::json j = rad::solve_report_json(prepared, solved, exposure);
  j["dynrad_version"] = host.version;
  j["input"] = host.input;
  j["output"] = host.output;
  j["grids"] = host.grids;
  j["views"] = views_json(host.pictures);
  j["luminaires"] = nlohmann::json::array();
  for (const rad::Luminaire& l : solved.solver->luminaires()) j["luminaires"].push_back(luminaire_json(l));
  if (solved.lit && !prepared.request.path.empty())
    add_design_checks(j, prepared.request.path, *solved.lit, solved.grids);
  if (!host.scenes.empty()) j["scenes"] = host.scenes;
  return j;
}

}  // namespace dynrad::report
