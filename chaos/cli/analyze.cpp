// chaos analyze: the embedding parameters of a series chosen and justified. The delay is the first
// mutual-information minimum, the Theiler window the autocorrelation's 1/e time or half the dominant
// oscillation period (time_scales.hpp; a series that never decorrelates is reported non-stationary), the dimension
// where Cao's E1 saturates, corroborated by false nearest neighbours; then, in that embedding, D2,
// the largest Lyapunov exponent (Rosenstein) and the surrogate test for nonlinearity. With no file
// it analyses a built-in Lorenz x series, the project's default demonstration.

#include <cmath>

#include "chaos/autocorrelation.hpp"
#include "chaos/cao.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/error.hpp"
#include "chaos/fnn.hpp"
#include "chaos/generate.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/nonlinearity_test.hpp"
#include "chaos/surrogates.hpp"
#include "chaos/time_scales.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct AnalyzeArgs {
  InputOptions input;
  OutputOptions output;
  std::optional<std::size_t> delay;
  std::optional<std::size_t> theiler;
  std::size_t max_delay = 50;
  std::size_t boxes = 16;
  std::size_t max_dimension = 10;
  std::size_t length = 20000;  // of the built-in series
  std::size_t test_length = 4096;  // samples given to the nonlinearity test
  std::size_t surrogates = 19;
  std::uint64_t seed = 1;
};

// The built-in demonstration: Lorenz (10, 28, 8/3), x, RK4 h = 0.001 sampled every 0.01.
Series builtin_series(std::size_t length) {
  GenerateRequest request;
  request.system = SystemKind::lorenz;
  request.length = length;
  Trajectory t = generate(request);
  return Series{std::move(t.components[0]), t.dt};
}

