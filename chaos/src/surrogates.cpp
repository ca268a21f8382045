#include "chaos/surrogates.hpp"

#include <fftw3.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <complex>
#include <limits>
#include <mutex>
#include <new>
#include <string>
#include <utility>

#include "chaos/error.hpp"
#include "chaos/format.hpp"
#include "fftw.hpp"
#include "chaos/random.hpp"
#include "chaos/series.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

using detail::FftwBuffer;
using detail::fftw_buffer;
using detail::Plan;

std::string num(double v) { return format_number(v, Precision::shortest); }



// A real-to-complex / complex-to-real pair for one length on its own buffers. FFTW_ESTIMATE picks
// the algorithm without timing anything, so the same length always gets the same plan and the
// output is bit-reproducible; FFTW_MEASURE could choose differently from run to run.
struct Transform {
  std::size_t n = 0;
  FftwBuffer<double> real;
  FftwBuffer<fftw_complex> spectrum;
  Plan forward, backward;

  explicit Transform(std::size_t length)
      : n(length), real(fftw_buffer<double>(length)), spectrum(fftw_buffer<fftw_complex>(length / 2 + 1)) {
    std::lock_guard lock(detail::fftw_planner_mutex());
    const int ni = static_cast<int>(n);
    forward = Plan(fftw_plan_dft_r2c_1d(ni, real.get(), spectrum.get(), FFTW_ESTIMATE));
    backward = Plan(fftw_plan_dft_c2r_1d(ni, spectrum.get(), real.get(), FFTW_ESTIMATE));
  }
  std::size_t bins() const noexcept { return n / 2 + 1; }
};

// Weight of half-spectrum bin k in the full DFT: bins 1 .. ceil(N/2) - 1 stand for k and N - k.
double bin_weight(std::size_t k, std::size_t n) noexcept { return 2 * k == n ? 1.0 : 2.0; }

// Only correctly rounded operations (std::hypot is not), so the value is the same everywhere;
// check_series keeps the squares finite.
double modulus(const fftw_complex& c) noexcept { return std::sqrt(c[0] * c[0] + c[1] * c[1]); }

// sqrt( sum_{k=1}^{N-1} (|S_k| - A_k)^2 / sum_{k=1}^{N-1} A_k^2 ) from a half spectrum.
double deviation(const fftw_complex* s, const std::vector<double>& amplitude, double amplitude_norm, std::size_t n) {
  double sum = 0.0;
  for (std::size_t k = 1; k < amplitude.size(); ++k) {
    const double d = modulus(s[k]) - amplitude[k];
    sum += bin_weight(k, n) * d * d;
  }
  return std::sqrt(sum / amplitude_norm);
}

