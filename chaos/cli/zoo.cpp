// chaos zoo: the out-of-sample regression suite (zoo_suite.hpp) over the zoo's chaotic systems and
// the controls, in parallel on threads (run_zoo, commands.hpp), written as a Markdown report
// (docs/validation/zoo.md is made by `chaos zoo --threads 2 -o docs/validation/zoo.md`, resumable with --checkpoint,
// zoo_checkpoint.hpp). Exits with the validation-failure code when any estimate is confident and
// outside its band.

#include <iostream>
#include <sstream>

#include "chaos/error.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "output_path.hpp"
#include "safe_output.hpp"

namespace chaos::cli {

namespace {

struct ZooArgs {
  bool fast = false;
  bool no_grid = false;
  std::size_t grid_points = 2;
  std::vector<std::string> only;
  std::size_t threads = 1;
  std::string output;
  std::string checkpoint;  // finished cases appended here; those it holds are not run again
  bool quiet = false;
  std::string series;  // write this case's series instead of running the suite
  bool json = false;   // --series as one JSON object
};

// A time in seconds to `digits` significant digits, as the report writes it.
std::string seconds(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

// The exact series a case is analysed with (the N = 10^4 rows use its first 10^4 samples), so that
// any row of docs/validation/zoo.md can be reproduced with chaos d2, lyapunov or analyze.
void write_case_series(const ZooArgs& args) {
  OutputOptions output;
  output.json = args.json;
  output.path = args.output;
  ZooSeriesRun run = run_zoo_series({args.series, args.fast, args.threads}, output);
  Report& report = run.report;
  std::ostream& out = report.stream();
  if (report.json_mode()) {
    report.write_json(out);
    return;
  }
  report.write_header(out);
  write_columns(out, {"x"}, {std::span<const double>(run.x)});
}

void run(const ZooArgs& args) {
  if (args.threads == 0) throw InvalidInput(ErrorCode::invalid_parameter, "zoo: --threads must be at least 1 (got 0)");
  if (!args.series.empty()) {
    write_case_series(args);
    return;
  }
  if (args.json) throw InvalidInput(ErrorCode::invalid_parameter, "zoo: --json writes a case's series: give --series NAME");
  ZooParams params;
  params.fast = args.fast;
  params.grid = !args.no_grid;
  params.grid_points = args.grid_points;
  params.only = args.only;
  params.threads = args.threads;
  params.checkpoint = args.checkpoint;
  const ZooRun run = run_zoo(params, [&](std::size_t done, std::size_t total, const ZooCase& c, const ZooCaseResult& r) {
    if (!args.quiet)
      std::cerr << "zoo: " << done << "/" << total << " " << c.name << " (" << seconds(r.seconds, 3) << " s)"
                << (r.error.empty() ? "" : " error: " + r.error) << "\n";
  });
  if (args.output.empty()) {
    std::cout << run.markdown;
  } else {
    safe_output::open_pending(args.output).stream() << run.markdown;
  }
  if (!args.quiet)
    std::cerr << "zoo: " << run.wrong << " confident and wrong; D2 coverage " << run.d2_covered << "/" << run.chaotic
              << ", lambda coverage " << run.lambda_covered << "/" << run.chaotic << "; " << seconds(run.wall_seconds, 4)
              << " s" << (run.resumed > 0 ? " (" + std::to_string(run.resumed) + " case(s) read from " + args.checkpoint + ")" : "")
              << "\n";
  if (run.wrong > 0) throw ValidationFailed{};
}

}  // namespace

void register_zoo(CLI::App& app) {
  auto args = std::make_shared<ZooArgs>();
  CLI::App* command = app.add_subcommand(
      "zoo", "regression suite: every zoo system and control through the automatic estimates, judged against "
             "bands fixed in advance; Markdown report; exit 4 if any estimate is confident and wrong");
  command->add_flag("--fast", args->fast, "the CI subset: 4 systems and 5 controls at N = 10^4, automatic choices only");
  command->add_flag("--no-grid", args->no_grid, "automatic choices only, no neighbourhood grid");
  command->add_option("--grid-points", args->grid_points,
                      "grid points per chaotic system at N = 10^5, 1 to 12 (12: the whole grid of three Theiler "
                      "windows by four dimensions; fewer are chosen by the system's name, so that the zoo covers them all)")
      ->capture_default_str();
  command->add_option("--only", args->only, "run only these cases (by name; repeatable or comma-separated)")
      ->delimiter(',');
  command->add_option("--threads", args->threads, "cases run in parallel (the report does not depend on it)")
      ->capture_default_str();
  cli_support::check_output_option(
      command->add_option("-o,--output", args->output, "write the Markdown report here (default: standard output)"), "-o",
      nullptr, false, [](const std::string& why, bool) { throw InvalidInput(ErrorCode::io, why); });
  command->add_option("--checkpoint", args->checkpoint,
                      "append each finished case to this file (JSON lines) and skip the cases it already holds, so that "
                      "a stopped run resumes; the file belongs to one build and one choice of --fast, --no-grid and --grid-points");
  command->add_flag("-q,--quiet", args->quiet, "no progress on standard error");
  command->add_option("--series", args->series,
                      "write the series of this case (full precision, one value per line) instead of running the suite");
  command->add_flag("--json", args->json, "with --series: the series and its parameters as one JSON object");
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
