#include "chaos/models/control_signals.hpp"

#include <fftw3.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <mutex>
#include <numbers>
#include <numeric>
#include <string>
#include <utility>

#include "chaos/error.hpp"
#include "chaos/random.hpp"
#include "chaos/series.hpp"
#include "fftw.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

// GCC/Clang 128-bit product; __extension__ keeps -Wpedantic quiet about the non-ISO type.
__extension__ typedef unsigned __int128 uint128;

// Integers up to 2^53 are exact in a double, so p, q and n q mod p convert without rounding.
constexpr std::uint64_t max_exact = std::uint64_t{1} << 53;

// Shortest text that reads back as the same double: 0.15, not 0.14999999999999999.
std::string num(double v) { return format_number(v, Precision::shortest); }

void require_samples(std::size_t n, std::size_t minimum, const char* what) {
  if (n < minimum)
    refuse_parameter(std::string(what) + ": the number of samples n must be at least " + std::to_string(minimum) +
           " (got n = " + std::to_string(n) + ")");
}

// Checks shared by the transforms of a given series: not empty, finite, and (where a range or a
// standard deviation is needed) not constant.
void check_input(std::span<const double> x, const char* what, bool needs_variation) {
  if (x.empty())
    throw InvalidInput(ErrorCode::empty, std::string(what) + ": the series is empty (N = 0); at least 1 sample is needed");
  require_finite(x, what);
  if (needs_variation) require_not_constant(x, what);
}

Trajectory scalar(std::vector<double> values) {
  Trajectory out;
  out.names = {"x"};
  out.components.push_back(std::move(values));
  out.dt = 1.0;
  return out;
}

// ---- Exact rational phases ----------------------------------------------------------------------

// sin(2 pi r / p) for 0 <= r < p, reduced to the first quadrant in integers: the angle becomes
// +-pi m / p with m in 0 .. p/2. Phases whose sines are mathematically equal (r and p/2 - r mod p)
// give the same m and sign, so the same bits; sin(pi) is exactly 0. 4 r < 2^55 cannot overflow.
double sin_of_turn(std::uint64_t r, std::uint64_t p) {
  const std::uint64_t u = 4 * r;
  std::uint64_t m = 0;
  double sign = 1.0;
  if (u <= p) {
    m = 2 * r;
  } else if (u <= 2 * p) {
    m = p - 2 * r;
  } else if (u <= 3 * p) {
    m = 2 * r - p;
    sign = -1.0;
  } else {
    m = 2 * p - 2 * r;
    sign = -1.0;
  }
  return sign * std::sin(std::numbers::pi * static_cast<double>(m) / static_cast<double>(p));
}

// A rational period p / q reduced by gcd and checked: p, q in 1 .. 2^53 and p / q > 2.
struct Reduced {
  std::uint64_t p, q;
};

std::string fraction(RationalPeriod period) {
  return std::to_string(period.numerator) + "/" + std::to_string(period.denominator);
}

Reduced reduce(RationalPeriod period, const char* what) {
  const auto [p, q] = period;
  if (p == 0 || q == 0 || p > max_exact || q > max_exact)
    refuse_parameter(std::string(what) + ": the numerator and denominator of the period must lie in 1 .. 2^53 (got P = " +
           fraction(period) + ")");
  if (p <= 2 * q)
    refuse_parameter(std::string(what) + ": the period P must be > 2 samples, below the Nyquist frequency (got P = " +
           fraction(period) + " = " + num(static_cast<double>(p) / static_cast<double>(q)) +
           "; at P = 2 the sine is sin(pi n) = 0 and 1 < P < 2 is an alias of P / (P - 1))");
  const std::uint64_t g = std::gcd(p, q);
  return {p / g, q / g};
}

void require_real_period(double period, const char* what) {
  if (!(std::isfinite(period) && period > 2.0))
    refuse_parameter(std::string(what) + ": the period P must be finite and > 2 samples, below the Nyquist frequency (got P = " +
           num(period) + "; at P = 2 the sine is sin(pi n) = 0 and 1 < P < 2 is an alias of P / (P - 1))");
}

// The amplitudes: not empty, finite, not all zero, and harmonic h (1-based) below the Nyquist
// frequency, 2 h < P, wherever a_h != 0. `twice_h_below` tells whether 2 h < P.
template <class Below>
void check_amplitudes(const std::vector<double>& a, const char* what, const std::string& period_text,
                      const Below& twice_h_below) {
  if (a.empty()) refuse_parameter(std::string(what) + ": at least one amplitude is needed (got an empty list)");
  bool any = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i]))
      refuse_parameter(std::string(what) + ": amplitudes must be finite (got a_" + std::to_string(i + 1) + " = " + num(a[i]) + ")");
    if (a[i] != 0.0) {
      any = true;
      if (!twice_h_below(i + 1))
        refuse_parameter(std::string(what) + ": harmonic h = " + std::to_string(i + 1) + " has amplitude " + num(a[i]) +
               " but 2 h >= P = " + period_text + ": it lies at or above the Nyquist frequency and would alias");
    }
  }
  if (!any) refuse_parameter(std::string(what) + ": the amplitudes are all zero (got " + std::to_string(a.size()) + " of them)");
}

