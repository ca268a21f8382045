// chaos nonlinearity: the rank-order surrogate test for nonlinearity (null hypothesis: a linear
// Gaussian process seen through a static monotone function), with K surrogates, a seed and a
// choice of discriminating statistic.

#include "chaos/error.hpp"
#include "chaos/nonlinearity_test.hpp"
#include "chaos/surrogates.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct NonlinearityArgs {
  InputOptions input;
  OutputOptions output;
  NonlinearityTestOptions options;
  std::string statistic = "prediction_error";
  std::string alternative = "two_sided";
  std::string method = "iaaft";
  std::string norm = "max";
  std::size_t delay = 1;
  bool end_match = false;
  bool quiet = false;
};

NonlinearityStatistic parse_statistic(const std::string& name) {
  if (name == "prediction_error") return NonlinearityStatistic::prediction_error;
  if (name == "time_reversal_asymmetry") return NonlinearityStatistic::time_reversal_asymmetry;
  throw InvalidInput(ErrorCode::invalid_parameter,
                     "statistic must be prediction_error or time_reversal_asymmetry (got '" + name + "')");
}

Alternative parse_alternative(const std::string& name) {
  if (name == "two_sided") return Alternative::two_sided;
  if (name == "smaller") return Alternative::smaller;
  if (name == "larger") return Alternative::larger;
  throw InvalidInput(ErrorCode::invalid_parameter, "alternative must be two_sided, smaller or larger (got '" + name + "')");
}

SurrogateMethod parse_method(const std::string& name) {
  if (name == "ft") return SurrogateMethod::fourier;
  if (name == "aaft") return SurrogateMethod::aaft;
  if (name == "iaaft") return SurrogateMethod::iaaft;
  throw InvalidInput(ErrorCode::invalid_parameter, "method must be ft, aaft or iaaft (got '" + name + "')");
}

void run(NonlinearityArgs& args) {
  const Series series = load_series(args.input);
  auto& o = args.options;
  o.statistic = parse_statistic(args.statistic);
  o.alternative = parse_alternative(args.alternative);
  o.surrogate.method = parse_method(args.method);
  o.prediction.norm = parse_norm(args.norm);
  // One delay option serves both statistics: the embedding delay of the predictor, the lag of Q.
  o.prediction.delay = args.delay;
  o.time_reversal_delay = args.delay;
  std::span<const double> x(series.values);
  std::optional<EndMatch> match;
  if (args.end_match) {
    match = end_match(x);
    x = x.subspan(match->offset, match->length);
  }
  Progress progress(args.quiet);
  progress.hint("nonlinearity", x.size(),
                "each surrogate takes up to --max-iterations Fourier transforms of all the samples and may take "
                "long; -l 100000 tests the first 10^5 samples");
  o.progress = progress.callback("surrogates");
  const NonlinearityTestResult r = nonlinearity_test(x, o);

  Report report("nonlinearity", args.output);
  report.parameter("file", args.input.file).parameter("column", series.column).parameter("N", series.values.size())
      .parameter("dt", series.dt).parameter("statistic", args.statistic).parameter("alternative", args.alternative)
      .parameter("count", o.surrogates).parameter("seed", o.seed).parameter("method", args.method)
      .parameter("max_iterations", o.surrogate.max_iterations).parameter("delay", args.delay);
  if (o.statistic == NonlinearityStatistic::prediction_error)
    report.parameter("dimension", o.prediction.dimension).parameter("theiler", o.prediction.theiler)
        .parameter("horizon", o.prediction.horizon).parameter("neighbours", o.prediction.neighbours)
        .parameter("norm", args.norm);
  report.parameter("end_match", args.end_match);
  if (match) report.parameter("offset", match->offset).parameter("length", match->length);
  std::ostream& out = report.stream();
  auto& j = report.json();
  j["statistic"] = r.data_statistic;
  j["statistic_name"] = args.statistic;
  j["surrogate_statistics"] = r.surrogate_statistics;
  j["rank"] = r.test.rank;
  j["count"] = r.surrogate_statistics.size();
  j["below"] = r.test.below;
  j["above"] = r.test.above;
  j["rejected"] = r.test.rejected;
  j["significance"] = r.test.significance;
  j["surrogates_not_converged"] = r.surrogates_not_converged;
  if (report.json_mode()) {
    report.write_json(out);
    return;
  }
  report.write_header(out);
  out << "# data_statistic = " << number(r.data_statistic) << "\n# rank = " << r.test.rank << " of "
      << r.surrogate_statistics.size() + 1 << " (1 = lowest)\n# significance = " << number(r.test.significance) << "\n"
      << "# rejected = " << (r.test.rejected ? "true: the data's statistic lies beyond every surrogate's"
                                             : "false: the data are consistent with the null hypothesis")
      << "\n# surrogates_not_converged = " << r.surrogates_not_converged << "\n# surrogate\tstatistic\titerations\n";
  for (std::size_t k = 0; k < r.surrogate_statistics.size(); ++k)
    out << k + 1 << "\t" << number(r.surrogate_statistics[k]) << "\t" << r.surrogate_iterations[k] << "\n";
}

}  // namespace

void register_nonlinearity(CLI::App& app) {
  auto args = std::make_shared<NonlinearityArgs>();
  CLI::App* command = app.add_subcommand("nonlinearity", "rank-order surrogate test for nonlinearity");
  add_input_options(*command, args->input);
  command->add_option("-n,--count", args->options.surrogates, "surrogates K (39: two-sided 5%; 19: one-sided 5%)")
      ->capture_default_str();
  command->add_option("--seed", args->options.seed, "seed of the surrogates")->capture_default_str();
  command->add_option("--statistic", args->statistic, "prediction_error or time_reversal_asymmetry")->capture_default_str();
  command->add_option("--alternative", args->alternative, "two_sided, smaller or larger")->capture_default_str();
  command->add_option("--method", args->method, "surrogates: ft, aaft or iaaft")->capture_default_str();
  command->add_option("--max-iterations", args->options.surrogate.max_iterations, "IAAFT: iteration limit")
      ->capture_default_str();
  command->add_option("-d,--delay", args->delay, "delay: of the predictor's embedding, or the lag of the asymmetry")
      ->capture_default_str();
  command->add_option("-m,--dimension", args->options.prediction.dimension, "prediction: embedding dimension")
      ->capture_default_str();
  command->add_option("-t,--theiler", args->options.prediction.theiler, "prediction: Theiler window in samples")
      ->capture_default_str();
  command->add_option("--horizon", args->options.prediction.horizon, "prediction: steps ahead")->capture_default_str();
  command->add_option("-k,--neighbours", args->options.prediction.neighbours, "prediction: neighbours averaged")
      ->capture_default_str();
  command->add_option("--norm", args->norm, "prediction: max or euclidean")->capture_default_str();
  command->add_flag("--end-match", args->end_match,
                    "first trim the series to the segment whose ends match best (TISEAN endtoend)");
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
