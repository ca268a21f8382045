#pragma once
// A rank-order surrogate test for nonlinearity (Theiler, Eubank, Longtin, Galdrikian & Farmer 1992,
// Physica D 58:77; Schreiber & Schmitz 2000, Physica D 142:346). Null hypothesis: the data are a
// linear Gaussian process observed through a static monotone function. K surrogates realising the
// null (IAAFT by default, surrogates.hpp) are made; a discriminating statistic is computed on the
// data and on each surrogate; the null is rejected when the data's value is more extreme than every
// surrogate's. One-sided, the probability of that under the null is 1/(K + 1); two-sided, 2/(K + 1).
// So K = 19 gives a one-sided test at 5%, K = 39 a two-sided test at 5%.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "chaos/norm.hpp"
#include "chaos/surrogates.hpp"

namespace chaos {

enum class NonlinearityStatistic {
  // Q(tau) = <(x_{t+tau} - x_t)^3> / <(x_{t+tau} - x_t)^2>^{3/2}, averages over t = 0 .. N - tau - 1:
  // the skewness of the increments (Schreiber & Schmitz 2000; TISEAN `timerev` prints the ratio of
  // the plain sums, which has the units of x). Zero in expectation for any time-reversible process,
  // which every linear Gaussian process (and a static transform of one) is.
  time_reversal_asymmetry,
  // In-sample zeroth-order prediction (locally constant predictor, Farmer & Sidorowich 1987;
  // TISEAN `zeroth`): in a delay embedding, the future `horizon` steps ahead of each point is
  // predicted as the mean future of its k nearest neighbours (Theiler window excluded); the
  // statistic is the RMS prediction error divided by the standard deviation of the series.
  prediction_error,
};

enum class Alternative {
  two_sided,  // reject if the data's value is below or above every surrogate's: alpha = 2/(K+1)
  smaller,    // reject if below every surrogate's (prediction error: the data are more predictable)
  larger,     // reject if above every surrogate's
};

const char* to_string(NonlinearityStatistic statistic) noexcept;
const char* to_string(Alternative alternative) noexcept;

struct PredictionErrorOptions {
  std::size_t dimension = 3;   // embedding dimension m
  std::size_t delay = 1;       // tau, samples
  std::size_t horizon = 1;     // prediction steps ahead, samples
  std::size_t neighbours = 5;  // k
  std::size_t theiler = 0;     // neighbours j of i need |i - j| > theiler (j = i always excluded)
  Norm norm = Norm::max;
  void validate() const;
};

// RMS error of the locally constant predictor divided by the standard deviation of x (population,
// 1/N). Point i (i = 0 .. P - 1, P = N - (m - 1) tau - horizon) is (x_i, x_{i+tau}, ...,
// x_{i+(m-1)tau}), its future x_{i+(m-1)tau+horizon}; neighbours are searched among the same P
// points, nearest first, ties in distance broken by the smaller index. Needs P > 2 theiler + k + 1
// so every point has k admissible neighbours.
double prediction_error(std::span<const double> x, const PredictionErrorOptions& options = {});

// Q(tau) as defined above; 0 when every difference x_{t+tau} - x_t is zero (a series that repeats
// itself after tau samples is symmetric at that lag). Needs N > tau.
double time_reversal_asymmetry(std::span<const double> x, std::size_t delay = 1);

struct NonlinearityTestOptions {
  NonlinearityStatistic statistic = NonlinearityStatistic::prediction_error;
  Alternative alternative = Alternative::two_sided;
  std::size_t surrogates = 39;  // K: two-sided 5% (39), one-sided 5% (19)
  std::uint64_t seed = 1;       // surrogate k uses the k-th draw of chaos::Random(seed) (surrogates.hpp)
  SurrogateOptions surrogate;   // method (IAAFT by default) and its iteration limits
  std::size_t time_reversal_delay = 1;
  PredictionErrorOptions prediction;
  // Called with the fraction of surrogates done, for a progress display; the test does not depend on it.
  std::function<void(double)> progress = nullptr;
  void validate() const;
};

// Ties. A surrogate's statistic s ties with the data's d when
//   |s - d| <= max(rank_tie_relative * max(|s|, |d|), rank_tie_absolute).
// Both statistics are dimensionless (an error over a standard deviation, a skewness) and are
// computed in double precision, the surrogates through FFTs, whose rounding is about 1e-13
// relative: the statistics of 4,999 ones followed by one 2 and of its surrogates agree to 13
// digits, and compared exactly the data's ranked beyond all 19 surrogates' on rounding alone.
// 1e-9 is 10^4 times that rounding and far below any difference the test is meant to detect; the
// absolute floor ties values that are zero up to rounding (an exactly symmetric series' Q); it
// assumes a statistic of order one, as both of these are, when rank_test ranks others.
inline constexpr double rank_tie_relative = 1e-9;
inline constexpr double rank_tie_absolute = 1e-12;

// The rank logic on its own, for statistics computed elsewhere.
struct RankTest {
  std::size_t rank = 0;      // 1 + number of surrogate values below the data's (1 = lowest)
  std::size_t below = 0;     // surrogate values below the data's, beyond a tie
  std::size_t above = 0;     // surrogate values above the data's, beyond a tie
  std::size_t ties = 0;      // surrogate values that tie with the data's (neither below nor above)
  double significance = 0.0; // the test's size: 1/(K+1) one-sided, 2/(K+1) two-sided
  bool rejected = false;     // the data's value is beyond every surrogate's on the tested side
};

// Conservative with ties: the data's value ranks at the least extreme end of its tie group, so a
// tie with any surrogate's value never lets it reject (with K surrogates all tied with the data,
// no alternative rejects).
RankTest rank_test(double data_statistic, std::span<const double> surrogate_statistics, Alternative alternative);

struct NonlinearityTestResult {
  double data_statistic = 0.0;
  std::vector<double> surrogate_statistics;  // in the order the surrogates were made
  RankTest test;
  // Diagnostics of the surrogates (IAAFT: how they converged).
  std::vector<std::size_t> surrogate_iterations;
  std::vector<double> surrogate_spectral_deviations;
  std::size_t surrogates_not_converged = 0;  // IAAFT surrogates stopped by max_iterations
  NonlinearityTestOptions options;           // the settings used
  // A sentence when most pairs of samples tie (quantised data; ties_note, series.hpp), else empty.
  std::string value_ties;
};

// Refuses what the surrogates refuse (N < 4, non-finite, constant) and series too short for the
// statistic.
NonlinearityTestResult nonlinearity_test(std::span<const double> x, const NonlinearityTestOptions& options = {});

// The test as the automatic pipelines run it (`chaos analyze`, `study sweep --surrogates`): on the
// first `length` samples, trimmed to their best end match (an end mismatch alone makes surrogates
// look rougher than the data, surrogates.hpp), K IAAFT surrogates, one-sided (deterministic data are
// more predictable than their surrogates: Alternative::smaller), the prediction error in the
// embedding (dimension, delay) with the Theiler window the pipeline chose.
struct EmbeddedNonlinearityTest {
  EndMatch segment;  // offset and length within the first `length` samples
  NonlinearityTestResult result;
};
EmbeddedNonlinearityTest embedded_nonlinearity_test(std::span<const double> x, std::size_t length,
                                                    std::size_t dimension, std::size_t delay, std::size_t theiler,
                                                    std::size_t surrogates, std::uint64_t seed,
                                                    std::function<void(double)> progress = nullptr);

}  // namespace chaos
