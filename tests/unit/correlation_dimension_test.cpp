// D2 from correlation sums built by hand: exact power laws C = (eps/eps0)^D give D exactly; slopes
// that grow with m (noise) give "not saturated"; empty sums give "no scaling region"; and the
// Takens-Theiler estimate is exact for an exact power law (its integral is then exact).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "chaos/correlation_dimension.hpp"
#include "chaos/error.hpp"

namespace {

// Appends dimension m with correlation sums c (one per radius of s) and the pair counts they
// stand for out of `pairs_total` examined pairs.
void add_dimension(chaos::CorrelationSumResult& s, std::size_t m, std::vector<double> c, std::uint64_t pairs_total) {
  std::vector<std::uint64_t> pairs;
  for (const double v : c) pairs.push_back(static_cast<std::uint64_t>(std::llround(v * static_cast<double>(pairs_total))));
  s.dimension.push_back(m);
  s.correlation_sum.push_back(std::move(c));
  s.pairs.push_back(std::move(pairs));
  s.examined.emplace_back(s.radius.size(), pairs_total);
}

// Sums for m = 1..dims over radii 0.01..1 with C(eps, m) = min(1, (eps / 2)^slope(m)); pair
// counts from `pairs_total` examined pairs.
chaos::CorrelationSumResult power_law(std::size_t dims, double (*slope)(std::size_t), std::uint64_t pairs_total = 1000000000) {
  chaos::CorrelationSumResult s;
  s.radius = chaos::log_radii(0.01, 1.0, 30);
  s.points = 100000;
  for (std::size_t m = 1; m <= dims; ++m) {
    std::vector<double> c;
    for (const double r : s.radius) c.push_back(std::min(1.0, std::pow(r / 2.0, slope(m))));
    add_dimension(s, m, std::move(c), pairs_total);
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
  EXPECT_TRUE(r.other_plateaus.empty());  // the region is the whole grid: nothing above or below
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

// C(eps) = (eps / knee)^low below the knee and (eps / knee)^high above it (continuous), for every
// m, from 10^10 examined pairs: two exact plateaus meeting at `knee`.
chaos::CorrelationSumResult broken_power_law(std::size_t dims, double knee, double low, double high) {
  auto s = power_law(dims, [](std::size_t) { return 1.0; });
  const double total = 1e10;
  for (std::size_t d = 0; d < dims; ++d)
    for (std::size_t k = 0; k < s.radius.size(); ++k) {
      const double r = s.radius[k] / knee;
      const double c = 1e-5 * std::pow(r, r < 1.0 ? low : high);
      s.correlation_sum[d][k] = c;
      s.pairs[d][k] = static_cast<std::uint64_t>(std::llround(c * total));
      s.examined[d][k] = static_cast<std::uint64_t>(total);
    }
  return s;
}

TEST(CorrelationDimension, APlateauAtSmallerScalesWithAnotherSlopeIsScaleDependent) {
  // The Mackey-Glass tau = 30 shape: slope 3.0 at small radii, 2.4 at large ones. The large-scale
  // plateau has more pairs, but D2 is the small-scale limit: neither is reported as D2.
  const auto r = chaos::correlation_dimension(broken_power_law(5, 0.05, 3.0, 2.4));
  ASSERT_EQ(r.status, chaos::D2Status::scale_dependent) << r.explanation;
  EXPECT_FALSE(r.d2.has_value());
  ASSERT_EQ(r.plateaus.size(), 2u);
  EXPECT_NEAR(r.plateaus[0].slope, 2.4, 0.05);  // the best-supported one
  EXPECT_NEAR(r.plateaus[1].slope, 3.0, 0.05);  // below it
  EXPECT_LT(r.plateaus[1].radii.high, r.plateaus[0].radii.low);

  // Means within twice the tolerance (2.40 against 2.60: allowances [2.28, 2.52] and [2.47, 2.73]
  // overlap) are one plateau seen through oscillating slopes: saturated.
  const auto same = chaos::correlation_dimension(broken_power_law(5, 0.05, 2.6, 2.4));
  EXPECT_EQ(same.status, chaos::D2Status::saturated) << same.explanation;
  ASSERT_EQ(same.plateaus.size(), 1u);

  // The same two slopes with a bump of 3.2 between them (as Henon's lacunar slopes have) are two
  // plateaus: 2.4 over the most radii is D2, and 2.6 below is reported beside it, not judged.
  auto bumped = broken_power_law(5, 0.05, 2.6, 2.4);
  for (std::size_t d = 0; d < bumped.dimension.size(); ++d) {
    const std::size_t n = bumped.radius.size();
    std::vector<double> log_c(n);
    log_c[n - 1] = std::log(1e-2);
    for (std::size_t k = n - 1; k-- > 0;) {  // slope by interval: 2.6, then 3.2 for 4 intervals, then 2.4
      const double slope = k < 9 ? 2.6 : k < 13 ? 3.2 : 2.4;
      log_c[k] = log_c[k + 1] - slope * std::log(bumped.radius[k + 1] / bumped.radius[k]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      bumped.correlation_sum[d][k] = std::exp(log_c[k]);
      bumped.pairs[d][k] = static_cast<std::uint64_t>(std::llround(std::exp(log_c[k]) * 1e16));
      bumped.examined[d][k] = 10'000'000'000'000'000ull;
    }
  }
  const auto two = chaos::correlation_dimension(bumped);
  ASSERT_EQ(two.status, chaos::D2Status::saturated) << two.explanation;
  EXPECT_NEAR(*two.d2, 2.4, 0.01);
  ASSERT_EQ(two.other_plateaus.size(), 1u);
  EXPECT_NEAR(two.other_plateaus[0].slope, 2.6, 0.01);
  EXPECT_LT(two.other_plateaus[0].radii.high, two.scaling_region->low);

  // A different slope only at larger scales (the attractor's edge) leaves the small-scale plateau
  // alone when that one is chosen: here the small-scale stretch has the larger support.
  const auto edge = chaos::correlation_dimension(broken_power_law(5, 0.4, 2.0, 1.0));
  EXPECT_EQ(edge.status, chaos::D2Status::saturated) << edge.explanation;
  ASSERT_TRUE(edge.d2.has_value());
  EXPECT_NEAR(*edge.d2, 2.0, 0.05);
}

TEST(CorrelationDimension, APlateauTheHalvesDoNotReproduceIsWithdrawn) {
  // Exact power laws stand in for the full record and its halves: the rule reads only the three
  // results (the splitting itself is automatic_correlation_dimension's).
  const auto at = [](double d) { return chaos::correlation_dimension(broken_power_law(5, 0.05, d, d)); };
  const auto full = at(2.3);
  ASSERT_EQ(full.status, chaos::D2Status::saturated) << full.explanation;

  // Halves at 2.2 and 2.4: allowances [2.09, 2.31] and [2.28, 2.52] overlap: reproduced, unchanged.
  auto same = full;
  chaos::require_reproduced_by_halves(same, at(2.2), at(2.4));
  EXPECT_EQ(same.status, chaos::D2Status::saturated) << same.explanation;
  EXPECT_EQ(same.d2, full.d2);
  ASSERT_TRUE(same.first_half_d2 && same.second_half_d2);
  EXPECT_NEAR(*same.first_half_d2, 2.2, 1e-6);

  // Halves at 1.97 and 2.5 (Sprott F at N = 10^4): withdrawn, with both halves' values reported.
  // A jackknife error (subset sums) goes with the value: none is left on a withdrawn plateau.
  auto apart = full;
  apart.d2_standard_error = 0.01;
  chaos::require_reproduced_by_halves(apart, at(1.97), at(2.5));
  EXPECT_EQ(apart.status, chaos::D2Status::not_reproduced);
  EXPECT_FALSE(apart.d2.has_value());
  EXPECT_FALSE(apart.d2_interval.has_value());
  EXPECT_FALSE(apart.d2_standard_error.has_value());
  EXPECT_NE(apart.explanation.find("disagree"), std::string::npos) << apart.explanation;

  // A half without a plateau: withdrawn too.
  auto missing = full;
  chaos::require_reproduced_by_halves(missing, at(2.3), chaos::CorrelationDimensionResult{});
  EXPECT_EQ(missing.status, chaos::D2Status::not_reproduced);
  EXPECT_EQ(*missing.second_half_status, chaos::D2Status::no_scaling_region);

  // An unsure full record stays what it was.
  chaos::CorrelationDimensionResult unsure;
  unsure.status = chaos::D2Status::not_saturated;
  chaos::require_reproduced_by_halves(unsure, at(2.3), at(2.3));
  EXPECT_EQ(unsure.status, chaos::D2Status::not_saturated);
}

TEST(CorrelationDimension, APlateauThatMovesWithTheDelayIsWithdrawn) {
  // Exact power laws stand in for the sums at the chosen delay and at twice it; the rule reads only
  // the two results (the second sum is check_delay_variant's). Tolerance 0.05, the default.
  const auto at = [](double d) { return chaos::correlation_dimension(broken_power_law(5, 0.05, d, d)); };
  const auto chosen = at(1.87);
  ASSERT_EQ(chosen.status, chaos::D2Status::saturated) << chosen.explanation;

  // 0.03 apart (inside 0.05): reproduced, unchanged, the variant reported.
  auto close = chosen;
  chaos::require_reproduced_at_delay(close, at(1.90), 30);
  EXPECT_EQ(close.status, chaos::D2Status::saturated) << close.explanation;
  EXPECT_EQ(close.d2, chosen.d2);
  ASSERT_TRUE(close.variant_delay && close.variant_delay_d2);
  EXPECT_EQ(*close.variant_delay, 30u);
  EXPECT_NEAR(*close.variant_delay_d2, 1.90, 1e-6);

  // 0.08 apart (Rossler x at N = 10^5: 1.871 at tau = 15, 1.950 at 30): withdrawn.
  auto apart = chosen;
  apart.d2_standard_error = 0.01;
  chaos::require_reproduced_at_delay(apart, at(1.95), 30);
  EXPECT_EQ(apart.status, chaos::D2Status::not_reproduced);
  EXPECT_FALSE(apart.d2.has_value());
  EXPECT_FALSE(apart.d2_standard_error.has_value());
  EXPECT_FALSE(apart.scaling_region.has_value());
  EXPECT_NE(apart.explanation.find("at delay 30"), std::string::npos) << apart.explanation;

  // The same gap passes a looser tolerance: the rule is the stated one, not a fixed number.
  chaos::CorrelationDimensionOptions loose;
  loose.delay_tolerance = 0.1;
  auto loosened = chosen;
  chaos::require_reproduced_at_delay(loosened, at(1.95), 30, loose);
  EXPECT_EQ(loosened.status, chaos::D2Status::saturated);

  // No plateau at twice the delay: withdrawn too.
  auto missing = chosen;
  chaos::require_reproduced_at_delay(missing, chaos::CorrelationDimensionResult{}, 30);
  EXPECT_EQ(missing.status, chaos::D2Status::not_reproduced);
  EXPECT_EQ(*missing.variant_delay_status, chaos::D2Status::no_scaling_region);

  // An unsure result stays what it was; a negative tolerance is refused.
  chaos::CorrelationDimensionResult unsure;
  unsure.status = chaos::D2Status::not_saturated;
  chaos::require_reproduced_at_delay(unsure, at(1.87), 30);
  EXPECT_EQ(unsure.status, chaos::D2Status::not_saturated);
  chaos::CorrelationDimensionOptions negative;
  negative.delay_tolerance = -0.01;
  auto refused = chosen;
  EXPECT_THROW(chaos::require_reproduced_at_delay(refused, at(1.87), 30, negative), chaos::InvalidInput);
}

TEST(CorrelationDimension, MaxRegionFractionKeepsTheRegionAtSmallScales) {
  // Slope 2.0 below eps = 0.1 and 2.6 above it (a shape bending the slope at large scales, as the
  // curvature of a torus does); the series' range is 1, so a fraction of 0.1 allows radii <= 0.1.
  auto sums = broken_power_law(5, 0.1, 2.0, 2.6);
  sums.range = 1.0;
  const auto open = chaos::correlation_dimension(sums);  // default: no limit
  EXPECT_FALSE(open.max_region_radius.has_value());
  ASSERT_FALSE(open.plateaus.empty());
  EXPECT_GT(open.plateaus[0].radii.high, 0.5) << open.explanation;  // the large-scale plateau is seen

  chaos::CorrelationDimensionOptions capped;
  capped.max_region_fraction = 0.1;
  const auto r = chaos::correlation_dimension(sums, capped);
  ASSERT_EQ(r.status, chaos::D2Status::saturated) << r.explanation;
  ASSERT_TRUE(r.max_region_radius.has_value());
  EXPECT_DOUBLE_EQ(*r.max_region_radius, 0.1);
  EXPECT_NEAR(*r.d2, 2.0, 1e-6);
  EXPECT_LE(r.scaling_region->high, 0.1);
  for (const auto& region : r.region_by_dimension) {
    ASSERT_TRUE(region.has_value());
    EXPECT_LE(region->high, 0.1);
  }
  EXPECT_EQ(r.local_slope[4].size(), sums.radius.size());  // slopes above the limit are still reported
  ASSERT_TRUE(r.local_slope[4].back().has_value());

  // A limit below every radius leaves no region, and the explanation names the limit.
  capped.max_region_fraction = 0.001;
  const auto none = chaos::correlation_dimension(sums, capped);
  EXPECT_EQ(none.status, chaos::D2Status::no_scaling_region);
  EXPECT_NE(none.explanation.find("of the range"), std::string::npos) << none.explanation;

  for (const double bad : {0.0, -0.1, std::nan("")}) {
    capped.max_region_fraction = bad;
    EXPECT_THROW(chaos::correlation_dimension(sums, capped), chaos::InvalidInput) << bad;
  }
}

// Sums for m = 1..6 over radii 0.1..1 (40 log-spaced) whose local slope is 1 for m = 1, 2 for m = 2,
// and for m >= 3 is 3 on a stretch of `crest` e-folds of eps centred at ln eps = -1.15, rising
// steeply (3 per e-fold) on both sides: the crest of a hump, flat for a while but not a scaling
// law. ln C is the integral of the slope, C = 0.5 at the largest radius.
chaos::CorrelationSumResult crest_of_a_hump(double crest) {
  chaos::CorrelationSumResult s;
  s.radius = chaos::log_radii(0.1, 1.0, 40);
  s.points = 100000;
  const double a = -1.15 - crest / 2, b = -1.15 + crest / 2;
  const auto slope = [&](std::size_t m, double x) {
    if (m < 3) return double(m);
    return x < a ? 3.0 - 3.0 * (a - x) : x > b ? 3.0 + 3.0 * (x - b) : 3.0;
  };
  for (std::size_t m = 1; m <= 6; ++m) {
    std::vector<double> c(s.radius.size());
    double log_c = std::log(0.5);
    c.back() = 0.5;
    for (std::size_t k = s.radius.size() - 1; k-- > 0;) {  // integrate the slope downwards in ln eps
      const double x0 = std::log(s.radius[k]), x1 = std::log(s.radius[k + 1]);
      const int steps = 1000;
      for (int i = 0; i < steps; ++i) {
        const double u = x1 - (x1 - x0) * (i + 0.5) / steps;
        log_c -= slope(m, u) * (x1 - x0) / steps;
      }
      c[k] = std::exp(log_c);
    }
    add_dimension(s, m, std::move(c), 1000000000000);
  }
  return s;
}

TEST(CorrelationDimension, APlateauShorterThanAnOctaveIsNotSaturation) {
  // A crest 0.4 e-folds wide (a factor 1.49 in eps): every local slope of m = 4..6 there is within
  // 5% of 3, with enough radii and pairs for a region, but it spans less than the octave a plateau
  // needs (min_plateau_ratio = 2). Found on a slider-crank series: 3.13 over a factor 1.76,
  // against D_KY = 2.00 (docs/reference/correlation_dimension.md, step 3).
  const auto narrow = crest_of_a_hump(0.4);
  const auto r = chaos::correlation_dimension(narrow);
  EXPECT_EQ(r.status, chaos::D2Status::not_saturated) << r.explanation;
  EXPECT_FALSE(r.d2.has_value());
  EXPECT_NE(r.explanation.find("too short"), std::string::npos) << r.explanation;
  // Without the rule (a ratio of 1) the same sums read as saturated at 3: the rule is what refuses.
  chaos::CorrelationDimensionOptions any_width;
  any_width.min_plateau_ratio = 1.0;
  const auto old = chaos::correlation_dimension(narrow, any_width);
  ASSERT_EQ(old.status, chaos::D2Status::saturated) << old.explanation;
  EXPECT_NEAR(*old.d2, 3.0, 0.05);
  EXPECT_LT(old.scaling_region->high / old.scaling_region->low, 2.0);
  // A crest 0.9 e-folds wide (a factor 2.46) is a plateau.
  const auto wide = chaos::correlation_dimension(crest_of_a_hump(0.9));
  ASSERT_EQ(wide.status, chaos::D2Status::saturated) << wide.explanation;
  EXPECT_NEAR(*wide.d2, 3.0, 0.05);
  EXPECT_GE(wide.scaling_region->high / wide.scaling_region->low, 2.0);

  for (const double bad : {0.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    any_width.min_plateau_ratio = bad;
    EXPECT_THROW(chaos::correlation_dimension(narrow, any_width), chaos::InvalidInput) << bad;
  }
}

// Sums for m = 1, 2, ... with C(eps, m) = prefactor * (eps / 2)^slope, one (prefactor, slope) per m,
// over radii 0.01..1. The callers keep C falling with m at every radius, as the maximum norm makes it.
chaos::CorrelationSumResult power_laws(const std::vector<std::pair<double, double>>& curves) {
  chaos::CorrelationSumResult s;
  s.radius = chaos::log_radii(0.01, 1.0, 30);
  s.points = 100000;
  std::size_t m = 0;
  for (const auto& [prefactor, slope] : curves) {
    std::vector<double> c;
    for (const double r : s.radius) c.push_back(prefactor * std::pow(r / 2.0, slope));
    add_dimension(s, ++m, std::move(c), 1000000000);
  }
  return s;
}

// m = 4..7 on 0.1 (eps / 2)^0.85, m = 3 steeper at (eps / 2)^lower: over the plateau of m = 5..7
// the projection m = 3 (>= 2 D2 + 1 = 2.7) reads `lower`.
chaos::CorrelationSumResult steeper_projection(double lower) {
  return power_laws({{1.0, 0.8}, {1.0, 0.9}, {1.0, lower}, {0.1, 0.85}, {0.1, 0.85}, {0.1, 0.85}, {0.1, 0.85}});
}

TEST(CorrelationDimension, APlateauBelowALowerDimensionsSlopeIsNotSaturation) {
  // A projection cannot have a larger correlation dimension than the set it projects. Found on a
  // slider-crank series: m = 8..10 agreed on 0.85 where m = 3 read 0.97, against D_KY = 2.00 from
  // the equations of motion (docs/reference/correlation_dimension.md, step 3).
  const auto sums = steeper_projection(1.2);
  const auto r = chaos::correlation_dimension(sums);
  EXPECT_EQ(r.status, chaos::D2Status::not_saturated) << r.explanation;
  EXPECT_FALSE(r.d2.has_value());
  ASSERT_EQ(r.plateaus.size(), 1u);  // the plateau is still reported
  EXPECT_NEAR(r.plateaus[0].slope, 0.85, 1e-9);
  EXPECT_EQ(r.steepest_lower_dimension, 3u);
  EXPECT_NEAR(*r.steepest_lower_slope, 1.2, 1e-9);
  EXPECT_NE(r.explanation.find("projection"), std::string::npos) << r.explanation;
  // The check off: the same sums read as saturated at 0.85.
  chaos::CorrelationDimensionOptions off;
  off.projection_tolerance = std::numeric_limits<double>::infinity();
  const auto unchecked = chaos::correlation_dimension(sums, off);
  ASSERT_EQ(unchecked.status, chaos::D2Status::saturated) << unchecked.explanation;
  EXPECT_NEAR(*unchecked.d2, 0.85, 1e-9);
  // 8% above the plateau is inside the 10% allowance: saturated, with the lower slope reported.
  const auto close = chaos::correlation_dimension(steeper_projection(0.918));
  ASSERT_EQ(close.status, chaos::D2Status::saturated) << close.explanation;
  EXPECT_EQ(close.steepest_lower_dimension, 3u);
  EXPECT_NEAR(*close.steepest_lower_slope, 0.918, 1e-9);
  // m = 2 < 2 D2 + 1 = 2.7 need not embed the set: a steep m = 2 alone (pairs across the folds of
  // the delay map) does not refuse the plateau of m = 5..7 (C_2 >= C_3 needs 0.005^0.55 >= 0.05).
  const auto folded = chaos::correlation_dimension(
      power_laws({{1.0, 0.8}, {1.0, 1.4}, {0.05, 0.85}, {0.05, 0.85}, {0.05, 0.85}, {0.05, 0.85}, {0.05, 0.85}}));
  ASSERT_EQ(folded.status, chaos::D2Status::saturated) << folded.explanation;
  EXPECT_EQ(folded.steepest_lower_dimension, 3u);
  for (const double bad : {-0.1, std::nan("")}) {
    off.projection_tolerance = bad;
    EXPECT_THROW(chaos::correlation_dimension(sums, off), chaos::InvalidInput) << bad;
  }
}

TEST(CorrelationDimension, SlopesGrowingWithDimensionAreNotSaturated) {
  // Noise-like: D2(m) = m for every m.
  const auto r = chaos::correlation_dimension(power_law(5, [](std::size_t m) { return double(m); }));
  EXPECT_EQ(r.status, chaos::D2Status::not_saturated) << r.explanation;
  EXPECT_FALSE(r.d2.has_value());
  for (std::size_t k = 0; k < 5; ++k) EXPECT_NEAR(*r.d2_by_dimension[k], double(k + 1), 1e-9);
}

// Measurement noise of level eps_n: above it C_m ~ eps^D (D = 2, the attractor), below it every
// dimension fills its space, C_m ~ eps^m (Kantz & Schreiber 2004, ch. 6), continuous at eps_n.
// `below` caps the small-scale slope (infinity: m, noise; 3: another regime of dimension 3); a
// negative `below` sets it to -below times m instead (bursts steeper than m).
chaos::CorrelationSumResult noisy_power_law(std::size_t dims, double eps_n, std::uint64_t pairs_total,
                                            double below = std::numeric_limits<double>::infinity()) {
  chaos::CorrelationSumResult s;
  s.radius = chaos::log_radii(0.01, 1.0, 30);
  s.points = 100000;
  for (std::size_t m = 1; m <= dims; ++m) {
    const double d = std::min(2.0, static_cast<double>(m));
    std::vector<double> c;
    for (const double r : s.radius)
      c.push_back(0.5 * std::pow(std::max(r, eps_n), d) *
                  std::pow(std::min(r / eps_n, 1.0), below < 0.0 ? -below * static_cast<double>(m)
                                                                 : std::min(static_cast<double>(m), std::max(d, below))));
    add_dimension(s, m, std::move(c), pairs_total);
  }
  return s;
}

TEST(CorrelationDimension, APlateauBoundedBelowByNoiseIsNotD2) {
  // eps_n = 0.05: the plateau of m = 4..6 at slope 2 spans [0.05, 1] (a factor 20); below it the
  // slopes are m = 4, 5, 6, all of the way from 2 to m, over every radius down to 0.01, with 10^12
  // examined pairs: noise_limited, the plateau and the noise floor reported, no D2.
  const auto noisy = chaos::correlation_dimension(noisy_power_law(6, 0.05, 1000000000000));
  EXPECT_EQ(noisy.status, chaos::D2Status::noise_limited) << noisy.explanation;
  EXPECT_FALSE(noisy.d2.has_value());
  ASSERT_EQ(noisy.plateaus.size(), 1u);
  EXPECT_NEAR(noisy.plateaus[0].slope, 2.0, 0.05);
  ASSERT_TRUE(noisy.noise_floor.has_value());
  EXPECT_LT(*noisy.noise_floor, noisy.plateaus[0].radii.low);
  ASSERT_EQ(noisy.noise_floor_slopes.size(), 3u);
  EXPECT_GT(noisy.noise_floor_slopes[2], 4.0);  // m = 6: more than halfway from 2 to 6
  EXPECT_NE(noisy.explanation.find("noise"), std::string::npos) << noisy.explanation;

  // The same shape with 10^5 examined pairs: below the plateau only one radius keeps min_pairs (100)
  // pairs, one slope is no regime, and the plateau stands.
  const auto sparse = chaos::correlation_dimension(noisy_power_law(6, 0.05, 100000));
  EXPECT_EQ(sparse.status, chaos::D2Status::saturated) << sparse.explanation;
  EXPECT_FALSE(sparse.noise_floor.has_value());

  // The check can be turned off; the plateau is then the saturated D2 (what a noise-free record with
  // a plateau down to eps_n would give).
  chaos::CorrelationDimensionOptions off;
  off.noise_fill_fraction = std::numeric_limits<double>::infinity();
  const auto unchecked = chaos::correlation_dimension(noisy_power_law(6, 0.05, 1000000000000), off);
  EXPECT_EQ(unchecked.status, chaos::D2Status::saturated) << unchecked.explanation;
  EXPECT_NEAR(*unchecked.d2, 2.0, 0.05);

  // Slopes that rise less than halfway to m below the plateau (slope 3 for m = 4..6: a second regime
  // of another dimension, not noise) are not noise: step 4 finds the second plateau.
  const auto regime = chaos::correlation_dimension(noisy_power_law(6, 0.05, 1000000000000, 3.0));
  EXPECT_EQ(regime.status, chaos::D2Status::scale_dependent) << regime.explanation;
  EXPECT_FALSE(regime.noise_floor.has_value());

  // Bursts: below the plateau every dimension reads 1.5 m (pairs entering at lattice distances, as in
  // a torus sampled at small scales), above m (1 + tolerance): not noise, and the plateau stands.
  const auto bursts = chaos::correlation_dimension(noisy_power_law(6, 0.05, 1000000000000, -1.5));
  EXPECT_EQ(bursts.status, chaos::D2Status::saturated) << bursts.explanation;
  EXPECT_FALSE(bursts.noise_floor.has_value());

  // A fraction of 0 is refused (every slope above the plateau would count as noise).
  chaos::CorrelationDimensionOptions bad;
  bad.noise_fill_fraction = 0.0;
  EXPECT_THROW(chaos::correlation_dimension(noisy_power_law(6, 0.05, 1000000000000), bad), chaos::InvalidInput);
}

// Slope 2 for every m >= 3 at eps >= 0.1; below, the slope rises by `rise` per decade of eps towards
// eps = 0.01, too steeply for a second plateau (5 radii span more than the 5% band): the slope still
// moves below the plateau without settling. m = 1, 2 read m. C is continuous at 0.1.
chaos::CorrelationSumResult rising_below(double rise, std::uint64_t pairs_total) {
  chaos::CorrelationSumResult s;
  s.radius = chaos::log_radii(0.01, 1.0, 30);
  s.points = 100000;
  for (std::size_t m = 1; m <= 6; ++m) {
    std::vector<double> c;
    for (const double r : s.radius) {
      if (m < 3) {
        c.push_back(std::pow(r / 2.0, static_cast<double>(m)));
        continue;
      }
      // ln C = 2 ln(r / 2) above 0.1; below, d ln C / d ln r = 2 + rise * ln(0.1 / r) / ln 10.
      const double u = std::log(std::min(r, 0.1) / 0.1);  // <= 0
      c.push_back(std::pow(std::min(r, 0.1) / 2.0, 2.0) * std::pow(std::max(r, 0.1) / 0.1, 2.0) *
                  std::exp(-0.5 * rise / std::log(10.0) * u * u));
    }
    add_dimension(s, static_cast<std::size_t>(m), std::move(c), pairs_total);
  }
  return s;
}

TEST(CorrelationDimension, TheSmallestWellCountedScalesBelowThePlateauAreReported) {
  // Step 7. A rise of 1.5 per decade below eps = 0.1: the plateau of m = 4..6 reads 2 over [0.1, 1],
  // and the lowest three radii (as many as a plateau's local slopes need: 5 points, half-width 1)
  // read 2 + 1.5 log10(0.1 / eps), analytically 3.5, 3.4 and 3.3 at eps = 0.01, 0.0117 and 0.0137.
  const auto r = chaos::correlation_dimension(rising_below(1.5, 1000000000000));
  ASSERT_EQ(r.status, chaos::D2Status::saturated) << r.explanation;
  EXPECT_NEAR(*r.d2, 2.0, 0.05);
  ASSERT_TRUE(r.smallest_scales.has_value());
  EXPECT_NEAR(r.smallest_scales->radii.low, 0.01, 1e-12);
  EXPECT_NEAR(r.smallest_scales->radii.high, r.radius[2], 1e-12);
  EXPECT_GT(r.smallest_scales->slopes.low, 3.1);
  EXPECT_LT(r.smallest_scales->slopes.high, 3.6);

  // Fewer pairs: 10^8 examined, C(0.01) = 2.5e-5 exp(-0.326 ln(10)^2), about 4.5e-6, holds some 450
  // pairs, so the reported radii start where every saturating dimension has 10^4 of them, higher up
  // and still below the plateau.
  const auto fewer_sums = rising_below(1.5, 100000000);
  const auto fewer = chaos::correlation_dimension(fewer_sums);
  ASSERT_TRUE(fewer.smallest_scales.has_value()) << fewer.explanation;
  const std::size_t first = static_cast<std::size_t>(
      std::find(fewer.radius.begin(), fewer.radius.end(), fewer.smallest_scales->radii.low) - fewer.radius.begin());
  ASSERT_LT(first, fewer.radius.size());
  EXPECT_GT(first, 0u);
  for (std::size_t d = 3; d < 6; ++d) {
    EXPECT_GE(fewer_sums.pairs[d][first], 10000u);
    EXPECT_LT(fewer_sums.pairs[d][first - 1], 10000u);
  }
  // The reading carries the fewest pairs of its dimensions and radii (by brute force over them),
  // from which d2_answer weighs it.
  std::uint64_t fewest = std::numeric_limits<std::uint64_t>::max();
  for (std::size_t d = 3; d < 6; ++d)
    for (std::size_t k = first; k < first + 3; ++k) fewest = std::min(fewest, fewer_sums.pairs[d][k]);
  EXPECT_EQ(fewer.smallest_scales->pairs, fewest);

  // A finite set of points below eps = 0.02 (counts that stop changing, slope 0): no dimension can be
  // read there, so the reported radii start above it.
  auto finite = rising_below(1.5, 1000000000000);
  for (std::size_t d = 0; d < finite.dimension.size(); ++d) {
    std::size_t k0 = 0;
    while (finite.radius[k0] < 0.02) ++k0;
    for (std::size_t k = 0; k < k0; ++k) {
      finite.correlation_sum[d][k] = finite.correlation_sum[d][k0];
      finite.pairs[d][k] = finite.pairs[d][k0];
    }
  }
  const auto lattice = chaos::correlation_dimension(finite);
  ASSERT_TRUE(lattice.finite_set_below.has_value()) << lattice.explanation;
  ASSERT_TRUE(lattice.smallest_scales.has_value()) << lattice.explanation;
  EXPECT_GT(lattice.smallest_scales->radii.low, *lattice.finite_set_below);
  EXPECT_GT(lattice.smallest_scales->slopes.low, 2.5);  // the rise, not the lattice's 0

  // Nothing below a plateau that spans the whole grid; nothing when the step is off.
  const auto whole = chaos::correlation_dimension(power_law(6, [](std::size_t m) { return m < 3 ? double(m) : 2.3; }));
  EXPECT_FALSE(whole.smallest_scales.has_value());
  chaos::CorrelationDimensionOptions off;
  off.small_scale_min_pairs = 0;
  EXPECT_FALSE(chaos::correlation_dimension(rising_below(1.5, 1000000000000), off).smallest_scales.has_value());
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

// The counts of `sums` split into `groups` jackknife groups of reference points (as a subset walk
// reports them): group g gets share[g] of every pair count and of every examined count.
void split_into_groups(chaos::CorrelationSumResult& sums, const std::vector<double>& share) {
  sums.group_pairs.assign(share.size(), sums.pairs);
  sums.group_examined.assign(share.size(), sums.examined);
  for (std::size_t g = 0; g < share.size(); ++g)
    for (std::size_t d = 0; d < sums.pairs.size(); ++d)
      for (std::size_t k = 0; k < sums.pairs[d].size(); ++k) {
        sums.group_pairs[g][d][k] = static_cast<std::uint64_t>(std::llround(share[g] * static_cast<double>(sums.pairs[d][k])));
        sums.group_examined[g][d][k] =
            static_cast<std::uint64_t>(std::llround(share[g] * static_cast<double>(sums.examined[d][k])));
      }
}

TEST(CorrelationDimension, GroupsThatAgreeGiveJackknifeErrorsOfZero) {
  // Four groups with a quarter of every count each: every leave-one-out curve is the full curve
  // (C is a ratio of counts that all shrink by 3/4), so every local slope and D2 have a jackknife
  // error of 0 (Efron & Tibshirani's formula with identical replicates), no slope is left out, and
  // D2 is the exact power law's 2.3 as without groups.
  auto sums = power_law(6, [](std::size_t m) { return m < 3 ? double(m) : 2.3; }, 4'000'000'000);
  split_into_groups(sums, {0.25, 0.25, 0.25, 0.25});
  const auto r = chaos::correlation_dimension(sums);
  ASSERT_EQ(r.status, chaos::D2Status::saturated) << r.explanation;
  EXPECT_NEAR(*r.d2, 2.3, 1e-9);
  ASSERT_TRUE(r.d2_standard_error.has_value());
  EXPECT_NEAR(*r.d2_standard_error, 0.0, 1e-6);
  EXPECT_EQ(r.slopes_too_uncertain, 0u);
  ASSERT_EQ(r.local_slope_error.size(), 6u);
  for (const auto& row : r.local_slope_error)
    for (const auto& e : row)
      if (e) {
        EXPECT_NEAR(*e, 0.0, 1e-6);
      }
  // Exact counts (no groups): no jackknife at all.
  const auto exact = chaos::correlation_dimension(power_law(6, [](std::size_t m) { return m < 3 ? double(m) : 2.3; }));
  EXPECT_TRUE(exact.local_slope_error.empty());
  EXPECT_FALSE(exact.d2_standard_error.has_value());
}

TEST(CorrelationDimension, SlopesOneGroupCarriesAreLeftOut) {
  // Below eps = 0.1 every pair comes from group 0 (one reference point's neighbourhood, say); the
  // other three groups have none there. Leaving group 0 out empties those radii, so their slopes
  // have no jackknife error and cannot be trusted: they are left out of the search, and the
  // region starts where all four groups contribute (the local slope at 0.1's grid point still
  // leans on the radius below it, so the region starts one grid point higher). D2 is still 2.3.
  auto sums = power_law(6, [](std::size_t m) { return m < 3 ? double(m) : 2.3; }, 4'000'000'000);
  split_into_groups(sums, {0.25, 0.25, 0.25, 0.25});
  std::size_t first_shared = 0;
  while (sums.radius[first_shared] < 0.1) ++first_shared;
  for (std::size_t d = 0; d < sums.pairs.size(); ++d)
    for (std::size_t k = 0; k < first_shared; ++k) {
      sums.group_pairs[0][d][k] = sums.pairs[d][k];
      for (std::size_t g = 1; g < 4; ++g) sums.group_pairs[g][d][k] = 0;
    }
  const auto r = chaos::correlation_dimension(sums);
  ASSERT_EQ(r.status, chaos::D2Status::saturated) << r.explanation;
  EXPECT_NEAR(*r.d2, 2.3, 1e-9);
  EXPECT_GE(r.slopes_too_uncertain, 3 * first_shared);  // at least those radii in the three top dimensions
  EXPECT_GT(r.scaling_region->low, sums.radius[first_shared - 1]);
  EXPECT_NE(r.explanation.find("jackknife"), std::string::npos) << r.explanation;
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