void run(AnalyzeArgs& args) {
  const bool builtin = args.input.file.empty();
  const Series series = builtin ? builtin_series(args.length) : load_series(args.input);
  const std::vector<double>& x = series.values;
  require_not_constant(x, builtin ? "built-in Lorenz x" : args.input.file);

  // Theiler window from the series' time scales (the 1/e time, or half the dominant oscillation
  // period when that is longer), unless given; the same reading says whether the record is
  // stationary at all.
  const TimeScales scales = time_scales(x);
  const std::size_t max_lag = scales.max_lag;
  const auto decay = scales.decorrelation_time;
  const auto zero = scales.first_zero_crossing;
  std::size_t theiler = 0;
  std::string theiler_source;
  if (args.theiler) {
    theiler = *args.theiler;
    theiler_source = "given (-t)";
  } else {
    theiler = scales.theiler;
    theiler_source = scales.theiler_source;
  }
  if (!scales.stationary) {
    // A random walk has no mutual-information minimum, no saturating dimension and no exponent to
    // find: say what the series is instead of failing on the first estimator.
    Report report("analyze", args.output);
    report.parameter("file", builtin ? std::string("(built-in Lorenz x)") : args.input.file).parameter("N", x.size());
    std::ostream& out = report.stream();
    auto& j = report.json();
    j["stationary"] = false;
    j["stationarity_explanation"] = scales.stationarity_explanation;
    j["d2_status"] = "not_run";
    j["lambda_status"] = "not_run";
    j["autocorrelation"] = {{"first_zero_crossing", optional_json(zero)}, {"decorrelation_time", nullptr}};
    if (report.json_mode()) {
      report.write_json(out);
      return;
    }
    report.write_header(out);
    out << "stationarity\tnon-stationary\t[" << scales.stationarity_explanation << "]\n";
    out << "correlation_dimension\tnot run\t[non-stationary series]\n";
    out << "largest_lyapunov_exponent\tnot run\t[non-stationary series]\n";
    return;
  }

  // Delay from the first mutual-information minimum, unless given; no silent fallback.
  MutualInformationOptions mi_options;
  mi_options.max_delay = std::min(args.max_delay, x.size() / 2);
  mi_options.boxes = args.boxes;
  const MutualInformationResult mi = mutual_information(x, mi_options);
  const auto minimum = first_minimum(mi);
  std::size_t delay = 0;
  std::string delay_source;
  if (args.delay) {
    delay = *args.delay;
    delay_source = "given (-d)";
  } else if (minimum) {
    delay = *minimum;
    delay_source = "first mutual-information minimum";
  } else {
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "no mutual-information minimum for delays 1.." + std::to_string(mi_options.max_delay) +
                           ": raise -D or give the delay with -d (chaos mutual shows the curve)");
  }

  CaoOptions cao_options;
  cao_options.delay = delay;
  cao_options.theiler = theiler;
  cao_options.max_dimension = args.max_dimension;
  const CaoResult cao_result = cao(x, cao_options);
  FnnOptions fnn_options;
  fnn_options.delay = delay;
  fnn_options.theiler = theiler;
  fnn_options.max_dimension = args.max_dimension;
  const FnnResult fnn = false_nearest_neighbors(x, fnn_options);

  // D2 in the chosen embedding, with three dimensions above the embedding dimension so saturation
  // can be judged; radii from the data's range as in `chaos d2`.
  CorrelationSumOptions d2_options;
  d2_options.delay = delay;
  d2_options.theiler = theiler;
  d2_options.max_dimension =
      cao_result.embedding_dimension ? std::min(args.max_dimension, *cao_result.embedding_dimension + 3) : args.max_dimension;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  d2_options.radii = log_radii((*hi - *lo) / 1000.0, (*hi - *lo) / 4.0, 40);
  const CorrelationDimensionResult d2 = correlation_dimension(correlation_sum(x, d2_options));

  // The largest Lyapunov exponent (Rosenstein) and the nonlinearity test need an embedding
  // dimension; Cao's, else the false-neighbour one, else they are not run (and say why).
  const std::optional<std::size_t> dimension =
      cao_result.embedding_dimension ? cao_result.embedding_dimension : fnn.embedding_dimension;
  std::optional<LyapunovResult> lyapunov;
  std::optional<NonlinearityTestResult> nonlinear;
  std::optional<EndMatch> segment;
  if (dimension) {
    LyapunovOptions l;
    l.dimension = *dimension;
    l.delay = delay;
    l.theiler = theiler;
    // As `chaos lyapunov`: 20 correlation times or periods, at least 20 steps, at most N/10; local
    // slopes over a whole period; m, m+1 and m+2 must agree on the linear region and its slope.
    const std::size_t correlation = std::max(scales.theiler, scales.period());
    l.steps = std::max<std::size_t>(20, std::min(20 * correlation, x.size() / 10));
    LyapunovFitOptions fit;
    fit.period = scales.period();
    fit.dimensions = 3;
    lyapunov = largest_lyapunov(x, l, fit, series.dt);

    // The surrogate test on the first test_length samples, trimmed to their best end match (an end
    // mismatch alone makes surrogates look rougher than the data): K = 19 IAAFT surrogates, one-sided
    // (deterministic data are more predictable than their surrogates), the prediction error in the
    // chosen embedding. Kept short so the demonstration stays quick.
    const std::span<const double> head(x.data(), std::min(x.size(), args.test_length));
    segment = end_match(head);
    NonlinearityTestOptions t;
    t.statistic = NonlinearityStatistic::prediction_error;
    t.alternative = Alternative::smaller;
    t.surrogates = args.surrogates;
    t.seed = args.seed;
    t.prediction.dimension = *dimension;
    t.prediction.delay = delay;
    t.prediction.theiler = theiler;
    nonlinear = nonlinearity_test(head.subspan(segment->offset, segment->length), t);
  }

  Report report("analyze", args.output);
  report.parameter("file", builtin ? std::string("(built-in Lorenz x: sigma=10 rho=28 beta=8/3, RK4 h=0.001, dt=0.01)") : args.input.file)
      .parameter("N", x.size()).parameter("dt", series.dt).parameter("max_delay", mi_options.max_delay)
      .parameter("boxes", args.boxes).parameter("max_dimension", args.max_dimension)
      .parameter("test_length", args.test_length).parameter("surrogates", args.surrogates).parameter("seed", args.seed);
  std::ostream& out = report.stream();
  const auto time = [&](std::size_t samples) {
    return series.dt ? nlohmann::ordered_json(static_cast<double>(samples) * *series.dt) : nullptr;
  };
  auto& j = report.json();
  j["stationary"] = true;
  j["delay"] = delay;
  j["delay_time"] = time(delay);
  j["delay_source"] = delay_source;
  j["theiler"] = theiler;
  j["theiler_source"] = theiler_source;
  j["embedding_dimension"] = optional_json(cao_result.embedding_dimension);
  j["fnn_embedding_dimension"] = optional_json(fnn.embedding_dimension);
  j["max_E2_deviation"] = cao_result.max_E2_deviation;
  j["stochastic"] = cao_result.stochastic;
  j["d2"] = optional_json(d2.d2);
  j["d2_interval"] = d2.d2_interval ? nlohmann::ordered_json::array({d2.d2_interval->low, d2.d2_interval->high})
                                    : nlohmann::ordered_json(nullptr);
  j["d2_status"] = to_string(d2.status);
  j["d2_explanation"] = d2.explanation;
  const auto interval = [](const std::optional<Interval>& i) {
    return i ? nlohmann::ordered_json::array({i->low, i->high}) : nlohmann::ordered_json(nullptr);
  };
  const bool per_time = series.dt.has_value();
  if (lyapunov) {
    j["lambda"] = optional_json(per_time ? lyapunov->lambda_per_time : lyapunov->fit.lambda);
    j["lambda_interval"] = interval(per_time ? lyapunov->lambda_per_time_interval : lyapunov->fit.lambda_interval);
    j["lambda_per"] = per_time ? "time" : "sample";
    j["lambda_status"] = to_string(lyapunov->fit.status);
    j["lambda_explanation"] = lyapunov->fit.explanation;
    j["lambda_fit_range_time"] = interval(lyapunov->fit_range_time);
  } else {
    j["lambda"] = nullptr;
    j["lambda_interval"] = nullptr;
    j["lambda_per"] = per_time ? "time" : "sample";
    j["lambda_status"] = "not_run";
    j["lambda_explanation"] = "no embedding dimension";
  }
  if (nonlinear)
    j["nonlinearity"] = {{"statistic", nonlinear->data_statistic}, {"rank", nonlinear->test.rank},
                         {"count", nonlinear->surrogate_statistics.size()}, {"rejected", nonlinear->test.rejected},
                         {"significance", nonlinear->test.significance}, {"offset", segment->offset},
                         {"length", segment->length}};
  else
    j["nonlinearity"] = nullptr;
  j["autocorrelation"] = {{"first_zero_crossing", optional_json(zero)}, {"decorrelation_time", optional_json(decay)}};
  j["mutual_information"] = {{"delay", mi.delay}, {"information", mi.information}, {"first_minimum", optional_json(minimum)}};
  j["cao"] = {{"dimension", cao_result.dimension}, {"E1", cao_result.E1}, {"E2", cao_result.E2}};
  j["fnn"] = {{"dimension", fnn.dimension}, {"false_fraction", fnn.false_fraction}};
  if (report.json_mode()) {
    report.write_json(out);
    return;
  }
  report.write_header(out);
  const auto in_time = [&](std::size_t samples) {
    return series.dt ? " (" + number(static_cast<double>(samples) * *series.dt) + " time units)" : std::string();
  };
  out << "delay\t" << delay << " samples" << in_time(delay) << "\t[" << delay_source << "]\n";
  out << "theiler_window\t" << theiler << " samples" << in_time(theiler) << "\t[" << theiler_source << "]\n";
  out << "embedding_dimension\t" << describe_dimension(cao_result) << "\t[Cao: E1 >= "
      << number(cao_options.saturation_level) << " and steps <= " << number(cao_options.saturation_change)
      << " from there on]\n";
  out << "fnn_embedding_dimension\t"
      << (fnn.embedding_dimension ? std::to_string(*fnn.embedding_dimension) : "none")
      << "\t[false fraction <= " << number(fnn_options.threshold) << "]\n";
  out << "determinism\tmax|E2-1| = " << number(cao_result.max_E2_deviation)
      << (cao_result.stochastic ? "\t[E2 within its sampling error of 1: indistinguishable from noise]\n"
                                : "\t[E2 departs from 1 beyond its sampling error: deterministic structure]\n");
  out << "correlation_dimension\t" << (d2.d2 ? number(*d2.d2) : "none");
  if (d2.d2_interval) out << " in [" << number(d2.d2_interval->low) << ", " << number(d2.d2_interval->high) << "]";
  out << "\t[" << to_string(d2.status) << ": " << d2.explanation << "]\n";
  if (lyapunov) {
    const auto lambda = per_time ? lyapunov->lambda_per_time : lyapunov->fit.lambda;
    const auto range = per_time ? lyapunov->lambda_per_time_interval : lyapunov->fit.lambda_interval;
    out << "largest_lyapunov_exponent\t";
    if (lambda)
      out << number(*lambda) << " in [" << number(range->low) << ", " << number(range->high) << "] per "
          << (per_time ? "time unit" : "sample");
    else
      out << "none";
    out << "\t[Rosenstein, " << lyapunov->options.steps << " steps; " << to_string(lyapunov->fit.status) << ": "
        << lyapunov->fit.explanation << "]\n";
    out << "nonlinearity\t" << (nonlinear->test.rejected ? "rejected" : "not rejected") << ": rank "
        << nonlinear->test.rank << " of " << nonlinear->surrogate_statistics.size() + 1 << ", significance "
        << number(nonlinear->test.significance) << "\t[prediction error " << number(nonlinear->data_statistic)
        << " vs " << nonlinear->surrogate_statistics.size() << " IAAFT surrogates, samples " << segment->offset << ".."
        << segment->offset + segment->length - 1 << " (end-matched)]\n";
  } else {
    out << "largest_lyapunov_exponent\tnone\t[not run: no embedding dimension]\n";
    out << "nonlinearity\tnot run\t[no embedding dimension]\n";
  }
  out << "#\n# evidence: mutual information (nats) around the chosen delay\n# delay\tI\n";
  const std::size_t from = delay > 3 ? delay - 3 : 0;
  for (std::size_t k = from; k <= std::min(delay + 3, mi.delay.back()); ++k)
    out << k << "\t" << number(mi.information[k]) << (k == delay ? "\t<-\n" : "\n");
  out << "#\n# evidence: Cao and false nearest neighbours\n# m\tE1\tE2\tfalse_fraction\n";
  for (std::size_t k = 0; k < cao_result.dimension.size(); ++k)
    out << cao_result.dimension[k] << "\t" << number(cao_result.E1[k]) << "\t" << number(cao_result.E2[k]) << "\t"
        << number(fnn.false_fraction[k]) << "\n";
}

}  // namespace

