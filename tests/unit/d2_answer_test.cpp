// The answers of D2 (d2_answer.hpp) and the zoo's finite-record reference (zoo_state_d2.hpp).
// Expected values come from:
//   - the rules as stated in d2_answer.hpp, on correlation-dimension results built by hand (which
//     value, which interval, which status for each detailed status, the floors of the interval);
//   - brute force: the state's correlation sums equal a direct count over every pair;
//   - a cited value: Henon D2 = 1.21 +- 0.01 (Grassberger & Procaccia,
//     Physica D 9, 189 (1983); references/references.tsv), with a band of 0.1 for a finite record;
//   - a property: white noise has no D2, so no confident one.
#include "chaos/d2_answer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "chaos/automatic_analysis.hpp"
#include "chaos/models/systems.hpp"
#include "chaos/models/zoo.hpp"
#include "chaos/models/zoo_state_d2.hpp"

namespace {

using chaos::CorrelationDimensionResult;
using chaos::D2Plateau;
using chaos::D2Status;
using chaos::Estimate;
using chaos::EstimateStatus;
using chaos::Interval;

CorrelationDimensionResult saturated(double d2, Interval interval) {
  CorrelationDimensionResult r;
  r.status = D2Status::saturated;
  r.d2 = d2;
  r.d2_interval = interval;
  r.scaling_region = Interval{0.1, 1.0};
  r.saturation_dimensions_used = {4, 5, 6};
  r.plateaus = {D2Plateau{Interval{0.1, 1.0}, d2, interval}};
  r.eckmann_ruelle_limit = 10.0;
  return r;
}

bool holds(const Estimate& e, double v) { return e.interval && e.interval->low <= v && v <= e.interval->high; }

TEST(D2Answer, ANarrowReproducedPlateauIsConfidentAndItsIntervalSpansTheHalvesAndTheFloor) {
  CorrelationDimensionResult r = saturated(2.0, Interval{1.95, 2.06});
  r.first_half_status = D2Status::saturated;
  r.second_half_status = D2Status::saturated;
  r.first_half_d2 = 1.93;
  r.second_half_d2 = 2.08;
  const Estimate e = chaos::d2_answer(r);
  EXPECT_EQ(e.status, EstimateStatus::confident) << e.reason;
  EXPECT_DOUBLE_EQ(*e.value, 2.0);
  // The halves span [1.93, 2.08]: the confident floor, 0.1 either side, is wider.
  EXPECT_DOUBLE_EQ(e.interval->low, 2.0 - chaos::d2_confident_floor);
  EXPECT_DOUBLE_EQ(e.interval->high, 2.0 + chaos::d2_confident_floor);
  // Before the floor (the zoo's state reference), the interval is what the plateau and halves read.
  const Estimate reading = chaos::d2_reading(r);
  EXPECT_EQ(reading.status, EstimateStatus::confident);
  EXPECT_DOUBLE_EQ(reading.interval->low, 1.93);
  EXPECT_DOUBLE_EQ(reading.interval->high, 2.08);
  // A second half further out than the floor widens the interval to it (half-width 0.095: confident).
  r.first_half_d2 = 1.95;
  r.second_half_d2 = 2.14;
  const Estimate wider = chaos::d2_answer(r);
  EXPECT_EQ(wider.status, EstimateStatus::confident) << wider.reason;
  EXPECT_DOUBLE_EQ(wider.interval->low, 1.9);
  EXPECT_DOUBLE_EQ(wider.interval->high, 2.14);
}

TEST(D2Answer, AWideIntervalAnotherPlateauOrTheEckmannRuelleLimitMakeItRough) {
  const Estimate wide = chaos::d2_answer(saturated(2.0, Interval{1.85, 2.12}));  // half-width 0.135
  EXPECT_EQ(wide.status, EstimateStatus::rough);
  EXPECT_DOUBLE_EQ(*wide.value, 2.0);

  CorrelationDimensionResult other = saturated(1.23, Interval{1.2, 1.26});
  other.other_plateaus = {D2Plateau{Interval{0.005, 0.015}, 1.12, Interval{1.1, 1.14}}};
  const Estimate e = chaos::d2_answer(other);
  EXPECT_EQ(e.status, EstimateStatus::rough);
  EXPECT_TRUE(holds(e, 1.12)) << "the interval spans the other reading";
  EXPECT_NE(e.reason.find("another plateau"), std::string::npos) << e.reason;

  // The same reading at larger scales than the region [0.1, 1] is the attractor's larger-scale shape,
  // not a rival for the small-scale limit: reported in the reason, no downgrade, no wider interval.
  CorrelationDimensionResult large = saturated(1.23, Interval{1.2, 1.26});
  large.other_plateaus = {D2Plateau{Interval{1.5, 4.0}, 1.05, Interval{1.03, 1.07}}};
  const Estimate l = chaos::d2_answer(large);
  EXPECT_EQ(l.status, EstimateStatus::confident) << l.reason;
  EXPECT_FALSE(holds(l, 1.05)) << "the interval is the plateau's own, at least +-0.1";
  EXPECT_NE(l.reason.find("at larger scales"), std::string::npos) << l.reason;
  // Overlapping the region's upper end is not "above": it still withdraws confidence.
  large.other_plateaus = {D2Plateau{Interval{0.9, 4.0}, 1.05, Interval{1.03, 1.07}}};
  EXPECT_EQ(chaos::d2_answer(large).status, EstimateStatus::rough);

  CorrelationDimensionResult near = saturated(1.23, Interval{1.2, 1.26});
  near.other_plateaus = {D2Plateau{Interval{0.005, 0.015}, 1.18, Interval{1.16, 1.2}}};  // within 0.1: not a rival
  EXPECT_EQ(chaos::d2_answer(near).status, EstimateStatus::confident);

  CorrelationDimensionResult bare = saturated(2.0, Interval{1.95, 2.05});
  bare.saturation_dimensions_used.clear();  // a result built by hand: still an answer, no crash
  EXPECT_EQ(chaos::d2_answer(bare).status, EstimateStatus::confident);

  CorrelationDimensionResult high = saturated(2.0, Interval{1.95, 2.05});
  high.exceeds_eckmann_ruelle = true;
  EXPECT_EQ(chaos::d2_answer(high).status, EstimateStatus::rough);
}

TEST(D2Answer, SlopesStillMovingAtTheSmallestWellCountedScalesMakeItRough) {
  // Every slope at the smallest well-counted scales more than 0.1 above the plateau: rough, and the
  // interval reaches them.
  CorrelationDimensionResult rising = saturated(1.61, Interval{1.59, 1.70});
  rising.smallest_scales = D2Plateau{Interval{0.0037, 0.005}, 1.94, Interval{1.76, 2.04}};
  const Estimate e = chaos::d2_answer(rising);
  EXPECT_EQ(e.status, EstimateStatus::rough) << e.reason;
  EXPECT_DOUBLE_EQ(*e.value, 1.61);
  EXPECT_TRUE(holds(e, 2.04)) << "the interval reaches the smallest scales' slopes";
  EXPECT_NE(e.reason.find("smallest well-counted scales"), std::string::npos) << e.reason;

  // The same below the plateau.
  CorrelationDimensionResult falling = saturated(2.0, Interval{1.95, 2.05});
  falling.smallest_scales = D2Plateau{Interval{0.01, 0.02}, 1.8, Interval{1.75, 1.85}};
  EXPECT_EQ(chaos::d2_answer(falling).status, EstimateStatus::rough);

  // One slope within 0.1 of the plateau, or slopes on both sides of it: the slope has not clearly
  // moved (lacunarity oscillates around one value), and the answer stays confident with its own
  // interval.
  CorrelationDimensionResult near = saturated(2.0, Interval{1.95, 2.05});
  near.smallest_scales = D2Plateau{Interval{0.01, 0.02}, 2.2, Interval{2.08, 2.3}};
  const Estimate n = chaos::d2_answer(near);
  EXPECT_EQ(n.status, EstimateStatus::confident) << n.reason;
  EXPECT_FALSE(holds(n, 2.3));
  CorrelationDimensionResult both = saturated(2.0, Interval{1.95, 2.05});
  both.smallest_scales = D2Plateau{Interval{0.01, 0.02}, 2.0, Interval{1.8, 2.2}};
  EXPECT_EQ(chaos::d2_answer(both).status, EstimateStatus::confident);
}

TEST(D2Answer, AReadingBelowThePlateauDisputesItOnlyBeyondItsCountingError) {
  // The counting error of a reading from p pairs is pair_counting_error / sqrt(p) (16.5 / sqrt(p) by
  // default), and a reading disputes the value only beyond max(0.1, that error). The numbers are a
  // held-out Lorenz x record's (N = 10^5): a plateau of 2.078, another one below at 2.222 read from
  // 7211 pairs, counting error 16.5 / sqrt(7211) = 0.194, so 0.144 away is within its noise.
  CorrelationDimensionResult few = saturated(2.078, Interval{2.03, 2.13});
  few.other_plateaus = {D2Plateau{Interval{0.038, 0.117}, 2.222, Interval{2.139, 2.292}, 7211}};
  const Estimate f = chaos::d2_answer(few);
  EXPECT_EQ(f.status, EstimateStatus::confident) << f.reason;
  // The same reading from 10^6 pairs (error 0.0165): beyond 0.1 and beyond its error.
  CorrelationDimensionResult many = few;
  many.other_plateaus[0].pairs = 1000000;
  const Estimate m = chaos::d2_answer(many);
  EXPECT_EQ(m.status, EstimateStatus::rough) << m.reason;
  EXPECT_NE(m.reason.find("counting error about 0.0165"), std::string::npos) << m.reason;
  // The boundary: 16.5 / sqrt(p) = 0.144 at p = 13 129; below it the reading is within its error,
  // above it it is not.
  many.other_plateaus[0].pairs = 13050;
  EXPECT_EQ(chaos::d2_answer(many).status, EstimateStatus::confident);
  many.other_plateaus[0].pairs = 13200;
  EXPECT_EQ(chaos::d2_answer(many).status, EstimateStatus::rough);
  // The factor is an option: 0 is the bare 0.1 rule.
  chaos::CorrelationDimensionOptions bare;
  bare.pair_counting_error = 0.0;
  EXPECT_EQ(chaos::d2_answer(few, bare).status, EstimateStatus::rough);

  // The smallest scales: every slope more than 0.1 to one side is not enough when their mean lies
  // within the counting error. Slopes 1.80..1.88, mean 1.85, under a plateau of 2.0: from 10^4 pairs
  // the error is 0.165 > 0.15 (confident); from 10^5 pairs it is 0.052 (rough).
  CorrelationDimensionResult falling = saturated(2.0, Interval{1.95, 2.05});
  falling.smallest_scales = D2Plateau{Interval{0.01, 0.02}, 1.85, Interval{1.80, 1.88}, 10000};
  EXPECT_EQ(chaos::d2_answer(falling).status, EstimateStatus::confident);
  falling.smallest_scales->pairs = 100000;
  EXPECT_EQ(chaos::d2_answer(falling).status, EstimateStatus::rough);
  // Linz-Sprott x (N = 10^5, m = 2..4, w = 99): 1.611 against slopes 1.761..2.037, mean 1.932, from
  // 34555 pairs (error 0.089 < 0.321): still rough, the slope still moves.
  CorrelationDimensionResult rising = saturated(1.611, Interval{1.59, 1.70});
  rising.smallest_scales = D2Plateau{Interval{0.0037, 0.005}, 1.932, Interval{1.761, 2.037}, 34555};
  const Estimate r = chaos::d2_answer(rising);
  EXPECT_EQ(r.status, EstimateStatus::rough) << r.reason;
  EXPECT_TRUE(holds(r, 2.037));
}

TEST(D2Answer, AWithdrawnPlateauStillGivesARoughValueWithTheDisagreementInItsInterval) {
  CorrelationDimensionResult r;
  r.status = D2Status::not_reproduced;
  r.plateaus = {D2Plateau{Interval{0.016, 0.076}, 1.254, Interval{1.22, 1.29}}};
  r.first_half_status = D2Status::saturated;
  r.second_half_status = D2Status::saturated;
  r.first_half_d2 = 1.363;
  r.second_half_d2 = 1.227;
  const Estimate e = chaos::d2_answer(r);
  EXPECT_EQ(e.status, EstimateStatus::rough);
  EXPECT_DOUBLE_EQ(*e.value, 1.254);
  EXPECT_TRUE(holds(e, 1.22) && holds(e, 1.363));  // the plateau's slopes and both halves
  // Rough: at least the rough floor, 0.4, either side.
  EXPECT_DOUBLE_EQ(e.interval->low, 1.254 - chaos::d2_rough_floor);
  EXPECT_DOUBLE_EQ(e.interval->high, 1.254 + chaos::d2_rough_floor);

  CorrelationDimensionResult scales;
  scales.status = D2Status::scale_dependent;
  scales.plateaus = {D2Plateau{Interval{0.06, 0.3}, 2.39, Interval{2.3, 2.45}},
                     D2Plateau{Interval{0.0066, 0.012}, 3.05, Interval{2.95, 3.1}}};
  const Estimate s = chaos::d2_answer(scales);
  EXPECT_EQ(s.status, EstimateStatus::rough);
  EXPECT_DOUBLE_EQ(*s.value, 3.05) << "D2 is the small-scale limit";
  EXPECT_DOUBLE_EQ(s.interval->low, 2.3);  // the other plateau, beyond the rough floor
  EXPECT_DOUBLE_EQ(s.interval->high, 3.05 + chaos::d2_rough_floor);

  CorrelationDimensionResult noisy;
  noisy.status = D2Status::noise_limited;
  noisy.plateaus = {D2Plateau{Interval{0.15, 0.61}, 2.46, Interval{2.4, 2.5}}};
  noisy.noise_floor = 0.1;
  EXPECT_EQ(chaos::d2_answer(noisy).status, EstimateStatus::rough);

  CorrelationDimensionResult projected;
  projected.status = D2Status::not_saturated;
  projected.plateaus = {D2Plateau{Interval{0.1, 0.4}, 0.85, Interval{0.82, 0.88}}};
  projected.steepest_lower_dimension = 3;
  projected.steepest_lower_slope = 0.97;
  const Estimate p = chaos::d2_answer(projected);
  EXPECT_EQ(p.status, EstimateStatus::rough);
  EXPECT_TRUE(holds(p, 0.97));
}

TEST(D2Answer, WithoutAPlateauItIsNoneUnlessTheHighestDimensionsAgree) {
  CorrelationDimensionResult growing;
  growing.status = D2Status::not_saturated;
  growing.dimension = {1, 2, 3, 4, 5, 6};
  growing.d2_by_dimension = {0.98, 1.9, 2.8, 3.7, 4.5, 5.3};  // noise: D2(m) follows m
  growing.d2_by_dimension_interval.assign(6, std::nullopt);
  const Estimate g = chaos::d2_answer(growing);
  EXPECT_EQ(g.status, EstimateStatus::none);
  EXPECT_FALSE(g.value);

  CorrelationDimensionResult agreeing = growing;
  agreeing.d2_by_dimension = {0.98, 1.7, 1.95, 2.02, 2.05, 2.08};  // within 2 x 5% of their mean
  const Estimate a = chaos::d2_answer(agreeing);
  EXPECT_EQ(a.status, EstimateStatus::rough);
  EXPECT_NEAR(*a.value, (2.02 + 2.05 + 2.08) / 3.0, 1e-12);
  EXPECT_TRUE(holds(a, 2.02) && holds(a, 2.08));

  CorrelationDimensionResult nothing;
  nothing.status = D2Status::no_scaling_region;
  EXPECT_EQ(chaos::d2_answer(nothing).status, EstimateStatus::none);
}

TEST(D2Answer, WhiteNoiseIsNeverConfident) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  std::vector<double> x(5000);
  for (auto& v : x) v = normal(rng);
  chaos::AutomaticAnalysisOptions options;
  options.rosenstein = options.kantz = options.local_maps = false;
  options.dimension = 6;  // Cao finds none for noise: give one, so that D2 runs
  options.delay = 1;
  const chaos::AutomaticAnalysis a = chaos::analyse_series(x, std::nullopt, options);
  ASSERT_TRUE(a.d2_estimate);
  EXPECT_NE(a.d2_estimate->status, EstimateStatus::confident) << a.d2_estimate->reason;
}