// Rank order by a distribution sort: each value goes to one of N buckets by linear interpolation
// between the minimum and the maximum (a weakly monotone map, so bucket order never contradicts
// value order), then each bucket is sorted by (value, index). For the bell- or bimodal-shaped
// values IAAFT ranks, buckets hold O(1) values and the ordering costs O(N), where a comparison sort
// costs O(N log N) and dominated the iteration; heavy tails only make it slower, never wrong. Equal
// values (and -0.0, +0.0) stay in index order, so the ordering is unique.
// The values are visited in the order `hint` (a permutation; index order when empty). The result
// does not depend on it, but memory access does: in IAAFT the previous iteration's ordering is
// nearly sorted for the new values, so buckets then fill almost sequentially instead of at random.
class RankSorter {
 public:
  // order[r] = index of the r-th smallest value of v.
  void order(const double* v, std::size_t n, std::vector<std::uint32_t>& order,
             const std::vector<std::uint32_t>& hint = {}) {
    order.resize(n);
    const auto [lo_it, hi_it] = std::minmax_element(v, v + n);
    // Halving first keeps hi - lo finite for any finite values; it is exact and monotone.
    const double s = std::isfinite(*hi_it - *lo_it) ? 1.0 : 0.5;
    const double lo = *lo_it * s, width = *hi_it * s - lo;
    if (!(width > 0.0)) {  // all equal: index order
      for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
      return;
    }
    const double per = static_cast<double>(n) / width;
    const bool hinted = hint.size() == n;
    visit_.resize(n);
    start_.assign(n + 1, 0);
    for (std::size_t j = 0; j < n; ++j) {
      const std::uint32_t i = hinted ? hint[j] : static_cast<std::uint32_t>(j);
      const double value = v[i];
      const auto b = std::min(n - 1, static_cast<std::size_t>((value * s - lo) * per));
      visit_[j] = {value, i, static_cast<std::uint32_t>(b)};
      ++start_[b + 1];
    }
    for (std::size_t b = 0; b < n; ++b) start_[b + 1] += start_[b];
    items_.resize(n);
    fill_ = start_;
    for (const Visit& e : visit_) items_[fill_[e.bucket]++] = {e.value, e.index};
    for (std::size_t b = 0; b < n; ++b) {
      Item* first = items_.data() + start_[b];
      Item* last = items_.data() + start_[b + 1];
      if (last - first < 2) continue;
      if (last - first <= 16) {
        for (Item* i = first + 1; i < last; ++i)  // insertion sort: buckets are tiny
          for (Item* j = i; j > first && less(*j, *(j - 1)); --j) std::swap(*j, *(j - 1));
      } else {
        std::sort(first, last, less);
      }
    }
    for (std::size_t r = 0; r < n; ++r) order[r] = items_[r].index;
  }

 private:
  struct Item {
    double value;
    std::uint32_t index;
  };
  static bool less(const Item& a, const Item& b) noexcept {
    return a.value < b.value || (a.value == b.value && a.index < b.index);
  }
  struct Visit {
    double value;
    std::uint32_t index, bucket;
  };
  std::vector<std::uint32_t> start_, fill_;
  std::vector<Visit> visit_;
  std::vector<Item> items_;
};

// A phase factor uniform on the unit circle: a point uniform in the unit disc (rejection), divided
// by its length. Only correctly rounded operations, so every platform draws the same factors.
std::pair<double, double> random_phase(Random& rng) {
  for (;;) {
    const double u = 2.0 * rng.uniform() - 1.0, v = 2.0 * rng.uniform() - 1.0;
    const double s = u * u + v * v;
    if (s < 1.0 && s > 0.0) {
      const double r = std::sqrt(s);
      return {u / r, v / r};
    }
  }
}

// Multiplies bins 1 .. ceil(N/2) - 1 by random phase factors; the mean (k = 0) and, for even N, the
// Nyquist bin (real for a real series) are left alone, so the surrogate is real and keeps them.
void randomise_phases(fftw_complex* s, std::size_t n, Random& rng) {
  for (std::size_t k = 1; 2 * k < n; ++k) {
    const auto [c, d] = random_phase(rng);
    const double re = s[k][0], im = s[k][1];
    s[k][0] = re * c - im * d;
    s[k][1] = re * d + im * c;
  }
}

void check_series(std::span<const double> x, const std::string& what) {
  require_length(x, 4, what, "a series needs at least one frequency besides the mean and the Nyquist frequency");
  if (x.size() > static_cast<std::size_t>(INT_MAX))
    throw InvalidInput(ErrorCode::invalid_parameter, what + ": at most 2^31 - 1 samples are supported (FFTW's int "
                                                            "sizes); got N = " + std::to_string(x.size()));
  require_finite(x, what);
  require_not_constant(x, what);
  // A Fourier coefficient is at most N max|x|, and its square must not overflow: the transforms
  // work on the series divided by standardising_exponent's power of two (numeric.hpp), exactly.
}

}  // namespace

const char* to_string(SurrogateMethod method) noexcept {
  switch (method) {
    case SurrogateMethod::fourier: return "fourier";
    case SurrogateMethod::aaft: return "aaft";
    case SurrogateMethod::iaaft: return "iaaft";
  }
  return "unknown";
}

