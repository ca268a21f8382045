// Control signals: spectral slopes of power-law noise against a band derived from the periodogram's
// distribution, exact repetition and distinct-value counts of rational periods (analytic), the
// torus constants, realised SNR against its sampling error, quantiser level counts, determinism
// and parameter validation.
#include "chaos/models/control_signals.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/random.hpp"

namespace {

using chaos::ErrorCode;
using chaos::RationalPeriod;

// Expects InvalidInput with `code` and every fragment in the message.
template <class F>
void expect_refused(F&& f, ErrorCode code, const std::vector<std::string>& fragments) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning " << fragments.front();
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    const std::string message = e.what();
    for (const auto& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << message;
  }
}

template <class F>
void expect_invalid(F&& f, const std::vector<std::string>& fragments) {
  expect_refused(std::forward<F>(f), ErrorCode::invalid_parameter, fragments);
}

const std::vector<double>& x_of(const chaos::Trajectory& t) { return t.components.front(); }

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v) s += x;
  return s / static_cast<double>(v.size());
}

// Population standard deviation (divided by N), the convention of add_noise.
double stdev(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0.0;
  for (const double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size()));
}

std::size_t distinct(const std::vector<double>& v) { return std::set<double>(v.begin(), v.end()).size(); }

std::size_t distinct_pairs(const std::vector<double>& v) {
  std::set<std::pair<double, double>> s;
  for (std::size_t i = 0; i + 1 < v.size(); ++i) s.insert({v[i], v[i + 1]});
  return s.size();
}

// Radix-2 Cooley-Tukey FFT written here, independent of the library's FFTW path.
void fft(std::vector<std::complex<double>>& a) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double angle = -2.0 * std::numbers::pi / static_cast<double>(len);
    for (std::size_t i = 0; i < n; i += len)
      for (std::size_t k = 0; k < len / 2; ++k) {
        const std::complex<double> w = std::polar(1.0, angle * static_cast<double>(k));
        const auto u = a[i + k], v = a[i + k + len / 2] * w;
        a[i + k] = u + v;
        a[i + k + len / 2] = u - v;
      }
  }
}

// OLS slope of ln I_k against ln f_k over k = 1 .. n/2 - 1 (the Nyquist bin, chi-square with one
// degree of freedom, left out), and its standard error under ln I_k = c - alpha ln f_k + ln E_k with
// E_k i.i.d. Exp(1): Var ln E = pi^2 / 6 (the trigamma function at 1), so
// SE = sqrt((pi^2 / 6) / sum_k (ln f_k - mean)^2).
std::pair<double, double> periodogram_slope(const std::vector<double>& x) {
  std::vector<std::complex<double>> a(x.begin(), x.end());
  fft(a);
  const std::size_t n = x.size();
  std::vector<double> lf, li;
  for (std::size_t k = 1; 2 * k < n; ++k) {
    lf.push_back(std::log(static_cast<double>(k) / static_cast<double>(n)));
    li.push_back(std::log(std::norm(a[k])));
  }
  const double mf = mean(lf), mi = mean(li);
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < lf.size(); ++i) {
    sxy += (lf[i] - mf) * (li[i] - mi);
    sxx += (lf[i] - mf) * (lf[i] - mf);
  }
  return {sxy / sxx, std::sqrt(std::numbers::pi * std::numbers::pi / 6.0 / sxx)};
}

// ---- Power-law noise ---------------------------------------------------------------------------