TEST(StateReference, TheStateCountsEqualBruteForceAtEveryWindow) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::size_t n = 700;
  std::vector<std::vector<double>> state(3, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (auto& c : state) c[i] = std::round(u(rng) * 64.0) / 64.0;  // ties at the radii too
  const std::vector<double> radii{0.0625, 0.125, 0.25, 0.5, 0.75};
  const std::vector<std::size_t> windows{0, 4, 30};
  const auto sums = chaos::state_correlation_sums(state, radii, windows);
  ASSERT_EQ(sums.size(), windows.size());
  for (std::size_t q = 0; q < windows.size(); ++q) {
    std::vector<std::uint64_t> expected(radii.size(), 0);
    std::uint64_t admissible = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + windows[q] + 1; j < n; ++j) {
        ++admissible;
        double d = 0.0;
        for (const auto& c : state) d = std::max(d, std::abs(c[i] - c[j]));
        for (std::size_t k = 0; k < radii.size(); ++k) expected[k] += d < radii[k];
      }
    EXPECT_EQ(sums[q].pairs.front(), expected) << "w = " << windows[q];
    EXPECT_EQ(sums[q].examined.front().front(), admissible);
  }
}

TEST(StateReference, APairCapEstimatesTheSameSumsAndTheSameReference) {
  // With a cap, each C(r) is pairs over pairs examined from a random subset of reference points
  // with partners on both sides: an unbiased estimate of the exact C, with a relative error of
  // about 1/sqrt(cap) inflated by the pairs' shared reference points (10% is well outside it; a
  // wrong normalisation, such as ordered pairs over unordered ones, is off by a factor of 2).
  const auto state = chaos::zoo_state(chaos::zoo_system("henon"), 10000);
  const auto radii = chaos::state_radii(state);
  const std::vector<std::size_t> window{1};
  const auto exact = chaos::state_correlation_sums(state, radii, window).front();
  const auto capped = chaos::state_correlation_sums(state, radii, window, 100000, 5).front();
  std::size_t compared = 0;
  for (std::size_t k = 0; k < radii.size(); ++k) {
    if (exact.pairs[0][k] < 1000) continue;
    ++compared;
    EXPECT_NEAR(capped.correlation_sum[0][k] / exact.correlation_sum[0][k], 1.0, 0.1) << "radius " << radii[k];
  }
  EXPECT_GT(compared, 20u);
  const Estimate a = chaos::state_d2_reference(exact), b = chaos::state_d2_reference(capped);
  ASSERT_TRUE(a.value && b.value);
  EXPECT_NEAR(*a.value, *b.value, 0.05);
}

