// The answers of lambda_1 (estimate.hpp, lyapunov.hpp's LyapunovFit::estimate, lyapunov_answer.hpp):
// a value with an interval and a status wherever a fit exists. Expected values come from:
//   - analytic curves: a straight divergence curve of slope s has every least-squares slope equal
//     to s, so the estimate is s and its interval [s, s]; a curve that never rises has no answer;
//   - the combination rule as stated in lyapunov_answer.hpp (median, span, statuses), on answers
//     built by hand;
//   - a control: white noise is never confident.
// The textbook cases with the defaults only (Lorenz, Henon, Rossler against cited lambda_1) are in
// tests/reference/textbook_answers_test.cpp.
#include "chaos/lyapunov_answer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "chaos/automatic_analysis.hpp"
#include "chaos/estimate.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::DivergenceCurve;
using chaos::Estimate;
using chaos::EstimateStatus;
using chaos::LyapunovFitOptions;
using chaos::LyapunovResult;

// A curve y(k) = f(k), k = 0..steps, with every reference point used.
template <class F>
DivergenceCurve curve(std::size_t steps, F f) {
  DivergenceCurve c;
  for (std::size_t k = 0; k <= steps; ++k) {
    c.step.push_back(k);
    c.divergence.push_back(f(static_cast<double>(k)));
    c.terms.push_back(100);
    c.zero_distances.push_back(0);
  }
  c.points = c.reference_points = c.references_used = 100;
  return c;
}

TEST(Estimate, IncludeWidensAndHalfWidthIsRelative) {
  Estimate e;
  e.value = 2.0;
  e.include(1.8);
  e.include(2.1);
  e.include(1.9);  // inside: no change
  ASSERT_TRUE(e.interval);
  EXPECT_EQ(e.interval->low, 1.8);
  EXPECT_EQ(e.interval->high, 2.1);
  EXPECT_DOUBLE_EQ(e.relative_half_width(), 0.15 / 2.0);
}

TEST(Estimate, DowngradeTurnsConfidentIntoRoughOnlyAndKeepsTheValue) {
  Estimate e{EstimateStatus::confident, 1.0, chaos::Interval{0.95, 1.05}, "narrow"};
  e.downgrade("a half disagrees");
  EXPECT_EQ(e.status, EstimateStatus::rough);
  EXPECT_EQ(e.value, 1.0);
  EXPECT_EQ(e.reason, "narrow; a half disagrees");
  Estimate none;
  none.downgrade("nothing rises");
  EXPECT_EQ(none.status, EstimateStatus::none);
}

TEST(Estimate, ScaledMultipliesValueAndInterval) {
  const Estimate e = chaos::scaled(Estimate{EstimateStatus::rough, 0.01, chaos::Interval{0.009, 0.012}, ""}, 100.0);
  EXPECT_DOUBLE_EQ(*e.value, 1.0);
  EXPECT_DOUBLE_EQ(e.interval->low, 0.9);
  EXPECT_DOUBLE_EQ(e.interval->high, 1.2);
}

// A straight rise of 1.5 e-folds, then a plateau: strictly no linear region (min_rise 2), but the
// answer is the line's slope, exact, and confident (flat within the tolerance, 1 e-fold or more).
TEST(LyapunovFitEstimate, AStraightRiseShorterThanTheStrictRuleStillAnswers) {
  const double slope = 0.015;  // 100 steps: 1.5 e-folds
  const auto c = curve(200, [&](double k) { return slope * std::min(k, 100.0); });
  const auto fit = chaos::fit_divergence(c, LyapunovFitOptions{});
  EXPECT_EQ(fit.status, chaos::LyapunovStatus::no_linear_region);
  EXPECT_FALSE(fit.lambda);
  ASSERT_TRUE(fit.estimate.value);
  EXPECT_NEAR(*fit.estimate.value, slope, 1e-12);
  EXPECT_EQ(fit.estimate.status, EstimateStatus::confident);
  EXPECT_LE(fit.estimate.interval->low, *fit.estimate.value);
  EXPECT_GE(fit.estimate.interval->high, *fit.estimate.value);
}

// A rise whose local slope decays as 0.05 exp(-k/100): over the minimum stretch (37 steps at K =
// 300) the slope falls by 31%, so no stretch is flat within 10% of its mean; within 20% one is. The
// answer is rough (the looser rung), and its interval, spanning the slopes over the stretch's halves,
// holds the value.
TEST(LyapunovFitEstimate, ACurvedRiseIsRough) {
  const auto c = curve(300, [](double k) { return 5.0 * (1.0 - std::exp(-k / 100.0)); });
  const auto fit = chaos::fit_divergence(c, LyapunovFitOptions{});
  EXPECT_EQ(fit.status, chaos::LyapunovStatus::no_linear_region);
  ASSERT_TRUE(fit.estimate.value);
  EXPECT_EQ(fit.estimate.status, EstimateStatus::rough) << fit.estimate.reason;
  EXPECT_LT(fit.estimate.interval->low, *fit.estimate.value);
  EXPECT_GT(fit.estimate.interval->high, *fit.estimate.value);
}

