// validate: the reference cases and the JSON (commands.hpp).

#include <algorithm>

#include "chaos/error.hpp"
#include "commands.hpp"
#include "report_parameters.hpp"

namespace chaos::cli {

std::vector<Reference> validate_cases(const ValidateParams& params) {
  std::vector<Reference> cases;
  for (const Reference& r : reference_table())
    if (params.filter.empty() || r.id.find(params.filter) != std::string::npos) cases.push_back(r);
  // A typo in --filter ran nothing and exited 0, as if every case had passed.
  if (cases.empty())
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "--filter '" + params.filter + "' matches no case id (chaos validate --list shows them)");
  return cases;
}

Report validate_report(const ValidateParams& params, const OutputOptions& output) {
  Report report("validate", output);
  report_parameters(report, params, validate_parameters());
  if (params.filter.empty()) report.parameter("filter", std::string("(all)"));
  return report;
}

ValidateTally run_validate(const ValidateParams& params, Report& report,
                           const std::function<void(const ValidationResult&)>& each) {
  const std::vector<Reference> selected = validate_cases(params);
  ValidateTally tally;
  auto& cases = report.json()["cases"] = nlohmann::ordered_json::array();
  for (const Reference& r : selected) {
    const ValidationResult v = validate(r);
    (v.passed ? tally.passed : tally.failed)++;
    cases.push_back({{"id", r.id}, {"system", r.system}, {"quantity", r.quantity}, {"value", optional_json(r.value)},
                     {"low", r.low}, {"high", r.high}, {"measured", optional_json(v.measured)}, {"passed", v.passed},
                     {"seconds", v.seconds}, {"source", r.source}, {"kind", r.kind}, {"detail", v.detail}});
    if (each) each(v);
  }
  report.json()["passed"] = tally.passed;
  report.json()["failed"] = tally.failed;
  return tally;
}

}  // namespace chaos::cli
