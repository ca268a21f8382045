// The fast D2 (adaptive_d2.hpp): its promise is checked against the exact counts of the same
// series. Either the rounds were accepted and D2 lies within the target of the exact D2, or the
// exact counts were used; a confident answer further from the exact one is the failure this
// guards against. Also the bookkeeping of the rounds and the refusals.
#include "chaos/adaptive_d2.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/models/systems.hpp"
#include "chaos/models/zoo.hpp"

namespace {

chaos::CorrelationSumOptions lorenz_options() {
  chaos::CorrelationSumOptions o;  // the issue-15 Lorenz job (docs/validation/performance-d2.md) at N = 2*10^4
  o.delay = 17;
  o.min_dimension = 1;
  o.max_dimension = 6;
  o.theiler = 200;
  o.radii = chaos::log_radii(0.25, 5.0, 40);
  return o;
}

chaos::CorrelationSumOptions henon_options() {
  chaos::CorrelationSumOptions o;  // the issue-15 Henon job at N = 2*10^4
  o.delay = 1;
  o.min_dimension = 1;
  o.max_dimension = 4;
  o.theiler = 10;
  o.radii = chaos::log_radii(0.005, 0.4, 40);
  return o;
}

void expect_promise_kept(const std::vector<double>& x, chaos::CorrelationSumOptions o, const chaos::AdaptiveD2Options& fast,
                         const std::string& what) {
  const auto exact = chaos::correlation_dimension(chaos::correlation_sum(x, o));
  ASSERT_TRUE(exact.d2.has_value()) << what << ": the exact counts must saturate for this check";
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    o.seed = seed;
    const auto r = chaos::adaptive_correlation_dimension(x, o, {}, fast);
    const std::string tag = what + " seed " + std::to_string(seed) + ": " + r.explanation;
    if (r.exact) {
      EXPECT_EQ(r.reference_points, 0u) << tag;
      EXPECT_EQ(r.d2.d2, exact.d2) << tag;  // the exact counts, hence the exact D2
      continue;
    }
    ASSERT_FALSE(r.rounds.empty()) << tag;
    if (!r.settled) {
      // No round accepted: the merged counts answer rough, with an interval that holds the exact D2.
      for (std::size_t k = 0; k < r.rounds.size(); ++k) EXPECT_FALSE(r.rounds[k].stable) << tag;
      const chaos::Estimate e = chaos::subsets_answer(r, r.d2);
      EXPECT_EQ(e.status, chaos::EstimateStatus::rough) << tag;
      ASSERT_TRUE(e.interval.has_value()) << tag << ": " << e.reason;
      EXPECT_LE(e.interval->low, *e.value - chaos::d2_rough_floor) << tag;  // the rough floor (d2_answer.hpp)
      EXPECT_GE(e.interval->high, *e.value + chaos::d2_rough_floor) << tag;
      EXPECT_LE(e.interval->low, *exact.d2) << tag << ": " << e.reason;
      EXPECT_GE(e.interval->high, *exact.d2) << tag << ": " << e.reason;
      continue;
    }
    const chaos::AdaptiveD2Round& accepted = r.rounds.back();
    EXPECT_TRUE(accepted.stable) << tag;
    // The accepted round's own evidence: regions that stopped moving, and a small enough error.
    ASSERT_TRUE(accepted.region_shift.has_value()) << tag;
    EXPECT_LE(*accepted.region_shift, fast.region_slack) << tag;
    ASSERT_TRUE(accepted.standard_error.has_value()) << tag;
    EXPECT_LE(fast.confidence * *accepted.standard_error, fast.target) << tag;
    for (std::size_t k = 0; k + 1 < r.rounds.size(); ++k) EXPECT_FALSE(r.rounds[k].stable) << tag;
    EXPECT_EQ(r.reference_points, 2 * r.rounds.back().reference_points) << tag;
    EXPECT_EQ(r.sums.points, r.reference_points) << tag;
    ASSERT_TRUE(r.d2.d2.has_value()) << tag;
    EXPECT_LE(std::abs(*r.d2.d2 - *exact.d2), fast.target) << tag << " (exact " << *exact.d2 << ")";
  }
}

// The zoo's delay, window and dimensions (docs/validation/zoo.md, N = 10^5 rows) and the automatic radii.
chaos::CorrelationSumOptions zoo_options(const std::vector<double>& x, std::size_t delay, std::size_t theiler,
                                         std::size_t max_dimension) {
  chaos::CorrelationSumOptions o;
  o.delay = delay;
  o.theiler = theiler;
  o.max_dimension = max_dimension;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  o.radii = chaos::log_radii((*hi - *lo) / 1000.0, (*hi - *lo) / 4.0, 40);
  return o;
}

chaos::AdaptiveD2Options first_round(std::size_t start) {
  chaos::AdaptiveD2Options fast;
  fast.initial_reference_points = start;
  return fast;
}