// sum_h a_h sin(2 pi h r / p) for the reduced phase r.
double rational_terms(std::uint64_t r, std::uint64_t p, const std::vector<double>& a) {
  double x = 0.0;
  for (std::size_t h = 1; h <= a.size(); ++h)
    if (a[h - 1] != 0.0) x += a[h - 1] * sin_of_turn(static_cast<std::uint64_t>(uint128{h} * r % p), p);
  return x;
}

// sin(2 pi h n / P) for a real period: fmod is exact, so the one rounding is the division.
double real_term(std::size_t h, std::size_t n, double period) {
  const double turns = std::fmod(static_cast<double>(h) * static_cast<double>(n), period) / period;
  return std::sin(2.0 * std::numbers::pi * turns);
}

}  // namespace

// ---- Noise -------------------------------------------------------------------------------------

Trajectory power_law_noise(std::size_t n, double alpha, std::uint64_t seed) {
  require_samples(n, 2, "power_law_noise");
  if (n > static_cast<std::size_t>(INT_MAX))
    refuse_parameter("power_law_noise: at most 2^31 - 1 samples are supported (FFTW's int sizes); got n = " + std::to_string(n));
  if (!(std::isfinite(alpha) && alpha >= 0.0))
    refuse_parameter("power_law_noise: alpha must be finite and >= 0 (got alpha = " + num(alpha) + ")");
  const std::size_t bins = n / 2 + 1;
  auto spectrum = detail::fftw_buffer<fftw_complex>(bins);
  auto real = detail::fftw_buffer<double>(n);
  detail::Plan backward;
  {
    std::lock_guard lock(detail::fftw_planner_mutex());
    backward = detail::Plan(
        fftw_plan_dft_c2r_1d(static_cast<int>(n), spectrum.get(), real.get(), FFTW_ESTIMATE));
  }
  Random rng(seed);
  spectrum[0][0] = spectrum[0][1] = 0.0;
  // f_k^(-alpha/2) up to the constant n^(alpha/2), which the normalisation removes: k^(-alpha/2).
  for (std::size_t k = 1; k < bins; ++k) {
    const double scale = alpha == 0.0 ? 1.0 : std::pow(static_cast<double>(k), -0.5 * alpha);
    const double re = rng.gaussian(), im = rng.gaussian();
    spectrum[k][0] = scale * re;
    spectrum[k][1] = 2 * k == n ? 0.0 : scale * im;
  }
  backward.execute();
  double mean = 0.0;
  for (std::size_t t = 0; t < n; ++t) mean += real[t];
  mean /= static_cast<double>(n);
  double var = 0.0;
  for (std::size_t t = 0; t < n; ++t) var += (real[t] - mean) * (real[t] - mean);
  const double sd = std::sqrt(var / static_cast<double>(n));
  std::vector<double> values(n);
  for (std::size_t t = 0; t < n; ++t) values[t] = (real[t] - mean) / sd;
  return scalar(std::move(values));
}

Trajectory random_walk(std::size_t n, std::uint64_t seed) {
  require_samples(n, 1, "random_walk");
  Random rng(seed);
  std::vector<double> values(n);
  values[0] = 0.0;
  for (std::size_t t = 1; t < n; ++t) values[t] = values[t - 1] + rng.gaussian();
  return scalar(std::move(values));
}

// ---- Periodic and quasi-periodic ---------------------------------------------------------------

Trajectory periodic(std::size_t count, RationalPeriod period, const std::vector<double>& amplitudes) {
  require_samples(count, 1, "periodic");
  const auto [p, q] = reduce(period, "periodic");
  check_amplitudes(amplitudes, "periodic", fraction(period),
                   [p = p, q = q](std::size_t h) { return uint128{2} * h * q < p; });
  std::vector<double> values(count);
  std::uint64_t r = 0;  // n q mod p, advanced by q each sample (q < p / 2, so r + q < 2^54)
  for (std::size_t n = 0; n < count; ++n) {
    values[n] = rational_terms(r, p, amplitudes);
    r += q;
    if (r >= p) r -= p;
  }
  return scalar(std::move(values));
}

Trajectory periodic(std::size_t count, double period, const std::vector<double>& amplitudes) {
  require_samples(count, 1, "periodic");
  require_real_period(period, "periodic");
  if (period <= static_cast<double>(max_exact) && period == std::floor(period))
    return periodic(count, RationalPeriod{static_cast<std::uint64_t>(period), 1}, amplitudes);
  check_amplitudes(amplitudes, "periodic", num(period),
                   [period](std::size_t h) { return 2.0 * static_cast<double>(h) < period; });
  std::vector<double> values(count);
  for (std::size_t n = 0; n < count; ++n) {
    double x = 0.0;
    for (std::size_t h = 1; h <= amplitudes.size(); ++h)
      if (amplitudes[h - 1] != 0.0) x += amplitudes[h - 1] * real_term(h, n, period);
    values[n] = x;
  }
  return scalar(std::move(values));
}

