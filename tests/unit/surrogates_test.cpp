// Surrogate data: what each method must keep (FT: the periodogram, exactly; AAFT and IAAFT: the
// values, exactly; IAAFT: the spectrum to its reported deviation), seeded reproducibility, the
// end-to-end mismatch of TISEAN's `endtoend` on hand-worked and brute-force cases, and refusals.
#include "chaos/surrogates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::SurrogateMethod;
using chaos::SurrogateOptions;
using chaos::SurrogateStatus;

// Periodogram |X_k|^2, k = 0 .. N - 1, by the O(N^2) definition in long double: independent of
// FFTW and of the library.
std::vector<long double> periodogram(const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::vector<long double> c(n), s(n);  // e^{-2 pi i m / N}, m = k t mod N
  for (std::size_t m = 0; m < n; ++m) {
    const long double a =
        -2.0L * std::numbers::pi_v<long double> * static_cast<long double>(m) / static_cast<long double>(n);
    c[m] = std::cos(a);
    s[m] = std::sin(a);
  }
  std::vector<long double> p(n);
  for (std::size_t k = 0; k < n; ++k) {
    long double re = 0.0L, im = 0.0L;
    for (std::size_t t = 0, m = 0; t < n; ++t, m = (m + k) % n) {
      re += x[t] * c[m];
      im += x[t] * s[m];
    }
    p[k] = re * re + im * im;
  }
  return p;
}

std::vector<double> sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v;
}

std::vector<double> lorenz_x(std::size_t n) { return chaos::lorenz(n, {}, {0.05, 0.005, 100.0}).components[0]; }

TEST(Surrogates, FourierKeepsThePeriodogramExactly) {
  // Phase randomisation multiplies X_k by |e^{i phi}| = 1 (Theiler et al. 1992): the periodogram is
  // unchanged up to rounding, 1e-9 relative to the largest bin (issue), for even and odd N. The
  // mean (k = 0) and, for even N, the Nyquist bin keep their phase, so they are kept exactly.
  for (const std::size_t n : {512u, 501u}) {
    const auto x = lorenz_x(n);
    const auto p = periodogram(x);
    const long double peak = *std::max_element(p.begin() + 1, p.end());
    chaos::SurrogateGenerator generator(x, {SurrogateMethod::fourier});
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const auto s = generator.generate(seed);
      ASSERT_EQ(s.values.size(), n);
      EXPECT_EQ(s.status, SurrogateStatus::exact);
      EXPECT_EQ(s.iterations, 0u);
      const auto q = periodogram(s.values);
      for (std::size_t k = 0; k < n; ++k)
        ASSERT_LE(std::abs(q[k] - p[k]), 1e-9L * std::max(p[k], peak)) << "n " << n << " k " << k;
      // X_0 = sum of the values: the means agree to rounding.
      double mean_x = 0.0, mean_s = 0.0;
      for (std::size_t t = 0; t < n; ++t) {
        mean_x += x[t];
        mean_s += s.values[t];
      }
      EXPECT_NEAR(mean_s, mean_x, 1e-9 * std::abs(mean_x) + 1e-9);
      EXPECT_LT(s.spectral_deviation, 1e-12);
      // The phases did change: the surrogate is not the data.
      double diff = 0.0;
      for (std::size_t t = 0; t < n; ++t) diff = std::max(diff, std::abs(s.values[t] - x[t]));
      EXPECT_GT(diff, 1.0);
    }
  }
}

TEST(Surrogates, FourierOfACosineIsACosineWithARandomPhase) {
  // x_t = cos(2 pi 5 t / N): only bins 5 and N - 5 are non-zero, so every FT surrogate is
  // cos(2 pi 5 t / N + phi) for some phi (analytic); its amplitude stays 1 and its mean 0.
  const std::size_t n = 64;
  std::vector<double> x(n);
  for (std::size_t t = 0; t < n; ++t) x[t] = std::cos(2.0 * std::numbers::pi * 5.0 * static_cast<double>(t) / 64.0);
  const auto s = chaos::surrogates(x, 1, 9, {SurrogateMethod::fourier})[0];
  const double phi = std::atan2(-s.values[16], s.values[0]);  // t = 16: angle 2 pi 5 16/64 = 5 pi/2
  for (std::size_t t = 0; t < n; ++t)
    EXPECT_NEAR(s.values[t], std::cos(2.0 * std::numbers::pi * 5.0 * static_cast<double>(t) / 64.0 + phi), 1e-12)
        << t;
}

