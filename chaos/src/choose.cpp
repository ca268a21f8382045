#include "chaos/choose.hpp"

#include <algorithm>
#include <utility>

#include "chaos/error.hpp"
#include "chaos/mutual_information.hpp"

namespace chaos {

DelaySearchLimits delay_search_limits(std::size_t n, const TimeScales& scales, const DelaySearch& search) {
  const std::size_t cap = std::max<std::size_t>(1, n / 10);
  return {std::max<std::size_t>(1, std::min(search.max_delay, cap)), std::min(cap, search.windows * scales.theiler)};
}

DelayChoice choose_delay(std::span<const double> x, const TimeScales& scales, const DelaySearch& search) {
  DelayChoice out;
  if (scales.decorrelation_time && *scales.decorrelation_time <= 1.0) {
    out.delay = 1;
    out.source = "autocorrelation below 1/e at lag 1: delay 1";
    return out;
  }
  // The first search as TISEAN's users know it (a fixed number of samples), then one scaled by the
  // record's own correlation time. The second repeats the first one's delays, so the first minimum
  // it finds is the one a single long search would find.
  const auto [first, second] = delay_search_limits(x.size(), scales, search);
  for (const std::size_t limit : {first, second}) {
    if (limit <= out.searched) continue;  // no wider than the search already made
    out.searched = limit;
    MutualInformationOptions mi;
    mi.max_delay = limit;
    mi.boxes = search.boxes;
    const std::string scope = limit == first ? "" : " (nothing up to " + std::to_string(first) + "; searched on to " +
                                                        std::to_string(search.windows) + " Theiler windows, " +
                                                        std::to_string(limit) + ")";
    out.information = mutual_information(x, mi);
    if (const auto minimum = first_minimum(out.information)) {
      out.delay = minimum;
      out.source = "first mutual-information minimum" + scope;
      return out;
    }
    if (scales.first_zero_crossing && *scales.first_zero_crossing <= limit) {
      out.delay = scales.first_zero_crossing;
      out.source = "no mutual-information minimum up to " + std::to_string(limit) +
                   "; autocorrelation first zero crossing" + scope;
      return out;
    }
  }
  out.stopped = "no mutual-information minimum and no autocorrelation zero crossing up to delay " +
                std::to_string(out.searched) + ": no delay can be chosen";
  return out;
}

TheilerChoice choose_theiler_window(const TimeScales& scales, std::size_t delay) {
  if (delay > scales.theiler)
    return {delay, "the delay (" + std::to_string(delay) + "), longer than the " + scales.theiler_source + " (" +
                       std::to_string(scales.theiler) + ")"};
  return {scales.theiler, scales.theiler_source};
}

DimensionChoice choose_embedding_dimension(std::span<const double> x, std::size_t delay, std::size_t theiler,
                                           std::size_t max_dimension, std::function<void(double)> progress,
                                           std::size_t threads) {
  CaoOptions c;
  c.threads = threads;
  c.delay = delay;
  c.theiler = theiler;
  c.max_dimension = max_dimension;
  c.progress = std::move(progress);
  const std::span<const double> read = x.first(std::min(x.size(), dimension_samples));
  DimensionChoice out{std::nullopt, cao(read, c), read.size(), {}};
  out.dimension = out.cao.embedding_dimension;
  if (!out.dimension)
    out.stopped = "Cao's E1 does not saturate up to m = " + std::to_string(max_dimension) +
                  (out.cao.stochastic ? " and E2 stays at 1 (stochastic)" : "") +
                  (read.size() < x.size() ? " over the first " + std::to_string(read.size()) + " samples" : "") +
                  ": no embedding dimension";
  return out;
}

std::string dimension_rule(std::size_t samples, std::size_t n) {
  std::string rule = "Cao's E1 saturation";
  if (samples < n) rule += " over the first " + std::to_string(samples) + " of " + std::to_string(n) + " samples";
  return rule;
}

RadiusRange choose_radius_range(std::span<const double> x) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  return {(*hi - *lo) / 1000.0, (*hi - *lo) / 4.0};
}

std::vector<double> choose_radii(std::span<const double> x, std::size_t count) {
  const RadiusRange r = choose_radius_range(x);
  return log_radii(r.smallest, r.largest, count);
}