Trajectory quasi_periodic_signal(std::size_t count, std::span<const double> periods) {
  require_samples(count, 1, "quasi_periodic_signal");
  if (periods.empty()) refuse_parameter("quasi_periodic_signal: at least one period is needed (got none)");
  for (const double period : periods) require_real_period(period, "quasi_periodic_signal");
  std::vector<double> values(count);
  for (std::size_t n = 0; n < count; ++n) {
    double x = 0.0;
    for (const double period : periods) x += real_term(1, n, period);
    values[n] = x;
  }
  return scalar(std::move(values));
}

Trajectory quasi_periodic_signal(std::size_t count, RationalPeriod first, std::span<const double> other_periods) {
  require_samples(count, 1, "quasi_periodic_signal");
  const auto [p, q] = reduce(first, "quasi_periodic_signal");
  for (const double period : other_periods) require_real_period(period, "quasi_periodic_signal");
  std::vector<double> values(count);
  std::uint64_t r = 0;
  for (std::size_t n = 0; n < count; ++n) {
    double x = sin_of_turn(r, p);
    for (const double period : other_periods) x += real_term(1, n, period);
    values[n] = x;
    r += q;
    if (r >= p) r -= p;
  }
  return scalar(std::move(values));
}

Trajectory two_torus(std::size_t count) {
  const double periods[] = {torus_period_1, torus_period_2};
  return quasi_periodic_signal(count, periods);
}

Trajectory three_torus(std::size_t count) {
  const double periods[] = {torus_period_1, torus_period_2, torus_period_3};
  return quasi_periodic_signal(count, periods);
}

Trajectory two_torus_rational_first(std::size_t count, RationalPeriod first) {
  const double others[] = {torus_period_2};
  return quasi_periodic_signal(count, first, others);
}

// ---- Corruptions -------------------------------------------------------------------------------

std::vector<double> add_noise(std::span<const double> x, double snr_db, std::uint64_t seed) {
  check_input(x, "add_noise", true);
  if (!std::isfinite(snr_db)) refuse_parameter("add_noise: the SNR must be finite (got snr_db = " + num(snr_db) + ")");
  // The standard deviation on x / 2^e (exact), so squares neither overflow nor underflow.
  const int e = detail::scale_exponent(x);
  const auto scaled = detail::scaled_by_power_of_two(x, e);
  double mean = 0.0;
  for (const double v : scaled) mean += v;
  mean /= static_cast<double>(scaled.size());
  double var = 0.0;
  for (const double v : scaled) var += (v - mean) * (v - mean);
  const double sd = std::ldexp(std::sqrt(var / static_cast<double>(scaled.size())), e);
  const double sigma = sd / std::pow(10.0, snr_db / 20.0);
  if (!std::isfinite(sigma))
    refuse_parameter("add_noise: the noise standard deviation std(x) / 10^(snr_db / 20) = " + num(sd) + " / 10^(" +
           num(snr_db) + " / 20) overflows; raise the SNR");
  Random rng(seed);
  std::vector<double> y(x.begin(), x.end());
  for (auto& v : y) v += sigma * rng.gaussian();
  return y;
}

std::vector<double> quantise_levels(std::span<const double> x, std::size_t levels) {
  check_input(x, "quantise_levels", true);
  if (levels < 2)
    refuse_parameter("quantise_levels: the number of levels must be at least 2 (got levels = " + std::to_string(levels) + ")");
  const auto [lo_it, hi_it] = std::minmax_element(x.begin(), x.end());
  const double lo = *lo_it, hi = *hi_it;
  const double range = hi - lo;
  if (!std::isfinite(range))
    refuse_parameter("quantise_levels: the range max - min = " + num(hi) + " - " + num(lo) + " overflows");
  const double top = static_cast<double>(levels - 1);
  const double delta = range / top;
  std::vector<double> y(x.size());
  for (std::size_t t = 0; t < x.size(); ++t) {
    const double k = std::clamp(std::round((x[t] - lo) / delta), 0.0, top);
    // The top level is the maximum itself, not lo + (levels - 1) delta with its rounding.
    y[t] = k == top ? hi : lo + k * delta;
  }
  return y;
}

std::vector<double> quantise_step(std::span<const double> x, double step) {
  check_input(x, "quantise_step", false);
  if (!(std::isfinite(step) && step > 0.0))
    refuse_parameter("quantise_step: the step must be finite and > 0 (got step = " + num(step) + ")");
  std::vector<double> y(x.size());
  for (std::size_t t = 0; t < x.size(); ++t) {
    const double k = x[t] / step;
    if (!std::isfinite(k))
      refuse_parameter("quantise_step: sample " + std::to_string(t) + " = " + num(x[t]) + " divided by the step " + num(step) +
             " is not finite; use a larger step");
    y[t] = step * std::round(k);
  }
  return y;
}

}  // namespace chaos
