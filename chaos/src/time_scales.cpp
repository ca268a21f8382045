#include "chaos/time_scales.hpp"

#include <algorithm>
#include <cmath>

#include "chaos/autocorrelation.hpp"
#include "chaos/error.hpp"
#include "chaos/series.hpp"
#include "numeric.hpp"

namespace chaos {

TimeScales time_scales(std::span<const double> x) {
  if (x.size() < 3)
    throw InvalidInput(ErrorCode::too_short, "time scales need at least 3 samples (got N = " + std::to_string(x.size()) + ")");
  require_finite(x, "time scales");
  require_not_constant(x, "time scales");
  TimeScales t;
  t.max_lag = std::max<std::size_t>(1, std::min<std::size_t>(x.size() / 4, 5000));
  const AutocorrelationResult acf = autocorrelation(x, t.max_lag);
  t.decorrelation_time = decorrelation_time(acf);
  t.first_zero_crossing = first_zero_crossing(acf);
  t.half_period = oscillation_half_period(acf);
  const double length = static_cast<double>(x.size());
  if (!t.decorrelation_time || *t.decorrelation_time * min_correlation_times > length) {
    t.stationary = false;
    t.theiler = t.decorrelation_time ? static_cast<std::size_t>(std::ceil(*t.decorrelation_time)) : t.max_lag;
    t.theiler_source = t.decorrelation_time ? "autocorrelation 1/e time"
                                            : "autocorrelation stays above 1/e up to lag " + std::to_string(t.max_lag) +
                                                  ": set to that lag";
    const std::string time = t.decorrelation_time ? std::to_string(static_cast<long long>(std::llround(*t.decorrelation_time)))
                                                  : "more than " + std::to_string(t.max_lag);
    t.stationarity_explanation =
        "the autocorrelation falls to 1/e only after " + time + " samples: the record (N = " +
        std::to_string(x.size()) + ") holds fewer than " + detail::format_number(min_correlation_times) +
        " of its own correlation times, as for a random walk, a trend or 1/f^2 noise; its statistics drift with the "
        "record and no attractor invariant can be read from it (analyse its increments, x[n+1] - x[n], or a "
        "longer record)";
    return t;
  }
  const auto decay = static_cast<std::size_t>(std::ceil(*t.decorrelation_time));
  if (t.half_period && *t.half_period > decay) {
    t.theiler = *t.half_period;
    t.theiler_source = "half the dominant oscillation period (first autocorrelation minimum, " +
                       std::to_string(*t.half_period) + " samples; the 1/e time is " + std::to_string(decay) + ")";
  } else {
    t.theiler = std::max<std::size_t>(decay, 1);
    t.theiler_source = "autocorrelation 1/e time";
  }
  return t;
}

}  // namespace chaos