void register_analyze(CLI::App& app) {
  auto args = std::make_shared<AnalyzeArgs>();
  args->input.file.clear();  // no file: the built-in Lorenz series
  CLI::App* command = app.add_subcommand("analyze", "choose and justify delay, Theiler window and embedding dimension; "
                                                    "then D2, the largest Lyapunov exponent and a nonlinearity test");
  command->add_option("file", args->input.file, "input file or - for stdin (default: built-in Lorenz x series)");
  command->add_option("-c,--column", args->input.column, "column to read (1-based)")->capture_default_str();
  command->add_option("-x,--skip", args->input.skip, "data rows to skip")->capture_default_str();
  command->add_option("-l,--length", args->input.length, "data rows to use");
  command->add_option("--dt", args->input.dt, "sampling interval");
  command->add_option("-d,--delay", args->delay, "use this delay instead of the mutual-information minimum");
  command->add_option("-t,--theiler", args->theiler, "use this Theiler window instead of the 1/e time");
  command->add_option("-D,--max-delay", args->max_delay, "largest delay searched for the MI minimum")->capture_default_str();
  command->add_option("-b,--boxes", args->boxes, "boxes for mutual information")->capture_default_str();
  command->add_option("-M,--max-dimension", args->max_dimension, "largest embedding dimension")->capture_default_str();
  command->add_option("--builtin-length", args->length, "length of the built-in Lorenz series")->capture_default_str();
  command->add_option("--test-length", args->test_length, "samples given to the nonlinearity test (the first ones)")
      ->capture_default_str();
  command->add_option("--surrogates", args->surrogates, "surrogates of the one-sided nonlinearity test (19: 5%)")
      ->capture_default_str();
  command->add_option("--seed", args->seed, "seed of the surrogates")->capture_default_str();
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