TEST(StateReference, HenonsStateReadsItsCitedD2) {
  const chaos::ZooEntry& henon = chaos::zoo_system("henon");
  const auto state = chaos::zoo_state(henon, 5000);
  ASSERT_EQ(state.size(), 2u);
  const std::vector<std::size_t> window{1};
  const auto sums = chaos::state_correlation_sums(state, chaos::state_radii(state), window);
  const Estimate e = chaos::state_d2_reference(sums.front());
  ASSERT_TRUE(e.value) << e.reason;
  EXPECT_NEAR(*e.value, 1.21, 0.1) << e.reason;
}

TEST(StateReference, AForcedFlowsPhaseBecomesACircleAndADelayEquationHasNoState) {
  const chaos::ZooEntry& duffing = chaos::zoo_system("duffing");
  ASSERT_TRUE(duffing.forced);
  const auto state = chaos::zoo_state(duffing, 200);
  ASSERT_EQ(state.size(), duffing.dimension + 1);  // the phase as two coordinates
  for (std::size_t i = 0; i < 200; ++i) {
    const double r = std::hypot(state[duffing.dimension - 1][i], state[duffing.dimension][i]);
    EXPECT_NEAR(r, std::hypot(state[duffing.dimension - 1][0], state[duffing.dimension][0]), 1e-9);
  }
  EXPECT_TRUE(chaos::zoo_state(chaos::zoo_system("mackey_glass"), 100).empty());
}

}  // namespace
