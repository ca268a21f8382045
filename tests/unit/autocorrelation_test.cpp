// Autocorrelation by FFT against the direct O(N K) sum, the closed form for a sampled sine, the
// AR(1) law r(k) = phi^k, and the zero-crossing and 1/e rules on hand-made curves.
#include "chaos/autocorrelation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

// The definition in the header, summed directly (brute force).
std::vector<double> direct(const std::vector<double>& x, std::size_t max_lag) {
  const double n = static_cast<double>(x.size());
  double mean = 0.0;
  for (const double v : x) mean += v;
  mean /= n;
  std::vector<double> c(max_lag + 1, 0.0);
  for (std::size_t k = 0; k <= max_lag; ++k) {
    for (std::size_t t = 0; t + k < x.size(); ++t) c[k] += (x[t] - mean) * (x[t + k] - mean);
    c[k] /= n;
  }
  for (std::size_t k = max_lag + 1; k-- > 0;) c[k] /= c[0];
  return c;
}

TEST(Autocorrelation, EqualsTheDirectSum) {
  std::vector<std::vector<double>> inputs = {
      chaos::lorenz(3000).components[0], chaos::ar1(1009, 0.6, 1).components[0],  // 1009: prime N
      chaos::white_noise(777, 2).components[0], {1.0, 2.0}, {3.0, -1.0, 2.0}};
  for (const auto& x : inputs)
    for (const std::size_t max_lag : {std::size_t{0}, std::size_t{1}, x.size() / 3, x.size() - 1}) {
      const auto r = chaos::autocorrelation(x, max_lag).correlation;
      const auto d = direct(x, max_lag);
      ASSERT_EQ(r.size(), max_lag + 1);
      EXPECT_EQ(r[0], 1.0);
      for (std::size_t k = 0; k <= max_lag; ++k) EXPECT_NEAR(r[k], d[k], 1e-12) << "N " << x.size() << " k " << k;
    }
}

TEST(Autocorrelation, HandComputedShortSeries) {
  // x = 1 2 3 4: deviations -1.5 -0.5 0.5 1.5; N c(k) = 5, 1.25, -1.5, -2.25.
  const auto r = chaos::autocorrelation(std::vector<double>{1, 2, 3, 4}, 3).correlation;
  EXPECT_NEAR(r[1], 0.25, 1e-15);
  EXPECT_NEAR(r[2], -0.3, 1e-15);
  EXPECT_NEAR(r[3], -0.45, 1e-15);
}

TEST(Autocorrelation, SampledSineMatchesTheClosedForm) {
  // x_t = sin(a t), a = 2 pi / P, N a whole number of periods (mean 0). Summing the products,
  // 2 N c(k) = (N - k) cos(a k) - cos(a (N - 1)) sin(a (N - k)) / sin(a) and c(0) = 1/2, so
  // r(k) = [(N - k) cos(a k) - cos(a (N - 1)) sin(a (N - k)) / sin(a)] / N (analytic).
  const std::size_t period = 100, n = 100 * period;
  const auto x = chaos::sine(n, 1.0, 1.0 / static_cast<double>(period)).components[0];
  const auto r = chaos::autocorrelation(x, 3 * period).correlation;
  const double a = 2 * std::numbers::pi / static_cast<double>(period), nd = static_cast<double>(n);
  for (std::size_t k = 0; k <= 3 * period; ++k) {
    const double kd = static_cast<double>(k);
    const double exact = ((nd - kd) * std::cos(a * kd) - std::cos(a * (nd - 1)) * std::sin(a * (nd - kd)) / std::sin(a)) / nd;
    EXPECT_NEAR(r[k], exact, 1e-10) << k;
  }
}