const char* null_hypothesis(SurrogateMethod method) noexcept {
  switch (method) {
    case SurrogateMethod::fourier: return "a linear Gaussian process";
    case SurrogateMethod::aaft:
    case SurrogateMethod::iaaft: return "a linear Gaussian process seen through a static monotone function";
  }
  return "unknown";
}

const char* to_string(SurrogateStatus status) noexcept {
  switch (status) {
    case SurrogateStatus::exact: return "exact";
    case SurrogateStatus::fixed_point: return "fixed_point";
    case SurrogateStatus::tolerance: return "tolerance";
    case SurrogateStatus::max_iterations: return "max_iterations";
  }
  return "unknown";
}

void SurrogateOptions::validate() const {
  if (method != SurrogateMethod::fourier && method != SurrogateMethod::aaft && method != SurrogateMethod::iaaft)
    throw InvalidInput(ErrorCode::invalid_parameter, "surrogates: unknown method " +
                                                         std::to_string(static_cast<int>(method)));
  if (max_iterations < 1)
    throw InvalidInput(ErrorCode::invalid_parameter, "surrogates: max_iterations must be at least 1 (got 0)");
  if (!(std::isfinite(tolerance) && tolerance >= 0.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "surrogates: tolerance must be finite and >= 0 (got tolerance = " + num(tolerance) + ")");
}

struct SurrogateGenerator::Impl {
  SurrogateOptions options;
  std::size_t n;
  Transform fft;
  std::vector<double> data;
  std::vector<double> sorted;               // the data's values, ascending
  std::vector<std::uint32_t> data_order;    // data_order[r] = index of the r-th smallest value
  std::vector<std::complex<double>> data_spectrum;  // X_k, k = 0 .. N/2
  std::vector<double> amplitude;            // |X_k|
  double amplitude_norm = 0.0;              // sum_{k=1}^{N-1} |X_k|^2 over the full DFT
  RankSorter sorter;
  std::vector<std::uint32_t> order, previous;

  // The transforms see the data divided by 2^exponent (0 for usual magnitudes): exact, so every
  // rank and ratio is that of the data; the surrogates are given back in the data's units (AAFT and
  // IAAFT: the data's own values, `original`).
  int exponent;
  std::vector<double> original;             // the data's values, ascending, as given

  Impl(std::span<const double> x, const SurrogateOptions& o)
      : options(o), n(x.size()), fft(x.size()), data(detail::scaled_by_power_of_two(x, detail::standardising_exponent(x))),
        exponent(detail::standardising_exponent(x)) {
    std::copy(data.begin(), data.end(), fft.real.get());
    fft.forward.execute();
    data_spectrum.resize(fft.bins());
    amplitude.resize(fft.bins());
    for (std::size_t k = 0; k < fft.bins(); ++k) {
      data_spectrum[k] = {fft.spectrum[k][0], fft.spectrum[k][1]};
      amplitude[k] = modulus(fft.spectrum[k]);
      if (k > 0) amplitude_norm += bin_weight(k, n) * amplitude[k] * amplitude[k];
    }
    sorter.order(data.data(), n, data_order);
    sorted.resize(n);
    for (std::size_t r = 0; r < n; ++r) sorted[r] = data[data_order[r]];
    original.resize(n);
    for (std::size_t r = 0; r < n; ++r) original[r] = x[data_order[r]];
  }

  // The surrogate in the data's units: the values computed (Fourier) times 2^exponent, or the data's
  // own values in the surrogate's rank order (AAFT, IAAFT: out.values holds sorted[r] values).
  void to_data_units(Surrogate& out, bool ranked) const {
    if (exponent == 0) return;
    if (!ranked) {
      for (double& v : out.values) v = std::ldexp(v, exponent);
      return;
    }
    for (double& v : out.values) v = original[static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), v) - sorted.begin())];
  }

  // Deviation of the series now in fft.real (destroys nothing: r2c keeps its input).
  double deviation_of_real() {
    fft.forward.execute();
    return deviation(fft.spectrum.get(), amplitude, amplitude_norm, n);
  }

  Surrogate fourier(Random& rng) {
    for (std::size_t k = 0; k < fft.bins(); ++k) {
      fft.spectrum[k][0] = data_spectrum[k].real();
      fft.spectrum[k][1] = data_spectrum[k].imag();
    }
    randomise_phases(fft.spectrum.get(), n, rng);
    fft.backward.execute();
    Surrogate out;
    out.values.resize(n);
    const double scale = 1.0 / static_cast<double>(n);  // FFTW's transforms are unnormalised
    for (std::size_t t = 0; t < n; ++t) fft.real[t] = out.values[t] = fft.real[t] * scale;
    out.spectral_deviation = deviation_of_real();
    to_data_units(out, false);
    return out;
  }

  // Theiler et al. (1992): Gaussian numbers put in the data's rank order, phase-randomised, and the
  // data's values put in the rank order of the result.
  Surrogate aaft(Random& rng) {
    std::vector<double> gaussian(n);
    for (auto& g : gaussian) g = rng.gaussian();
    std::sort(gaussian.begin(), gaussian.end());
    for (std::size_t r = 0; r < n; ++r) fft.real[data_order[r]] = gaussian[r];
    fft.forward.execute();
    randomise_phases(fft.spectrum.get(), n, rng);
    fft.backward.execute();  // scaled by N, which leaves the rank order unchanged
    sorter.order(fft.real.get(), n, order);
    Surrogate out;
    out.values.resize(n);
    for (std::size_t r = 0; r < n; ++r) out.values[order[r]] = sorted[r];
    std::copy(out.values.begin(), out.values.end(), fft.real.get());
    out.spectral_deviation = deviation_of_real();
    to_data_units(out, true);
    return out;
  }

  // Schreiber & Schmitz (1996): from a random permutation of the data, alternately (1) give the
  // series the data's Fourier amplitudes, keeping its phases, and (2) give it the data's values in
  // the rank order of (1). The deviation is always that of the series returned, which has the
  // data's values exactly.
  Surrogate iaaft(Random& rng) {
    Surrogate out;
    out.values = data;
    for (std::size_t i = n - 1; i > 0; --i) std::swap(out.values[i], out.values[rng.below(i + 1)]);
    std::copy(out.values.begin(), out.values.end(), fft.real.get());
    out.spectral_deviation = deviation_of_real();
    bool have_previous = false;
    for (;;) {
      if (options.tolerance > 0.0 && out.spectral_deviation <= options.tolerance) {
        out.status = SurrogateStatus::tolerance;
        break;
      }
      if (out.iterations == options.max_iterations) {
        out.status = SurrogateStatus::max_iterations;
        break;
      }
      // fft.spectrum holds the transform of out.values; impose the data's amplitudes.
      for (std::size_t k = 0; k < fft.bins(); ++k) {
        const double m = modulus(fft.spectrum[k]);
        if (m > 0.0) {
          const double f = amplitude[k] / m;
          fft.spectrum[k][0] *= f;
          fft.spectrum[k][1] *= f;
        } else {
          fft.spectrum[k][0] = amplitude[k];  // no phase to keep: take phase 0
          fft.spectrum[k][1] = 0.0;
        }
      }
      fft.backward.execute();
      sorter.order(fft.real.get(), n, order, previous);
      ++out.iterations;
      if (options.progress)
        options.progress(static_cast<double>(out.iterations) / static_cast<double>(options.max_iterations));
      if (have_previous && order == previous) {
        // Ranking (2) would rebuild out.values exactly: a fixed point of the iteration.
        out.status = SurrogateStatus::fixed_point;
        break;
      }
      for (std::size_t r = 0; r < n; ++r) out.values[order[r]] = sorted[r];
      previous.swap(order);
      have_previous = true;
      std::copy(out.values.begin(), out.values.end(), fft.real.get());
      out.spectral_deviation = deviation_of_real();
    }
    to_data_units(out, true);
    return out;
  }
};