TEST(Surrogates, AaftAndIaaftKeepTheValuesExactly) {
  // Both end by giving the data's own values a new rank order (Theiler et al. 1992; Schreiber &
  // Schmitz 1996): the sorted surrogate equals the sorted data bit for bit, ties included.
  auto x = lorenz_x(1000);
  for (std::size_t t = 0; t < x.size(); t += 7) x[t] = 3.0;  // ties
  const auto reference = sorted(x);
  for (const auto method : {SurrogateMethod::aaft, SurrogateMethod::iaaft}) {
    chaos::SurrogateGenerator generator(x, {method});
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const auto s = generator.generate(seed);
      EXPECT_EQ(sorted(s.values), reference) << chaos::to_string(method) << " seed " << seed;
      EXPECT_NE(s.values, x);
    }
  }
}

TEST(Surrogates, IaaftReportsTheDeviationOfWhatItReturns) {
  // The reported deviation is that of the returned series, recomputed here through the public
  // spectral_deviation (same definition). IAAFT must improve on AAFT's spectrum (Schreiber &
  // Schmitz 1996 report an order of magnitude or more); on Lorenz x it stops at a fixed point of
  // the rank order well within 1000 iterations.
  const auto x = lorenz_x(2048);
  const auto aaft = chaos::surrogates(x, 1, 5, {SurrogateMethod::aaft})[0];
  const auto iaaft = chaos::surrogates(x, 1, 5, {SurrogateMethod::iaaft})[0];
  EXPECT_NEAR(aaft.spectral_deviation, chaos::spectral_deviation(x, aaft.values), 1e-12);
  EXPECT_NEAR(iaaft.spectral_deviation, chaos::spectral_deviation(x, iaaft.values), 1e-12);
  EXPECT_EQ(iaaft.status, SurrogateStatus::fixed_point);
  EXPECT_GT(iaaft.iterations, 1u);
  EXPECT_LT(iaaft.iterations, 1000u);
  EXPECT_LT(iaaft.spectral_deviation, 0.1 * aaft.spectral_deviation);
  EXPECT_LT(iaaft.spectral_deviation, 0.01);
}

TEST(Surrogates, IaaftStopsAtItsTolerance) {
  // With a tolerance the iteration stops as soon as the deviation of the current series is within
  // it: the returned series keeps the spectrum within the tolerance, and one iteration fewer would
  // not have (the deviation before the last rank ordering was above it).
  const auto x = lorenz_x(2048);
  SurrogateOptions o;
  o.tolerance = 0.02;
  const auto s = chaos::surrogates(x, 1, 5, o)[0];
  EXPECT_EQ(s.status, SurrogateStatus::tolerance);
  EXPECT_LE(s.spectral_deviation, 0.02);
  EXPECT_NEAR(s.spectral_deviation, chaos::spectral_deviation(x, s.values), 1e-12);
  ASSERT_GE(s.iterations, 1u);
  SurrogateOptions fewer;
  fewer.max_iterations = s.iterations - 1;
  if (fewer.max_iterations >= 1) {
    const auto t = chaos::surrogates(x, 1, 5, fewer)[0];
    EXPECT_EQ(t.status, SurrogateStatus::max_iterations);
    EXPECT_GT(t.spectral_deviation, 0.02);
  }
}

TEST(Surrogates, IaaftStopsAtItsIterationLimit) {
  const auto x = lorenz_x(2048);
  SurrogateOptions o;
  o.max_iterations = 3;
  const auto s = chaos::surrogates(x, 1, 5, o)[0];
  EXPECT_EQ(s.status, SurrogateStatus::max_iterations);
  EXPECT_EQ(s.iterations, 3u);
  EXPECT_NEAR(s.spectral_deviation, chaos::spectral_deviation(x, s.values), 1e-12);
  EXPECT_EQ(sorted(s.values), sorted(x));
}

TEST(Surrogates, SameSeedSameOutputOtherSeedOtherOutput) {
  const auto x = lorenz_x(1000);
  for (const auto method : {SurrogateMethod::fourier, SurrogateMethod::aaft, SurrogateMethod::iaaft}) {
    chaos::SurrogateGenerator generator(x, {method});
    const auto a = generator.generate(11);
    const auto b = generator.generate(12);
    const auto c = generator.generate(11);  // the generator keeps no state between surrogates
    chaos::SurrogateGenerator fresh(x, {method});
    const auto d = fresh.generate(11);
    EXPECT_EQ(a.values, c.values) << chaos::to_string(method);
    EXPECT_EQ(a.values, d.values) << chaos::to_string(method);
    EXPECT_EQ(a.iterations, d.iterations);
    EXPECT_EQ(a.spectral_deviation, d.spectral_deviation);
    EXPECT_NE(a.values, b.values) << chaos::to_string(method);
  }
}

