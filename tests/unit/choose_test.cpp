// The automatic choices (chaos/choose.hpp). The delay: the first mutual-information minimum within
// max_delay samples, else the autocorrelation's first zero crossing; where neither exists there, the
// same two rules up to `windows` Theiler windows. Expected values come from:
//   - the rules themselves, applied here by calling mutual_information and first_minimum directly
//     over the stated ranges: the pipeline must report exactly that delay;
//   - a property of the mutual information of a sampled flow: it depends on the delay in time, not
//     in samples, so Lorenz x sampled ten times finer has its first minimum at about ten times as
//     many samples. The band, 15% of the coarse delay, is the spread of the minimum's position
//     allowed by one sample at dt = 0.01 (tau 17-19 there, docs/validation/zoo.md) plus the binning's noise.
// The fine series (Lorenz x at dt = 0.001, N = 40000) was chosen for the branch it reaches, measured
// before the test was written: no minimum and no zero crossing within 100 samples. The test asserts
// that precondition, so a change that moves it to another branch fails loudly.
#include "chaos/choose.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "chaos/automatic_analysis.hpp"
#include "chaos/cao.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/models/systems.hpp"
#include "chaos/time_scales.hpp"

namespace {

using chaos::AutomaticAnalysisOptions;
using chaos::DelaySearch;
using chaos::DelayChoice;

std::optional<std::size_t> first_minimum_up_to(std::span<const double> x, std::size_t max_delay) {
  chaos::MutualInformationOptions mi;
  mi.max_delay = max_delay;
  mi.boxes = DelaySearch{}.boxes;
  return chaos::first_minimum(chaos::mutual_information(x, mi));
}

std::vector<double> lorenz_x(std::size_t n, double dt) {
  return chaos::lorenz(n, {}, {dt, 0.001, 100.0}).components[0];
}

TEST(ChooseDelay, AMinimumWithinMaxDelayIsTakenAsBefore) {
  const std::vector<double> x = lorenz_x(20000, 0.01);
  const chaos::TimeScales scales = chaos::time_scales(x);
  const auto expected = first_minimum_up_to(x, 100);
  ASSERT_TRUE(expected);
  const DelayChoice d = chaos::choose_delay(x, scales, {});
  ASSERT_TRUE(d.delay) << d.stopped;
  EXPECT_EQ(*d.delay, *expected);
  EXPECT_EQ(d.searched, 100u);
  EXPECT_EQ(d.source, "first mutual-information minimum");
}

TEST(ChooseDelay, AFinelySampledFlowIsSearchedOnToTwoTheilerWindows) {
  const std::vector<double> fine = lorenz_x(40000, 0.001);
  const chaos::TimeScales scales = chaos::time_scales(fine);
  // Precondition: the fixed search of 100 samples finds neither rule's delay.
  ASSERT_FALSE(first_minimum_up_to(fine, 100));
  ASSERT_TRUE(!scales.first_zero_crossing || *scales.first_zero_crossing > 100u);
  const std::size_t limit = 2 * scales.theiler;
  ASSERT_LE(limit, fine.size() / 10);

  const DelayChoice d = chaos::choose_delay(fine, scales, {});
  ASSERT_TRUE(d.delay) << d.stopped;
  const auto expected = first_minimum_up_to(fine, limit);
  ASSERT_TRUE(expected);
  EXPECT_EQ(*d.delay, *expected);
  EXPECT_EQ(d.searched, limit);
  EXPECT_NE(d.source.find("nothing up to 100"), std::string::npos) << d.source;

  // The same delay in time as the coarse series' (dt = 0.01), within 15% of it.
  const std::vector<double> coarse = lorenz_x(20000, 0.01);
  const DelayChoice c = chaos::choose_delay(coarse, chaos::time_scales(coarse), {});
  ASSERT_TRUE(c.delay) << c.stopped;
  EXPECT_NEAR(static_cast<double>(*d.delay) * 0.001, static_cast<double>(*c.delay) * 0.01, 0.15 * static_cast<double>(*c.delay) * 0.01);
}

TEST(ChooseDelay, WithoutTheSecondSearchTheFixedCapStops) {
  const std::vector<double> fine = lorenz_x(40000, 0.001);
  AutomaticAnalysisOptions o;
  o.delay_search.windows = 0;
  const DelayChoice d = chaos::choose_delay(fine, chaos::time_scales(fine), o.delay_search);
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

TEST(ChooseDelay, ADecorrelatedSeriesGetsDelayOneWithoutASearch) {
  const std::vector<double> x = chaos::henon(5000).components[0];
  const DelayChoice d = chaos::choose_delay(x, chaos::time_scales(x), {});
  ASSERT_TRUE(d.delay);
  EXPECT_EQ(*d.delay, 1u);
  EXPECT_EQ(d.searched, 0u);
}

TEST(ChooseTheilerWindow, TheCorrelationTimeAtLeastTheDelay) {
  // The rule, applied to a stated time scale: the window is the longer of the two.
  chaos::TimeScales scales;
  scales.theiler = 12;
  scales.theiler_source = "autocorrelation 1/e time";
  const chaos::TheilerChoice shorter = chaos::choose_theiler_window(scales, 5);
  EXPECT_EQ(shorter.window, 12u);
  EXPECT_EQ(shorter.source, "autocorrelation 1/e time");
  const chaos::TheilerChoice longer = chaos::choose_theiler_window(scales, 19);
  EXPECT_EQ(longer.window, 19u);
  EXPECT_NE(longer.source.find("the delay (19)"), std::string::npos) << longer.source;
}

TEST(ChooseEmbedding, GivenValuesAreKeptAndTheOthersChosenByTheRules) {
  // Lorenz x at dt = 0.01: each left-out value equals the rule's own function on the same series
  // (choose_delay, choose_theiler_window, choose_embedding_dimension), and a given one is kept.
  const std::vector<double> x = lorenz_x(20000, 0.01);
  const chaos::TimeScales scales = chaos::time_scales(x);
  const DelayChoice d = chaos::choose_delay(x, scales);
  ASSERT_TRUE(d.delay);
  const chaos::TheilerChoice w = chaos::choose_theiler_window(scales, *d.delay);
  const chaos::DimensionChoice m = chaos::choose_embedding_dimension(x, *d.delay, w.window);
  ASSERT_TRUE(m.dimension) << m.stopped;

  const chaos::EmbeddingChoice automatic = chaos::choose_embedding(x, {}, {}, {});
  EXPECT_EQ(automatic.delay, *d.delay);
  EXPECT_EQ(automatic.delay_source, d.source);
  EXPECT_EQ(automatic.theiler, w.window);
  EXPECT_EQ(automatic.dimension, m.dimension);
  EXPECT_EQ(automatic.dimension_source, "Cao's E1 saturation");

  const chaos::EmbeddingChoice given = chaos::choose_embedding(x, 3, 7, 4);
  EXPECT_EQ(given.delay, 3u);
  EXPECT_EQ(given.theiler, 7u);
  EXPECT_EQ(given.dimension, 4u);
  EXPECT_EQ(given.delay_source, "given");
  // A given delay still sets the least window when the window is left out.
  EXPECT_EQ(chaos::choose_delay_and_window(x, 500, {}).theiler, 500u);
  // Without the dimension, Cao's method is not run.
  EXPECT_FALSE(chaos::choose_delay_and_window(x, {}, {}).dimension);
}

TEST(ChooseEmbedding, TheDimensionReadsOnlyTheFirstSamples) {
  // The rule (choose.hpp): Cao's method over at most the first dimension_samples samples. Hénon x
  // (delay 1, m = 2: docs/reference/cao.md) followed by 20000 samples of uniform noise, where Cao's
  // method over the whole record would see the noise: the choice must be Cao's on the prefix, to the
  // last bit, and the source must say how much it read. At or below the cap nothing changes.
  std::vector<double> x = chaos::henon(chaos::dimension_samples).components[0];
  std::uint64_t state = 7;
  for (std::size_t i = 0; i < 20000; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    x.push_back(static_cast<double>(state >> 11) * 0x1.0p-53 * 2.0 - 1.0);
  }
  const std::span<const double> prefix = std::span<const double>(x).first(chaos::dimension_samples);
  chaos::CaoOptions c;
  c.max_dimension = 3;  // E1(2) and the step after it: enough for m = 2
  const chaos::CaoResult on_prefix = chaos::cao(prefix, c);
  const chaos::DimensionChoice m = chaos::choose_embedding_dimension(x, 1, 0, 3);
  EXPECT_EQ(m.samples, chaos::dimension_samples);
  EXPECT_EQ(m.cao.E1, on_prefix.E1);
  EXPECT_EQ(m.cao.E2, on_prefix.E2);
  ASSERT_TRUE(m.dimension) << m.stopped;
  EXPECT_EQ(*m.dimension, 2u);
  const chaos::EmbeddingChoice chosen = chaos::choose_embedding(x, 1, 0, {}, {}, 3);
  EXPECT_EQ(chosen.dimension, m.dimension);
  EXPECT_EQ(chosen.dimension_source, "Cao's E1 saturation over the first 100000 of 120000 samples");

  const std::span<const double> short_record = prefix.first(5000);
  const chaos::DimensionChoice whole = chaos::choose_embedding_dimension(short_record, 1, 0, 3);
  EXPECT_EQ(whole.samples, short_record.size());
  EXPECT_EQ(whole.cao.E1, chaos::cao(short_record, c).E1);
  EXPECT_EQ(chaos::choose_embedding(short_record, 1, 0, {}, {}, 3).dimension_source, "Cao's E1 saturation");
}

TEST(ChooseEmbedding, WhereNoRuleAnswersTheFallbackStandsInAndSaysWhy) {
  // Uniform white noise: Cao's E2 stays at 1 (stochastic, Cao 1997), so no rule gives a dimension;
  // the fallback m = 2 stands in and the source names the rule that found nothing. Five samples are
  // too few for the mutual information (N >= max_delay + boxes): the fallback delay stands in there.
  std::vector<double> x(4000);
  std::uint64_t state = 12345;
  for (double& v : x) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    v = static_cast<double>(state >> 11) * 0x1.0p-53;
  }
  const chaos::EmbeddingChoice noise = chaos::choose_embedding(x, {}, {}, {});
  EXPECT_TRUE(noise.fallback);
  EXPECT_EQ(noise.dimension, chaos::fallback_dimension);
  EXPECT_NE(noise.dimension_source.find("stochastic"), std::string::npos) << noise.dimension_source;
  EXPECT_NE(noise.dimension_source.find("fallback"), std::string::npos) << noise.dimension_source;

  const std::vector<double> five{0.0, 0.1, 0.2, 0.3, 0.4};  // correlated beyond lag 1: the information is asked
  const chaos::EmbeddingChoice tiny = chaos::choose_delay_and_window(five, {}, {});
  EXPECT_TRUE(tiny.fallback);
  EXPECT_EQ(tiny.delay, chaos::fallback_delay);
  EXPECT_NE(tiny.delay_source.find("too short"), std::string::npos) << tiny.delay_source;
}

TEST(ChooseLyapunov, AnalyzeBoundsKantzNeighbourhoodsAsTheCommandDoes) {
  // chaos lyapunov represents a Kantz neighbourhood of more than 1000 members by 1000 of them
  // (--max-neighbours, lyapunov.hpp); chaos analyze and the zoo take their options from the same
  // chooser, so the bound (choose.hpp's default_max_neighbours) must reach them too.
  const auto x = chaos::henon(4000).components[0];
  const chaos::TimeScales scales = chaos::time_scales(x);
  const chaos::LyapunovOptions l =
      chaos::choose_lyapunov_options(scales, x.size(), 2, 1, 1, chaos::LyapunovMethod::kantz);
  EXPECT_EQ(l.max_neighbours, chaos::default_max_neighbours);
  EXPECT_EQ(chaos::default_max_neighbours, 1000u);
  AutomaticAnalysisOptions options;
  options.rosenstein = false;
  options.local_maps = false;
  const chaos::AutomaticAnalysis a = chaos::analyse_series(x, std::nullopt, options);
  ASSERT_TRUE(a.kantz.has_value()) << a.stopped;
  EXPECT_EQ(a.kantz->options.max_neighbours, chaos::default_max_neighbours);
}

}  // namespace
