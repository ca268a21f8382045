// The textbook cases with the pipeline's defaults only (chaos::analyse_series, what `chaos analyze`
// and `chaos.analyze` run): the answer for lambda_1 and D2 is confident and lies within a band of
// the cited value. Values (references/references.tsv):
//   Lorenz (10, 28, 8/3), x at dt = 0.01: lambda_1 = 0.9056 per time unit (Sprott 2003), band 10%;
//     D2 = 2.05 +- 0.01 (Grassberger & Procaccia, Physica D 9, 189 (1983)), band 0.1 for a finite record;
//   Henon (1.4, 0.3), x: lambda_1 = 0.41922 per iteration (Sprott 2003), band 5%;
//   Rossler (0.2, 0.2, 5.7), x at dt = 0.1: lambda_1 = 0.0714 per time unit (Sprott 2003), band 15%.
// Each case runs the whole automatic analysis on 10^4 or 2*10^4 samples (1-2 s in Release): the
// reference tier, so the sanitizer build does not run them.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "chaos/automatic_analysis.hpp"
#include "chaos/estimate.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::Estimate;
using chaos::EstimateStatus;

chaos::AutomaticAnalysis analyse(const std::vector<double>& x, std::optional<double> dt) {
  return chaos::analyse_series(x, dt, chaos::AutomaticAnalysisOptions{});
}

// One analysis, both answers (ctest runs each test in a process of its own).
TEST(TextbookAnswers, LorenzXAtTwentyThousandSamplesIsConfidentWithinTheBands) {
  const auto a = analyse(chaos::lorenz(20000).components[0], 0.01);
  ASSERT_TRUE(a.lyapunov) << a.stopped;
  const Estimate e = a.lyapunov->per_time();
  EXPECT_EQ(e.status, EstimateStatus::confident) << e.reason;
  ASSERT_TRUE(e.value);
  EXPECT_NEAR(*e.value, 0.9056, 0.1 * 0.9056);
  ASSERT_TRUE(a.d2_estimate);
  EXPECT_EQ(a.d2_estimate->status, EstimateStatus::confident) << a.d2_estimate->reason;
  ASSERT_TRUE(a.d2_estimate->value);
  EXPECT_NEAR(*a.d2_estimate->value, 2.05, 0.1);
}

TEST(TextbookAnswers, HenonXAtTenThousandSamplesIsConfidentWithinFivePercent) {
  const std::vector<double> x = chaos::henon(10000).components[0];
  const auto a = analyse(x, std::nullopt);
  ASSERT_TRUE(a.lyapunov) << a.stopped;
  EXPECT_EQ(a.lyapunov->estimate.status, EstimateStatus::confident) << a.lyapunov->estimate.reason;
  ASSERT_TRUE(a.lyapunov->estimate.value);
  EXPECT_NEAR(*a.lyapunov->estimate.value, 0.41922, 0.05 * 0.41922);
}

TEST(TextbookAnswers, RosslerXAtTwentyThousandSamplesIsConfidentWithinFifteenPercent) {
  const std::vector<double> x = chaos::rossler(20000).components[0];  // dt = 0.1
  const auto a = analyse(x, 0.1);
  ASSERT_TRUE(a.lyapunov) << a.stopped;
  const Estimate e = a.lyapunov->per_time();
  EXPECT_EQ(e.status, EstimateStatus::confident) << e.reason;
  ASSERT_TRUE(e.value);
  EXPECT_NEAR(*e.value, 0.0714, 0.15 * 0.0714);
}

}  // namespace