TEST(AdaptiveD2, AcceptedBudgetsLandWithinTheTargetOfTheExactD2) {
  expect_promise_kept(chaos::lorenz(20'000).components[0], lorenz_options(), first_round(250), "Lorenz x");
  expect_promise_kept(chaos::henon(20'000).components[0], henon_options(), first_round(250), "Henon x");
}

// `chaos d2 --fast`'s quick look (commands.hpp: one round of 2 x 200 points, one subset from each
// half): unsettled, it answers rough with an interval that holds the exact counts' D2 of the whole
// record, the same promise as the adaptive rounds.
TEST(AdaptiveD2, TheQuickLookOnTheHalvesHoldsTheExactD2) {
  chaos::AdaptiveD2Options quick;
  quick.initial_reference_points = 200;
  quick.budget = 400;
  quick.halves = true;
  expect_promise_kept(chaos::lorenz(20'000).components[0], lorenz_options(), quick, "Lorenz x");
  expect_promise_kept(chaos::henon(20'000).components[0], henon_options(), quick, "Henon x");
}

// On the halves, subset a is the first half's own sums and b the second's (CorrelationSumSubsets
// counts what correlation_sum counts with the same offset and number of reference points), the
// final D2 carries their halves verdict, and the rounds stop where another would pass the budget.
TEST(AdaptiveD2, OnTheHalvesEachSubsetIsItsHalfsSumsWithinTheBudget) {
  const auto x = chaos::lorenz(20'000).components[0];
  const auto o = lorenz_options();
  chaos::AdaptiveD2Options fast;
  fast.initial_reference_points = 100;
  fast.budget = 500;  // rounds of 2 x 100 and 2 x 200 points; a third (800 in all) would pass it
  fast.halves = true;
  const auto r = chaos::adaptive_correlation_dimension(x, o, {}, fast);
  ASSERT_FALSE(r.exact);
  EXPECT_TRUE(r.halves);
  ASSERT_FALSE(r.settled) << r.explanation;  // 2.5 standard errors of 400 points do not fit in 0.02
  ASSERT_EQ(r.rounds.size(), 2u) << r.explanation;
  EXPECT_EQ(r.reference_points, 400u);
  EXPECT_EQ(r.sums.points, 400u);
  EXPECT_NE(r.explanation.find("beyond the budget of 500"), std::string::npos) << r.explanation;
  const std::span<const double> all(x);
  for (std::size_t k = 0; k < 2; ++k) {
    auto sub = o;
    sub.reference_points = r.rounds[k].reference_points;
    const auto first = chaos::correlation_dimension(chaos::correlation_sum(all.first(x.size() / 2), sub));
    const auto second = chaos::correlation_dimension(chaos::correlation_sum(all.subspan(x.size() / 2), sub));
    EXPECT_EQ(r.rounds[k].d2_a, first.d2) << "round " << k;
    EXPECT_EQ(r.rounds[k].d2_b, second.d2) << "round " << k;
    EXPECT_EQ(r.rounds[k].status_a, first.status) << "round " << k;
    EXPECT_EQ(r.rounds[k].status_b, second.status) << "round " << k;
  }
  // The halves verdict (require_reproduced_by_halves) on the merged counts, from the last round.
  ASSERT_EQ(r.rounds.back().status_merged, chaos::D2Status::saturated) << r.explanation;
  EXPECT_EQ(r.d2.first_half_status, r.rounds.back().status_a);
  EXPECT_EQ(r.d2.second_half_status, r.rounds.back().status_b);
  EXPECT_EQ(r.d2.first_half_d2, r.rounds.back().d2_a);
  EXPECT_EQ(r.d2.second_half_d2, r.rounds.back().d2_b);
}

// Two systems --fast was not built on, with the zoo's choices. Without the region and precision
// tests (region_slack and confidence so loose they never refuse) seed 1 broke the promise on both:
// Chen 2.241 against the exact 2.175, Rössler 1.874 against 1.896 (docs/validation/fast-d2-zoo.md has the same
// failure at N = 10^5 on seven runs of 135).
TEST(AdaptiveD2, PromiseHoldsOutOfSample) {
  const auto chen = chaos::zoo_trajectory(chaos::zoo_system("chen"), 20'000).components[0];
  expect_promise_kept(chen, zoo_options(chen, 10, 26, 7), first_round(250), "Chen x");
  const auto rossler = chaos::zoo_trajectory(chaos::zoo_system("rossler"), 20'000).components[0];
  expect_promise_kept(rossler, zoo_options(rossler, 15, 29, 6), first_round(250), "Rossler x");
}

// A half too short to embed (N = 8000, tau = 400, m up to 10: each half of 4000 samples needs
// 9 * 400 + w + 2 = 4002): the subsets come from the whole record and the result says so, where
// counting the halves would have refused the whole run (check_record_halves then reports the half).
TEST(AdaptiveD2, HalvesTooShortToEmbedFallBackToTheWholeRecord) {
  const auto x = chaos::lorenz(8'000).components[0];
  chaos::CorrelationSumOptions o = lorenz_options();
  o.delay = 400;
  o.theiler = 400;
  o.max_dimension = 10;
  chaos::AdaptiveD2Options fast;
  fast.initial_reference_points = 100;
  fast.budget = 200;
  fast.halves = true;
  const auto r = chaos::adaptive_correlation_dimension(x, o, {}, fast);
  EXPECT_FALSE(r.exact);
  EXPECT_FALSE(r.halves);
  ASSERT_EQ(r.rounds.size(), 1u);
  EXPECT_EQ(r.reference_points, 200u);
  EXPECT_EQ(r.explanation.find("each half"), std::string::npos) << r.explanation;
}

TEST(AdaptiveD2, ShortSeriesGoStraightToTheExactCounts) {
  // The default first round (2 x 500 points) fits in an eighth of the embedded points only from
  // P = 8000 on: at N = 8000 (P = 7915) the exact counts are used at once.
  const auto x = chaos::lorenz(8'000).components[0];
  const auto r = chaos::adaptive_correlation_dimension(x, lorenz_options());
  EXPECT_TRUE(r.exact);
  EXPECT_TRUE(r.rounds.empty());
  EXPECT_NE(r.explanation.find("exact counts"), std::string::npos) << r.explanation;
}

// A plateau that alone would be confident (half-width 0.05) read from rounds that never settled:
// the answer turns rough, so its interval takes the rough floor, not the confident one it read
// as (the floor follows the final status, d2_answer.hpp).
TEST(AdaptiveD2, AnUnsettledAnswerTakesTheRoughFloor) {
  chaos::CorrelationDimensionResult d2;
  d2.status = chaos::D2Status::saturated;
  d2.d2 = 2.0;
  d2.d2_interval = chaos::Interval{1.95, 2.05};
  d2.scaling_region = chaos::Interval{0.1, 1.0};
  d2.saturation_dimensions_used = {4, 5, 6};
  d2.plateaus = {chaos::D2Plateau{chaos::Interval{0.1, 1.0}, 2.0, chaos::Interval{1.95, 2.05}}};
  d2.eckmann_ruelle_limit = 10.0;
  ASSERT_EQ(chaos::d2_answer(d2).status, chaos::EstimateStatus::confident);
  chaos::AdaptiveD2Result fast;
  fast.reference_points = 8000;
  chaos::AdaptiveD2Round last;
  last.reference_points = 4000;
  last.d2_a = 1.98;
  last.d2_b = 2.03;
  last.standard_error = 0.01;
  fast.rounds = {last};
  fast.settled = true;
  const chaos::Estimate settled = chaos::subsets_answer(fast, d2);
  EXPECT_EQ(settled.status, chaos::EstimateStatus::confident);
  ASSERT_TRUE(settled.interval.has_value());
  EXPECT_DOUBLE_EQ(settled.interval->low, 2.0 - chaos::d2_confident_floor);
  EXPECT_DOUBLE_EQ(settled.interval->high, 2.0 + chaos::d2_confident_floor);
  fast.settled = false;
  const chaos::Estimate unsettled = chaos::subsets_answer(fast, d2);
  EXPECT_EQ(unsettled.status, chaos::EstimateStatus::rough);
  ASSERT_TRUE(unsettled.interval.has_value());
  EXPECT_DOUBLE_EQ(unsettled.interval->low, 2.0 - chaos::d2_rough_floor);
  EXPECT_DOUBLE_EQ(unsettled.interval->high, 2.0 + chaos::d2_rough_floor);
}

TEST(AdaptiveD2, RefusesAFixedBudgetAndImpossibleTargets) {
  const auto x = chaos::henon(5'000).components[0];
  auto o = henon_options();
  o.reference_points = 100;
  EXPECT_THROW(chaos::adaptive_correlation_dimension(x, o), chaos::InvalidInput);
  o = henon_options();
  o.pairs_per_radius = 1000;
  EXPECT_THROW(chaos::adaptive_correlation_dimension(x, o), chaos::InvalidInput);
  chaos::AdaptiveD2Options bad;
  bad.target = 0.0;
  EXPECT_THROW(chaos::adaptive_correlation_dimension(x, henon_options(), {}, bad), chaos::InvalidInput);
  bad.target = std::nan("");
  EXPECT_THROW(chaos::adaptive_correlation_dimension(x, henon_options(), {}, bad), chaos::InvalidInput);
  bad = {};
  bad.confidence = 0.0;
  EXPECT_THROW(chaos::adaptive_correlation_dimension(x, henon_options(), {}, bad), chaos::InvalidInput);
  bad = {};
  bad.initial_reference_points = 1;
  EXPECT_THROW(chaos::adaptive_correlation_dimension(x, henon_options(), {}, bad), chaos::InvalidInput);
}

}  // namespace
