// Bifurcation diagrams of a map family and density maps (bifurcation.hpp). Expected values: the
// logistic map's period doubling (period 2 at r = 3.2, period 4 at r = 3.5, chaos at r = 3.9; May
// 1976) and its period-2 points in closed form; the Freedman-Diaconis count and Silverman's
// bandwidth worked by hand from their formulas (Freedman & Diaconis 1981; Silverman 1986, eq.
// 3.31); a uniform sample's flat histogram and a normal sample's kernel estimate against the
// normal density, each within a stated statistical band; normalisation (each density integrates
// to 1); the documented treatment of constant samples and of bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "chaos/bifurcation.hpp"
#include "chaos/error.hpp"
#include "chaos/poincare.hpp"
#include "chaos/random.hpp"

namespace chaos {
namespace {

double logistic(double r, double x) { return r * x * (1.0 - x); }

double integral(const DensityMap& m, std::size_t p) {
  double s = 0.0;
  for (std::size_t b = 0; b < m.centres.size(); ++b) s += m.density[p][b] * (m.edges[b + 1] - m.edges[b]);
  return s;
}

TEST(Bifurcation, LogisticPeriodDoubling) {
  const std::vector<double> r = {3.2, 3.5, 3.9};
  const BifurcationDiagram d = map_bifurcation(logistic, r, {.initial = 0.5, .transient = 5000, .keep = 2000});
  ASSERT_EQ(d.points.size(), 3u);
  for (const auto& p : d.points) ASSERT_EQ(p.size(), 2000u);
  EXPECT_EQ(distinct_values(d.points[0], 1e-6), 2u);  // 3 < r < 1 + sqrt 6: period 2
  EXPECT_EQ(distinct_values(d.points[1], 1e-6), 4u);  // 1 + sqrt 6 < r < 3.544: period 4
  EXPECT_GT(distinct_values(d.points[2], 1e-6), 100u);  // chaotic band
  for (const auto& p : d.points) {
    for (double x : p) {
      EXPECT_GT(x, 0.0);
      EXPECT_LT(x, 1.0);
    }
  }
}

TEST(Bifurcation, LogisticPeriodTwoPointsInClosedForm) {
  // f(f(x)) = x without the fixed points: x = (r + 1 -/+ sqrt((r - 3)(r + 1))) / (2 r).
  const double r = 3.2;
  const BifurcationDiagram d = map_bifurcation(logistic, std::vector<double>{r}, {.initial = 0.3, .transient = 2000, .keep = 10});
  const double root = std::sqrt((r - 3.0) * (r + 1.0));
  const double low = (r + 1.0 - root) / (2.0 * r), high = (r + 1.0 + root) / (2.0 * r);
  for (double x : d.points[0]) EXPECT_NEAR(std::min(std::abs(x - low), std::abs(x - high)), 0.0, 1e-12);
  EXPECT_NE(d.points[0][0] < 0.6, d.points[0][1] < 0.6);  // alternates between the two
}

TEST(Bifurcation, PeriodTwoHistogramHasTwoHalves) {
  // Two branches, equally visited: two non-empty bins each holding half the mass.
  const BifurcationDiagram d = map_bifurcation(logistic, std::vector<double>{3.2}, {.transient = 2000, .keep = 1000});
  DensityMapOptions o;
  o.bin_rule = BinRule::fixed;
  o.bins = 10;
  const DensityMap m = density_map(d.parameters, d.points, o);
  int occupied = 0;
  for (std::size_t b = 0; b < 10; ++b) {
    if (m.density[0][b] == 0.0) continue;
    ++occupied;
    EXPECT_NEAR(m.density[0][b] * (m.edges[b + 1] - m.edges[b]), 0.5, 1e-12);
  }
  EXPECT_EQ(occupied, 2);
  // The pooled range padded by 5% of the span on each side.
  const auto [lo, hi] = std::minmax_element(d.points[0].begin(), d.points[0].end());
  EXPECT_NEAR(m.edges.front(), *lo - 0.05 * (*hi - *lo), 1e-15);
  EXPECT_NEAR(m.edges.back(), *hi + 0.05 * (*hi - *lo), 1e-15);
}

TEST(Bifurcation, HistogramOfAUniformSampleIsFlat) {
  // 100 000 uniform samples in 20 bins over [0, 1]: each count is binomial(1e5, 0.05), standard
  // deviation sqrt(1e5 x 0.05 x 0.95) ~ 69 of 5000, i.e. 0.014 in density; band 4 sigma.
  Random rng(11);
  std::vector<std::vector<double>> samples(2);
  for (auto& s : samples) {
    for (int i = 0; i < 100'000; ++i) s.push_back(rng.uniform());
  }
  DensityMapOptions o;
  o.bin_rule = BinRule::fixed;
  o.bins = 20;
  o.low = 0.0;
  o.high = 1.0;
  const DensityMap m = density_map(std::vector<double>{1.0, 2.0}, samples, o);
  ASSERT_EQ(m.centres.size(), 20u);
  for (std::size_t p = 0; p < 2; ++p) {
    EXPECT_NEAR(integral(m, p), 1.0, 1e-12);
    for (double d : m.density[p]) EXPECT_NEAR(d, 1.0, 4 * 0.0138);
  }
  EXPECT_DOUBLE_EQ(m.centres.front(), 0.025);
}

TEST(Bifurcation, KernelEstimateOfANormalSampleMatchesTheNormalDensity) {
  // 20 000 standard normal samples: Silverman's bandwidth ~ 0.9 x 20000^(-1/5) = 0.124; the
  // estimate's bias at the mode is phi(0) (1 / sqrt(1 + h^2) - 1) ~ -0.003 and its standard
  // deviation sqrt(phi(0) / (2 sqrt(pi) n h)) ~ 0.007: band 0.03 over every bin of [-4, 4].
  Random rng(5);
  std::vector<double> x(20'000);
  for (auto& v : x) v = rng.gaussian();
  DensityMapOptions o;
  o.estimator = DensityEstimator::kernel;
  o.bin_rule = BinRule::fixed;
  o.bins = 80;
  o.low = -4.0;
  o.high = 4.0;
  const DensityMap m = density_map(std::vector<double>{0.0}, {x}, o);
  ASSERT_EQ(m.bandwidths.size(), 1u);
  EXPECT_NEAR(m.bandwidths[0], 0.9 * std::pow(20'000.0, -0.2), 0.05 * 0.124);  // s and IQR/1.34 ~ 1
  EXPECT_NEAR(integral(m, 0), 1.0, 1e-12);
  EXPECT_GT(m.kernel_mass[0], 0.999);  // P(|Z| > 4) ~ 6e-5
  for (std::size_t b = 0; b < m.centres.size(); ++b) {
    const double c = m.centres[b];
    EXPECT_NEAR(m.density[0][b], std::exp(-c * c / 2) / std::sqrt(2 * std::numbers::pi), 0.03) << "at " << c;
  }
}

TEST(Bifurcation, FreedmanDiaconisCountByHand) {
  // Values i / 999, i = 0 .. 999: type-7 quartiles 0.25 and 0.75, IQR 0.5, width
  // 2 x 0.5 x 1000^(-1/3) = 0.1; over [0, 1.05] that is ceil(10.5) = 11 bins; a cap of 5 wins.
  std::vector<double> x;
  for (int i = 0; i < 1000; ++i) x.push_back(i / 999.0);
  DensityMapOptions o;
  o.low = 0.0;
  o.high = 1.05;
  const DensityMap m = density_map(std::vector<double>{0.0}, {x}, o);
  ASSERT_TRUE(m.rule_bins);
  EXPECT_EQ(*m.rule_bins, 11u);
  EXPECT_EQ(m.centres.size(), 11u);
  o.bins = 5;
  const DensityMap capped = density_map(std::vector<double>{0.0}, {x}, o);
  EXPECT_EQ(*capped.rule_bins, 11u);
  EXPECT_EQ(capped.centres.size(), 5u);
}

TEST(Bifurcation, QuantileAndSilvermanByHand) {
  // R's quantile(1:4, 0.25) = 1.75 (type 7). For 1..5: quartiles 2 and 4, IQR / 1.34 = 1.4925 <
  // s = sqrt(2.5) = 1.5811, so h = 0.9 x (2 / 1.34) x 5^(-1/5).
  EXPECT_DOUBLE_EQ(quantile(std::vector<double>{4, 1, 3, 2}, 0.25), 1.75);
  EXPECT_DOUBLE_EQ(quantile(std::vector<double>{4, 1, 3, 2}, 1.0), 4.0);
  EXPECT_NEAR(silverman_bandwidth(std::vector<double>{1, 2, 3, 4, 5}), 0.9 * (2.0 / 1.34) * std::pow(5.0, -0.2), 1e-14);
  EXPECT_EQ(silverman_bandwidth(std::vector<double>{2, 2, 2}), 0.0);
}

TEST(Bifurcation, ConstantSamplesGiveFiniteDensities) {
  // Pooled constant 3: the range 3 -/+ max(|3|, 1) / 2 = [1.5, 4.5]; the histogram puts everything
  // in the bin holding 3; the kernel estimate uses one bin width and is finite, normalised and
  // largest there. No NaN, as the header documents.
  const std::vector<std::vector<double>> s = {std::vector<double>(50, 3.0), std::vector<double>(20, 3.0)};
  DensityMapOptions o;
  o.bin_rule = BinRule::fixed;
  o.bins = 7;
  for (auto estimator : {DensityEstimator::histogram, DensityEstimator::kernel}) {
    o.estimator = estimator;
    const DensityMap m = density_map(std::vector<double>{0.0, 1.0}, s, o);
    EXPECT_DOUBLE_EQ(m.edges.front(), 1.5);
    EXPECT_DOUBLE_EQ(m.edges.back(), 4.5);
    for (std::size_t p = 0; p < 2; ++p) {
      EXPECT_NEAR(integral(m, p), 1.0, 1e-12);
      for (double d : m.density[p]) EXPECT_TRUE(std::isfinite(d));
      EXPECT_EQ(std::max_element(m.density[p].begin(), m.density[p].end()) - m.density[p].begin(), 3);  // [2.786, 3.214)
    }
    if (estimator == DensityEstimator::histogram) EXPECT_DOUBLE_EQ(m.density[0][3], 7.0 / 3.0);
    else EXPECT_DOUBLE_EQ(m.bandwidths[0], 3.0 / 7.0);
  }
  // The Freedman-Diaconis rule has no IQR to use: the cap.
  DensityMapOptions nine;
  nine.bins = 9;
  const DensityMap fd = density_map(std::vector<double>{0.0, 1.0}, s, nine);
  EXPECT_FALSE(fd.rule_bins);
  EXPECT_EQ(fd.centres.size(), 9u);
}

TEST(Bifurcation, RefusesBadInput) {
  const std::vector<double> p = {1.0, 2.0};
  const std::vector<std::vector<double>> s = {{0.1, 0.2}, {0.3}};
  auto message = [&](auto&& call) {
    try {
      call();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message([&] { density_map(std::vector<double>{}, {}); }).find("no parameter values"), std::string::npos);
  EXPECT_NE(message([&] { density_map(p, {{0.1}}); }).find("2 parameter values but 1 sample sets"), std::string::npos);
  EXPECT_NE(message([&] { density_map(p, {{0.1}, {}}); }).find("no samples at parameter 2"), std::string::npos);
  EXPECT_NE(message([&] { density_map(p, {{0.1}, {NAN}}); }).find("non-finite"), std::string::npos);
  auto with = [](auto change) {
    DensityMapOptions o;
    change(o);
    return o;
  };
  EXPECT_NE(message([&] { density_map(p, s, with([](auto& o) { o.bins = 0; })); }).find("bins must be >= 1"), std::string::npos);
  EXPECT_NE(message([&] { density_map(p, s, with([](auto& o) { o.low = o.high = 1.0; })); }).find("low < high"), std::string::npos);
  EXPECT_NE(message([&] { density_map(p, s, with([](auto& o) { o.low = 0.0; })); }).find("both ends"), std::string::npos);
  EXPECT_NE(message([&] { density_map(p, s, with([](auto& o) { o.low = 5.0, o.high = 6.0; })); }).find("none of the 2 samples at parameter 1"),
            std::string::npos);
  EXPECT_NE(message([&] { density_map(p, s, with([](auto& o) { o.estimator = DensityEstimator::kernel, o.bandwidth = -1.0; })); }).find("bandwidth"),
            std::string::npos);
  EXPECT_NE(message([&] { map_bifurcation(logistic, p, {.keep = 0}); }).find("keep must be >= 1"), std::string::npos);
  EXPECT_NE(message([&] { map_bifurcation(logistic, std::vector<double>{}); }).find("no parameter values"), std::string::npos);
  // r = 5 sends x0 = 0.5 to 1.25, then below 0 and on to -infinity.
  EXPECT_NE(message([&] { map_bifurcation(logistic, std::vector<double>{5.0}); }).find("parameter 5 from x0 = 0.5 left the finite numbers"),
            std::string::npos);
}

}  // namespace
}  // namespace chaos