TEST(Surrogates, BatchSeedsDoNotDependOnTheCount) {
  // Surrogate k of surrogates(x, K, seed) is generate(k-th draw of Random(seed)) (surrogates.hpp).
  const auto x = lorenz_x(512);
  const auto five = chaos::surrogates(x, 5, 77);
  const auto eight = chaos::surrogates(x, 8, 77);
  chaos::Random seeds(77);
  chaos::SurrogateGenerator generator(x);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(five[k].values, eight[k].values) << k;
    EXPECT_EQ(five[k].values, generator.generate(seeds.next()).values) << k;
  }
}

TEST(Surrogates, SpectralDeviationIsZeroForShiftsAndReversal) {
  // A circular shift multiplies X_k by e^{-2 pi i k s / N} and time reversal conjugates it: |X_k|
  // is unchanged (analytic), so the deviation is 0 up to rounding.
  const auto x = lorenz_x(300);
  std::vector<double> shifted(x.size()), reversed(x.rbegin(), x.rend());
  for (std::size_t t = 0; t < x.size(); ++t) shifted[t] = x[(t + 37) % x.size()];
  EXPECT_LT(chaos::spectral_deviation(x, shifted), 1e-13);
  EXPECT_LT(chaos::spectral_deviation(x, reversed), 1e-13);
  EXPECT_EQ(chaos::spectral_deviation(x, x), 0.0);
  // A shuffled series has a flat expected spectrum: far from Lorenz's red one.
  std::vector<double> shuffled = x;
  chaos::Random rng(3);
  for (std::size_t i = shuffled.size() - 1; i > 0; --i) std::swap(shuffled[i], shuffled[rng.below(i + 1)]);
  EXPECT_GT(chaos::spectral_deviation(x, shuffled), 0.5);
}

TEST(EndMatch, HandWorkedSeries) {
  // x = (0, 1, 3, 1, 0.5): mean 1.1, sum of squared deviations N var = 5.2;
  // jump = (0 - 0.5)^2 / 5.2, slip = ((0.5 - 1) - (1 - 0))^2 / 5.2; mismatch = (jump + slip) / 2.
  const std::vector<double> x = {0.0, 1.0, 3.0, 1.0, 0.5};
  chaos::EndMatchOptions o;
  o.max_trim = 0.0;
  o.smooth_lengths = true;  // 5 is 5^1
  const auto m = chaos::end_match(x, o);
  EXPECT_EQ(m.offset, 0u);
  EXPECT_EQ(m.length, 5u);
  EXPECT_NEAR(m.jump, 0.25 / 5.2, 1e-15);
  EXPECT_NEAR(m.slip, 2.25 / 5.2, 1e-15);
  EXPECT_NEAR(m.mismatch, 0.5 * (0.25 + 2.25) / 5.2, 1e-15);
  EXPECT_DOUBLE_EQ(m.whole_series_mismatch, m.mismatch);
}

TEST(EndMatch, EqualsBruteForce) {
  // Every admissible (offset, length) evaluated directly with a two-pass variance; the library's
  // prefix-sum search must find the same segment and the same numbers.
  for (const bool smooth : {true, false}) {
    const auto x = lorenz_x(700);
    chaos::EndMatchOptions o;
    o.max_trim = 0.2;
    o.smooth_lengths = smooth;
    const auto m = chaos::end_match(x, o);
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_offset = 0, best_length = 0;
    for (std::size_t length = 700; length >= 560; --length) {
      std::size_t r = length;
      for (const std::size_t f : {2u, 3u, 5u})
        while (r % f == 0) r /= f;
      if (smooth && r != 1) continue;
      for (std::size_t offset = 0; offset + length <= 700; ++offset) {
        double mean = 0.0, ss = 0.0;
        for (std::size_t t = offset; t < offset + length; ++t) mean += x[t];
        mean /= static_cast<double>(length);
        for (std::size_t t = offset; t < offset + length; ++t) ss += (x[t] - mean) * (x[t] - mean);
        const double a = x[offset], b = x[offset + length - 1];
        const double slip = (b - x[offset + length - 2]) - (x[offset + 1] - a);
        const double value = 0.5 * ((a - b) * (a - b) + slip * slip) / ss;
        if (value < best) {
          best = value;
          best_offset = offset;
          best_length = length;
        }
      }
    }
    EXPECT_EQ(m.offset, best_offset) << smooth;
    EXPECT_EQ(m.length, best_length) << smooth;
    EXPECT_NEAR(m.mismatch, best, 1e-12 * best + 1e-15) << smooth;
    EXPECT_LE(m.mismatch, m.whole_series_mismatch);
  }
}