TEST(ControlSignals, PowerLawNoiseHasPeriodogramSlopeMinusAlphaWithinFiveStandardErrors) {
  // Timmer & König (1995) shaping without cutting gives a periodogram exactly C f^-alpha E_k at the
  // Fourier frequencies (E_k i.i.d. Exp(1), see the header), so the fitted slope is unbiased with
  // the standard error above: about sqrt(1.645 / 8191) = 0.014 for n = 2^14. Band: 5 SE (a
  // two-sided normal tail of 6e-7 per fit; the seeds are fixed, so the test is deterministic).
  const std::size_t n = std::size_t{1} << 14;
  for (const double alpha : {0.0, 1.0, 2.0}) {
    for (const std::uint64_t seed : {1u, 2u}) {
      const auto x = x_of(chaos::power_law_noise(n, alpha, seed));
      ASSERT_EQ(x.size(), n);
      const auto [slope, se] = periodogram_slope(x);
      EXPECT_LT(se, 0.015);
      EXPECT_NEAR(slope, -alpha, 5.0 * se) << "alpha " << alpha << " seed " << seed;
    }
  }
  // alpha = 1.5 too: any alpha >= 0.
  const auto [slope, se] = periodogram_slope(x_of(chaos::power_law_noise(n, 1.5, 7)));
  EXPECT_NEAR(slope, -1.5, 5.0 * se);
}

TEST(ControlSignals, PowerLawNoiseIsNormalisedAndReproducible) {
  // Documented: sample mean 0 and sample variance 1 (divided by n), to rounding; odd and even n.
  for (const std::size_t n : {2u, 3u, 1000u, 1001u}) {
    const auto t = chaos::power_law_noise(n, 1.0, 3);
    EXPECT_EQ(t.names, std::vector<std::string>{"x"});
    EXPECT_EQ(t.dt, 1.0);
    const auto& x = x_of(t);
    EXPECT_NEAR(mean(x), 0.0, 1e-12) << n;
    EXPECT_NEAR(stdev(x), 1.0, 1e-12) << n;
  }
  // n = 2 has only the Nyquist bin, so the series is +-(1, -1).
  const auto two = x_of(chaos::power_law_noise(2, 2.0, 5));
  EXPECT_NEAR(std::abs(two[0]), 1.0, 1e-15);
  EXPECT_NEAR(two[0] + two[1], 0.0, 1e-15);
  EXPECT_EQ(x_of(chaos::power_law_noise(4096, 2.0, 11)), x_of(chaos::power_law_noise(4096, 2.0, 11)));
  EXPECT_NE(x_of(chaos::power_law_noise(4096, 2.0, 11)), x_of(chaos::power_law_noise(4096, 2.0, 12)));
}

TEST(ControlSignals, RedNoiseIsStronglyCorrelatedAndWhiteNoiseIsNot) {
  // A property of the spectra: the lag-1 autocorrelation of white noise is O(1/sqrt(n)) = 0.016
  // for n = 4096, that of 1/f^2 noise close to 1 (its variance sits at the lowest frequencies).
  const auto lag1 = [](const std::vector<double>& x) {
    double s = 0.0;
    for (std::size_t t = 1; t < x.size(); ++t) s += x[t] * x[t - 1];
    return s / static_cast<double>(x.size());  // mean 0 and variance 1 by construction
  };
  EXPECT_LT(std::abs(lag1(x_of(chaos::power_law_noise(4096, 0.0, 1)))), 5.0 / 64.0);
  EXPECT_GT(lag1(x_of(chaos::power_law_noise(4096, 2.0, 1))), 0.95);
}

TEST(ControlSignals, PowerLawNoiseRefusesImpossibleParameters) {
  expect_invalid([] { chaos::power_law_noise(100, -0.5); }, {"power_law_noise", "alpha must be finite and >= 0",
                                                             "alpha = -0.5"});
  expect_invalid([] { chaos::power_law_noise(100, std::nan("")); }, {"alpha", "nan"});
  expect_invalid([] { chaos::power_law_noise(100, INFINITY); }, {"alpha", "inf"});
  expect_invalid([] { chaos::power_law_noise(1, 1.0); }, {"power_law_noise", "at least 2", "n = 1"});
  expect_invalid([] { chaos::power_law_noise(0, 1.0); }, {"n = 0"});
}

// ---- Random walk -------------------------------------------------------------------------------

