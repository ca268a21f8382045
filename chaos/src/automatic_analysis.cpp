#include "chaos/automatic_analysis.hpp"

#include <algorithm>
#include <cmath>

#include "chaos/autocorrelation.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/error.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/series.hpp"
#include "lyapunov_local_maps_detail.hpp"

namespace chaos {

std::pair<std::span<const double>, std::span<const double>> record_halves(std::span<const double> x) {
  const std::size_t half = x.size() / 2;
  return {x.first(half), x.subspan(half)};
}

CorrelationDimensionResult automatic_correlation_dimension(std::span<const double> x, const CorrelationSumOptions& sums,
                                                           bool check_halves, bool check_delay) {
  CorrelationDimensionResult d2 = correlation_dimension(correlation_sum(x, sums));
  if (check_halves) check_record_halves(d2, x, sums);
  if (check_delay) check_delay_variant(d2, x, sums);
  return d2;
}

void check_record_halves(CorrelationDimensionResult& d2, std::span<const double> x, const CorrelationSumOptions& sums,
                         const CorrelationDimensionOptions& options) {
  if (d2.status != D2Status::saturated) return;
  const auto [first, second] = record_halves(x);
  try {
    require_reproduced_by_halves(d2, correlation_dimension(correlation_sum(first, sums), options),
                                 correlation_dimension(correlation_sum(second, sums), options), options);
  } catch (const InvalidInput& e) {
    // A half too short to embed in the highest dimension: the plateau cannot be reproduced.
    const CorrelationDimensionResult none;  // no_scaling_region
    require_reproduced_by_halves(d2, none, none, options);
    d2.explanation += std::string(" (a half cannot be analysed: ") + e.what() + ")";
  }
}

void check_record_halves(LyapunovResult& result, std::span<const double> x, LyapunovOptions options,
                         const LyapunovFitOptions& fit) {
  if (!result.fit.estimate.value) return;
  const auto [first, second] = record_halves(x);
  options.progress = nullptr;  // the progress shown is the whole record's curve
  try {
    require_reproduced_by_halves(result, largest_lyapunov(first, options, fit, result.dt),
                                 largest_lyapunov(second, options, fit, result.dt), fit.tolerance);
  } catch (const InvalidInput& e) {
    // A half too short for the curve's steps in the highest dimension: the slope cannot be reproduced.
    const LyapunovResult none;  // no_neighbours
    require_reproduced_by_halves(result, none, none, fit.tolerance);
    result.fit.explanation += std::string(" (a half cannot be analysed: ") + e.what() + ")";
  }
}

void check_record_halves(std::span<LyapunovResult* const> results, std::span<const double> x,
                         const std::vector<LyapunovOptions>& options, const LyapunovFitOptions& fit) {
  if (results.size() != options.size())
    throw InvalidInput(ErrorCode::invalid_parameter, "Lyapunov halves check: one set of options per result");
  std::vector<LyapunovResult*> checked;
  std::vector<LyapunovOptions> runs;
  for (std::size_t r = 0; r < results.size(); ++r)
    if (results[r]->fit.estimate.value) {
      checked.push_back(results[r]);
      runs.push_back(options[r]);
      runs.back().progress = nullptr;  // the progress shown is the whole record's curves
    }
  if (checked.empty()) return;
  const auto [first, second] = record_halves(x);
  std::vector<LyapunovResult> a, b;
  try {
    // Each half embedded once for every run (largest_lyapunov_runs).
    a = largest_lyapunov_runs(first, runs, fit, checked.front()->dt);
    b = largest_lyapunov_runs(second, runs, fit, checked.front()->dt);
  } catch (const InvalidInput&) {
    // A half that cannot be analysed: each run on its own, so each says why in its own words.
    for (std::size_t r = 0; r < checked.size(); ++r) check_record_halves(*checked[r], x, runs[r], fit);
    return;
  }
  for (std::size_t r = 0; r < checked.size(); ++r) require_reproduced_by_halves(*checked[r], a[r], b[r], fit.tolerance);
}

void check_delay_variant(CorrelationDimensionResult& d2, std::span<const double> x, const CorrelationSumOptions& sums,
                         const CorrelationDimensionOptions& options) {
  if (d2.status != D2Status::saturated) return;
  CorrelationSumOptions other = sums;
  other.delay = 2 * sums.delay;
  other.progress = nullptr;  // the progress shown is the chosen delay's sums
  try {
    require_reproduced_at_delay(d2, correlation_dimension(correlation_sum(x, other), options), other.delay, options);
  } catch (const InvalidInput& e) {
    // Too short to embed the highest dimension at twice the delay: the plateau cannot be reproduced.
    require_reproduced_at_delay(d2, CorrelationDimensionResult{}, other.delay, options);
    d2.explanation += std::string(" (the record cannot be embedded at that delay: ") + e.what() + ")";
  }
}

LocalMapsRuns local_maps_with_next_dimension(std::span<const double> x, const LocalMapOptions& options,
                                             std::optional<double> dt, bool next_dimension,
                                             const std::function<void()>& retrying) {
  // The run at m computes its "m + 1" variant, which is the base of the run at m + 1 to the last
  // bit: the retry takes it instead of computing it again. (0.05: largest_lyapunov_local_maps's tolerance.)
  std::optional<LocalMapEstimate> next_base;
  LocalMapsRuns runs{detail::local_maps_run(x, options, dt, 0.05, nullptr, next_dimension ? &next_base : nullptr),
                     std::nullopt};
  // Only an inconsistent run is tried again: noise (not_deterministic) and a series without
  // exponential divergence (not_positive) are what the data are, not an effect of m.
  if (!next_dimension || runs.result.status != LocalMapStatus::inconsistent) return runs;
  LocalMapOptions next_options = options;
  const std::size_t m = ++next_options.dimension;
  if (retrying) retrying();
  try {
    LocalMapResult next = detail::local_maps_run(x, next_options, dt, 0.05, next_base ? &*next_base : nullptr, nullptr);
    if (next.status == LocalMapStatus::consistent) {
      next.explanation = "at m = " + std::to_string(m) + ": " + next.explanation + "; at m = " +
                         std::to_string(options.dimension) + ", inconsistent: " + runs.result.explanation;
      runs.at_m = std::move(runs.result);
      runs.result = std::move(next);
    } else {
      runs.result.explanation += "; at m = " + std::to_string(m) + ", " + to_string(next.status) + ": " + next.explanation;
    }
  } catch (const InvalidInput& e) {
    runs.result.explanation += "; at m = " + std::to_string(m) + " not run: " + e.what();
  }
  return runs;
}

AutomaticAnalysis analyse_series(std::span<const double> x, std::optional<double> dt,
                                 const AutomaticAnalysisOptions& options) {
  // Refused here, where every step gets the count: a step would otherwise refuse it on its own and
  // the analysis report a stopped step instead of a bad option.
  if (options.threads == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "automatic analysis: threads must be at least 1 (got 0)");
  require_finite(x, "automatic analysis");
  require_not_constant(x, "automatic analysis");
  AutomaticAnalysis a;
  a.scales = time_scales(x);
  // The window, given or by the rule (at least the delay, where there is one); reported even where
  // the analysis stops before it is used.
  const auto choose_window = [&](std::size_t delay) {
    if (options.theiler) {
      a.theiler = *options.theiler;
      a.theiler_source = "given";
    } else {
      TheilerChoice w = choose_theiler_window(a.scales, delay);
      a.theiler = w.window;
      a.theiler_source = std::move(w.source);
    }
  };
  if (options.check_stationarity && !a.scales.stationary) {
    choose_window(0);
    a.stopped = a.scales.stationarity_explanation;
    return a;
  }

  if (options.delay) {
    a.delay = options.delay;
    a.delay_source = "given";
  } else {
    DelayChoice choice = choose_delay(x, a.scales, options.delay_search);
    a.delay = choice.delay;
    a.delay_source = std::move(choice.source);
    a.delay_searched = choice.searched;
    a.delay_information = std::move(choice.information);
    a.stopped = std::move(choice.stopped);
  }
  choose_window(a.delay.value_or(0));
  if (!a.delay) return a;

  if (options.dimension) {
    a.dimension = options.dimension;
  } else {
    std::function<void(double)> progress;
    if (options.progress) progress = [&](double f) { options.progress("Cao's method", f); };
    try {
      DimensionChoice m = choose_embedding_dimension(x, *a.delay, a.theiler, options.max_dimension, std::move(progress),
                                                     options.threads);
      a.cao = std::move(m.cao);
      a.cao_samples = m.samples;
      a.dimension = m.dimension;
      if (!a.dimension) a.stopped = std::move(m.stopped);
    } catch (const InvalidInput& e) {  // too short for Cao's method: the delay and window stand
      a.stopped = std::string("no embedding dimension: Cao's method refused the series: ") + e.what();
    }
    if (!a.dimension) return a;
  }

  CorrelationSumOptions s =
      choose_correlation_sum_options(x, *a.delay, a.theiler, *a.dimension + options.extra_dimensions, options.radii);
  s.threads = options.threads;
  if (options.progress) s.progress = [&](double f) { options.progress("correlation sums", f); };
  // A step that refuses the series (too short for its embedding) says so in `stopped`; what the
  // steps before it found, and the steps after it, stand.
  const auto stop = [&](const std::string& why) { a.stopped += (a.stopped.empty() ? "" : "; ") + why; };
  try {
    a.d2 = automatic_correlation_dimension(x, s, options.check_halves, options.check_delay);
    a.d2_estimate = d2_answer(*a.d2);
  } catch (const InvalidInput& e) {
    stop(std::string("correlation dimension not estimated: ") + e.what());
  }

  const auto lyapunov = [&](LyapunovMethod method) {
    LyapunovOptions l = choose_lyapunov_options(a.scales, x.size(), *a.dimension, *a.delay, a.theiler, method);
    l.threads = options.threads;
    if (options.progress)
      l.progress = [&options, method](double f) {
        options.progress(std::string("Lyapunov exponent (") + to_string(method) + ")", f);
      };
    LyapunovResult r = largest_lyapunov(x, l, choose_lyapunov_fit(a.scales), dt);
    if (options.check_halves) check_record_halves(r, x, l, choose_lyapunov_fit(a.scales));
    return r;
  };
  try {
    if (options.rosenstein) a.rosenstein = lyapunov(LyapunovMethod::rosenstein);
    if (options.kantz) a.kantz = lyapunov(LyapunovMethod::kantz);
    if (options.cross_check && a.rosenstein && a.kantz)
      cross_check(*a.rosenstein, *a.kantz, choose_lyapunov_fit(a.scales).tolerance);
  } catch (const InvalidInput& e) {
    // Too short for the curve's steps in m + 2 dimensions: the exponent is not estimated.
    stop(std::string("largest Lyapunov exponent not estimated: ") + e.what());
  }
  if (options.local_maps) {
    LocalMapOptions l = choose_local_map_options(*a.dimension, *a.delay, a.theiler);
    l.threads = options.threads;
    if (options.progress) options.progress("Lyapunov exponent (local maps)", 0.0);
    try {
      LocalMapsRuns runs = local_maps_with_next_dimension(x, l, dt, options.local_maps_next_dimension, [&] {
        if (options.progress) options.progress("Lyapunov exponent (local maps)", 0.5);
      });
      a.local_maps = std::move(runs.result);
      a.local_maps_at_m = std::move(runs.at_m);
    } catch (const InvalidInput& e) {
      a.local_maps_refusal = e.what();
    }
    // A divergence slope stands only where the consistent local-map exponent confirms it.
    if (options.cross_check && a.local_maps) {
      const double tolerance = choose_lyapunov_fit(a.scales).tolerance;
      if (a.rosenstein) cross_check(*a.rosenstein, *a.local_maps, tolerance);
      if (a.kantz) cross_check(*a.kantz, *a.local_maps, tolerance);
    } else if (options.cross_check) {
      if (a.rosenstein) cross_check_without_local_maps(*a.rosenstein, a.local_maps_refusal);
      if (a.kantz) cross_check_without_local_maps(*a.kantz, a.local_maps_refusal);
    }
    if (options.progress) options.progress("Lyapunov exponent (local maps)", 1.0);
  }
  if (a.rosenstein || a.kantz || a.local_maps)
    a.lyapunov = combine_lyapunov(a.rosenstein ? &*a.rosenstein : nullptr, a.kantz ? &*a.kantz : nullptr,
                                  a.local_maps ? &*a.local_maps : nullptr, dt);
  return a;
}

}  // namespace chaos
