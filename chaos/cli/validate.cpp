// chaos validate: run every reference case of references/references.tsv on this machine and show
// reference, source, band, measured value and verdict. Exit code 4 if any case fails.

#include <algorithm>
#include <iostream>

#include "chaos/error.hpp"
#include "chaos/validation.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct ValidateArgs {
  OutputOptions output;
  std::string filter;
  bool list = false;
};

std::string band(const Reference& r) { return "[" + number(r.low) + ", " + number(r.high) + "]"; }

void run(const ValidateArgs& args) {
  // A typo in --filter ran nothing and exited 0, as if every case had passed (issue 16).
  if (!args.filter.empty() && std::none_of(reference_table().begin(), reference_table().end(),
                                           [&](const Reference& r) { return r.id.find(args.filter) != std::string::npos; }))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "--filter '" + args.filter + "' matches no case id (chaos validate --list shows them)");
  Report report("validate", args.output);
  report.parameter("filter", args.filter.empty() ? std::string("(all)") : args.filter);
  std::ostream& out = report.stream();
  if (!report.json_mode()) {
    report.write_header(out);
    out << "# id\tquantity\tvalue\tband\tmeasured\tresult\tseconds\tsource\tkind\tdetail\n";
    out.flush();
  }
  std::size_t passed = 0, failed = 0;
  auto& cases = report.json()["cases"] = nlohmann::ordered_json::array();
  for (const Reference& r : reference_table()) {
    if (!args.filter.empty() && r.id.find(args.filter) == std::string::npos) continue;
    if (args.list) {
      out << r.id << "\t" << r.quantity << "\t" << (r.value ? number(*r.value) : "-") << "\t" << band(r) << "\t" << r.source
          << "\t" << r.kind << "\n";
      continue;
    }
    const ValidationResult v = validate(r);
    (v.passed ? passed : failed)++;
    if (report.json_mode()) {
      cases.push_back({{"id", r.id}, {"system", r.system}, {"quantity", r.quantity}, {"value", optional_json(r.value)},
                       {"low", r.low}, {"high", r.high}, {"measured", optional_json(v.measured)}, {"passed", v.passed},
                       {"seconds", v.seconds}, {"source", r.source}, {"kind", r.kind}, {"detail", v.detail}});
    } else {
      out << r.id << "\t" << r.quantity << "\t" << (r.value ? number(*r.value) : "-") << "\t" << band(r) << "\t"
          << (v.measured ? number(*v.measured) : "none") << "\t" << (v.passed ? "pass" : "FAIL") << "\t"
          << number(v.seconds) << "\t" << r.source << "\t" << r.kind << "\t" << v.detail << "\n";
      out.flush();
    }
  }
  if (args.list) return;
  if (report.json_mode()) {
    report.json()["passed"] = passed;
    report.json()["failed"] = failed;
    report.write_json(out);
  } else {
    out << "# " << passed << " passed, " << failed << " failed\n";
  }
  if (failed > 0) throw ValidationFailed{};
}

}  // namespace

void register_validate(CLI::App& app) {
  auto args = std::make_shared<ValidateArgs>();
  CLI::App* command = app.add_subcommand("validate", "run the reference cases (references/references.tsv) on this machine");
  command->add_option("--filter", args->filter, "only cases whose id contains this text");
  command->add_flag("--list", args->list, "list the cases without running them");
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