TEST(Autocorrelation, SineCrossesZeroJustAfterAQuarterPeriod) {
  // r(k) ~ cos(2 pi k / P): the first lag with r <= 0 is the first integer above P / 4 when P / 4
  // is not close to an integer (the finite-N terms are O(P / N), far below |cos| there).
  for (const double period : {37.0, 102.0, 250.4}) {
    const auto x = chaos::sine(20'000, 1.0, 1.0 / period).components[0];
    const auto r = chaos::autocorrelation(x, 200);
    const auto zero = chaos::first_zero_crossing(r);
    ASSERT_TRUE(zero.has_value());
    EXPECT_EQ(*zero, static_cast<std::size_t>(std::ceil(period / 4))) << period;
    // And r falls to 1/e where cos(2 pi k / P) = 1/e: k = P acos(1/e) / (2 pi), up to the linear
    // interpolation (O(1/P^2) samples) and the (1 - k/N) factor of the biased estimator (k/N r/|r'|).
    const auto tau = chaos::decorrelation_time(r);
    ASSERT_TRUE(tau.has_value());
    EXPECT_NEAR(*tau, period * std::acos(std::exp(-1.0)) / (2 * std::numbers::pi), 0.05) << period;
  }
}

TEST(Autocorrelation, Ar1FollowsPhiToTheK) {
  // r(k) = phi^k for an AR(1) process; Bartlett's formula gives the variance of the estimate,
  // Var r(k) ~ [(1 + phi^2)(1 - phi^2k) / (1 - phi^2) - 2 k phi^2k] / N. Bounds at 5 of its sd.
  const double phi = 0.8;
  const std::size_t n = 200'000;
  const auto r = chaos::autocorrelation(chaos::ar1(n, phi, 12).components[0], 15).correlation;
  for (std::size_t k = 1; k <= 15; ++k) {
    const double p2k = std::pow(phi, 2.0 * static_cast<double>(k));
    const double var = ((1 + phi * phi) * (1 - p2k) / (1 - phi * phi) - 2.0 * static_cast<double>(k) * p2k) /
                       static_cast<double>(n);
    EXPECT_NEAR(r[k], std::pow(phi, static_cast<double>(k)), 5 * std::sqrt(var)) << k;
  }
}

chaos::AutocorrelationResult curve(std::vector<double> r) { return {std::move(r)}; }

TEST(Autocorrelation, ZeroCrossingAndDecorrelationRulesOnHandMadeCurves) {
  EXPECT_EQ(chaos::first_zero_crossing(curve({1, 0.5, 0.0, -0.2})), 2u);  // r <= 0 includes 0
  EXPECT_EQ(chaos::first_zero_crossing(curve({1, -0.1, 0.3})), 1u);
  EXPECT_EQ(chaos::first_zero_crossing(curve({1, 0.5, 0.2})), std::nullopt);
  EXPECT_EQ(chaos::first_zero_crossing(curve({1})), std::nullopt);
  // {1, 0.5, 0.25}: 1/e lies between lags 1 and 2; linear interpolation gives
  // 1 + (0.5 - 1/e) / (0.5 - 0.25) (hand-computed).
  const auto tau = chaos::decorrelation_time(curve({1, 0.5, 0.25, 0.125}));
  ASSERT_TRUE(tau.has_value());
  EXPECT_NEAR(*tau, 1.0 + (0.5 - std::exp(-1.0)) / 0.25, 1e-15);
  EXPECT_NEAR(*chaos::decorrelation_time(curve({1, std::exp(-1.0)})), 1.0, 1e-15);  // exactly at a lag
  EXPECT_EQ(chaos::decorrelation_time(curve({1, 0.9, 0.5})), std::nullopt);
  EXPECT_EQ(chaos::decorrelation_time(curve({})), std::nullopt);
}

template <class F>
void expect_refused(F&& f, chaos::ErrorCode code, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// A Lorenz series times 1e150 gave -nan rows and a wrong zero crossing, and so did one
// below 1e-170 or in denormals. r(k) does not depend on the scale: times a power of two it is the
// same bit for bit (the series is divided by a power of two internally, which is exact), and even
// in denormals, where few bits are left, it stays a finite correlation with the same crossing.
TEST(Autocorrelation, IndependentOfTheScale) {
  const std::vector<double> x = chaos::lorenz(3000).components[0];
  const chaos::AutocorrelationResult reference = chaos::autocorrelation(x, 300);
  for (const int exponent : {-1000, -600, 500, 1000}) {
    std::vector<double> y(x);
    for (double& v : y) v = std::ldexp(v, exponent);
    EXPECT_EQ(chaos::autocorrelation(y, 300).correlation, reference.correlation) << "x 2^" << exponent;
  }
  std::vector<double> denormal(x);
  for (double& v : denormal) v = std::ldexp(v, -1060);  // |x| <= 20 * 2^-1060 < 2^-1022
  const chaos::AutocorrelationResult r = chaos::autocorrelation(denormal, 300);
  for (const double v : r.correlation) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_LE(std::fabs(v), 1.0 + 1e-12);
  }
  EXPECT_EQ(chaos::first_zero_crossing(r), chaos::first_zero_crossing(reference));
}

TEST(Autocorrelation, RefusesInvalidInput) {
  using chaos::ErrorCode;
  std::vector<double> x = {1, 2, 3, 4, 5};
  expect_refused([&] { chaos::autocorrelation(x, 5); }, ErrorCode::too_short, "max_lag = 5");
  expect_refused([&] { chaos::autocorrelation(std::vector<double>{}, 0); }, ErrorCode::too_short, "N = 0");
  expect_refused([&] { chaos::autocorrelation(std::vector<double>(10, 1.5), 3); }, ErrorCode::constant, "1.5");
  x[2] = NAN;
  expect_refused([&] { chaos::autocorrelation(x, 2); }, ErrorCode::non_finite, "sample 2");
}

}  // namespace
