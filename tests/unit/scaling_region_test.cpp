// Local slopes, least-squares fits and the automatic scaling region on curves whose answers are
// known by construction (exact power laws, piecewise-linear slope profiles).

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/scaling_region.hpp"

namespace {

using Curve = std::vector<std::optional<double>>;

TEST(LocalSlopes, ExactOnAStraightLine) {
  // y = 2.5 x + 1: every least-squares fit has slope 2.5 (to rounding), ends included.
  std::vector<double> x;
  Curve y;
  for (int k = 0; k < 10; ++k) {
    x.push_back(-3.0 + 0.4 * k);
    y.push_back(2.5 * x.back() + 1.0);
  }
  for (const auto& s : chaos::local_slopes(x, y, 2)) {
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(*s, 2.5, 1e-12);
  }
}

TEST(LocalSlopes, UndefinedPointsStayUndefinedAndAreSkipped) {
  const std::vector<double> x{0, 1, 2, 3, 4};
  const Curve y{std::nullopt, 1.0, 2.0, std::nullopt, 4.0};
  const auto s = chaos::local_slopes(x, y, 1);
  EXPECT_FALSE(s[0].has_value());
  EXPECT_FALSE(s[3].has_value());
  ASSERT_TRUE(s[1].has_value());
  EXPECT_DOUBLE_EQ(*s[1], 1.0);  // fit through (1,1), (2,2): the undefined neighbour is left out
  EXPECT_THROW(chaos::local_slopes(x, Curve(4), 1), chaos::InvalidInput);
}

TEST(FitSlope, ByHand) {
  // Points (0,0), (1,1), (2,4): least-squares slope = sum (x-1)(y-5/3) / sum (x-1)^2 = 4/2 = 2.
  const std::vector<double> x{0, 1, 2};
  const Curve y{0.0, 1.0, 4.0};
  EXPECT_DOUBLE_EQ(*chaos::fit_slope(x, y, 0, 2), 2.0);
  EXPECT_FALSE(chaos::fit_slope(x, Curve{1.0, std::nullopt, std::nullopt}, 0, 2).has_value());
}

TEST(FindScalingRegion, PicksTheWidestFlatStretchSharedByAllCurves) {
  // Slopes rise 0.5, 1.0, 1.5 then stay at 2 (+-0.02) for indices 3..11, then fall: the region is 3..11.
  std::vector<double> x;
  for (int k = 0; k < 15; ++k) x.push_back(0.1 * k);
  Curve a{0.5, 1.0, 1.5, 2.00, 2.02, 1.98, 2.01, 2.00, 1.99, 2.02, 1.98, 2.00, 1.2, 0.8, 0.3};
  Curve b{0.4, 0.9, 1.6, 2.01, 1.99, 2.00, 2.00, 2.02, 1.98, 2.00, 2.01, 1.99, 1.5, 0.9, 0.2};
  const auto region = chaos::find_scaling_region(x, {a, b});
  ASSERT_TRUE(region.has_value());
  EXPECT_EQ(region->first, 3u);
  EXPECT_EQ(region->last, 11u);
  EXPECT_NEAR(region->slope, 2.0, 0.01);
  EXPECT_DOUBLE_EQ(region->slope_min, 1.98);
  EXPECT_DOUBLE_EQ(region->slope_max, 2.02);
  // A second curve that is flat only on 6..11 narrows the shared region to that.
  Curve c = b;
  c[3] = 2.5;
  c[4] = 2.4;
  c[5] = 2.3;
  const auto narrower = chaos::find_scaling_region(x, {a, c});
  ASSERT_TRUE(narrower.has_value());
  EXPECT_EQ(narrower->first, 6u);
  EXPECT_EQ(narrower->last, 11u);
}

TEST(FindScalingRegion, MinWidthRefusesShorterStretches) {
  // Flat (2.0) on indices 3..8, i.e. 0.5 wide in x, and on 10..19, 0.9 wide; steep in between.
  std::vector<double> x;
  Curve a;
  for (int k = 0; k < 20; ++k) {
    x.push_back(0.1 * k);
    a.push_back(k >= 3 && k <= 8 ? 2.0 : k >= 10 ? 3.0 : 1.0 - 0.2 * k);
  }
  const auto any = chaos::find_scaling_region(x, {a});  // the widest: 10..19
  ASSERT_TRUE(any.has_value());
  EXPECT_EQ(any->first, 10u);
  chaos::ScalingRegionOptions wide;
  wide.min_width = 0.95;  // wider than both: none
  EXPECT_FALSE(chaos::find_scaling_region(x, {a}, wide).has_value());
  wide.min_width = 0.6;  // only 10..19 qualifies, also when it gains less support than 3..8
  std::vector<double> support(20, 0.0);
  for (int k = 0; k < 20; ++k) support[k] = k <= 8 ? 10.0 * k : 80.0 + 0.1 * (k - 8);
  const auto chosen = chaos::find_scaling_region(x, {a}, wide, support);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(chosen->first, 10u);
  EXPECT_EQ(chosen->last, 19u);
  wide.min_width = std::nan("");
  EXPECT_THROW(chaos::find_scaling_region(x, {a}, wide), chaos::InvalidInput);
  wide.min_width = -1.0;
  EXPECT_THROW(chaos::find_scaling_region(x, {a}, wide), chaos::InvalidInput);
}

TEST(FindScalingRegion, NoneWhenNothingIsFlatOrDefined) {
  std::vector<double> x;
  Curve rising, undefined(12);
  for (int k = 0; k < 12; ++k) {
    x.push_back(k);
    rising.push_back(1.0 + 0.3 * k);  // steps of 0.3 on a level of ~2: never within 5%
  }
  EXPECT_FALSE(chaos::find_scaling_region(x, {rising}).has_value());
  EXPECT_FALSE(chaos::find_scaling_region(x, {undefined}).has_value());
  chaos::ScalingRegionOptions bad;
  bad.tolerance = 0.0;
  EXPECT_THROW(chaos::find_scaling_region(x, {rising}, bad), chaos::InvalidInput);
}

}  // namespace
