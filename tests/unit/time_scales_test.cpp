// Time scales behind the automatic choices: the oscillation half period, the Theiler window and
// the stationarity verdict, on series whose autocorrelation is known in closed form.
#include "chaos/time_scales.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

std::vector<double> sine(std::size_t n, double period) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = std::sin(2.0 * std::numbers::pi * static_cast<double>(i) / period);
  return x;
}

// A sinusoid's autocorrelation is cos(2 pi k / P) (up to the biased estimator's (1 - k/N)): its
// first minimum after the zero crossing is at P/2, so the window is half a period, not the 1/e time
// (0.19 P).
TEST(TimeScales, SineWindowIsHalfThePeriod) {
  const auto t = chaos::time_scales(sine(20000, 40.0));
  ASSERT_TRUE(t.half_period.has_value());
  EXPECT_NEAR(static_cast<double>(*t.half_period), 20.0, 1.0);
  EXPECT_EQ(t.theiler, *t.half_period);
  EXPECT_EQ(t.period(), 2 * *t.half_period);
  EXPECT_TRUE(t.stationary);
  ASSERT_TRUE(t.decorrelation_time.has_value());
  EXPECT_NEAR(*t.decorrelation_time, 40.0 * std::acos(std::exp(-1.0)) / (2.0 * std::numbers::pi), 0.5);
}

// AR(1) with phi = 0.9: r(k) = 0.9^k never goes negative, so there is no oscillation; the window is
// the 1/e time, ln(1/e) / ln 0.9 = 9.49 samples, rounded up.
TEST(TimeScales, Ar1WindowIsTheDecayTime) {
  const auto x = chaos::ar1(100000, 0.9, 3).components[0];
  const auto t = chaos::time_scales(x);
  EXPECT_FALSE(t.half_period.has_value());
  EXPECT_TRUE(t.stationary);
  EXPECT_NEAR(static_cast<double>(t.theiler), 10.0, 1.0);
}

// A random walk's (biased) autocorrelation falls to 1/e at a fixed fraction of N whatever N, so it
// never holds min_correlation_times of its own correlation times: non-stationary, with advice.
TEST(TimeScales, RandomWalkIsNotStationary) {
  for (const std::size_t n : {2000u, 20000u, 100000u}) {
    const auto e = chaos::white_noise(n, 5).components[0];
    std::vector<double> walk(n);
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) walk[i] = (sum += e[i]);
    const auto t = chaos::time_scales(walk);
    EXPECT_FALSE(t.stationary) << n;
    EXPECT_NE(t.stationarity_explanation.find("increments"), std::string::npos);
  }
}

TEST(TimeScales, WhiteNoiseIsStationaryWithAWindowOfOne) {
  const auto t = chaos::time_scales(chaos::white_noise(10000, 2).components[0]);
  EXPECT_TRUE(t.stationary);
  EXPECT_EQ(t.theiler, 1u);
  EXPECT_FALSE(t.half_period.has_value());
}

TEST(TimeScales, RefusesTooShortAndConstant) {
  EXPECT_THROW(chaos::time_scales(std::vector<double>{1.0, 2.0}), chaos::InvalidInput);
  EXPECT_THROW(chaos::time_scales(std::vector<double>(100, 3.0)), chaos::InvalidInput);
}

}  // namespace
