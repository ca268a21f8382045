// d2, lyapunov, analyze: the computation and the JSON (commands.hpp).

#include <algorithm>
#include <cmath>
#include <limits>

#include "chaos/choose.hpp"
#include "chaos/d2_answer.hpp"
#include "chaos/error.hpp"
#include "chaos/lyapunov_answer.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/time_scales.hpp"
#include "commands.hpp"
#include "report_parameters.hpp"

namespace chaos::cli {

CorrelationSearch parse_search(const std::string& name) {
  if (name == "box") return CorrelationSearch::box_assisted;
  if (name == "kd") return CorrelationSearch::kd_tree;
  if (name == "brute") return CorrelationSearch::brute_force;
  throw InvalidInput(ErrorCode::invalid_parameter, "search must be box, kd or brute (got '" + name + "')");
}

D2Run run_d2(const SeriesInput& in, D2Params params, const OutputOptions& output) {
  const std::span<const double> x = in.values;
  require_not_constant(x, in.file);
  params.sums.norm = parse_norm(params.norm);
  params.sums.search = parse_search(params.search);

  const EmbeddingChoice chosen = choose_delay_and_window(x, params.delay, params.theiler);
  params.sums.delay = chosen.delay;
  params.sums.theiler = chosen.theiler;
  // Radii: given, or the automatic range (choose_radius_range).
  const RadiusRange automatic = choose_radius_range(x);
  const double r_max = params.r_max.value_or(automatic.largest);
  const double r_min = params.r_min.value_or(automatic.smallest);
  // Checked before the grid is made: with one radius log_radii would ask for r_min = r_max, naming
  // radii the user may not have given, when the rule that fails is D2's (a slope needs two radii).
  if (params.radius_list.empty() && params.radii < 2)
    throw InvalidInput(ErrorCode::invalid_parameter, "the correlation dimension needs at least 2 radii for a slope (got -# " +
                                                         std::to_string(params.radii) + ")");
  params.sums.radii = params.radius_list.empty() ? log_radii(r_min, r_max, params.radii) : params.radius_list;

  std::optional<AdaptiveD2Result> fast;
  if (params.fast) {
    if (params.sums.reference_points != 0 || params.sums.pairs_per_radius != 0)
      throw InvalidInput(ErrorCode::invalid_parameter,
                         "--fast chooses the reference subset itself: it cannot be combined with --reference-points or -N "
                         "(got --reference-points " + std::to_string(params.sums.reference_points) + ", -N " +
                             std::to_string(params.sums.pairs_per_radius) + ")");
    // With a budget and the halves check, each round's two subsets are the record's halves
    // (adaptive_d2.hpp): the check comes with the rounds instead of two more counts. Without a
    // budget the rounds draw from the whole record, as validated (docs/validation/fast-d2-zoo.md):
    // halves that differ by more than the 0.02 target (Lorenz x at 10^5: 2.072 and 2.045) would
    // never let them settle.
    params.adaptive.halves = params.halves && params.adaptive.budget != 0;
    fast = adaptive_correlation_dimension(x, params.sums, params.dimension, params.adaptive);
  }
  CorrelationSumResult sums = fast ? std::move(fast->sums) : correlation_sum(x, params.sums);
  CorrelationDimensionResult d2 = fast ? std::move(fast->d2) : correlation_dimension(sums, params.dimension);
  // The same sums over each half of the record (same radii): a saturated plateau must be reproduced.
  CorrelationSumOptions halves = params.sums;
  halves.progress = params.halves_progress;  // each half from 0 to 1 (and where a caller may stop them)
  // After --fast, the rounds' subsets were the halves (half the final budget each), or each half
  // is counted with the budget the rounds chose, so the check costs about what the final D2 did;
  // after a fast run that fell back to exact counts, the halves are counted exactly too.
  if (fast && fast->halves)
    halves.reference_points = fast->reference_points / 2;
  else if (fast && !fast->exact)
    halves.reference_points = fast->reference_points;
  if (params.halves && !(fast && fast->halves)) check_record_halves(d2, x, halves, params.dimension);
  // The same sums at twice the delay (same radii): D2 must not depend on the embedding.
  if (params.delay_check) check_delay_variant(d2, x, params.sums, params.dimension);

  Report report("d2", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", x.size()).parameter("dt", in.dt);
  report.parameter("delay", params.sums.delay).parameter("delay_source", chosen.delay_source)
      .parameter("theiler", params.sums.theiler).parameter("theiler_source", chosen.theiler_source)
      .parameter("min_radius", params.sums.radii.front()).parameter("max_radius", params.sums.radii.back())
      .parameter("radii", params.sums.radii.size())
      .parameter("halves_reference_points",  // null with --no-halves: no half was counted
                 params.halves ? std::optional<std::size_t>(halves.reference_points) : std::nullopt)
      .parameter("max_region_radius", d2.max_region_radius)
      .parameter("points", sums.points);
  report_parameters(report, params, d2_parameters());
  auto& j = report.json();
  j["dimension"] = sums.dimension;
  j["radius"] = sums.radius;
  j["correlation_sum"] = sums.correlation_sum;
  j["pairs"] = sums.pairs;
  // [m index][radius index] of optional values: null where undefined.
  const auto table_json = [](const std::vector<std::vector<std::optional<double>>>& table) {
    auto rows = nlohmann::ordered_json::array();
    for (const auto& row : table) {
      auto line = nlohmann::ordered_json::array();
      for (const auto& v : row) line.push_back(optional_json(v));
      rows.push_back(line);
    }
    return rows;
  };
  j["local_slope"] = table_json(d2.local_slope);
  if (!d2.local_slope_error.empty()) {
    j["local_slope_error"] = table_json(d2.local_slope_error);
    j["slopes_too_uncertain"] = d2.slopes_too_uncertain;
    j["jackknife_groups"] = sums.group_pairs.size();
  }
  auto by_m = nlohmann::ordered_json::array(), by_m_interval = nlohmann::ordered_json::array();
  for (std::size_t d = 0; d < sums.dimension.size(); ++d) {
    by_m.push_back(optional_json(d2.d2_by_dimension[d]));
    by_m_interval.push_back(interval_json(d2.d2_by_dimension_interval[d]));
  }
  j["d2_by_dimension"] = by_m;
  j["d2_by_dimension_interval"] = by_m_interval;
  j["d2"] = optional_json(d2.d2);
  j["d2_interval"] = interval_json(d2.d2_interval);
  j["d2_standard_error"] = optional_json(d2.d2_standard_error);
  j["scaling_region"] = interval_json(d2.scaling_region);
  const auto plateaus_json = [](const std::vector<D2Plateau>& list) {
    auto out = nlohmann::ordered_json::array();
    for (const auto& p : list)
      out.push_back({{"radii", interval_json(p.radii)}, {"slope", p.slope}, {"slopes", interval_json(p.slopes)},
                     {"pairs", p.pairs}});
    return out;
  };
  j["plateaus"] = plateaus_json(d2.plateaus);
  j["other_plateaus"] = plateaus_json(d2.other_plateaus);
  if (d2.noise_floor)
    j["noise_floor"] = {{"radius", *d2.noise_floor}, {"slopes", d2.noise_floor_slopes}};
  else
    j["noise_floor"] = nullptr;
  if (d2.smallest_scales)
    j["smallest_scales"] = {{"radii", interval_json(d2.smallest_scales->radii)},
                            {"slope", d2.smallest_scales->slope},
                            {"slopes", interval_json(d2.smallest_scales->slopes)},
                            {"pairs", d2.smallest_scales->pairs}};
  else
    j["smallest_scales"] = nullptr;
  if (d2.steepest_lower_dimension)
    j["steepest_lower"] = {{"dimension", *d2.steepest_lower_dimension}, {"slope", *d2.steepest_lower_slope}};
  else
    j["steepest_lower"] = nullptr;
  if (d2.first_half_status) {
    j["first_half"] = {{"status", to_string(*d2.first_half_status)}, {"d2", optional_json(d2.first_half_d2)}};
    j["second_half"] = {{"status", to_string(*d2.second_half_status)}, {"d2", optional_json(d2.second_half_d2)}};
  }
  if (d2.variant_delay)
    j["delay_variant"] = {{"delay", *d2.variant_delay}, {"status", to_string(*d2.variant_delay_status)},
                          {"d2", optional_json(d2.variant_delay_d2)}};
  const Estimate estimate = fast ? subsets_answer(*fast, d2, params.dimension) : d2_answer(d2, params.dimension);
  j["estimate"] = estimate_json(estimate);
  j["saturated"] = d2.status == D2Status::saturated;
  j["status"] = to_string(d2.status);
  j["explanation"] = d2.explanation;
  j["takens_theiler"] = optional_json(d2.takens_theiler);
  j["takens_theiler_error"] = optional_json(d2.takens_theiler_error);
  j["eckmann_ruelle_limit"] = d2.eckmann_ruelle_limit;
  j["exceeds_eckmann_ruelle"] = d2.exceeds_eckmann_ruelle;
  if (fast) {
    auto rounds = nlohmann::ordered_json::array();
    for (const auto& r : fast->rounds)
      rounds.push_back({{"reference_points", r.reference_points},
                        {"status_a", to_string(r.status_a)}, {"d2_a", optional_json(r.d2_a)},
                        {"status_b", to_string(r.status_b)}, {"d2_b", optional_json(r.d2_b)},
                        {"status_merged", to_string(r.status_merged)}, {"d2_merged", optional_json(r.d2_merged)},
                        {"region_a", interval_json(r.region_a)}, {"region_b", interval_json(r.region_b)},
                        {"region_merged", interval_json(r.region_merged)},
                        {"standard_error", optional_json(r.standard_error)}, {"agreed", r.agreed},
                        {"region_shift", optional_json(r.region_shift)}, {"same_region", r.same_region},
                        {"precise", r.precise}, {"stable", r.stable}, {"competing_plateau", optional_json(r.competing)}});
    j["fast"] = {{"target", params.adaptive.target},
                 {"reference_points", fast->exact ? nlohmann::ordered_json("exact") : nlohmann::ordered_json(fast->reference_points)},
                 {"exact", fast->exact},
                 {"settled", fast->settled},
                 {"halves", fast->halves},
                 {"explanation", fast->explanation},
                 {"rounds", rounds}};
  }
  return {std::move(sums), std::move(d2), estimate, std::move(report), std::move(fast)};
}

namespace {

LyapunovMethod parse_method(const std::string& name) {
  if (name == "rosenstein") return LyapunovMethod::rosenstein;
  if (name == "kantz") return LyapunovMethod::kantz;
  throw InvalidInput(ErrorCode::invalid_parameter, "method must be rosenstein or kantz (got '" + name + "')");
}

// Refuses settings the curve of N samples cannot satisfy, as chaos d2 refuses its reference points,
// rather than answering them with a status about the data (no exponential divergence, no linear
// region). Only the values given are checked: the automatic ones are chosen to fit.
void require_lyapunov_settings_fit(const LyapunovParams& params, std::size_t n, const std::string& steps_source) {
  const std::size_t k = params.options.steps;
  const std::string steps = "K = " + std::to_string(k) + " (" + steps_source + ", N = " + std::to_string(n) + ")";
  const auto refuse = [](const std::string& rule) {
    throw InvalidInput(ErrorCode::invalid_parameter, "Lyapunov exponent: " + rule);
  };
  if (params.period && *params.period > 1 && *params.period > k)
    refuse("the local slopes span one whole period, so the period must not exceed the curve's steps: period <= " + steps +
           " (got period = " + std::to_string(*params.period) + ")");
  if (params.fit.min_steps > k + 1)
    refuse("a linear region of min_steps steps must fit in the curve's K + 1 steps k = 0..K: min_steps <= K + 1 with " +
           steps + " (got min_steps = " + std::to_string(params.fit.min_steps) + ")");
  if (params.fit.half_width > k / 2)
    refuse("a local slope spans 2 half_width + 1 steps, which must fit in the curve's K + 1 steps k = 0..K: "
           "2 half_width <= K with " + steps + " (got half_width = " + std::to_string(params.fit.half_width) + ")");
  // The reference points are drawn from the P points that can be followed for K steps, fewest at
  // the largest dimension fitted; the series-length rule itself is the estimator's (lyapunov.hpp).
  // Only a given number is checked: the automatic one is at most P by construction.
  if (!params.reference_points || *params.reference_points == 0 || params.options.dimension > n || params.fit.dimensions > n) return;
  const std::size_t m = params.options.dimension + (params.fit.dimensions > 0 ? params.fit.dimensions - 1 : 0);
  const std::size_t tau = params.options.delay;
  if (m - 1 > n / std::max<std::size_t>(tau, 1) || (m - 1) * tau + k >= n) return;  // too short: the estimator says so
  const std::size_t points = n - (m - 1) * tau - k;
  if (*params.reference_points > points)
    refuse("reference_points must not exceed the " + std::to_string(points) +
           " points that can be followed for all K steps at the largest dimension fitted, m = " + std::to_string(m) +
           ": P = N - (m-1)*tau - K = " + std::to_string(n) + " - " + std::to_string(m - 1) + "*" + std::to_string(tau) +
           " - " + std::to_string(k) + " (got reference_points = " + std::to_string(*params.reference_points) + ")");
}

}  // namespace

LyapunovRun run_lyapunov(const SeriesInput& in, LyapunovParams params, const OutputOptions& output) {
  const std::span<const double> x = in.values;
  require_not_constant(x, in.file);
  params.options.method = parse_method(params.method);
  params.options.norm = parse_norm(params.norm);

  // Left-out choices by the rules of choose.hpp, as in chaos analyze: delay, window and Cao's m, the
  // steps (20 correlation times or periods) and the period of the local slopes.
  const EmbeddingChoice chosen = choose_embedding(x, params.delay, params.theiler, params.dimension, {}, 10,
                                                  params.choice_progress, params.options.threads);
  params.options.delay = chosen.delay;
  params.options.theiler = chosen.theiler;
  params.options.dimension = *chosen.dimension;
  // The steps and the period come from the time scales also where the delay and window were given.
  const TimeScales scales = chosen.scales ? *chosen.scales : time_scales(x);
  std::string steps_source = "given (-s)", period_source = "given (--period)";
  if (!params.period) {
    params.fit.period = scales.period();
    period_source = scales.period() ? "twice the first autocorrelation minimum" : "no dominant oscillation";
  } else {
    params.fit.period = *params.period;
  }
  if (params.steps) {
    params.options.steps = *params.steps;
  } else {
    params.options.steps = choose_lyapunov_steps(scales.theiler, params.fit.period, x.size());
    steps_source = "20 correlation times or periods, at least 20, at most N/10";
  }
  std::string reference_points_source = "given (--reference-points)";
  if (params.reference_points) {
    params.options.reference_points = *params.reference_points;
  } else {
    params.options.reference_points =
        choose_lyapunov_options(scales, x.size(), params.options.dimension, params.options.delay,
                                params.options.theiler, params.options.method).reference_points;
    reference_points_source = "at most 10^4, evenly spaced, as chaos analyze";
  }
  // As chaos analyze stops there: the automatic delay, window, dimension and steps come from the
  // record's correlation time, which on a non-stationary record grows with the record (a random
  // walk at N = 10^5 asked for 10^4 steps and Kantz neighbourhoods of hundreds, minutes of work for
  // no answer). Given all four, the estimator runs as told.
  // A record too short for the curve is refused as such by the estimator, first.
  if (!scales.stationary && x.size() >= minimum_length(params.options, params.fit.dimensions) &&
      (!params.delay || !params.theiler || !params.dimension || !params.steps))
    throw InvalidInput(ErrorCode::too_short,
                       "largest Lyapunov exponent with automatic choices: " + scales.stationarity_explanation +
                           "; or give -d, -t, -m and -s to run the estimator anyway");
  require_lyapunov_settings_fit(params, x.size(), steps_source);
  // This estimator and, for the cross-check, the other one, on one embedding per dimension.
  std::vector<LyapunovOptions> runs{params.options};
  if (params.cross_check) {
    LyapunovOptions other = params.options;
    other.method = other.method == LyapunovMethod::rosenstein ? LyapunovMethod::kantz : LyapunovMethod::rosenstein;
    other.progress = params.check_progress;
    runs.push_back(other);
  }
  std::vector<LyapunovResult> results = largest_lyapunov_runs(x, runs, params.fit, in.dt);
  LyapunovResult r = std::move(results.front());
  std::optional<LyapunovResult> check;
  if (params.cross_check) check = std::move(results.back());
  // The same estimators over each half of the record: a linear region must be reproduced.
  if (params.halves) {
    std::vector<LyapunovResult*> both{&r};
    if (check) both.push_back(&*check);
    check_record_halves(std::span<LyapunovResult* const>(both), x, runs, params.fit);
  }
  if (params.cross_check) {
    const LyapunovOptions& other = runs.back();
    if (other.method == LyapunovMethod::kantz)
      cross_check(r, *check, params.fit.tolerance);
    else
      cross_check(*check, r, params.fit.tolerance);
  }
  // The pipeline's third estimator, at the same m, delay, window and norm (and at m + 1 where m is
  // inconsistent): noise at the neighbours' scale biases both curves low alike, which their mutual
  // check cannot see (docs/notes/zoo-noise.md).
  std::optional<LocalMapResult> maps;
  std::string maps_refusal;
  // The reference points bound the maps too: a chain of at most 10 maps per reference point (the
  // maps along one trajectory are correlated, so a chain needs more of them than the curves need
  // reference points; at the default 10^4, every record of up to 10^5 samples keeps its whole chain).
  // 0 reference points (all): the whole chain.
  const std::size_t max_maps = 10 * std::min<std::size_t>(params.options.reference_points, std::numeric_limits<std::size_t>::max() / 10);
  if (params.cross_check) {
    LocalMapOptions l = choose_local_map_options(params.options.dimension, params.options.delay, params.options.theiler);
    l.norm = params.options.norm;
    l.threads = params.options.threads;
    l.max_maps = max_maps;
    const auto& report_progress = params.maps_progress;
    if (report_progress) report_progress(0.0);
    try {
      maps = local_maps_with_next_dimension(x, l, in.dt, true, [&] {
               if (report_progress) report_progress(0.5);
             }).result;
    } catch (const InvalidInput& e) {
      maps_refusal = e.what();
    }
    if (report_progress) report_progress(1.0);
    if (maps) {
      cross_check(r, *maps, params.fit.tolerance);
      if (check) cross_check(*check, *maps, params.fit.tolerance);
    } else {
      cross_check_without_local_maps(r, maps_refusal);
      if (check) cross_check_without_local_maps(*check, maps_refusal);
    }
  }

  const bool per_time = r.dt.has_value();
  const std::optional<double> lambda = per_time ? r.lambda_per_time : r.fit.lambda;
  const std::optional<Interval> lambda_interval = per_time ? r.lambda_per_time_interval : r.fit.lambda_interval;
  Report report("lyapunov", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", x.size()).parameter("dt", in.dt);
  report.parameter("dimension", params.options.dimension).parameter("dimension_source", chosen.dimension_source)
      .parameter("delay", params.options.delay).parameter("delay_source", chosen.delay_source)
      .parameter("theiler", params.options.theiler).parameter("theiler_source", chosen.theiler_source)
      .parameter("steps", params.options.steps).parameter("steps_source", steps_source);
  if (params.options.method == LyapunovMethod::kantz)
    report.parameter("radius", r.curve.radius)
        .parameter("radius_source", std::string(params.options.radius ? "given (-r)"
                                                                       : "data range / 1000 times a power of two: half "
                                                                         "the reference points have a neighbour, at most "
                                                                         "20 on average"));
  report.parameter("max_maps", params.cross_check ? std::optional<std::size_t>(max_maps) : std::nullopt)
      .parameter("reference_points", params.options.reference_points)
      .parameter("reference_points_source", reference_points_source)
      .parameter("half_width", r.fit.half_width).parameter("min_steps", r.fit.min_steps)
      .parameter("period", params.fit.period).parameter("period_source", period_source);
  report_parameters(report, params, lyapunov_parameters());
  auto& j = report.json();
  // The answer: this method's estimate, and lambda_1 from every estimator run (lyapunov_answer.hpp).
  // Without the cross-checks a confident estimate is only the fit's own verdict: rough.
  Estimate estimate = r.fit.estimate;
  if (!params.cross_check || !params.halves)
    estimate.downgrade(std::string("checks off (") + (!params.cross_check ? "--no-cross-check" : "--no-halves") + ")");
  if (per_time) estimate = scaled(estimate, 1.0 / *in.dt);
  std::optional<LyapunovAnswer> answer;
  if (params.cross_check && params.halves)
    answer = combine_lyapunov(r.options.method == LyapunovMethod::rosenstein ? &r : check ? &*check : nullptr,
                              r.options.method == LyapunovMethod::kantz ? &r : check ? &*check : nullptr,
                              maps ? &*maps : nullptr, in.dt);
  j["estimate"] = estimate_json(estimate);
  if (answer) {
    j["lambda_1"] = estimate_json(answer->per_time());
    j["lambda_1"]["source"] = answer->source;
  } else {
    j["lambda_1"] = nullptr;
  }
  j["lambda"] = optional_json(lambda);
  j["lambda_interval"] = interval_json(lambda_interval);
  j["per"] = per_time ? "time" : "sample";
  j["lambda_per_sample"] = optional_json(r.fit.lambda);
  j["lambda_per_sample_interval"] = interval_json(r.fit.lambda_interval);
  j["status"] = to_string(r.fit.status);
  j["explanation"] = r.fit.explanation;
  j["region"] = r.fit.first_step ? nlohmann::ordered_json::array({*r.fit.first_step, *r.fit.last_step})
                                 : nlohmann::ordered_json(nullptr);
  j["region_time"] = interval_json(r.fit_range_time);
  j["dimensions"] = r.dimensions;
  j["lambda_by_dimension"] = r.fit.lambda_by_curve;
  j["step"] = r.curve.step;
  if (per_time) {
    std::vector<double> time(r.curve.step.size());
    for (std::size_t k = 0; k < time.size(); ++k) time[k] = static_cast<double>(r.curve.step[k]) * *r.dt;
    j["time"] = time;
  }
  auto divergence = nlohmann::ordered_json::array(), slope = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < r.curve.step.size(); ++k) {
    divergence.push_back(optional_json(r.curve.divergence[k]));
    slope.push_back(optional_json(r.fit.local_slope[k]));
  }
  j["divergence"] = divergence;
  j["local_slope"] = slope;
  j["terms"] = r.curve.terms;
  j["zero_distances"] = r.curve.zero_distances;
  j["points"] = r.curve.points;
  j["reference_points_examined"] = r.curve.reference_points;
  j["references_used"] = r.curve.references_used;
  j["mean_neighbours"] = r.curve.mean_neighbours;
  // Kantz: reference points whose neighbourhood was cut to max_neighbours members (0 where none was).
  const std::size_t capped = r.curve.capped_neighbourhoods + (check ? check->curve.capped_neighbourhoods : 0);
  j["capped_neighbourhoods"] = capped;
  if (check) {
    auto& c = j["cross_check"];
    c["method"] = to_string(check->options.method);
    c["status"] = to_string(check->fit.status);
    c["lambda"] = optional_json(per_time ? check->lambda_per_time : check->fit.lambda);
    c["explanation"] = check->fit.explanation;
    c["estimate"] = estimate_json(check->estimate_per_time());
    if (check->options.method == LyapunovMethod::kantz) c["radius"] = check->curve.radius;
  } else {
    j["cross_check"] = nullptr;
  }
  if (maps) {
    const bool maps_per_time = maps->dt.has_value();
    j["local_maps"] = {{"status", to_string(maps->status)},
                       {"lambda", optional_json(maps_per_time ? maps->lambda_per_time : maps->lambda)},
                       {"lambda_interval", interval_json(maps_per_time ? maps->lambda_per_time_interval : maps->lambda_interval)},
                       {"dimension", maps->variants.front().dimension},
                       {"base", maps->base.lambda / (maps_per_time ? *maps->dt : 1.0)},
                       {"variants", [&] {
                          auto v = nlohmann::ordered_json::array();
                          for (const auto& variant : maps->variants)
                            v.push_back({{"name", variant.name}, {"lambda", variant.lambda / (maps_per_time ? *maps->dt : 1.0)}});
                          return v;
                        }()},
                       {"explanation", maps->explanation}};
  } else if (params.cross_check) {
    j["local_maps"] = {{"status", "not_run"}, {"explanation", maps_refusal}};
  } else {
    j["local_maps"] = nullptr;
  }
  return {std::move(r),        std::move(check),  std::move(maps), std::move(maps_refusal),
          std::move(estimate), std::move(answer), std::move(report)};
}

LyapunovMapsRun run_lyapunov_maps(const SeriesInput& in, LyapunovMapsParams params, const OutputOptions& output) {
  const std::span<const double> x = in.values;
  require_not_constant(x, in.file);
  params.options.norm = parse_norm(params.norm);
  const EmbeddingChoice chosen = choose_embedding(x, params.delay, params.theiler, params.dimension, {}, 10,
                                                  params.choice_progress, params.options.threads);
  params.options.delay = chosen.delay;
  params.options.theiler = chosen.theiler;
  params.options.dimension = *chosen.dimension;
  LocalMapResult r = largest_lyapunov_local_maps(x, params.options, in.dt, params.tolerance);
  const bool per_time = r.dt.has_value();
  Report report("lyapunov-maps", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", x.size()).parameter("dt", in.dt);
  report.parameter("dimension", params.options.dimension).parameter("dimension_source", chosen.dimension_source)
      .parameter("delay", params.options.delay).parameter("delay_source", chosen.delay_source)
      .parameter("theiler", params.options.theiler).parameter("theiler_source", chosen.theiler_source)
      .parameter("step", r.base.step).parameter("neighbours", r.base.neighbours).parameter("tolerance", r.tolerance);
  report_parameters(report, params, lyapunov_maps_parameters());
  auto& j = report.json();
  const double scale = per_time ? 1.0 / *r.dt : 1.0;
  j["lambda"] = optional_json(per_time ? r.lambda_per_time : r.lambda);
  j["lambda_interval"] = interval_json(per_time ? r.lambda_per_time_interval : r.lambda_interval);
  j["per"] = per_time ? "time" : "sample";
  j["lambda_per_sample"] = optional_json(r.lambda);
  j["status"] = to_string(r.status);
  j["explanation"] = r.explanation;
  auto variants = nlohmann::ordered_json::array();
  for (const auto& v : r.variants)
    variants.push_back({{"name", v.name}, {"dimension", v.dimension}, {"delay", v.delay}, {"neighbours", v.neighbours},
                        {"lambda", v.lambda * scale}});
  j["variants"] = variants;
  j["median_residual"] = r.base.median_residual;
  j["residual_q90"] = r.base.residual_q90;
  j["residual_q99"] = r.base.residual_q99;
  j["mean_rank"] = r.base.mean_rank;
  j["maps"] = r.base.maps;
  j["restarts"] = r.base.restarts;
  j["poor_fits"] = r.base.poor_fits;
  return {std::move(r), std::move(report)};
}

const char* const builtin_series_name = "(built-in Lorenz x: sigma=10 rho=28 beta=8/3, RK4 h=0.001, dt=0.01)";

Series builtin_series(std::size_t length) {
  GenerateRequest request;
  request.system = SystemKind::lorenz;
  request.length = length;
  Trajectory t = generate(request);
  return Series{std::move(t.components[0]), t.dt};
}

AnalyzeRun run_analyze(const SeriesInput& in, const AnalyzeParams& params, const OutputOptions& output) {
  const std::span<const double> x = in.values;
  const bool builtin = in.file == builtin_series_name;
  require_not_constant(x, builtin ? "built-in Lorenz x" : in.file);

  // The choices, D2 and both exponents come from the library's automatic pipeline, the one
  // `chaos zoo` validates (automatic_analysis.hpp); false neighbours and the surrogate test are
  // added here as corroboration.
  AutomaticAnalysisOptions options;
  options.threads = params.threads;
  options.delay = params.delay;
  options.theiler = params.theiler;
  options.delay_search.max_delay = params.max_delay;
  options.delay_search.boxes = params.boxes;
  options.max_dimension = params.max_dimension;
  options.check_delay = params.delay_check;
  options.progress = params.progress;
  // A step's own callback, copied into the options of that one call (the options kept in the run
  // hold none).
  const auto step = [&](const char* name) -> std::function<void(double)> {
    if (!params.progress) return nullptr;
    return [progress = params.progress, name](double fraction) { progress(name, fraction); };
  };
  AnalyzeRun run{analyse_series(x, in.dt, options), std::nullopt, {}, std::nullopt, std::nullopt, std::nullopt, {}, {}, {},
                 Report("analyze", output)};
  const AutomaticAnalysis& a = run.analysis;
  const TimeScales& scales = a.scales;
  run.theiler_source = params.theiler ? "given (-t)" : a.theiler_source;

  if (a.delay) {
    run.fnn_options.delay = *a.delay;
    run.fnn_options.theiler = a.theiler;
    run.fnn_options.max_dimension = params.max_dimension;
    run.fnn_options.threads = params.threads;
    FnnOptions fnn_options = run.fnn_options;
    fnn_options.progress = step("false nearest neighbours");
    run.fnn = false_nearest_neighbors(x, fnn_options);
  }
  // The surrogate test on the first test_length samples (embedded_nonlinearity_test), K = 19 by
  // default; kept short so the demonstration stays quick.
  if (a.dimension && a.delay) {
    EmbeddedNonlinearityTest test = embedded_nonlinearity_test(x, params.test_length, *a.dimension, *a.delay, a.theiler,
                                                               params.surrogates, params.seed,
                                                               step("nonlinearity test"));
    run.segment = test.segment;
    run.nonlinear = std::move(test.result);
  }
  if (!a.cao) {
    run.determinism = "not_run";
    run.determinism_explanation = "Cao's method was not run";
  } else if (a.cao->stochastic) {
    run.determinism = "stochastic";
    run.determinism_explanation = "E2 within its sampling error of 1: indistinguishable from noise";
  } else if (!run.nonlinear) {
    run.determinism = "not_shown";
    run.determinism_explanation = "E2 departs from 1 beyond its sampling error, but the surrogate test was not run: "
                                  "a linear process seen through a static nonlinearity can do that too";
  } else if (run.nonlinear->test.rejected) {
    run.determinism = "deterministic";
    run.determinism_explanation = "E2 departs from 1 beyond its sampling error, and the surrogate test rejects a "
                                  "linear Gaussian process: deterministic structure";
  } else {
    run.determinism = "not_shown";
    run.determinism_explanation = "E2 departs from 1 beyond its sampling error, but the surrogate test does not reject "
                                  "a linear Gaussian process seen through a static transformation, which can do that "
                                  "too: no evidence of determinism";
  }
  if (params.mutual_curve && scales.stationary) {
    // The information curve the delay was read from, as far as the search went (further than
    // max_delay where the first search found nothing); where the autocorrelation gave delay 1 and no
    // curve was computed, up to max_delay.
    if (!a.delay_information.delay.empty()) {
      run.mutual = a.delay_information;
    } else {
      MutualInformationOptions mi_options;
      mi_options.max_delay = std::max<std::size_t>(1, std::min(params.max_delay, x.size() / 10));
      mi_options.boxes = params.boxes;
      run.mutual = mutual_information(x, mi_options);
    }
  }

  const auto& fnn = run.fnn;
  const auto& nonlinear = run.nonlinear;
  const auto& segment = run.segment;
  Report& report = run.report;
  report.parameter("file", in.file).parameter("N", x.size()).parameter("dt", in.dt);
  report.parameter("delay", a.delay).parameter("theiler", a.theiler);
  report_parameters(report, params, analyze_parameters());
  const bool per_time = in.dt.has_value();
  const auto time = [&](std::size_t samples) {
    return in.dt ? nlohmann::ordered_json(static_cast<double>(samples) * *in.dt) : nullptr;
  };
  auto& j = report.json();
  j["stationary"] = scales.stationary;
  j["stationarity_explanation"] = scales.stationarity_explanation;
  j["stopped"] = a.stopped.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(a.stopped);
  j["delay"] = optional_json(a.delay);
  j["delay_time"] = a.delay ? time(*a.delay) : nullptr;
  j["delay_source"] = a.delay_source;
  j["delay_searched"] = a.delay_searched;
  j["theiler"] = a.theiler;
  j["theiler_source"] = run.theiler_source;
  j["embedding_dimension"] = optional_json(a.dimension);
  j["fnn_embedding_dimension"] = fnn ? optional_json(fnn->embedding_dimension) : nullptr;
  j["max_E2_deviation"] = a.cao ? nlohmann::ordered_json(a.cao->max_E2_deviation) : nullptr;
  j["stochastic"] = a.cao ? nlohmann::ordered_json(a.cao->stochastic) : nullptr;
  j["determinism"] = run.determinism;
  j["determinism_explanation"] = run.determinism_explanation;
  j["d2"] = a.d2 ? optional_json(a.d2->d2) : nullptr;
  j["d2_interval"] = a.d2 ? interval_json(a.d2->d2_interval) : nullptr;
  j["d2_status"] = a.d2 ? to_string(a.d2->status) : "not_run";
  j["d2_estimate"] = estimate_json(a.d2_estimate ? *a.d2_estimate
                                                 : Estimate{EstimateStatus::none, std::nullopt, std::nullopt, a.stopped});
  j["d2_explanation"] = a.d2 ? a.d2->explanation : a.stopped;
  if (a.d2 && a.d2->variant_delay)
    j["d2_delay_variant"] = {{"delay", *a.d2->variant_delay}, {"status", to_string(*a.d2->variant_delay_status)},
                             {"d2", optional_json(a.d2->variant_delay_d2)}};
  else
    j["d2_delay_variant"] = nullptr;
  // lambda_1, one answer (lyapunov_answer.hpp); the three estimators below are its evidence.
  if (a.lyapunov) {
    j["lambda_1"] = estimate_json(a.lyapunov->per_time());
    j["lambda_1"]["source"] = a.lyapunov->source;
  } else {
    j["lambda_1"] = estimate_json(Estimate{EstimateStatus::none, std::nullopt, std::nullopt, a.stopped});
  }
  const auto lambda_json = [&](const std::optional<LyapunovResult>& l, const std::string& prefix) {
    j[prefix + "_estimate"] = l ? estimate_json(l->estimate_per_time())
                                : nlohmann::ordered_json(nullptr);
    if (l) {
      j[prefix] = optional_json(per_time ? l->lambda_per_time : l->fit.lambda);
      j[prefix + "_interval"] = interval_json(per_time ? l->lambda_per_time_interval : l->fit.lambda_interval);
      j[prefix + "_status"] = to_string(l->fit.status);
      j[prefix + "_explanation"] = l->fit.explanation;
      j[prefix + "_fit_range_time"] = interval_json(l->fit_range_time);
    } else {
      j[prefix] = nullptr;
      j[prefix + "_interval"] = nullptr;
      j[prefix + "_status"] = "not_run";
      j[prefix + "_explanation"] = a.stopped;
      j[prefix + "_fit_range_time"] = nullptr;
    }
  };
  lambda_json(a.rosenstein, "lambda");  // Rosenstein, the key earlier versions reported
  j["lambda_per"] = per_time ? "time" : "sample";
  lambda_json(a.kantz, "lambda_kantz");
  if (a.local_maps) {
    const LocalMapResult& l = *a.local_maps;
    j["lambda_local_maps"] = optional_json(per_time ? l.lambda_per_time : l.lambda);
    j["lambda_local_maps_interval"] = interval_json(per_time ? l.lambda_per_time_interval : l.lambda_interval);
    j["lambda_local_maps_status"] = to_string(l.status);
    j["lambda_local_maps_dimension"] = l.variants.front().dimension;  // m, or m + 1 (automatic_analysis.hpp, step 6)
    j["lambda_local_maps_explanation"] = l.explanation;
  } else {
    j["lambda_local_maps"] = nullptr;
    j["lambda_local_maps_interval"] = nullptr;
    j["lambda_local_maps_status"] = "not_run";
    j["lambda_local_maps_dimension"] = nullptr;
    j["lambda_local_maps_explanation"] = a.local_maps_refusal.empty() ? a.stopped : a.local_maps_refusal;
  }
  if (nonlinear)
    j["nonlinearity"] = {{"statistic", nonlinear->data_statistic}, {"rank", nonlinear->test.rank},
                         {"count", nonlinear->surrogate_statistics.size()}, {"ties", nonlinear->test.ties},
                         {"rejected", nonlinear->test.rejected},
                         {"significance", nonlinear->test.significance}, {"offset", segment->offset},
                         {"length", segment->length}};
  else
    j["nonlinearity"] = nullptr;
  j["autocorrelation"] = {{"first_zero_crossing", optional_json(scales.first_zero_crossing)},
                          {"decorrelation_time", optional_json(scales.decorrelation_time)},
                          {"half_period", optional_json(scales.half_period)}};
  if (a.cao)
    j["cao"] = {{"dimension", a.cao->dimension}, {"E1", a.cao->E1}, {"E2", a.cao->E2}, {"samples", a.cao_samples}};
  if (fnn) j["fnn"] = {{"dimension", fnn->dimension}, {"false_fraction", fnn->false_fraction}};
  return run;
}

}  // namespace chaos::cli