TEST(EndMatch, FindsSegmentsThatCloseOnThemselves) {
  // A sine of period 50 samples over 1013 samples. The mismatch vanishes (analytic) for segments
  // whose ends agree in value and slope: length 50 j + 1 starting at a zero crossing (first and
  // last sample one period apart, second difference zero there), or length 50 j + 2 centred on a
  // crest or trough (the ends mirror each other). Such lengths are not 2^a 3^b 5^c, so every
  // length is admitted; which of the exact solutions wins is decided by rounding, so the test checks
  // the defining property. The whole series ends near a crest: its mismatch is of order 1/N.
  std::vector<double> x(1013);
  for (std::size_t t = 0; t < x.size(); ++t) x[t] = std::sin(2.0 * std::numbers::pi * static_cast<double>(t) / 50.0);
  chaos::EndMatchOptions o;
  o.smooth_lengths = false;
  const auto m = chaos::end_match(x, o);
  const std::size_t first = m.offset, last = m.offset + m.length - 1;
  EXPECT_NEAR(x[first], x[last], 1e-12);
  EXPECT_NEAR(x[last] - x[last - 1], x[first + 1] - x[first], 1e-12);
  EXPECT_TRUE(m.length % 50 == 1 || m.length % 50 == 2) << m.length;
  EXPECT_LT(m.mismatch, 1e-20);
  EXPECT_GT(m.whole_series_mismatch, 1e-4);
}

template <class F>
void expect_refusal(const F& f, chaos::ErrorCode code, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning '" << fragment << "'";
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Surrogates, RefusesBadInputAndOptions) {
  using chaos::ErrorCode;
  const std::vector<double> constant(100, 2.5);
  expect_refusal([&] { chaos::SurrogateGenerator g(constant); }, ErrorCode::constant, "the series is constant");
  const std::vector<double> short_series = {1.0, 2.0, 3.0};
  expect_refusal([&] { chaos::SurrogateGenerator g(short_series); }, ErrorCode::too_short, "N = 3 samples");
  auto x = lorenz_x(100);
  x[17] = std::nan("");
  expect_refusal([&] { chaos::SurrogateGenerator g(x); }, ErrorCode::non_finite, "sample 17 is nan");
  x[17] = std::numeric_limits<double>::infinity();
  expect_refusal([&] { chaos::surrogates(x, 3, 1); }, ErrorCode::non_finite, "sample 17 is inf");
  // 1e149 among values of order 10: the Fourier coefficients reach N 1e149, whose squares were
  // refused as beyond double; the transforms now see the series divided by a power of two, and the
  // IAAFT surrogate is still a permutation of the data, with a finite spectral deviation.
  x[17] = 1e149;
  {
    const chaos::Surrogate big = chaos::surrogates(x, 1, 1).front();
    std::vector<double> a(x), b(big.values);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);
    EXPECT_TRUE(std::isfinite(big.spectral_deviation));
  }
  const auto y = lorenz_x(100);
  SurrogateOptions o;
  o.max_iterations = 0;
  expect_refusal([&] { chaos::SurrogateGenerator g(y, o); }, ErrorCode::invalid_parameter,
                 "max_iterations must be at least 1 (got 0)");
  o = {};
  o.tolerance = -0.1;
  expect_refusal([&] { chaos::SurrogateGenerator g(y, o); }, ErrorCode::invalid_parameter,
                 "tolerance must be finite and >= 0 (got tolerance = -0.1)");
  o = {};
  o.tolerance = std::nan("");
  expect_refusal([&] { chaos::SurrogateGenerator g(y, o); }, ErrorCode::invalid_parameter, "tolerance must be");
  expect_refusal([&] { chaos::spectral_deviation(y, std::vector<double>(99, 1.0)); }, ErrorCode::invalid_parameter,
                 "different lengths (100 and 99)");
  chaos::EndMatchOptions e;
  e.jump_weight = 1.5;
  expect_refusal([&] { chaos::end_match(y, e); }, ErrorCode::invalid_parameter, "jump_weight must lie in [0, 1]");
  e = {};
  e.max_trim = 1.0;
  expect_refusal([&] { chaos::end_match(y, e); }, ErrorCode::invalid_parameter, "max_trim must lie in [0, 1)");
  e = {};
  e.max_trim = 0.0;
  const auto z = lorenz_x(101);  // 101 is prime: no smooth length in [101, 101]
  expect_refusal([&] { chaos::end_match(z, e); }, ErrorCode::invalid_parameter, "no admissible segment length");
  expect_refusal([&] { chaos::end_match(constant); }, ErrorCode::constant, "constant");
}

}  // namespace
