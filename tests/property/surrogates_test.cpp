// Properties every surrogate must have, whatever the input: FT keeps the periodogram (phase
// randomisation changes no modulus), AAFT and IAAFT keep the values (they end with a rank-order
// remapping of the data's own values), IAAFT's reported deviation is that of its output and within
// its tolerance when it stops there, output is a function of the seed alone, and scaling the data
// by a power of two scales every surrogate by it exactly (every step is linear or order-based, and
// such scalings are exact in floating point).
#include "chaos/surrogates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::SurrogateMethod;
using chaos::SurrogateOptions;
using chaos::SurrogateStatus;

struct Named {
  std::string name;
  std::vector<double> x;
};

std::vector<Named> inputs() {
  std::vector<Named> v;
  v.push_back({"lorenz", chaos::lorenz(2048, {}, {0.05, 0.005, 100.0}).components[0]});
  v.push_back({"henon", chaos::henon(1000).components[0]});
  v.push_back({"logistic_odd", chaos::logistic(999).components[0]});
  v.push_back({"ar1", chaos::ar1(1500, 0.95, 3).components[0]});
  v.push_back({"noise", chaos::white_noise(777, 4).components[0]});
  v.push_back({"sine", chaos::sine(1000, 1.0, 0.013).components[0]});
  // Short series of few distinct values (ties everywhere), odd and even lengths down to N = 4.
  for (std::uint64_t seed = 0; seed < 12; ++seed) {
    chaos::Random rng(seed);
    std::vector<double> x(4 + seed * 3);
    do {
      for (auto& value : x) value = static_cast<double>(rng.below(3 + seed % 4)) - 1.0;
    } while (*std::min_element(x.begin(), x.end()) == *std::max_element(x.begin(), x.end()));
    v.push_back({"ties" + std::to_string(seed), x});
  }
  return v;
}

// |X_k|^2 by the O(N^2) definition in long double, independent of FFTW.
std::vector<long double> periodogram(const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::vector<long double> c(n), s(n);  // e^{-2 pi i m / N}, m = k t mod N
  for (std::size_t m = 0; m < n; ++m) {
    const long double a =
        -2.0L * 3.14159265358979323846264338327950288L * static_cast<long double>(m) / static_cast<long double>(n);
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

TEST(SurrogateProperties, FourierKeepsThePeriodogram) {
  for (const auto& [name, x] : inputs()) {
    if (x.size() > 1100) continue;  // the O(N^2) reference periodogram
    const auto p = periodogram(x);
    const long double peak = *std::max_element(p.begin(), p.end());
    const auto all = chaos::surrogates(x, 3, 21, {SurrogateMethod::fourier});
    for (const auto& s : all) {
      const auto q = periodogram(s.values);
      for (std::size_t k = 0; k < x.size(); ++k)
        ASSERT_LE(std::abs(q[k] - p[k]), 1e-9L * std::max(p[k], peak)) << name << " k " << k;
      EXPECT_LT(s.spectral_deviation, 1e-12) << name;
    }
  }
}

TEST(SurrogateProperties, AaftAndIaaftKeepTheValues) {
  for (const auto& [name, x] : inputs()) {
    const auto reference = sorted(x);
    for (const auto method : {SurrogateMethod::aaft, SurrogateMethod::iaaft})
      for (const auto& s : chaos::surrogates(x, 3, 5, {method}))
        ASSERT_EQ(sorted(s.values), reference) << name << " " << chaos::to_string(method);
  }
}

TEST(SurrogateProperties, IaaftDeviationIsThatOfItsOutput) {
  for (const auto& [name, x] : inputs()) {
    for (const double tolerance : {0.0, 0.05}) {
      SurrogateOptions o;
      o.tolerance = tolerance;
      o.max_iterations = 500;
      for (const auto& s : chaos::surrogates(x, 2, 8, o)) {
        EXPECT_NEAR(s.spectral_deviation, chaos::spectral_deviation(x, s.values), 1e-12) << name;
        EXPECT_LE(s.iterations, 500u) << name;
        if (s.status == SurrogateStatus::tolerance) {
          EXPECT_LE(s.spectral_deviation, tolerance) << name;
        }
        if (tolerance == 0.0) {
          EXPECT_NE(s.status, SurrogateStatus::tolerance) << name;
        }
        EXPECT_NE(s.status, SurrogateStatus::exact) << name;
      }
    }
  }
}

TEST(SurrogateProperties, OutputIsAFunctionOfTheSeed) {
  for (const auto& [name, x] : inputs())
    for (const auto method : {SurrogateMethod::fourier, SurrogateMethod::aaft, SurrogateMethod::iaaft}) {
      chaos::SurrogateGenerator one(x, {method});
      chaos::SurrogateGenerator two(x, {method});
      (void)two.generate(99);  // a different history must not matter
      for (const std::uint64_t seed : {0ull, 1ull, 123456789ull}) {
        const auto a = one.generate(seed);
        const auto b = two.generate(seed);
        ASSERT_EQ(a.values, b.values) << name << " " << chaos::to_string(method) << " seed " << seed;
        ASSERT_EQ(a.iterations, b.iterations);
      }
    }
}

TEST(SurrogateProperties, PowerOfTwoScalingScalesTheSurrogatesExactly) {
  for (const auto& [name, x] : inputs())
    for (const double factor : {4.0, 0.125}) {
      std::vector<double> y(x.size());
      for (std::size_t t = 0; t < x.size(); ++t) y[t] = factor * x[t];
      for (const auto method : {SurrogateMethod::fourier, SurrogateMethod::aaft, SurrogateMethod::iaaft}) {
        const auto sx = chaos::surrogates(x, 1, 31, {method})[0];
        const auto sy = chaos::surrogates(y, 1, 31, {method})[0];
        ASSERT_EQ(sx.values.size(), sy.values.size());
        for (std::size_t t = 0; t < x.size(); ++t)
          ASSERT_EQ(sy.values[t], factor * sx.values[t]) << name << " " << chaos::to_string(method) << " t " << t;
        EXPECT_EQ(sx.iterations, sy.iterations);
      }
    }
}

TEST(SurrogateProperties, EndMatchNeverWorseThanTheWholeSeries) {
  // The whole series is always admissible when max_trim >= 0 and smooth_lengths is off, so the
  // best segment's mismatch is at most the whole series'.
  for (const auto& [name, x] : inputs()) {
    chaos::EndMatchOptions o;
    o.smooth_lengths = false;
    const auto m = chaos::end_match(x, o);
    EXPECT_LE(m.mismatch, m.whole_series_mismatch * (1.0 + 1e-12)) << name;
    EXPECT_GE(m.length, static_cast<std::size_t>(std::ceil(0.9 * static_cast<double>(x.size())) - 1e-9)) << name;
    EXPECT_LE(m.offset + m.length, x.size()) << name;
  }
}

}  // namespace
