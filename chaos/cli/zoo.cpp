// chaos zoo: the out-of-sample regression suite (zoo_suite.hpp) over the zoo's chaotic systems and
// the controls, in parallel on threads (run_zoo, commands.hpp), written as a Markdown report
// (docs/validation/zoo.md is made by `chaos zoo --threads 2 -o docs/validation/zoo.md`, resumable with --checkpoint,
// zoo_checkpoint.hpp). Exits with the validation-failure code when any estimate is confident and
// outside its band.

#include <iostream>

#include "chaos/error.hpp"
#include "chaos/format.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "output_path.hpp"
#include "parameter_options.hpp"
#include "safe_output.hpp"

namespace chaos::cli {

namespace {

struct ZooArgs {
  ZooParams params;
  std::string output;
  bool quiet = false;
  std::string series;  // write this case's series instead of running the suite
  bool json = false;   // --series as one JSON object
};

// The exact series a case is analysed with (the N = 10^4 rows use its first 10^4 samples), so that
// any row of docs/validation/zoo.md can be reproduced with chaos d2, lyapunov or analyze.
void write_case_series(const ZooArgs& args) {
  OutputOptions output;
  output.json = args.json;
  output.path = args.output;
  ZooSeriesRun run = run_zoo_series({args.series, args.params.fast, args.params.threads}, output);
  std::ostream* table = run.report.begin_table();
  if (!table) return;
  std::ostream& out = *table;
  write_columns(out, {"x"}, {std::span<const double>(run.x)});
}

void run(const ZooArgs& args) {
  if (args.params.threads == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "zoo: --threads must be at least 1 (got 0)");
  if (!args.series.empty()) {
    write_case_series(args);
    return;
  }
  if (args.json) throw InvalidInput(ErrorCode::invalid_parameter, "zoo: --json writes a case's series: give --series NAME");
  const ZooRun run = run_zoo(args.params, [&](std::size_t done, std::size_t total, const ZooCase& c, const ZooCaseResult& r) {
    if (!args.quiet)
      std::cerr << "zoo: " << done << "/" << total << " " << c.name << " (" << format_number(r.seconds, Precision::coarse) << " s)"
                << (r.error.empty() ? "" : " error: " + r.error) << "\n";
  });
  if (args.output.empty()) {
    std::cout << run.markdown;
  } else {
    safe_output::open_pending(args.output).stream() << run.markdown;
  }
  if (!args.quiet)
    std::cerr << "zoo: " << run.wrong << " confident and wrong; D2 coverage " << run.d2_covered << "/" << run.chaotic
              << ", lambda coverage " << run.lambda_covered << "/" << run.chaotic << "; " << format_number(run.wall_seconds, Precision::title)
              << " s" << (run.resumed > 0 ? " (" + std::to_string(run.resumed) + " case(s) read from " + args.params.checkpoint + ")" : "")
              << "\n";
  if (run.wrong > 0) throw ValidationFailed{};
}

}  // namespace

void register_zoo(CLI::App& app) {
  auto args = std::make_shared<ZooArgs>();
  CLI::App* command = app.add_subcommand(
      "zoo", "regression suite: every zoo system and control through the automatic estimates, judged against "
             "bands fixed in advance; Markdown report; exit 4 if any estimate is confident and wrong");
  add_options(*command, args->params, zoo_parameters());
  cli_support::check_output_option(
      command->add_option("-o,--output", args->output, "write the Markdown report here (default: standard output)"), "-o",
      nullptr, false, [](const std::string& why, bool) { throw InvalidInput(ErrorCode::io, why); });
  command->add_flag("-q,--quiet", args->quiet, "no progress on standard error");
  command->add_option("--series", args->series,
                      "write the series of this case (full precision, one value per line) instead of running the suite");
  command->add_flag("--json", args->json, "with --series: the series and its parameters as one JSON object");
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
