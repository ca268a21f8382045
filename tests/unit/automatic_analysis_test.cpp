// The automatic pipeline's local-map step (chaos/automatic_analysis.hpp, step 6): the estimator at
// m, and once more at m + 1 where the run at m is inconsistent. Expected values come from:
//   - the estimator itself, called directly at m and at m + 1 with the pipeline's settings
//     (automatic_local_map_options): the pipeline must report exactly one of those runs, bit for bit,
//     by the stated rule;
//   - the cited Henon value lambda_1 = 0.41922 (Sprott, Chaos and Time-Series Analysis, 2003,
//     App. A; references/references.tsv), band 10% as in the zoo (zoo_suite.hpp).
// The series were chosen for the branch they reach, measured before the test was written: Henon x at
// N = 5000 is inconsistent at m = 2 (the m + 1 variant reads 6% lower) and consistent at m = 3;
// Henon x at N = 20000 is consistent at m = 2; Lorenz x at N = 20000 (tau 19, w 31) is inconsistent
// at m = 3 and at m = 4; white noise is not_deterministic. The tests assert those preconditions, so
// a change to the estimator that moves a series to another branch fails loudly instead of testing
// nothing. The last test checks a property of the whole pipeline: a step that refuses the series
// keeps what the others found.
#include "chaos/automatic_analysis.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/lyapunov_local_maps.hpp"
#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::AutomaticAnalysis;
using chaos::AutomaticAnalysisOptions;
using chaos::LocalMapResult;
using chaos::LocalMapStatus;

// The pipeline with the embedding given, and only the local-map exponent among the Lyapunov steps.
AutomaticAnalysis analyse(std::span<const double> x, std::size_t delay, std::size_t theiler, std::size_t m,
                          bool next_dimension = true) {
  AutomaticAnalysisOptions o;
  o.delay = delay;
  o.theiler = theiler;
  o.dimension = m;
  o.extra_dimensions = 1;
  o.rosenstein = false;
  o.kantz = false;
  o.local_maps_next_dimension = next_dimension;
  return chaos::analyse_series(x, std::nullopt, o);
}

LocalMapResult direct(std::span<const double> x, std::size_t delay, std::size_t theiler, std::size_t m) {
  return chaos::largest_lyapunov_local_maps(x, chaos::choose_local_map_options(m, delay, theiler));
}

TEST(AutomaticAnalysis, InconsistentLocalMapsAtMAreRunAgainAtMPlusOne) {
  const std::vector<double> x = chaos::henon(5000).components[0];
  const LocalMapResult at_2 = direct(x, 1, 1, 2), at_3 = direct(x, 1, 1, 3);
  ASSERT_EQ(at_2.status, LocalMapStatus::inconsistent) << at_2.explanation;
  ASSERT_EQ(at_3.status, LocalMapStatus::consistent) << at_3.explanation;

  const AutomaticAnalysis a = analyse(x, 1, 1, 2);
  ASSERT_TRUE(a.local_maps && a.local_maps_at_m);
  EXPECT_EQ(a.local_maps->status, LocalMapStatus::consistent);
  EXPECT_EQ(a.local_maps->variants.front().dimension, 3u);
  EXPECT_EQ(*a.local_maps->lambda, *at_3.lambda);  // the run at m + 1, bit for bit
  EXPECT_NEAR(*a.local_maps->lambda, 0.41922, 0.1 * 0.41922);
  EXPECT_EQ(a.local_maps_at_m->status, LocalMapStatus::inconsistent);
  EXPECT_EQ(a.local_maps_at_m->variants.front().dimension, 2u);
  EXPECT_EQ(a.local_maps_at_m->explanation, at_2.explanation);
  // The reported explanation names both runs.
  EXPECT_EQ(a.local_maps->explanation, "at m = 3: " + at_3.explanation + "; at m = 2, inconsistent: " + at_2.explanation);

  // Switched off, the run at m stands alone.
  const AutomaticAnalysis off = analyse(x, 1, 1, 2, false);
  ASSERT_TRUE(off.local_maps);
  EXPECT_FALSE(off.local_maps_at_m);
  EXPECT_EQ(off.local_maps->status, LocalMapStatus::inconsistent);
  EXPECT_EQ(off.local_maps->explanation, at_2.explanation);
}

