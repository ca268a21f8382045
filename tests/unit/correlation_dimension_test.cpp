// D2 from correlation sums built by hand: exact power laws C = (eps/eps0)^D give D exactly; slopes
// that grow with m (noise) give "not saturated"; empty sums give "no scaling region"; and the
// Takens-Theiler estimate is exact for an exact power law (its integral is then exact).

#include <gtest/gtest.h>

#include <cmath>

#include "chaos/correlation_dimension.hpp"
#include "chaos/error.hpp"

namespace {

// Sums for m = 1..dims over radii 0.01..1 with C(eps, m) = min(1, (eps / 2)^slope(m)); pair
// counts from `pairs_total` examined pairs.
chaos::CorrelationSumResult power_law(std::size_t dims, double (*slope)(std::size_t), std::uint64_t pairs_total = 1000000000) {
  chaos::CorrelationSumResult s;
  s.radius = chaos::log_radii(0.01, 1.0, 30);
  s.points = 100000;
  for (std::size_t m = 1; m <= dims; ++m) {
    s.dimension.push_back(m);
    std::vector<double> c;
    std::vector<std::uint64_t> pairs, examined;
    for (const double r : s.radius) {
      c.push_back(std::min(1.0, std::pow(r / 2.0, slope(m))));
      pairs.push_back(static_cast<std::uint64_t>(std::llround(c.back() * static_cast<double>(pairs_total))));
      examined.push_back(pairs_total);
    }
    s.correlation_sum.push_back(c);
    s.pairs.push_back(pairs);
    s.examined.push_back(examined);
  }
  return s;
}

TEST(CorrelationDimension, ExactPowerLawSaturates) {
  // Slope m for m < 3, then 2.3 for every m >= 3: D2 = 2.3 and the region is the whole grid.
  const auto sums = power_law(6, [](std::size_t m) { return m < 3 ? double(m) : 2.3; });
  const auto r = chaos::correlation_dimension(sums);
  ASSERT_EQ(r.status, chaos::D2Status::saturated) << r.explanation;
  EXPECT_NEAR(*r.d2, 2.3, 1e-9);
  EXPECT_NEAR(r.d2_interval->low, 2.3, 1e-9);
  EXPECT_NEAR(r.d2_interval->high, 2.3, 1e-9);
  EXPECT_EQ(r.saturation_dimensions_used, (std::vector<std::size_t>{4, 5, 6}));
  EXPECT_NEAR(r.scaling_region->low, 0.01, 1e-12);
  EXPECT_NEAR(r.scaling_region->high, 1.0, 1e-12);
  EXPECT_NEAR(*r.d2_by_dimension[0], 1.0, 1e-9);
  EXPECT_NEAR(*r.takens_theiler, 2.3, 1e-9);
  EXPECT_FALSE(r.exceeds_eckmann_ruelle);
  EXPECT_NEAR(r.eckmann_ruelle_limit, 10.0, 1e-12);  // 2 log10(1e5)
}

// A finite set of points at small scales: below eps = 0.05 no pair enters (the counts stay at
// their value there, as for a sine sampled at a rational period), above it C grows as eps^1. The
// stretch of constant counts is long and perfectly flat (slope 0) but carries no information: it
// is never the scaling region, D2 = 1 comes from the radii where pairs enter, and the finite-set
// structure is reported with the radius where it ends.
TEST(CorrelationDimension, RadiiWhereNoPairEntersAreNeverTheRegion) {
  auto sums = power_law(5, [](std::size_t) { return 1.0; });
  std::size_t last_flat = 0;
  for (std::size_t k = 0; k < sums.radius.size(); ++k)
    if (sums.radius[k] < 0.05) last_flat = k;
  for (std::size_t d = 0; d < sums.dimension.size(); ++d)
    for (std::size_t k = 0; k <= last_flat; ++k) {
      sums.pairs[d][k] = sums.pairs[d][last_flat + 1];
      sums.correlation_sum[d][k] = sums.correlation_sum[d][last_flat + 1];
    }
  const auto r = chaos::correlation_dimension(sums);
  ASSERT_EQ(r.status, chaos::D2Status::saturated) << r.explanation;
  EXPECT_NEAR(*r.d2, 1.0, 1e-9);
  EXPECT_GE(r.scaling_region->low, 0.05);
  ASSERT_TRUE(r.finite_set_below.has_value());
  EXPECT_DOUBLE_EQ(*r.finite_set_below, sums.radius[last_flat + 1]);
  EXPECT_NE(r.explanation.find("finite set"), std::string::npos);

  // With only the flat stretch and no radius where pairs enter, there is no region at all (the old
  // rule answered "saturated, D2 = 0").
  for (std::size_t d = 0; d < sums.dimension.size(); ++d)
    for (std::size_t k = 0; k < sums.radius.size(); ++k) {
      sums.pairs[d][k] = 5000;
      sums.correlation_sum[d][k] = 5e-6;
    }
  const auto flat = chaos::correlation_dimension(sums);
  EXPECT_EQ(flat.status, chaos::D2Status::no_scaling_region) << flat.explanation;
  EXPECT_FALSE(flat.d2.has_value());
}

TEST(CorrelationDimension, SlopesGrowingWithDimensionAreNotSaturated) {
  // Noise-like: D2(m) = m for every m.
  const auto r = chaos::correlation_dimension(power_law(5, [](std::size_t m) { return double(m); }));
  EXPECT_EQ(r.status, chaos::D2Status::not_saturated) << r.explanation;
  EXPECT_FALSE(r.d2.has_value());
  for (std::size_t k = 0; k < 5; ++k) EXPECT_NEAR(*r.d2_by_dimension[k], double(k + 1), 1e-9);
}

TEST(CorrelationDimension, EckmannRuelleLimitIsReported) {
  // 1000 points: the limit is 2 log10(1000) = 6; D2(m) = m reaches 8.
  auto sums = power_law(8, [](std::size_t m) { return double(m); });
  sums.points = 1000;
  const auto r = chaos::correlation_dimension(sums);
  EXPECT_TRUE(r.exceeds_eckmann_ruelle);
  EXPECT_NE(r.explanation.find("Eckmann-Ruelle"), std::string::npos);
}

TEST(CorrelationDimension, NoPairsMeansNoScalingRegion) {
  auto sums = power_law(3, [](std::size_t) { return 2.0; });
  for (auto& row : sums.pairs) std::fill(row.begin(), row.end(), 10);  // below min_pairs everywhere
  const auto r = chaos::correlation_dimension(sums);
  EXPECT_EQ(r.status, chaos::D2Status::no_scaling_region);
  EXPECT_FALSE(r.d2.has_value());
}

TEST(CorrelationDimension, RadiiWhereEveryPairIsCloserAreLeftOut) {
  // Slope 0 with C = 1 (every pair within eps: the radius exceeds the set) carries no scaling.
  auto sums = power_law(3, [](std::size_t) { return 0.0; });
  const auto r = chaos::correlation_dimension(sums);
  EXPECT_EQ(r.status, chaos::D2Status::no_scaling_region) << r.explanation;
}

TEST(TakensTheiler, ExactForAPowerLawAndUndefinedWithoutPairs) {
  const auto radius = chaos::log_radii(0.01, 1.0, 20);
  std::vector<double> c;
  for (const double r : radius) c.push_back(std::pow(r, 1.7));
  const auto tt = chaos::takens_theiler(radius, c, 400, 19);
  ASSERT_TRUE(tt.has_value());
  EXPECT_NEAR(tt->first, 1.7, 1e-12);
  EXPECT_NEAR(tt->second, 1.7 / 20.0, 1e-12);  // D / sqrt(pairs)
  EXPECT_FALSE(chaos::takens_theiler(radius, std::vector<double>(20, 0.0), 0, 19).has_value());
}

TEST(CorrelationDimension, RefusesTooFewRadii) {
  chaos::CorrelationSumResult s;
  s.dimension = {1};
  s.radius = {0.1};
  s.correlation_sum = {{0.5}};
  s.pairs = {{5}};
  s.examined = {{10}};
  EXPECT_THROW(chaos::correlation_dimension(s), chaos::InvalidInput);
}

}  // namespace
