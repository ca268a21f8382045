#pragma once
// Surrogate data for the null hypothesis of a linear Gaussian process, possibly observed through a
// static monotone function (Theiler, Eubank, Longtin, Galdrikian & Farmer 1992, Physica D 58:77;
// Schreiber & Schmitz 1996, PRL 77:635; review: Schreiber & Schmitz 2000, Physica D 142:346).
//   fourier  phase randomisation: the periodogram |X_k|^2 is kept exactly (to rounding); the
//            values are not.
//   aaft     amplitude-adjusted FT (Theiler et al.): the values are kept exactly (a permutation of
//            the data); the spectrum only approximately.
//   iaaft    iterative AAFT (Schreiber & Schmitz): alternately impose the data's Fourier amplitudes
//            and, by rank ordering, its values, until the rank order stops changing; the values are
//            kept exactly, the spectrum to the reported deviation.
//
// The DFT is taken over the series as given, with no zero padding, so it treats the series as one
// period of a periodic signal: a jump between the last and the first value, or a mismatch of the
// slopes there, leaks power to high frequencies and surrogates then differ from the data for that
// reason alone (spurious rejections). TISEAN's advice, followed here: trim the series so that the
// first and last values and slopes match; `end_match` finds the sub-series with the best match,
// as TISEAN's `endtoend` does.
//
// Output is bit-reproducible for a given seed with the same build (FFTW plans are made with
// FFTW_ESTIMATE, which chooses the same algorithm every time; the random phases use only
// correctly rounded arithmetic).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace chaos {

enum class SurrogateMethod { fourier, aaft, iaaft };

const char* to_string(SurrogateMethod method) noexcept;
// What the method's surrogates realise, in words: the process a rejection says the data are not
// (Theiler et al. 1992; Schreiber & Schmitz 1996 for the amplitude-adjusted ones).
const char* null_hypothesis(SurrogateMethod method) noexcept;

struct SurrogateOptions {
  SurrogateMethod method = SurrogateMethod::iaaft;
  // IAAFT only. Iterations stop at the first of: the rank order did not change (a fixed point,
  // further iterations would repeat it), the spectral deviation is <= `tolerance` (0 disables this
  // test), or `max_iterations` rounds.
  std::size_t max_iterations = 1000;
  double tolerance = 0.0;
  // IAAFT only: called after each iteration with iterations / max_iterations, for a progress
  // display; the surrogate does not depend on it.
  std::function<void(double)> progress = nullptr;
  void validate() const;
};

enum class SurrogateStatus {
  exact,           // fourier and aaft: not iterative
  fixed_point,     // iaaft: the rank order stopped changing
  tolerance,       // iaaft: the spectral deviation reached the tolerance
  max_iterations,  // iaaft: stopped by the iteration limit
};

const char* to_string(SurrogateStatus status) noexcept;

struct Surrogate {
  std::vector<double> values;
  SurrogateStatus status = SurrogateStatus::exact;
  std::size_t iterations = 0;  // iaaft: rounds of amplitude adjustment + rank ordering
  // sqrt( sum_k (|S_k| - |X_k|)^2 / sum_k |X_k|^2 ) over every frequency k = 1 .. N - 1 of the full
  // DFT (k = 0, the mean, left out so an offset does not dilute it): the relative RMS deviation of
  // the surrogate's Fourier amplitudes from the data's.
  double spectral_deviation = 0.0;
};

// Made once for a series: the data's Fourier amplitudes, its sorted values and the FFTW plans are
// computed in the constructor and reused by every surrogate. Not thread-safe (it owns work
// buffers): use one generator per thread.
class SurrogateGenerator {
 public:
  // Refuses fewer than 4 samples, non-finite values and a constant series (InvalidInput), and
  // more than 2^31 - 1 samples (FFTW's int sizes).
  explicit SurrogateGenerator(std::span<const double> x, const SurrogateOptions& options = {});
  ~SurrogateGenerator();
  SurrogateGenerator(SurrogateGenerator&&) noexcept;
  SurrogateGenerator& operator=(SurrogateGenerator&&) noexcept;

  // One surrogate from its own seed (chaos::Random): the same seed gives the same output.
  Surrogate generate(std::uint64_t seed);

  std::size_t size() const noexcept;
  const SurrogateOptions& options() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// `options` for the k-th of `count` surrogates made by one generator: its progress (when set) is
// options.progress of the fraction of all of them, (done + fraction) / count, with `done` read at
// each report (surrogates() and nonlinearity_test() count with it).
SurrogateOptions with_progress_over(const SurrogateOptions& options, const std::size_t& done, std::size_t count);

// A rank test with K surrogates resolves p down to 1/(K+1): beyond 10^4 more surrogates add
// nothing but time, and each holds a copy of the series. Larger counts are refused.
inline constexpr std::size_t max_surrogates = 10000;

// `count` surrogates (at most max_surrogates); surrogate k uses the k-th draw of chaos::Random(seed).next() as its seed,
// so it does not depend on how many others are made.
std::vector<Surrogate> surrogates(std::span<const double> x, std::size_t count, std::uint64_t seed,
                                  const SurrogateOptions& options = {});

// The relative RMS deviation of y's Fourier amplitudes from x's, as defined for
// Surrogate::spectral_deviation; x and y must have the same length. For tests and diagnostics.
double spectral_deviation(std::span<const double> x, std::span<const double> y);

// End-to-end mismatch of a segment x[offset .. offset + length) (TISEAN `endtoend`, Schreiber 1999):
//   jump = (x_first - x_last)^2 / (length * variance),
//   slip = ((x_last - x_{last-1}) - (x_{first+1} - x_first))^2 / (length * variance),
//   mismatch = jump_weight * jump + (1 - jump_weight) * slip,
// with the variance of the segment.
struct EndMatchOptions {
  double jump_weight = 0.5;        // TISEAN -j
  double max_trim = 0.1;           // at most this fraction of the series may be cut off
  bool smooth_lengths = true;      // only lengths 2^a 3^b 5^c, which FFTW transforms fastest
  void validate() const;
};

struct EndMatch {
  std::size_t offset = 0;
  std::size_t length = 0;
  double jump = 0.0;
  double slip = 0.0;
  double mismatch = 0.0;
  double whole_series_mismatch = 0.0;  // the same measure for the untrimmed series
};

// The segment with the smallest mismatch among the admissible lengths (>= (1 - max_trim) N) and
// every offset; ties go to the longer segment, then to the smaller offset. Refuses N < 4,
// non-finite and constant input.
EndMatch end_match(std::span<const double> x, const EndMatchOptions& options = {});

}  // namespace chaos
