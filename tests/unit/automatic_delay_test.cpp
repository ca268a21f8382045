// The automatic pipeline's delay (chaos/automatic_analysis.hpp, step 2): the first mutual-information
// minimum within max_delay samples, else the autocorrelation's first zero crossing; where neither
// exists there, the same two rules up to delay_search_windows Theiler windows. Expected values come
// from:
//   - the rules themselves, applied here by calling mutual_information and first_minimum directly
//     over the stated ranges: the pipeline must report exactly that delay;
//   - a property of the mutual information of a sampled flow: it depends on the delay in time, not
//     in samples, so Lorenz x sampled ten times finer has its first minimum at about ten times as
//     many samples. The band, 15% of the coarse delay, is the spread of the minimum's position
//     allowed by one sample at dt = 0.01 (tau 17-19 there, docs/zoo.md) plus the binning's noise.
// The fine series (Lorenz x at dt = 0.001, N = 40000) was chosen for the branch it reaches, measured
// before the test was written: no minimum and no zero crossing within 100 samples. The test asserts
// that precondition, so a change that moves it to another branch fails loudly.
#include "chaos/automatic_analysis.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "chaos/mutual_information.hpp"
#include "chaos/systems.hpp"
#include "chaos/time_scales.hpp"

namespace {

using chaos::AutomaticAnalysisOptions;
using chaos::DelayChoice;

std::optional<std::size_t> first_minimum_up_to(std::span<const double> x, std::size_t max_delay) {
  chaos::MutualInformationOptions mi;
  mi.max_delay = max_delay;
  mi.boxes = AutomaticAnalysisOptions{}.boxes;
  return chaos::first_minimum(chaos::mutual_information(x, mi));
}

std::vector<double> lorenz_x(std::size_t n, double dt) {
  return chaos::lorenz(n, {}, {dt, 0.001, 100.0}).components[0];
}

TEST(AutomaticDelay, AMinimumWithinMaxDelayIsTakenAsBefore) {
  const std::vector<double> x = lorenz_x(20000, 0.01);
  const chaos::TimeScales scales = chaos::time_scales(x);
  const auto expected = first_minimum_up_to(x, 100);
  ASSERT_TRUE(expected);
  const DelayChoice d = chaos::automatic_delay(x, scales, {});
  ASSERT_TRUE(d.delay) << d.stopped;
  EXPECT_EQ(*d.delay, *expected);
  EXPECT_EQ(d.searched, 100u);
  EXPECT_EQ(d.source, "first mutual-information minimum");
}

TEST(AutomaticDelay, AFinelySampledFlowIsSearchedOnToTwoTheilerWindows) {
  const std::vector<double> fine = lorenz_x(40000, 0.001);
  const chaos::TimeScales scales = chaos::time_scales(fine);
  // Precondition: the fixed search of 100 samples finds neither rule's delay.
  ASSERT_FALSE(first_minimum_up_to(fine, 100));
  ASSERT_TRUE(!scales.first_zero_crossing || *scales.first_zero_crossing > 100u);
  const std::size_t limit = 2 * scales.theiler;
  ASSERT_LE(limit, fine.size() / 10);

  const DelayChoice d = chaos::automatic_delay(fine, scales, {});
  ASSERT_TRUE(d.delay) << d.stopped;
  const auto expected = first_minimum_up_to(fine, limit);
  ASSERT_TRUE(expected);
  EXPECT_EQ(*d.delay, *expected);
  EXPECT_EQ(d.searched, limit);
  EXPECT_NE(d.source.find("nothing up to 100"), std::string::npos) << d.source;

  // The same delay in time as the coarse series' (dt = 0.01), within 15% of it.
  const std::vector<double> coarse = lorenz_x(20000, 0.01);
  const DelayChoice c = chaos::automatic_delay(coarse, chaos::time_scales(coarse), {});
  ASSERT_TRUE(c.delay) << c.stopped;
  EXPECT_NEAR(static_cast<double>(*d.delay) * 0.001, static_cast<double>(*c.delay) * 0.01, 0.15 * static_cast<double>(*c.delay) * 0.01);
}

TEST(AutomaticDelay, WithoutTheSecondSearchTheFixedCapStops) {
  const std::vector<double> fine = lorenz_x(40000, 0.001);
  AutomaticAnalysisOptions o;
  o.delay_search_windows = 0;
  const DelayChoice d = chaos::automatic_delay(fine, chaos::time_scales(fine), o);
  EXPECT_FALSE(d.delay);
  EXPECT_EQ(d.searched, 100u);
  EXPECT_EQ(d.stopped, "no mutual-information minimum and no autocorrelation zero crossing up to delay 100: no delay "
                       "can be chosen");

  // And the pipeline stops there with that reason, before any estimate.
  o.rosenstein = o.kantz = o.local_maps = false;
  const chaos::AutomaticAnalysis a = chaos::analyse_series(fine, std::nullopt, o);
  EXPECT_FALSE(a.delay);
  EXPECT_EQ(a.stopped, d.stopped);
  EXPECT_FALSE(a.dimension);
}

TEST(AutomaticDelay, ADecorrelatedSeriesGetsDelayOneWithoutASearch) {
  const std::vector<double> x = chaos::henon(5000).components[0];
  const DelayChoice d = chaos::automatic_delay(x, chaos::time_scales(x), {});
  ASSERT_TRUE(d.delay);
  EXPECT_EQ(*d.delay, 1u);
  EXPECT_EQ(d.searched, 0u);
}

}  // namespace