SurrogateGenerator::SurrogateGenerator(std::span<const double> x, const SurrogateOptions& options) {
  options.validate();
  check_series(x, "surrogates");
  impl_ = std::make_unique<Impl>(x, options);
}

SurrogateGenerator::~SurrogateGenerator() = default;
SurrogateGenerator::SurrogateGenerator(SurrogateGenerator&&) noexcept = default;
SurrogateGenerator& SurrogateGenerator::operator=(SurrogateGenerator&&) noexcept = default;

Surrogate SurrogateGenerator::generate(std::uint64_t seed) {
  Random rng(seed);
  switch (impl_->options.method) {
    case SurrogateMethod::fourier: return impl_->fourier(rng);
    case SurrogateMethod::aaft: return impl_->aaft(rng);
    case SurrogateMethod::iaaft: return impl_->iaaft(rng);
  }
  return {};
}

std::size_t SurrogateGenerator::size() const noexcept { return impl_->n; }
const SurrogateOptions& SurrogateGenerator::options() const noexcept { return impl_->options; }

SurrogateOptions with_progress_over(const SurrogateOptions& options, const std::size_t& done, std::size_t count) {
  SurrogateOptions each = options;
  if (options.progress)
    each.progress = [&options, &done, count](double fraction) {
      options.progress((static_cast<double>(done) + fraction) / static_cast<double>(count));
    };
  return each;
}