TEST(ControlSignals, RandomWalkIsTheCumulativeSumOfTheSeededGaussianStream) {
  // Documented: x_0 = 0 and x_t = x_{t-1} + e_t with e_t the t-th draw of Random(seed).gaussian().
  const auto x = x_of(chaos::random_walk(10'000, 9));
  chaos::Random rng(9);
  double expected = 0.0;
  ASSERT_EQ(x[0], 0.0);
  for (std::size_t t = 1; t < x.size(); ++t) {
    expected += rng.gaussian();
    ASSERT_EQ(x[t], expected) << t;
  }
  // Unit-variance steps: the sample variance of 9999 N(0, 1) draws is within 5 SE = 5 sqrt(2/9999).
  std::vector<double> steps;
  for (std::size_t t = 1; t < x.size(); ++t) steps.push_back(x[t] - x[t - 1]);
  EXPECT_NEAR(stdev(steps) * stdev(steps), 1.0, 5.0 * std::sqrt(2.0 / 9999.0));
  EXPECT_EQ(x_of(chaos::random_walk(1, 4)), std::vector<double>{0.0});
  expect_invalid([] { chaos::random_walk(0); }, {"random_walk", "n = 0"});
}

// ---- Periodic ----------------------------------------------------------------------------------

TEST(ControlSignals, RationalPeriodMatchesTheFormula) {
  // Analytic: sin(2 pi n / 4) = 0, 1, 0, -1, exactly with the integer quadrant reduction.
  EXPECT_EQ(x_of(chaos::periodic(8, RationalPeriod{4, 1})), (std::vector<double>{0, 1, 0, -1, 0, 1, 0, -1}));
  // Any P = p/q: x_n = sum_h a_h sin(2 pi h n q / p), to rounding.
  const std::vector<double> a = {1.0, 0.5, -0.25};
  const auto x = x_of(chaos::periodic(1000, RationalPeriod{317, 3}, a));
  for (std::size_t n = 0; n < x.size(); ++n) {
    double expected = 0.0;
    for (std::size_t h = 1; h <= a.size(); ++h)
      expected += a[h - 1] * std::sin(2.0 * std::numbers::pi * static_cast<double>(h * n * 3 % 317) / 317.0);
    ASSERT_NEAR(x[n], expected, 1e-13) << n;
  }
}

TEST(ControlSignals, RationalPeriodRepeatsExactlyWithPDistinctPhases) {
  // P = 317/3 = 105.67 samples: n -> 3n mod 317 runs through all 317 residues, so the series
  // repeats bit for bit after exactly p = 317 samples and never sooner.
  const auto x = x_of(chaos::periodic(2000, RationalPeriod{317, 3}));
  for (std::size_t n = 0; n + 317 < x.size(); ++n) ASSERT_EQ(x[n + 317], x[n]) << n;
  for (std::size_t d = 1; d < 317; ++d) {
    bool same = true;
    for (std::size_t n = 0; n + d < x.size() && same; ++n) same = x[n + d] == x[n];
    EXPECT_FALSE(same) << "shorter period " << d;
  }
  // Distinct values (header): p for odd p; distinct delay vectors: p.
  EXPECT_EQ(distinct(x), 317u);
  EXPECT_EQ(distinct_pairs(x), 317u);
  // {634, 6} is reduced by gcd 2 to the same period.
  EXPECT_EQ(x_of(chaos::periodic(2000, RationalPeriod{634, 6})), x);
}

TEST(ControlSignals, DistinctValueCountsFollowTheSymmetryOfTheSine) {
  // Header (analytic): with odd harmonics only, sin(pi - t) = sin(t) pairs the phases, giving p
  // (odd p), p/2 (p = 2 mod 4) or p/2 + 1 (p = 0 mod 4) values; a nonzero even harmonic breaks the
  // pairing, leaving p values for odd p and p - 1 for even p (x = 0 at both t = 0 and t = pi).
  // Delay vectors are always p.
  struct Case {
    RationalPeriod period;
    std::vector<double> amplitudes;
    std::size_t values;
  };
  const std::vector<Case> cases = {
      {{25, 1}, {1.0}, 25},            {{100, 1}, {1.0}, 51},           {{302, 3}, {1.0}, 151},
      {{100, 1}, {1.0, 0.0, 0.3}, 51}, {{100, 1}, {1.0, 0.5}, 99},      {{302, 3}, {1.0, 0.5}, 301},
      {{317, 3}, {1.0, 0.5}, 317},     {{7, 2}, {1.0}, 7},              {{8, 3}, {1.0}, 5},
  };
  for (const auto& c : cases) {
    const auto x = x_of(chaos::periodic(4 * c.period.numerator + 1, c.period, c.amplitudes));
    const std::string label = std::to_string(c.period.numerator) + "/" + std::to_string(c.period.denominator);
    EXPECT_EQ(distinct(x), c.values) << label;
    EXPECT_EQ(distinct_pairs(x), c.period.numerator) << label;
  }
}

TEST(ControlSignals, WholeNumberRealPeriodIsTheRationalOneAndIrrationalNeverRepeats) {
  // Documented: a whole-number double P is handed to the rational overload as {P, 1}.
  EXPECT_EQ(x_of(chaos::periodic(500, 25.0, {1.0, 0.2})), x_of(chaos::periodic(500, RationalPeriod{25, 1}, {1.0, 0.2})));
  // P = 25 phi: the phases n / P mod 1 are all distinct and no two are mirror images (that would
  // need (n + m) / P = j + 1/2 with P irrational), so every sample is a new value; the values
  // match the formula to rounding.
  const double period = 25.0 * std::numbers::phi;
  const auto x = x_of(chaos::periodic(3000, period));
  EXPECT_EQ(distinct(x), x.size());
  for (std::size_t n = 0; n < x.size(); ++n)
    ASSERT_NEAR(x[n], std::sin(2.0 * std::numbers::pi * static_cast<double>(n) / period), 1e-12) << n;
}

TEST(ControlSignals, PeriodicRefusesImpossibleParameters) {
  expect_invalid([] { chaos::periodic(100, 2.0); }, {"periodic", "must be finite and > 2", "P = 2"});
  expect_invalid([] { chaos::periodic(100, 1.0); }, {"P = 1"});
  expect_invalid([] { chaos::periodic(100, 1.5); }, {"P = 1.5", "alias"});
  expect_invalid([] { chaos::periodic(100, std::nan("")); }, {"P = nan"});
  expect_invalid([] { chaos::periodic(100, RationalPeriod{2, 1}); }, {"> 2 samples", "P = 2/1"});
  expect_invalid([] { chaos::periodic(100, RationalPeriod{3, 2}); }, {"P = 3/2 = 1.5"});
  expect_invalid([] { chaos::periodic(100, RationalPeriod{0, 1}); }, {"1 .. 2^53", "P = 0/1"});
  expect_invalid([] { chaos::periodic(100, RationalPeriod{5, 0}); }, {"P = 5/0"});
  expect_invalid([] { chaos::periodic(0, RationalPeriod{5, 1}); }, {"periodic", "n = 0"});
  expect_invalid([] { chaos::periodic(100, RationalPeriod{25, 1}, {}); }, {"at least one amplitude"});
  expect_invalid([] { chaos::periodic(100, RationalPeriod{25, 1}, {0.0, 0.0}); }, {"all zero"});
  expect_invalid([] { chaos::periodic(100, 31.5, {1.0, INFINITY}); }, {"a_2 = inf"});
  // Harmonic 13 of P = 25: 2 h = 26 >= 25 aliases; a zero amplitude there is allowed.
  std::vector<double> a(13, 0.0);
  a[0] = 1.0;
  EXPECT_NO_THROW(chaos::periodic(100, RationalPeriod{25, 1}, a));
  a[12] = 0.1;
  expect_invalid([&] { chaos::periodic(100, RationalPeriod{25, 1}, a); }, {"harmonic h = 13", "Nyquist"});
  expect_invalid([&] { chaos::periodic(100, 25.5, a); }, {"harmonic h = 13", "P = 25.5"});
}

// ---- Quasi-periodic ----------------------------------------------------------------------------

TEST(ControlSignals, TorusConstantsAndSignalsMatchTheDocumentedFrequencies) {
  const double p1 = 10.0 * std::numbers::pi;
  EXPECT_DOUBLE_EQ(chaos::torus_period_1, p1);
  EXPECT_DOUBLE_EQ(chaos::torus_period_2, p1 / ((1.0 + std::sqrt(5.0)) / 2.0));
  EXPECT_DOUBLE_EQ(chaos::torus_period_3, p1 / std::sqrt(2.0));
  const auto two = x_of(chaos::two_torus(5000));
  const auto three = x_of(chaos::three_torus(5000));
  const auto tone = [](std::size_t n, double p) {
    return std::sin(2.0 * std::numbers::pi * static_cast<double>(n) / p);
  };
  for (std::size_t n = 0; n < two.size(); ++n) {
    const double a = tone(n, chaos::torus_period_1), b = tone(n, chaos::torus_period_2);
    ASSERT_NEAR(two[n], a + b, 1e-11) << n;
    ASSERT_NEAR(three[n], a + b + tone(n, chaos::torus_period_3), 1e-11) << n;
  }
  // No exact repetition on a torus with incommensurate frequencies.
  EXPECT_EQ(distinct(two), two.size());
  EXPECT_EQ(distinct(three), three.size());
}

TEST(ControlSignals, RationalFirstTorusHasItsFirstToneExactlyPeriodic) {
  // First period exactly 25 samples: subtracting the second tone leaves sin(2 pi j / 25) at every
  // sample n = 25 k + j, so the sampled orbit lies on 25 curves (header); the second tone is the
  // same as two_torus's.
  const auto x = x_of(chaos::two_torus_rational_first(5000));
  const auto general = x_of(chaos::quasi_periodic_signal(5000, RationalPeriod{25, 1},
                                                         std::vector<double>{chaos::torus_period_2}));
  EXPECT_EQ(x, general);
  for (std::size_t n = 0; n < x.size(); ++n) {
    const double second = std::sin(2.0 * std::numbers::pi * static_cast<double>(n) / chaos::torus_period_2);
    ASSERT_NEAR(x[n] - second, std::sin(2.0 * std::numbers::pi * static_cast<double>(n % 25) / 25.0), 1e-11) << n;
  }
  // With the rational first tone replaced by 10 pi, it is two_torus (to rounding).
  const auto other = x_of(chaos::two_torus_rational_first(100, RationalPeriod{317, 3}));
  for (std::size_t n = 0; n < other.size(); ++n)
    ASSERT_NEAR(other[n],
                std::sin(2.0 * std::numbers::pi * static_cast<double>(3 * n % 317) / 317.0) +
                    std::sin(2.0 * std::numbers::pi * static_cast<double>(n) / chaos::torus_period_2),
                1e-12);
}

TEST(ControlSignals, QuasiPeriodicRefusesImpossibleParameters) {
  expect_invalid([] { chaos::quasi_periodic_signal(100, std::vector<double>{}); }, {"at least one period"});
  expect_invalid([] { chaos::quasi_periodic_signal(100, std::vector<double>{30.0, 2.0}); },
                 {"quasi_periodic_signal", "P = 2"});
  expect_invalid([] { chaos::quasi_periodic_signal(100, std::vector<double>{INFINITY}); }, {"P = inf"});
  expect_invalid([] { chaos::quasi_periodic_signal(100, RationalPeriod{4, 2}, std::vector<double>{30.0}); },
                 {"P = 4/2 = 2"});
  expect_invalid([] { chaos::two_torus(0); }, {"n = 0"});
  expect_invalid([] { chaos::two_torus_rational_first(10, RationalPeriod{1, 1}); }, {"P = 1/1"});
}

// ---- Measurement noise -------------------------------------------------------------------------

TEST(ControlSignals, AddNoiseRealisesTheRequestedSnr) {
  // The realised SNR 20 log10(std x / std(y - x)) has sampling standard deviation about
  // (20 / ln 10) / sqrt(2 N) (the delta method on the sample standard deviation of N normals):
  // 0.019 dB for N = 10^5. Band: 5 of those.
  const std::size_t n = 100'000;
  const auto x = x_of(chaos::periodic(n, RationalPeriod{317, 3}, {1.0, 0.5}));
  const double band = 5.0 * 20.0 / std::log(10.0) / std::sqrt(2.0 * static_cast<double>(n));
  for (const double snr : {40.0, 20.0, 0.0, -10.0}) {
    const auto y = chaos::add_noise(x, snr, 17);
    ASSERT_EQ(y.size(), n);
    std::vector<double> e(n);
    for (std::size_t t = 0; t < n; ++t) e[t] = y[t] - x[t];
    EXPECT_NEAR(20.0 * std::log10(stdev(x) / stdev(e)), snr, band) << snr;
    EXPECT_NEAR(mean(e) / stdev(e), 0.0, 5.0 / std::sqrt(static_cast<double>(n))) << snr;
  }
  // Seeded: the same seed gives the same noise; the noise is sigma times the Gaussian stream.
  EXPECT_EQ(chaos::add_noise(x, 10.0, 3), chaos::add_noise(x, 10.0, 3));
  EXPECT_NE(chaos::add_noise(x, 10.0, 3), chaos::add_noise(x, 10.0, 4));
  const std::vector<double> two = {-1.0, 1.0};  // std 1, so sigma = 10^(-20/20) = 0.1 at 20 dB
  const auto y = chaos::add_noise(two, 20.0, 8);
  chaos::Random rng(8);
  EXPECT_NEAR(y[0], -1.0 + 0.1 * rng.gaussian(), 1e-15);
  EXPECT_NEAR(y[1], 1.0 + 0.1 * rng.gaussian(), 1e-15);
  // The scale of the data does not matter: 1e200 x gets 1e200 times the same noise.
  std::vector<double> big = {-1e200, 1e200};
  const auto yb = chaos::add_noise(big, 20.0, 8);
  EXPECT_NEAR(yb[0] / 1e200, y[0], 1e-14);
}

TEST(ControlSignals, AddNoiseRefusesBadInput) {
  expect_refused([] { chaos::add_noise(std::vector<double>{}, 10.0); }, ErrorCode::empty, {"add_noise", "empty"});
  expect_refused([] { chaos::add_noise(std::vector<double>{1.0, NAN}, 10.0); }, ErrorCode::non_finite,
                 {"add_noise", "sample 1"});
  expect_refused([] { chaos::add_noise(std::vector<double>{2.0, 2.0}, 10.0); }, ErrorCode::constant,
                 {"add_noise", "constant"});
  expect_invalid([] { chaos::add_noise(std::vector<double>{1.0, 2.0}, INFINITY); }, {"SNR must be finite", "inf"});
  expect_invalid([] { chaos::add_noise(std::vector<double>{1.0, 2.0}, NAN); }, {"snr_db = nan"});
  expect_invalid([] { chaos::add_noise(std::vector<double>{0.0, 1e300}, -400.0); }, {"overflows"});
}

// ---- Quantisation ------------------------------------------------------------------------------

TEST(ControlSignals, QuantiseLevelsGivesExactlyTheLevelsOverTheRange) {
  // A densely sampled sine (P = 1000) visits every level, so the count is exactly `levels`; every
  // output is min + k Delta (the top one max itself) within Delta / 2 of its input.
  const auto x = x_of(chaos::periodic(2000, RationalPeriod{1000, 1}));
  const double lo = *std::min_element(x.begin(), x.end()), hi = *std::max_element(x.begin(), x.end());
  for (const std::size_t levels : {2u, 3u, 8u, 256u}) {
    const auto y = chaos::quantise_levels(x, levels);
    EXPECT_EQ(distinct(y), levels) << levels;
    const double delta = (hi - lo) / static_cast<double>(levels - 1);
    for (std::size_t t = 0; t < x.size(); ++t) {
      ASSERT_LE(std::abs(y[t] - x[t]), 0.5 * delta * (1.0 + 1e-12)) << t;
      const double k = (y[t] - lo) / delta;
      ASSERT_NEAR(k, std::round(k), 1e-9) << t;
    }
    EXPECT_EQ(*std::min_element(y.begin(), y.end()), lo);
    EXPECT_EQ(*std::max_element(y.begin(), y.end()), hi);
  }
  // Gaussian noise, 10^4 samples, 16 levels: at most 16 values (the tails may leave some empty).
  const auto w = x_of(chaos::white_noise(10'000, 2));
  EXPECT_LE(distinct(chaos::quantise_levels(w, 16)), 16u);
  EXPECT_EQ(chaos::quantise_levels(std::vector<double>{0.0, 0.24, 0.26, 1.0}, 3),
            (std::vector<double>{0.0, 0.0, 0.5, 1.0}));
}

TEST(ControlSignals, QuantiseStepRoundsToTheGridThroughZero) {
  // A sine of amplitude 1 rounded to steps of 0.1 takes k = -10 .. 10: 21 values (P = 1000 hits all).
  const auto x = x_of(chaos::periodic(1000, RationalPeriod{1000, 1}));
  const auto y = chaos::quantise_step(x, 0.1);
  EXPECT_EQ(distinct(y), 21u);
  for (std::size_t t = 0; t < x.size(); ++t) ASSERT_LE(std::abs(y[t] - x[t]), 0.05 + 1e-15) << t;
  EXPECT_EQ(chaos::quantise_step(std::vector<double>{0.26, -0.26, 0.25, -0.25, 3.0}, 0.5),
            (std::vector<double>{0.5, -0.5, 0.5, -0.5, 3.0}));  // halves away from zero
  // A constant series is fine for a fixed grid.
  EXPECT_EQ(chaos::quantise_step(std::vector<double>{0.3, 0.3}, 0.25), (std::vector<double>{0.25, 0.25}));
}

TEST(ControlSignals, QuantisersRefuseBadInput) {
  const std::vector<double> x = {0.0, 1.0, 2.0};
  expect_invalid([&] { chaos::quantise_levels(x, 1); }, {"quantise_levels", "at least 2", "levels = 1"});
  expect_invalid([&] { chaos::quantise_levels(x, 0); }, {"levels = 0"});
  expect_refused([] { chaos::quantise_levels(std::vector<double>{3.0, 3.0}, 4); }, ErrorCode::constant,
                 {"quantise_levels", "constant"});
  expect_refused([] { chaos::quantise_levels(std::vector<double>{}, 4); }, ErrorCode::empty, {"empty"});
  expect_refused([] { chaos::quantise_levels(std::vector<double>{1.0, INFINITY}, 4); }, ErrorCode::non_finite,
                 {"sample 1"});
  expect_invalid([] { chaos::quantise_levels(std::vector<double>{-1e308, 1e308}, 4); }, {"overflows"});
  expect_invalid([&] { chaos::quantise_step(x, 0.0); }, {"quantise_step", "finite and > 0", "step = 0"});
  expect_invalid([&] { chaos::quantise_step(x, -0.1); }, {"step = -0.1"});
  expect_invalid([&] { chaos::quantise_step(x, NAN); }, {"step = nan"});
  expect_invalid([] { chaos::quantise_step(std::vector<double>{1e300}, 1e-300); }, {"not finite", "larger step"});
  expect_refused([] { chaos::quantise_step(std::vector<double>{}, 0.1); }, ErrorCode::empty, {"empty"});
}

}  // namespace