TEST(LyapunovFitEstimate, AFallingCurveHasNoAnswer) {
  const auto c = curve(100, [](double k) { return -0.01 * k; });
  const auto fit = chaos::fit_divergence(c, LyapunovFitOptions{});
  EXPECT_EQ(fit.status, chaos::LyapunovStatus::not_diverging);
  EXPECT_EQ(fit.estimate.status, EstimateStatus::none);
  EXPECT_FALSE(fit.estimate.value);
  EXPECT_FALSE(fit.estimate.reason.empty());
}

LyapunovResult with_answer(EstimateStatus status, std::optional<double> value, double low, double high) {
  LyapunovResult r;
  r.fit.estimate.status = status;
  r.fit.estimate.value = value;
  if (value) r.fit.estimate.interval = chaos::Interval{low, high};
  r.fit.estimate.reason = "by hand";
  return r;
}

// The floors of lyapunov_answer.hpp: a confident interval reaches at least 10% of the value either
// side, a rough one 40%.
TEST(CombineLyapunov, TwoAgreeingAnswersGiveTheirMeanAndTheirSpanAtLeastTheFloor) {
  const auto r = with_answer(EstimateStatus::confident, 1.0, 0.97, 1.03);
  const auto k = with_answer(EstimateStatus::rough, 1.04, 0.99, 1.08);
  const auto a = chaos::combine_lyapunov(&r, &k, nullptr, 0.5);
  EXPECT_EQ(a.estimate.status, EstimateStatus::confident);
  EXPECT_DOUBLE_EQ(*a.estimate.value, 1.02);
  EXPECT_DOUBLE_EQ(a.estimate.interval->low, 1.02 * 0.9);  // the span [0.97, 1.08] is narrower
  EXPECT_DOUBLE_EQ(a.estimate.interval->high, 1.02 * 1.1);
  EXPECT_DOUBLE_EQ(*a.per_time().value, 2.04);  // per time unit, dt = 0.5
}

TEST(CombineLyapunov, ASpanWiderThanTenPercentIsRoughAndKeepsItsSpan) {
  const auto r = with_answer(EstimateStatus::confident, 1.0, 0.6, 1.03);
  const auto k = with_answer(EstimateStatus::confident, 1.3, 1.25, 1.7);
  const auto a = chaos::combine_lyapunov(&r, &k, nullptr);
  EXPECT_EQ(a.estimate.status, EstimateStatus::rough);
  EXPECT_DOUBLE_EQ(*a.estimate.value, 1.15);
  EXPECT_DOUBLE_EQ(a.estimate.interval->low, 0.6);   // wider than 1.15 * 0.6 = 0.69
  EXPECT_DOUBLE_EQ(a.estimate.interval->high, 1.7);  // wider than 1.15 * 1.4 = 1.61
}

TEST(CombineLyapunov, OneAnswerAloneIsRoughAndNoAnswerIsNone) {
  const auto r = with_answer(EstimateStatus::confident, 1.0, 0.99, 1.01);
  const auto k = with_answer(EstimateStatus::none, std::nullopt, 0, 0);
  const auto one = chaos::combine_lyapunov(&r, &k, nullptr);
  EXPECT_EQ(one.estimate.status, EstimateStatus::rough);
  EXPECT_EQ(one.estimate.value, 1.0);
  EXPECT_DOUBLE_EQ(one.estimate.interval->low, 0.6);  // its own [0.99, 1.01] widened to the rough floor
  EXPECT_DOUBLE_EQ(one.estimate.interval->high, 1.4);
  const auto none = chaos::combine_lyapunov(&k, &k, nullptr);
  EXPECT_EQ(none.estimate.status, EstimateStatus::none);
  EXPECT_FALSE(none.estimate.value);
}

TEST(CombineLyapunov, ConsistentLocalMapsJoinAsTheMediansThirdValue) {
  const auto r = with_answer(EstimateStatus::confident, 1.0, 0.98, 1.02);
  const auto k = with_answer(EstimateStatus::confident, 1.06, 1.04, 1.08);
  chaos::LocalMapResult maps;
  maps.status = chaos::LocalMapStatus::consistent;
  maps.lambda = 1.03;
  maps.lambda_interval = chaos::Interval{1.01, 1.05};
  const auto a = chaos::combine_lyapunov(&r, &k, &maps);
  EXPECT_DOUBLE_EQ(*a.estimate.value, 1.03);
  EXPECT_EQ(a.estimate.status, EstimateStatus::confident);
}

