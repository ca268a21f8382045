// Properties of density maps that must hold for any input: every parameter value's density is
// non-negative and integrates to 1 over the common bins, for both estimators and both bin rules,
// whatever the sample sizes and spreads (including samples of one value); the bins are equal and
// cover the pooled range padded as documented.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "chaos/bifurcation.hpp"
#include "chaos/random.hpp"

namespace chaos {
namespace {

TEST(BifurcationProperty, DensitiesIntegrateToOne) {
  Random rng(99);
  for (int trial = 0; trial < 60; ++trial) {
    const std::size_t count = 1 + rng.below(8);
    std::vector<double> parameters;
    std::vector<std::vector<double>> samples(count);
    for (std::size_t p = 0; p < count; ++p) {
      parameters.push_back(static_cast<double>(p));
      const std::size_t n = 1 + rng.below(300);
      const double centre = 10 * rng.gaussian(), scale = rng.below(4) == 0 ? 0.0 : std::exp(3 * rng.gaussian());
      for (std::size_t i = 0; i < n; ++i) samples[p].push_back(centre + scale * rng.gaussian());
    }
    DensityMapOptions o;
    o.estimator = trial % 2 ? DensityEstimator::kernel : DensityEstimator::histogram;
    o.bin_rule = (trial / 2) % 2 ? BinRule::fixed : BinRule::freedman_diaconis;
    o.bins = 1 + rng.below(300);
    const DensityMap m = density_map(parameters, samples, o);
    ASSERT_EQ(m.edges.size(), m.centres.size() + 1);
    ASSERT_LE(m.centres.size(), o.bins);
    std::vector<double> pooled;
    for (const auto& s : samples) pooled.insert(pooled.end(), s.begin(), s.end());
    const auto [lo, hi] = std::minmax_element(pooled.begin(), pooled.end());
    EXPECT_LT(m.edges.front(), *lo);
    EXPECT_GT(m.edges.back(), *hi);
    const double width = m.edges[1] - m.edges[0];
    for (std::size_t p = 0; p < count; ++p) {
      double integral = 0.0;
      for (double d : m.density[p]) {
        ASSERT_TRUE(std::isfinite(d) && d >= 0.0) << "trial " << trial;
        integral += d * width;
      }
      EXPECT_NEAR(integral, 1.0, 1e-9) << "trial " << trial << " parameter " << p;
    }
  }
}

}  // namespace
}  // namespace chaos