std::vector<Surrogate> surrogates(std::span<const double> x, std::size_t count, std::uint64_t seed,
                                  const SurrogateOptions& options) {
  if (count > max_surrogates)
    throw InvalidInput(ErrorCode::invalid_parameter, "surrogates: at most " + std::to_string(max_surrogates) +
                                                         " surrogates (got " + std::to_string(count) + ")");
  std::size_t k = 0;
  SurrogateGenerator generator(x, with_progress_over(options, k, count));
  Random seeds(seed);
  std::vector<Surrogate> out;
  out.reserve(count);
  for (; k < count; ++k) {
    out.push_back(generator.generate(seeds.next()));
    if (options.progress) options.progress(static_cast<double>(k + 1) / static_cast<double>(count));
  }
  return out;
}

double spectral_deviation(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size())
    throw InvalidInput(ErrorCode::invalid_parameter, "spectral_deviation: the series have different lengths (" +
                                                         std::to_string(x.size()) + " and " +
                                                         std::to_string(y.size()) + ")");
  check_series(x, "spectral_deviation");
  require_finite(y, "spectral_deviation");
  // Both series divided by one power of two (0 for usual magnitudes): the ratio is unchanged.
  const int exponent = std::max(detail::standardising_exponent(x), detail::standardising_exponent(y));
  const std::vector<double> xs = detail::scaled_by_power_of_two(x, exponent);
  const std::vector<double> ys = detail::scaled_by_power_of_two(y, exponent);
  Transform fft(x.size());
  std::copy(xs.begin(), xs.end(), fft.real.get());
  fft.forward.execute();
  std::vector<double> amplitude(fft.bins());
  double norm = 0.0;
  for (std::size_t k = 0; k < fft.bins(); ++k) {
    amplitude[k] = modulus(fft.spectrum[k]);
    if (k > 0) norm += bin_weight(k, x.size()) * amplitude[k] * amplitude[k];
  }
  std::copy(ys.begin(), ys.end(), fft.real.get());
  fft.forward.execute();
  return deviation(fft.spectrum.get(), amplitude, norm, x.size());
}

