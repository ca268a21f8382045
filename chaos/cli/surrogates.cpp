// chaos surrogates: FT, AAFT or IAAFT surrogates of a series, one column per surrogate, with an
// explicit seed (surrogate k uses the k-th draw of the seed's stream, so it does not depend on
// --count) and optional end matching (TISEAN's advice: trim rather than zero-pad).

#include <cstdio>

#include "chaos/error.hpp"
#include "chaos/surrogates.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct SurrogatesArgs {
  InputOptions input;
  OutputOptions output;
  SurrogateOptions options;
  std::string method = "iaaft";
  std::size_t count = 1;
  std::uint64_t seed = 1;
  bool end_match = false;
  EndMatchOptions end;
  bool quiet = false;
};

SurrogateMethod parse_method(const std::string& name) {
  if (name == "ft") return SurrogateMethod::fourier;
  if (name == "aaft") return SurrogateMethod::aaft;
  if (name == "iaaft") return SurrogateMethod::iaaft;
  throw InvalidInput(ErrorCode::invalid_parameter, "method must be ft, aaft or iaaft (got '" + name + "')");
}

void run(SurrogatesArgs& args) {
  const Series series = load_series(args.input);
  args.options.method = parse_method(args.method);
  if (args.count == 0) throw InvalidInput(ErrorCode::invalid_parameter, "--count must be at least 1 (got 0)");
  std::span<const double> x(series.values);
  std::optional<EndMatch> match;
  if (args.end_match) {
    match = end_match(x, args.end);
    x = x.subspan(match->offset, match->length);
  }
  Progress progress(args.quiet);
  progress.hint("surrogates", x.size(),
                "each surrogate takes up to --max-iterations Fourier transforms of all the samples and may take "
                "long; -l 100000 uses the first 10^5 samples");
  args.options.progress = progress.callback("surrogates");
  const std::vector<Surrogate> made = surrogates(x, args.count, args.seed, args.options);

  Report report("surrogates", args.output);
  report.parameter("file", args.input.file).parameter("column", series.column).parameter("N", series.values.size())
      .parameter("dt", series.dt).parameter("method", args.method).parameter("count", args.count)
      .parameter("seed", args.seed).parameter("max_iterations", args.options.max_iterations)
      .parameter("tolerance", args.options.tolerance).parameter("end_match", args.end_match);
  if (match)
    report.parameter("offset", match->offset).parameter("length", match->length)
        .parameter("end_mismatch", match->mismatch).parameter("whole_series_end_mismatch", match->whole_series_mismatch);
  std::ostream& out = report.stream();
  auto& j = report.json();
  std::vector<std::string> status;
  std::vector<std::size_t> iterations;
  std::vector<double> deviation;
  for (const Surrogate& s : made) {
    status.emplace_back(to_string(s.status));
    iterations.push_back(s.iterations);
    deviation.push_back(s.spectral_deviation);
  }
  j["offset"] = match ? match->offset : 0;
  j["length"] = x.size();
  j["status"] = status;
  j["iterations"] = iterations;
  j["spectral_deviation"] = deviation;
  if (report.json_mode()) {
    auto columns = nlohmann::ordered_json::array();
    for (const Surrogate& s : made) columns.push_back(s.values);
    j["surrogates"] = columns;
    report.write_json(out);
    return;
  }
  report.write_header(out);
  out << "# surrogate\tstatus\titerations\tspectral_deviation\n";
  for (std::size_t k = 0; k < made.size(); ++k)
    out << "# " << k + 1 << "\t" << status[k] << "\t" << iterations[k] << "\t" << number(deviation[k]) << "\n";
  out << "#";
  for (std::size_t k = 0; k < made.size(); ++k) out << (k ? "\t" : " ") << "s" << k + 1;
  out << "\n";
  // Full precision: IAAFT and AAFT surrogates are permutations of the data, and the output keeps
  // them so.
  char buffer[32];
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t k = 0; k < made.size(); ++k) {
      std::snprintf(buffer, sizeof buffer, "%.17g", made[k].values[i]);
      out << (k ? "\t" : "") << buffer;
    }
    out << "\n";
  }
}

}  // namespace

void register_surrogates(CLI::App& app) {
  auto args = std::make_shared<SurrogatesArgs>();
  CLI::App* command = app.add_subcommand("surrogates", "FT, AAFT or IAAFT surrogate series, one column per surrogate");
  add_input_options(*command, args->input);
  command->add_option("--method", args->method, "ft (phase randomised), aaft or iaaft")->capture_default_str();
  command->add_option("-n,--count", args->count, "number of surrogates")->capture_default_str();
  command->add_option("--seed", args->seed, "seed; surrogate k uses the k-th draw of its stream")->capture_default_str();
  command->add_option("--max-iterations", args->options.max_iterations, "IAAFT: iteration limit")->capture_default_str();
  command->add_option("--tolerance", args->options.tolerance,
                      "IAAFT: stop when the spectral deviation is this small (0: only at a fixed point)")
      ->capture_default_str();
  command->add_flag("--end-match", args->end_match,
                    "first trim the series to the segment whose ends match best (TISEAN endtoend)");
  command->add_option("--max-trim", args->end.max_trim, "end matching: largest fraction cut off")->capture_default_str();
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