// Three values within 7% of the centre of their span (lyapunov_answer.hpp) confirm one another
// where neither fit is confident and the fits' own intervals spread further: the centre, confident,
// the interval spanning the three and at least 10% either side.
TEST(CombineLyapunov, ThreeAgreeingEstimatorsAreConfidentAboutTheCentreOfTheirSpan) {
  const auto r = with_answer(EstimateStatus::rough, 0.94, 0.80, 1.00);
  const auto k = with_answer(EstimateStatus::rough, 0.97, 0.90, 1.15);
  chaos::LocalMapResult maps;
  maps.status = chaos::LocalMapStatus::consistent;
  maps.lambda = 1.06;  // span [0.94, 1.06]: centre 1.00, half-width 6%
  maps.lambda_interval = chaos::Interval{1.05, 1.07};
  const auto a = chaos::combine_lyapunov(&r, &k, &maps);
  EXPECT_EQ(a.estimate.status, EstimateStatus::confident) << a.estimate.reason;
  EXPECT_DOUBLE_EQ(*a.estimate.value, 1.0);
  EXPECT_DOUBLE_EQ(a.estimate.interval->low, 0.9);
  EXPECT_DOUBLE_EQ(a.estimate.interval->high, 1.1);
  // 8% from the centre is beyond the agreement: no longer the centre of three, but the consistent
  // maps' own answer (next test).
  maps.lambda = 1.10;  // span [0.94, 1.10]: centre 1.02, half-width 7.8%
  const auto wide = chaos::combine_lyapunov(&r, &k, &maps);
  EXPECT_EQ(wide.estimate.status, EstimateStatus::confident);
  EXPECT_EQ(wide.source, "local maps");
  EXPECT_DOUBLE_EQ(*wide.estimate.value, 1.10);
  // Local maps that are not consistent are no third estimator: rough, spanning the fits' intervals.
  maps.lambda = 1.06;
  maps.status = chaos::LocalMapStatus::inconsistent;
  const auto rough = chaos::combine_lyapunov(&r, &k, &maps);
  EXPECT_EQ(rough.estimate.status, EstimateStatus::rough);
  EXPECT_LE(rough.estimate.interval->low, 0.80);
}

// Consistent local maps answer on their own (lyapunov_answer.hpp): their value, confident, the
// interval spanning their variants' range and at least 10% either side, whatever the curves give
// beside them: disagreeing with each other, one alone, or none.
TEST(CombineLyapunov, ConsistentLocalMapsAnswerOnTheirOwn) {
  chaos::LocalMapResult maps;
  maps.status = chaos::LocalMapStatus::consistent;
  maps.lambda = 2.0;
  maps.lambda_interval = chaos::Interval{1.96, 2.04};
  const auto r = with_answer(EstimateStatus::rough, 1.2, 1.0, 1.4);
  const auto k = with_answer(EstimateStatus::rough, 2.6, 2.3, 2.9);
  const auto none = with_answer(EstimateStatus::none, std::nullopt, 0, 0);
  for (const auto& [rosenstein, kantz] : {std::pair{&r, &k}, std::pair{&r, &none}, std::pair{&none, &none}}) {
    const auto a = chaos::combine_lyapunov(rosenstein, kantz, &maps);
    EXPECT_EQ(a.estimate.status, EstimateStatus::confident) << a.estimate.reason;
    EXPECT_EQ(a.source, "local maps");
    EXPECT_DOUBLE_EQ(*a.estimate.value, 2.0);
    EXPECT_DOUBLE_EQ(a.estimate.interval->low, 1.8);  // the variants' [1.96, 2.04] widened to 10%
    EXPECT_DOUBLE_EQ(a.estimate.interval->high, 2.2);
  }
  // A range of the variants wider than 10% stays the interval.
  maps.lambda_interval = chaos::Interval{1.75, 2.1};
  const auto wide = chaos::combine_lyapunov(&none, &none, &maps);
  EXPECT_DOUBLE_EQ(wide.estimate.interval->low, 1.75);
  EXPECT_DOUBLE_EQ(wide.estimate.interval->high, 2.2);
  // Inconsistent maps alone: their base estimate, rough.
  maps.status = chaos::LocalMapStatus::inconsistent;
  maps.lambda.reset();
  maps.lambda_interval.reset();
  maps.base.lambda = 1.9;
  maps.base.maps = 100;
  const auto rough = chaos::combine_lyapunov(&none, &none, &maps);
  EXPECT_EQ(rough.estimate.status, EstimateStatus::rough);
  EXPECT_DOUBLE_EQ(*rough.estimate.value, 1.9);
}

chaos::AutomaticAnalysis lyapunov_only(const std::vector<double>& x, std::optional<double> dt) {
  return chaos::analyse_series(x, dt, chaos::AutomaticAnalysisOptions{});
}

// A control: white noise gets no confident lambda_1.
TEST(LyapunovAnswer, WhiteNoiseIsNotConfident) {
  const std::vector<double> x = chaos::white_noise(5000).components[0];
  const auto a = lyapunov_only(x, std::nullopt);
  if (a.lyapunov) {
    EXPECT_NE(a.lyapunov->estimate.status, EstimateStatus::confident) << a.lyapunov->estimate.reason;
  }
}

}  // namespace