TEST(AutomaticAnalysis, ConsistentLocalMapsAtMAreNotRunAgain) {
  const std::vector<double> x = chaos::henon(20000).components[0];
  const LocalMapResult at_2 = direct(x, 1, 1, 2);
  ASSERT_EQ(at_2.status, LocalMapStatus::consistent) << at_2.explanation;

  const AutomaticAnalysis a = analyse(x, 1, 1, 2);
  ASSERT_TRUE(a.local_maps);
  EXPECT_FALSE(a.local_maps_at_m);
  EXPECT_EQ(a.local_maps->variants.front().dimension, 2u);
  EXPECT_EQ(*a.local_maps->lambda, *at_2.lambda);
  EXPECT_EQ(a.local_maps->explanation, at_2.explanation);
}

TEST(AutomaticAnalysis, WhenMPlusOneIsUnsureTooTheRunAtMIsReportedWithBothReasons) {
  const std::vector<double> x = chaos::lorenz(20000).components[0];
  const LocalMapResult at_3 = direct(x, 19, 31, 3), at_4 = direct(x, 19, 31, 4);
  ASSERT_EQ(at_3.status, LocalMapStatus::inconsistent) << at_3.explanation;
  ASSERT_NE(at_4.status, LocalMapStatus::consistent) << at_4.explanation;

  const AutomaticAnalysis a = analyse(x, 19, 31, 3);
  ASSERT_TRUE(a.local_maps);
  EXPECT_FALSE(a.local_maps_at_m);
  EXPECT_EQ(a.local_maps->status, LocalMapStatus::inconsistent);
  EXPECT_FALSE(a.local_maps->lambda);
  EXPECT_EQ(a.local_maps->variants.front().dimension, 3u);
  EXPECT_EQ(a.local_maps->explanation, at_3.explanation + "; at m = 4, " + chaos::to_string(at_4.status) + ": " +
                                           at_4.explanation);
}

TEST(AutomaticAnalysis, NoiseIsNotRunAgainAtMPlusOne) {
  // Only `inconsistent` is an effect of m that one more dimension can resolve; the maps explaining
  // nothing (white noise) is what the data are.
  chaos::Random random(7);
  std::vector<double> x(5000);
  for (double& v : x) v = random.gaussian();
  const LocalMapResult at_2 = direct(x, 1, 1, 2);
  ASSERT_EQ(at_2.status, LocalMapStatus::not_deterministic) << at_2.explanation;

  const AutomaticAnalysis a = analyse(x, 1, 1, 2);
  ASSERT_TRUE(a.local_maps);
  EXPECT_FALSE(a.local_maps_at_m);
  EXPECT_EQ(a.local_maps->status, LocalMapStatus::not_deterministic);
  EXPECT_EQ(a.local_maps->explanation, at_2.explanation);
}

TEST(AutomaticAnalysis, AStepThatRefusesTheSeriesKeepsWhatTheOthersFound) {
  // A property of the pipeline: an estimator's refusal (here the correlation sums and the divergence
  // curves, whose embedding of m = 40 at delay 100 spans more than the 3000 samples) is reported in
  // `stopped`, and the delay, window and dimension already chosen stand, as do the steps after it
  // (the local maps refuse too and say so in their own field).
  chaos::Random random(11);
  std::vector<double> x(3000);
  for (double& v : x) v = random.gaussian();
  AutomaticAnalysisOptions o;
  o.delay = 100;
  o.theiler = 5;
  o.dimension = 40;
  const AutomaticAnalysis a = chaos::analyse_series(x, std::nullopt, o);
  EXPECT_EQ(a.delay, std::optional<std::size_t>(100));
  EXPECT_EQ(a.theiler, 5u);
  EXPECT_EQ(a.dimension, std::optional<std::size_t>(40));
  EXPECT_FALSE(a.d2);
  EXPECT_FALSE(a.d2_estimate);
  EXPECT_NE(a.stopped.find("correlation dimension not estimated: "), std::string::npos) << a.stopped;
  EXPECT_NE(a.stopped.find("; largest Lyapunov exponent not estimated: "), std::string::npos) << a.stopped;
  EXPECT_FALSE(a.local_maps);
  EXPECT_FALSE(a.local_maps_refusal.empty());
}

TEST(AutomaticAnalysis, ZeroThreadsIsRefusedAsAnOptionNotReportedAsAStoppedStep) {
  // Every step takes options.threads and would refuse 0 on its own (Cao's refusal would end as "no
  // embedding dimension"); the analysis refuses the option before any step runs.
  const auto x = chaos::henon(2000).components[0];
  AutomaticAnalysisOptions o;
  o.threads = 0;
  EXPECT_THROW(chaos::analyse_series(x, std::nullopt, o), chaos::InvalidInput);
}

}  // namespace
