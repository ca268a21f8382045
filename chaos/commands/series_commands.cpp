// mutual, autocorrelation, cao, fnn: the computation and the JSON (commands.hpp).

#include <algorithm>

#include "chaos/choose.hpp"
#include "chaos/error.hpp"
#include "chaos/time_scales.hpp"
#include "commands.hpp"
#include "report_parameters.hpp"

namespace chaos::cli {

namespace {

MutualInformationEstimator parse_estimator(const std::string& name) {
  if (name == "equal_width") return MutualInformationEstimator::equal_width;
  if (name == "equiprobable") return MutualInformationEstimator::equiprobable;
  throw InvalidInput(ErrorCode::invalid_parameter, "estimator must be equal_width or equiprobable (got '" + name + "')");
}

}  // namespace

MutualRun run_mutual(const SeriesInput& in, MutualParams params, const OutputOptions& output) {
  params.options.estimator = parse_estimator(params.estimator);
  MutualInformationResult result;
  std::optional<std::size_t> minimum;
  std::string searched = "given (-D)";
  if (params.max_delay) {
    params.options.max_delay = *params.max_delay;
    result = mutual_information(in.values, params.options);
    minimum = first_minimum(result);
  } else {
    // The search of choose_delay, with this command's estimator and boxes: the first minimum within
    // 100 samples, else within two Theiler windows (at most N / 10).
    require_finite(in.values, in.file);
    require_not_constant(in.values, in.file);
    const DelaySearchLimits limits = delay_search_limits(in.values.size(), time_scales(in.values), DelaySearch{});
    params.options.max_delay = limits.first;
    searched = "automatic: " + std::to_string(limits.first) + " delays (at most N/10)";
    result = mutual_information(in.values, params.options);
    minimum = first_minimum(result);
    if (!minimum && limits.second > limits.first) {
      params.options.max_delay = limits.second;
      searched = "automatic: none within " + std::to_string(limits.first) +
                 " delays, searched on to two Theiler windows (" + std::to_string(limits.second) + ", at most N/10)";
      result = mutual_information(in.values, params.options);
      minimum = first_minimum(result);
    }
  }
  std::string no_minimum;
  if (!minimum) {
    const auto& I = result.information;
    const bool falling = I.size() >= 2 && I.back() < I[I.size() - 2];
    no_minimum = "no local minimum of the information for delays 1.." + std::to_string(params.options.max_delay) +
                 (falling ? ": it is still falling at the last delay (a longer -D may find one)"
                          : ": it falls without a minimum and then levels off or rises");
  }

  Report report("mutual", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", in.values.size()).parameter("dt", in.dt);
  report.parameter("max_delay", params.options.max_delay).parameter("max_delay_source", searched)
      .parameter("units", std::string("nats"));
  report_parameters(report, params, mutual_parameters());
  const double dt = in.dt.value_or(1.0);
  auto& j = report.json();
  j["delay"] = result.delay;
  if (in.dt) {
    std::vector<double> times;
    for (const auto d : result.delay) times.push_back(static_cast<double>(d) * dt);
    j["delay_time"] = times;
  }
  j["mutual_information"] = result.information;
  j["first_minimum"] = optional_json(minimum);
  j["first_minimum_time"] = minimum && in.dt ? nlohmann::ordered_json(static_cast<double>(*minimum) * dt) : nullptr;
  j["no_minimum"] = minimum ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(no_minimum);
  return {std::move(result), minimum, std::move(no_minimum), std::move(report)};
}

AutocorrelationRun run_autocorrelation(const SeriesInput& in, const AutocorrelationParams& params,
                                       const OutputOptions& output) {
  const std::size_t n = in.values.size();
  // Default: a tenth of the series, at most 1000 lags, at least 1.
  const std::size_t max_lag = params.max_lag.value_or(std::max<std::size_t>(1, std::min<std::size_t>(1000, n / 10)));
  AutocorrelationResult result = autocorrelation(in.values, max_lag);
  const auto zero = first_zero_crossing(result);
  const auto decay = decorrelation_time(result);

  Report report("autocorrelation", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", n).parameter("dt", in.dt);
  report_parameters(report, params, autocorrelation_parameters());
  report.parameter("max_lag", max_lag);
  const double dt = in.dt.value_or(1.0);
  auto& j = report.json();
  std::vector<std::size_t> lags(result.correlation.size());
  for (std::size_t k = 0; k < lags.size(); ++k) lags[k] = k;
  j["lag"] = lags;
  j["autocorrelation"] = result.correlation;
  j["first_zero_crossing"] = optional_json(zero);
  j["decorrelation_time"] = optional_json(decay);
  if (in.dt) j["decorrelation_time_units"] = decay ? nlohmann::ordered_json(*decay * dt) : nullptr;
  return {std::move(result), zero, decay, std::move(report)};
}

CaoRun run_cao(const SeriesInput& in, CaoParams params, const OutputOptions& output) {
  params.options.norm = parse_norm(params.norm);
  const EmbeddingChoice chosen = choose_delay_and_window(in.values, params.delay, params.theiler);
  params.options.delay = chosen.delay;
  params.options.theiler = chosen.theiler;
  CaoResult result = cao(in.values, params.options);

  Report report("cao", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", in.values.size()).parameter("dt", in.dt);
  report.parameter("delay", params.options.delay).parameter("delay_source", chosen.delay_source)
      .parameter("theiler", params.options.theiler).parameter("theiler_source", chosen.theiler_source);
  report_parameters(report, params, cao_parameters());
  if (in.dt) report.parameter("delay_time", static_cast<double>(params.options.delay) * *in.dt);
  auto& j = report.json();
  const auto used = static_cast<std::ptrdiff_t>(result.dimension.size());
  j["dimension"] = result.dimension;
  j["E1"] = result.E1;
  j["E2"] = result.E2;
  j["E"] = std::vector<double>(result.E.begin(), result.E.begin() + used);
  j["E_star"] = std::vector<double>(result.E_star.begin(), result.E_star.begin() + used);
  j["E2_standard_error"] = result.E2_standard_error;
  j["embedding_dimension"] = optional_json(result.embedding_dimension);
  j["e1_saturation"] = optional_json(result.e1_saturation);
  j["stochastic"] = result.stochastic;
  j["max_E2_deviation"] = result.max_E2_deviation;
  j["points_without_neighbor"] = result.points_without_neighbor;
  j["value_ties"] = result.value_ties.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(result.value_ties);
  return {std::move(result), std::move(report)};
}

FnnRun run_fnn(const SeriesInput& in, FnnParams params, const OutputOptions& output) {
  params.options.norm = parse_norm(params.norm);
  const EmbeddingChoice chosen = choose_delay_and_window(in.values, params.delay, params.theiler);
  params.options.delay = chosen.delay;
  params.options.theiler = chosen.theiler;
  FnnResult result = false_nearest_neighbors(in.values, params.options);

  Report report("fnn", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", in.values.size()).parameter("dt", in.dt);
  report.parameter("delay", params.options.delay).parameter("delay_source", chosen.delay_source)
      .parameter("theiler", params.options.theiler).parameter("theiler_source", chosen.theiler_source);
  report_parameters(report, params, fnn_parameters());
  auto& j = report.json();
  j["dimension"] = result.dimension;
  j["false_fraction"] = result.false_fraction;
  j["embedding_dimension"] = optional_json(result.embedding_dimension);
  j["value_ties"] = result.value_ties.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(result.value_ties);
  return {std::move(result), std::move(report)};
}

}  // namespace chaos::cli