void EndMatchOptions::validate() const {
  if (!(jump_weight >= 0.0 && jump_weight <= 1.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "end_match: jump_weight must lie in [0, 1] (got jump_weight = " + num(jump_weight) + ")");
  if (!(max_trim >= 0.0 && max_trim < 1.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "end_match: max_trim must lie in [0, 1) (got max_trim = " + num(max_trim) + ")");
}

namespace {

bool is_smooth(std::size_t m) noexcept {
  for (const std::size_t f : {2u, 3u, 5u})
    while (m % f == 0) m /= f;
  return m == 1;
}

struct Mismatch {
  double jump, slip, total;
};

// The variance from prefix sums of the centred series; exact enough to rank the segments, and the
// winner is recomputed directly.
Mismatch segment_mismatch(std::span<const double> x, std::size_t offset, std::size_t length, double variance,
                          double jump_weight) {
  const double first = x[offset], last = x[offset + length - 1];
  const double slope_first = x[offset + 1] - first, slope_last = last - x[offset + length - 2];
  const double scale = static_cast<double>(length) * variance;
  Mismatch m;
  m.jump = (first - last) * (first - last) / scale;
  m.slip = (slope_last - slope_first) * (slope_last - slope_first) / scale;
  m.total = jump_weight * m.jump + (1.0 - jump_weight) * m.slip;
  return m;
}

double direct_variance(std::span<const double> x) {
  double mean = 0.0;
  for (const double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double ss = 0.0;
  for (const double v : x) ss += (v - mean) * (v - mean);
  return ss / static_cast<double>(x.size());
}

}  // namespace

EndMatch end_match(std::span<const double> given, const EndMatchOptions& options) {
  options.validate();
  const std::string what = "end_match";
  require_length(given, 4, what, "the slip needs two samples at each end");
  require_finite(given, what);
  require_not_constant(given, what);
  // Squares of the centred values: on the series divided by a power of two where its magnitude
  // needs it (exact; every mismatch is a ratio, unchanged).
  const int exponent = detail::standardising_exponent(given);
  std::vector<double> scaled;
  if (exponent != 0) scaled = detail::scaled_by_power_of_two(given, exponent);
  const std::span<const double> x = exponent != 0 ? std::span<const double>(scaled) : given;
  const std::size_t n = x.size();
  const auto shortest = std::max<std::size_t>(
      4, static_cast<std::size_t>(std::ceil((1.0 - options.max_trim) * static_cast<double>(n) - 1e-9)));
  double mean = 0.0;
  for (const double v : x) mean += v;
  mean /= static_cast<double>(n);
  std::vector<double> s1(n + 1, 0.0), s2(n + 1, 0.0);
  for (std::size_t t = 0; t < n; ++t) {
    const double c = x[t] - mean;
    s1[t + 1] = s1[t] + c;
    s2[t + 1] = s2[t] + c * c;
  }
  EndMatch best;
  bool found = false;
  for (std::size_t length = n; length >= shortest; --length) {
    if (options.smooth_lengths && !is_smooth(length)) continue;
    const double l = static_cast<double>(length);
    for (std::size_t offset = 0; offset + length <= n; ++offset) {
      const double m1 = (s1[offset + length] - s1[offset]) / l;
      const double variance = (s2[offset + length] - s2[offset]) / l - m1 * m1;
      if (!(variance > 0.0)) continue;  // a constant segment has no spectrum to speak of
      const Mismatch m = segment_mismatch(x, offset, length, variance, options.jump_weight);
      // Strictly smaller only: ties keep the longer segment (visited first), then the smaller offset.
      if (!found || m.total < best.mismatch) {
        best = {offset, length, m.jump, m.slip, m.total, 0.0};
        found = true;
      }
    }
  }
  if (!found)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       what + ": no admissible segment length between " + std::to_string(shortest) + " and N = " +
                           std::to_string(n) + (options.smooth_lengths ? " of the form 2^a 3^b 5^c" : "") +
                           " with non-zero variance; raise max_trim = " + num(options.max_trim) +
                           (options.smooth_lengths ? " or set smooth_lengths = false" : ""));
  const auto segment = x.subspan(best.offset, best.length);
  const Mismatch exact = segment_mismatch(x, best.offset, best.length, direct_variance(segment), options.jump_weight);
  best.jump = exact.jump;
  best.slip = exact.slip;
  best.mismatch = exact.total;
  best.whole_series_mismatch = segment_mismatch(x, 0, n, direct_variance(x), options.jump_weight).total;
  return best;
}

}  // namespace chaos
