// surrogates, nonlinearity: the computation and the JSON (commands.hpp).

#include "chaos/choose.hpp"
#include "chaos/error.hpp"
#include "commands.hpp"
#include "report_parameters.hpp"

namespace chaos::cli {

SurrogateMethod parse_surrogate_method(const std::string& name) {
  if (name == "ft") return SurrogateMethod::fourier;
  if (name == "aaft") return SurrogateMethod::aaft;
  if (name == "iaaft") return SurrogateMethod::iaaft;
  throw InvalidInput(ErrorCode::invalid_parameter, "method must be ft, aaft or iaaft (got '" + name + "')");
}

SurrogatesRun run_surrogates(const SeriesInput& in, SurrogatesParams params, const OutputOptions& output) {
  params.options.method = parse_surrogate_method(params.method);
  if (params.count == 0) throw InvalidInput(ErrorCode::invalid_parameter, "--count must be at least 1 (got 0)");
  std::span<const double> x = in.values;
  std::optional<EndMatch> match;
  if (params.end_match) {
    match = end_match(x, params.end);
    x = x.subspan(match->offset, match->length);
  }
  std::vector<Surrogate> made = surrogates(x, params.count, params.seed, params.options);

  Report report("surrogates", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", in.values.size()).parameter("dt", in.dt);
  report_parameters(report, params, surrogates_parameters());
  if (match)
    report.parameter("offset", match->offset).parameter("length", match->length)
        .parameter("end_mismatch", match->mismatch).parameter("whole_series_end_mismatch", match->whole_series_mismatch);
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
  auto columns = nlohmann::ordered_json::array();
  for (const Surrogate& s : made) columns.push_back(s.values);
  j["surrogates"] = columns;
  return {std::move(made), match, x.size(), std::move(report)};
}

namespace {

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

}  // namespace

NonlinearityRun run_nonlinearity(const SeriesInput& in, NonlinearityParams params, const OutputOptions& output) {
  auto& o = params.options;
  o.statistic = parse_statistic(params.statistic);
  o.alternative = parse_alternative(params.alternative);
  o.surrogate.method = parse_surrogate_method(params.method);
  o.prediction.norm = parse_norm(params.norm);
  std::span<const double> x = in.values;
  std::optional<EndMatch> match;
  if (params.end_match) {
    match = end_match(x);
    x = x.subspan(match->offset, match->length);
  }
  // One delay option serves both statistics: the embedding delay of the predictor, the lag of Q.
  const bool prediction = o.statistic == NonlinearityStatistic::prediction_error;
  const EmbeddingChoice chosen = prediction ? choose_embedding(x, params.delay, params.theiler, params.dimension, {}, 10, params.choice_progress)
                                            : choose_delay_and_window(x, params.delay, params.theiler);
  o.prediction.delay = chosen.delay;
  o.time_reversal_delay = chosen.delay;
  if (prediction) {
    o.prediction.dimension = *chosen.dimension;
    o.prediction.theiler = chosen.theiler;
  }
  NonlinearityTestResult r = nonlinearity_test(x, o);

  Report report("nonlinearity", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", in.values.size()).parameter("dt", in.dt);
  report.parameter("delay", chosen.delay).parameter("delay_source", chosen.delay_source);
  if (prediction)
    report.parameter("dimension", o.prediction.dimension).parameter("dimension_source", chosen.dimension_source)
        .parameter("theiler", o.prediction.theiler).parameter("theiler_source", chosen.theiler_source);
  report_parameters(report, params, nonlinearity_parameters());
  if (match) report.parameter("offset", match->offset).parameter("length", match->length);
  auto& j = report.json();
  j["statistic"] = r.data_statistic;
  j["statistic_name"] = params.statistic;
  j["surrogate_statistics"] = r.surrogate_statistics;
  j["rank"] = r.test.rank;
  j["count"] = r.surrogate_statistics.size();
  j["below"] = r.test.below;
  j["above"] = r.test.above;
  j["ties"] = r.test.ties;
  j["value_ties"] = r.value_ties.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.value_ties);
  j["rejected"] = r.test.rejected;
  j["significance"] = r.test.significance;
  j["surrogates_not_converged"] = r.surrogates_not_converged;
  return {std::move(r), std::move(report)};
}

}  // namespace chaos::cli
