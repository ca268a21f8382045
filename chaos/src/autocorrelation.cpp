#include "chaos/autocorrelation.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <new>
#include <string>

#include "chaos/error.hpp"
#include "fftw.hpp"
#include "numeric.hpp"
#include "chaos/series.hpp"

namespace chaos {

namespace {

using detail::FftwBuffer;
using detail::fftw_buffer;
using detail::Plan;



// Smallest 2^a 3^b 5^c >= n: FFTW is fast on such sizes, and they are at most 25% above n
// where a power of two can be almost 100% above.
std::size_t smooth_size(std::size_t n) {
  for (std::size_t m = n;; ++m) {
    std::size_t r = m;
    for (const std::size_t f : {2u, 3u, 5u})
      while (r % f == 0) r /= f;
    if (r == 1) return m;
  }
}

}  // namespace

AutocorrelationResult autocorrelation(std::span<const double> x, std::size_t max_lag) {
  const std::string what = "autocorrelation";
  // Saturated: max_lag + 1 wraps to 0 for the largest size_t.
  require_length(x, detail::add_sat(max_lag, 1), what,
                 "max_lag = " + std::to_string(max_lag) + " needs N > max_lag (the largest lag must leave a pair)");
  require_finite(x, what);
  require_not_constant(x, what);
  const std::size_t n = x.size();
  // r(k) does not depend on the scale, but the sums of squares below overflow beyond |x| ~ 1e150
  // and underflow below ~ 1e-160 (NaN rows): work on x divided by the power of two near
  // its largest magnitude, which is exact.
  const std::vector<double> y = detail::scaled_by_power_of_two(x, detail::scale_exponent(x));
  double mean = 0.0;
  for (const double v : y) mean += v;
  mean /= static_cast<double>(n);

  // Zero padding to L >= N + max_lag: the circular correlation of the padded series equals the
  // linear one for every lag up to max_lag, because no product wraps onto a nonzero sample.
  const std::size_t l = smooth_size(n + max_lag);
  const std::size_t bins = l / 2 + 1;
  auto real = fftw_buffer<double>(l);
  auto spectrum = fftw_buffer<fftw_complex>(bins);
  const int size = static_cast<int>(l);
  if (static_cast<std::size_t>(size) != l)
    throw InvalidInput(ErrorCode::invalid_parameter, what + ": series too long for one FFT (N = " +
                                                         std::to_string(n) + ")");
  std::unique_ptr<Plan> forward, backward;
  {
    std::lock_guard lock(detail::fftw_planner_mutex());
    forward = std::make_unique<Plan>(fftw_plan_dft_r2c_1d(size, real.get(), spectrum.get(), FFTW_ESTIMATE));
    backward = std::make_unique<Plan>(fftw_plan_dft_c2r_1d(size, spectrum.get(), real.get(), FFTW_ESTIMATE));
  }
  for (std::size_t t = 0; t < n; ++t) real[t] = y[t] - mean;
  for (std::size_t t = n; t < l; ++t) real[t] = 0.0;
  forward->execute();
  // Wiener-Khinchin: the inverse transform of |X|^2 is the autocovariance sum (times L, FFTW's
  // transforms being unnormalised).
  for (std::size_t k = 0; k < bins; ++k) {
    spectrum[k][0] = spectrum[k][0] * spectrum[k][0] + spectrum[k][1] * spectrum[k][1];
    spectrum[k][1] = 0.0;
  }
  backward->execute();

  // r(k) = c(k) / c(0): the common factors 1/N and 1/L cancel.
  AutocorrelationResult result;
  result.correlation.resize(max_lag + 1);
  const double c0 = real[0];
  result.correlation[0] = 1.0;
  for (std::size_t k = 1; k <= max_lag; ++k) result.correlation[k] = real[k] / c0;
  return result;
}

std::optional<std::size_t> first_zero_crossing(const AutocorrelationResult& result) {
  const auto& r = result.correlation;
  for (std::size_t k = 1; k < r.size(); ++k)
    if (r[k] <= 0.0) return k;
  return std::nullopt;
}

std::optional<double> decorrelation_time(const AutocorrelationResult& result) {
  const auto& r = result.correlation;
  const double level = std::exp(-1.0);
  if (r.empty()) return std::nullopt;
  if (r[0] <= level) return 0.0;  // only for a hand-made result: autocorrelation() gives r(0) = 1
  for (std::size_t k = 1; k < r.size(); ++k)
    if (r[k] <= level) {
      // r[k-1] > 1/e >= r[k]: the straight line between them crosses 1/e inside [k-1, k].
      return static_cast<double>(k - 1) + (r[k - 1] - level) / (r[k - 1] - r[k]);
    }
  return std::nullopt;
}

std::optional<std::size_t> oscillation_half_period(const AutocorrelationResult& result, double min_depth,
                                                   double max_ratio) {
  const auto zero = first_zero_crossing(result);
  const auto decay = decorrelation_time(result);
  if (!zero || !decay || static_cast<double>(*zero) > max_ratio * std::max(*decay, 1.0)) return std::nullopt;
  const auto& r = result.correlation;
  for (std::size_t k = *zero; k + 1 < r.size(); ++k)
    if (r[k] <= r[k - 1] && r[k] < r[k + 1]) {
      if (r[k] > -min_depth) return std::nullopt;  // a shallow wiggle, not an oscillation
      return k;
    }
  return std::nullopt;
}

}  // namespace chaos
