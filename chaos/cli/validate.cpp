// chaos validate: run every reference case of references/references.tsv on this machine and show
// reference, source, band, measured value and verdict. Exit code 4 if any case fails.

#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"

namespace chaos::cli {

namespace {

struct ValidateArgs {
  OutputOptions output;
  ValidateParams params;
  bool list = false;
};

std::string band(const Reference& r) { return "[" + number(r.low) + ", " + number(r.high) + "]"; }

void run(const ValidateArgs& args) {
  const ValidateParams& params = args.params;
  const std::vector<Reference> selected = validate_cases(params);  // refuses a filter that matches nothing
  Report report = validate_report(params, args.output);
  std::ostream& out = report.stream();
  if (!report.json_mode()) {
    report.write_header(out);
    out << "# id\tquantity\tvalue\tband\tmeasured\tresult\tseconds\tsource\tkind\tdetail\n";
    out.flush();
  }
  if (args.list) {
    for (const Reference& r : selected)
      out << r.id << "\t" << r.quantity << "\t" << (r.value ? number(*r.value) : "-") << "\t" << band(r) << "\t" << r.source
          << "\t" << r.kind << "\n";
    return;
  }
  const ValidateTally tally = run_validate(params, report, [&](const ValidationResult& v) {
    if (report.json_mode()) return;
    const Reference& r = v.reference;
    out << r.id << "\t" << r.quantity << "\t" << (r.value ? number(*r.value) : "-") << "\t" << band(r) << "\t"
        << (v.measured ? number(*v.measured) : "none") << "\t" << (v.passed ? "pass" : "FAIL") << "\t"
        << number(v.seconds) << "\t" << r.source << "\t" << r.kind << "\t" << v.detail << "\n";
    out.flush();
  });
  if (report.json_mode()) {
    report.write_json(out);
  } else {
    out << "# " << tally.passed << " passed, " << tally.failed << " failed\n";
  }
  if (tally.failed > 0) throw ValidationFailed{};
}

}  // namespace

void register_validate(CLI::App& app) {
  auto args = std::make_shared<ValidateArgs>();
  CLI::App* command = app.add_subcommand("validate", "run the reference cases (references/references.tsv) on this machine");
  add_quiet_option(*command);
  add_options(*command, args->params, validate_parameters());
  command->add_flag("--list", args->list, "list the cases without running them");
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