CorrelationSumOptions choose_correlation_sum_options(std::span<const double> x, std::size_t delay, std::size_t theiler,
                                                     std::size_t max_dimension, std::size_t radii) {
  CorrelationSumOptions s;
  s.delay = delay;
  s.theiler = theiler;
  s.max_dimension = max_dimension;
  s.radii = choose_radii(x, radii);
  return s;
}

std::size_t choose_lyapunov_steps(std::size_t correlation_time, std::size_t period, std::size_t n) {
  return std::max<std::size_t>(20, std::min(20 * std::max(correlation_time, period), n / 10));
}

LyapunovOptions choose_lyapunov_options(const TimeScales& scales, std::size_t n, std::size_t dimension,
                                        std::size_t delay, std::size_t theiler, LyapunovMethod method) {
  LyapunovOptions l;
  l.method = method;
  l.dimension = dimension;
  l.delay = delay;
  l.theiler = theiler;
  l.steps = choose_lyapunov_steps(scales.theiler, scales.period(), n);
  // The curve is a mean over the reference points; at 10^4 its sampling error is far below the 10%
  // the fit tolerates, and the cost of a long curve stays linear in N / 10^4 instead of N.
  l.reference_points = std::min<std::size_t>(n, 10000);
  // A Kantz neighbourhood costs its size times the steps. At the automatic radius (at most 20
  // neighbours on average) none reaches 1000 on Lorenz, Hénon or Rössler x at N = 10^5; a given radius
  // on drifting or tied data can put most of the record in every one (docs/reference/lyapunov.md).
  l.max_neighbours = default_max_neighbours;
  return l;
}

LyapunovFitOptions choose_lyapunov_fit(const TimeScales& scales) {
  LyapunovFitOptions fit;
  fit.period = scales.period();
  fit.dimensions = 3;
  return fit;
}

LocalMapOptions choose_local_map_options(std::size_t dimension, std::size_t delay, std::size_t theiler) {
  LocalMapOptions options;
  options.dimension = dimension;
  options.delay = delay;
  options.theiler = theiler;
  return options;
}

EmbeddingChoice choose_delay_and_window(std::span<const double> x, std::optional<std::size_t> delay,
                                        std::optional<std::size_t> theiler, const DelaySearch& search) {
  EmbeddingChoice out;
  if (!delay || !theiler) out.scales = time_scales(x);
  if (delay) {
    out.delay = *delay;
    out.delay_source = "given";
  } else {
    DelayChoice d;
    try {
      d = choose_delay(x, *out.scales, search);
    } catch (const InvalidInput& e) {
      d.stopped = std::string("no delay can be chosen: ") + e.what();  // too short for the information
    }
    if (d.delay) {
      out.delay = *d.delay;
      out.delay_source = d.source;
    } else {
      out.delay = fallback_delay;
      out.delay_source = d.stopped + "; the fallback " + std::to_string(fallback_delay) + " stands in (give one with -d)";
      out.fallback = true;
    }
  }
  if (theiler) {
    out.theiler = *theiler;
    out.theiler_source = "given";
  } else {
    TheilerChoice w = choose_theiler_window(*out.scales, out.delay);
    out.theiler = w.window;
    out.theiler_source = std::move(w.source);
  }
  return out;
}

EmbeddingChoice choose_embedding(std::span<const double> x, std::optional<std::size_t> delay,
                                 std::optional<std::size_t> theiler, std::optional<std::size_t> dimension,
                                 const DelaySearch& search, std::size_t max_dimension,
                                 std::function<void(double)> progress, std::size_t threads) {
  EmbeddingChoice out = choose_delay_and_window(x, delay, theiler, search);
  if (dimension) {
    out.dimension = dimension;
    out.dimension_source = "given";
    return out;
  }
  std::string stopped;
  try {
    const DimensionChoice m = choose_embedding_dimension(x, out.delay, out.theiler, max_dimension, std::move(progress), threads);
    if (m.dimension) {
      out.dimension = m.dimension;
      out.dimension_source = dimension_rule(m.samples, x.size());
      return out;
    }
    stopped = m.stopped + " at delay " + std::to_string(out.delay);
  } catch (const InvalidInput& e) {
    stopped = std::string("no embedding dimension: ") + e.what();  // too short for Cao's method
  }
  out.dimension = fallback_dimension;
  out.dimension_source = stopped + "; the fallback m = " + std::to_string(fallback_dimension) + " stands in (give one with -m)";
  out.fallback = true;
  return out;
}

}  // namespace chaos
