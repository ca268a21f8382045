// The surrogate test for nonlinearity: the rank logic on constructed cases, both discriminating
// statistics against hand-worked values and an independent brute-force predictor, the test's
// bookkeeping against the public surrogate API, Henon and Lorenz rejected, and refusals. The size
// of the test on a linear Gaussian process (200 trials) is in tests/slow/nonlinearity_test.cpp.
#include "chaos/nonlinearity_test.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::Alternative;
using chaos::NonlinearityStatistic;
using chaos::NonlinearityTestOptions;
using chaos::PredictionErrorOptions;

TEST(RankTest, ConstructedRanks) {
  // K = 3 surrogates {1, 2, 3}: the data's rank among the K + 1 = 4 values decides (Theiler et al.
  // 1992); one-sided size 1/4, two-sided 2/4.
  const std::vector<double> s = {2.0, 1.0, 3.0};
  const auto high = chaos::rank_test(5.0, s, Alternative::larger);
  EXPECT_EQ(high.rank, 4u);
  EXPECT_EQ(high.below, 3u);
  EXPECT_EQ(high.above, 0u);
  EXPECT_DOUBLE_EQ(high.significance, 0.25);
  EXPECT_TRUE(high.rejected);
  EXPECT_FALSE(chaos::rank_test(5.0, s, Alternative::smaller).rejected);
  const auto two = chaos::rank_test(5.0, s, Alternative::two_sided);
  EXPECT_TRUE(two.rejected);
  EXPECT_DOUBLE_EQ(two.significance, 0.5);

  const auto low = chaos::rank_test(0.5, s, Alternative::smaller);
  EXPECT_EQ(low.rank, 1u);
  EXPECT_TRUE(low.rejected);
  EXPECT_TRUE(chaos::rank_test(0.5, s, Alternative::two_sided).rejected);
  EXPECT_FALSE(chaos::rank_test(0.5, s, Alternative::larger).rejected);

  const auto middle = chaos::rank_test(2.5, s, Alternative::two_sided);
  EXPECT_EQ(middle.rank, 3u);
  EXPECT_FALSE(middle.rejected);
}

TEST(RankTest, TiesNeverReject) {
  // The data equal to the lowest surrogate is not strictly below all of them.
  const std::vector<double> s = {1.0, 2.0, 3.0};
  const auto t = chaos::rank_test(1.0, s, Alternative::smaller);
  EXPECT_EQ(t.rank, 1u);
  EXPECT_EQ(t.below, 0u);
  EXPECT_EQ(t.above, 2u);
  EXPECT_FALSE(t.rejected);
  EXPECT_FALSE(chaos::rank_test(3.0, s, Alternative::larger).rejected);
  const std::vector<double> all_equal(19, 0.0);
  EXPECT_FALSE(chaos::rank_test(0.0, all_equal, Alternative::two_sided).rejected);
  EXPECT_DOUBLE_EQ(chaos::rank_test(0.0, all_equal, Alternative::smaller).significance, 0.05);
}

TEST(RankTest, StatisticsWithinTheToleranceAreTies) {
  // From the definition of the rank test with ties counted as neither below nor above (the data
  // at the least extreme end of its tie group): K surrogates all tied with the data leave it at
  // neither end, so no alternative rejects; a value one tolerance away is no tie and ranks as usual.
  const double d = 1.00040018;
  const std::vector<double> exact(19, d);
  // Rounding-level differences, as FFT surrogates give (about 1e-13 relative): all below, all
  // above, and both. Compared exactly, the first would be ranked highest and rejected.
  std::vector<double> below(19), above(19), both(19);
  for (std::size_t k = 0; k < 19; ++k) {
    below[k] = d * (1.0 - 1e-13 * static_cast<double>(k + 1));
    above[k] = d * (1.0 + 1e-13 * static_cast<double>(k + 1));
    both[k] = k % 2 ? below[k] : above[k];
  }
  const std::vector<double>* cases[] = {&exact, &below, &above, &both};
  for (const auto* s : cases) {
    for (const Alternative a : {Alternative::two_sided, Alternative::smaller, Alternative::larger}) {
      const auto t = chaos::rank_test(d, *s, a);
      EXPECT_EQ(t.ties, 19u);
      EXPECT_EQ(t.below, 0u);
      EXPECT_EQ(t.above, 0u);
      EXPECT_EQ(t.rank, 1u);
      EXPECT_FALSE(t.rejected) << chaos::to_string(a);
    }
  }
  // The relative tolerance is 1e-9 of the larger magnitude: 0.5e-9 below ties, 2e-9 below does not
  // (then the data is highest: rank K + 1, rejected one-sided upward and two-sided).
  EXPECT_DOUBLE_EQ(chaos::rank_tie_relative, 1e-9);
  EXPECT_EQ(chaos::rank_test(d, std::vector<double>(19, d * (1.0 - 0.5e-9)), Alternative::larger).ties, 19u);
  const auto apart = chaos::rank_test(d, std::vector<double>(19, d * (1.0 - 2e-9)), Alternative::larger);
  EXPECT_EQ(apart.ties, 0u);
  EXPECT_EQ(apart.below, 19u);
  EXPECT_EQ(apart.rank, 20u);
  EXPECT_TRUE(apart.rejected);
  EXPECT_TRUE(chaos::rank_test(d, std::vector<double>(19, d * (1.0 - 2e-9)), Alternative::two_sided).rejected);
  // Zeros: the absolute floor 1e-12 ties values that are zero up to rounding; 1e-11 is no tie.
  EXPECT_DOUBLE_EQ(chaos::rank_tie_absolute, 1e-12);
  const std::vector<double> near_zero = {1e-15, -1e-15, 0.0, 5e-13};
  EXPECT_EQ(chaos::rank_test(0.0, near_zero, Alternative::smaller).ties, 4u);
  EXPECT_FALSE(chaos::rank_test(0.0, near_zero, Alternative::two_sided).rejected);
  const auto off_zero = chaos::rank_test(0.0, std::vector<double>(4, 1e-11), Alternative::smaller);
  EXPECT_EQ(off_zero.above, 4u);
  EXPECT_TRUE(off_zero.rejected);
  // A mixed case, counted by hand: {d, d (1 + 1e-12), 0.5, 2, 3} around d: two ties, one below,
  // two above; rank 1 + 1 = 2; below + above + ties = K.
  const std::vector<double> mixed = {d, d * (1.0 + 1e-12), 0.5, 2.0, 3.0};
  const auto m = chaos::rank_test(d, mixed, Alternative::two_sided);
  EXPECT_EQ(m.ties, 2u);
  EXPECT_EQ(m.below, 1u);
  EXPECT_EQ(m.above, 2u);
  EXPECT_EQ(m.rank, 2u);
  EXPECT_FALSE(m.rejected);
  // One tie at the tested end is enough to keep the data from rejecting: {d (1 + 1e-13), 2, 3}
  // with the data below the other two.
  const auto end = chaos::rank_test(d, std::vector<double>{d * (1.0 + 1e-13), 2.0, 3.0}, Alternative::smaller);
  EXPECT_EQ(end.ties, 1u);
  EXPECT_EQ(end.above, 2u);
  EXPECT_FALSE(end.rejected);
  // Equal infinities tie; an infinity and the largest finite value do not.
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(chaos::rank_test(inf, std::vector<double>{inf, inf}, Alternative::two_sided).ties, 2u);
  const double largest = std::numeric_limits<double>::max();
  const auto big = chaos::rank_test(largest, std::vector<double>{inf, inf}, Alternative::smaller);
  EXPECT_EQ(big.ties, 0u);
  EXPECT_TRUE(big.rejected);
}

TEST(RankTest, TwoSidedNeedsTwoSurrogates) {
  // With K = 1 the data's value is below or above the one surrogate's unless they tie, so a
  // two-sided test would reject every untied series: its size 2/(K+1) is 1. Refused; one-sided
  // tests keep K = 1 (size 1/2, reported).
  const std::vector<double> one = {1.0};
  EXPECT_THROW(chaos::rank_test(2.0, one, Alternative::two_sided), chaos::InvalidInput);
  EXPECT_DOUBLE_EQ(chaos::rank_test(2.0, one, Alternative::larger).significance, 0.5);
  EXPECT_TRUE(chaos::rank_test(2.0, one, Alternative::larger).rejected);
  NonlinearityTestOptions o;
  o.surrogates = 1;
  EXPECT_THROW(o.validate(), chaos::InvalidInput);
  o.alternative = Alternative::smaller;
  EXPECT_NO_THROW(o.validate());
  o.alternative = Alternative::two_sided;
  o.surrogates = 2;
  EXPECT_NO_THROW(o.validate());
}

TEST(TimeReversalAsymmetry, HandWorked) {
  // x = (0, 1, 3, 2), delay 1: increments (1, 2, -1); <d^3> = 8/3, <d^2> = 2, Q = (8/3) / 2^1.5.
  const std::vector<double> x = {0.0, 1.0, 3.0, 2.0};
  EXPECT_NEAR(chaos::time_reversal_asymmetry(x), (8.0 / 3.0) / std::pow(2.0, 1.5), 1e-15);
  // Delay 2: increments (3, 1); <d^3> = 14, <d^2> = 5, Q = 14 / 5^1.5.
  EXPECT_NEAR(chaos::time_reversal_asymmetry(x, 2), 14.0 / std::pow(5.0, 1.5), 1e-15);
  // Reversing time negates every increment, hence Q (analytic).
  const std::vector<double> r(x.rbegin(), x.rend());
  EXPECT_NEAR(chaos::time_reversal_asymmetry(r), -chaos::time_reversal_asymmetry(x), 1e-15);
  // A series that repeats itself after `delay` samples has only zero increments: Q = 0 by definition.
  const std::vector<double> periodic = {1.0, 4.0, 1.0, 4.0, 1.0};
  EXPECT_EQ(chaos::time_reversal_asymmetry(periodic, 2), 0.0);
  // Scale invariance: Q is a skewness.
  std::vector<double> scaled = x;
  for (auto& v : scaled) v = 1000.0 * v + 7.0;
  EXPECT_NEAR(chaos::time_reversal_asymmetry(scaled), chaos::time_reversal_asymmetry(x), 1e-12);
}

// Locally constant predictor straight from its definition: every admissible candidate's distance,
// a full sort by (distance, index), the first k. Shares no code with the library's sweep.
double brute_force_prediction_error(const std::vector<double>& x, const PredictionErrorOptions& o) {
  const std::size_t ahead = (o.dimension - 1) * o.delay + o.horizon;
  const std::size_t p = x.size() - ahead;
  const auto distance = [&](std::size_t i, std::size_t j) {
    double acc = 0.0;
    for (std::size_t c = 0; c < o.dimension; ++c) {
      const double d = std::abs(x[i + c * o.delay] - x[j + c * o.delay]);
      acc = o.norm == chaos::Norm::max ? std::max(acc, d) : acc + d * d;
    }
    return o.norm == chaos::Norm::max ? acc : std::sqrt(acc);
  };
  double mean = 0.0;
  for (const double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double var = 0.0;
  for (const double v : x) var += (v - mean) * (v - mean);
  const double sd = std::sqrt(var / static_cast<double>(x.size()));
  double sum = 0.0;
  for (std::size_t i = 0; i < p; ++i) {
    std::vector<std::pair<double, std::size_t>> c;
    for (std::size_t j = 0; j < p; ++j)
      if ((i > j ? i - j : j - i) > o.theiler) c.push_back({distance(i, j), j});
    std::sort(c.begin(), c.end());
    double prediction = 0.0;
    for (std::size_t n = 0; n < o.neighbours; ++n) prediction += x[c[n].second + ahead];
    prediction /= static_cast<double>(o.neighbours);
    sum += (prediction - x[i + ahead]) * (prediction - x[i + ahead]);
  }
  return std::sqrt(sum / static_cast<double>(p)) / sd;
}

TEST(PredictionError, EqualsBruteForce) {
  std::vector<std::vector<double>> inputs;
  inputs.push_back(chaos::henon(400).components[0]);
  inputs.push_back(chaos::ar1(300, 0.8, 2).components[0]);
  chaos::Random rng(5);
  std::vector<double> quantised(300);  // few distinct values: many equal distances, the tie rule decides
  for (auto& v : quantised) v = static_cast<double>(rng.below(4));
  inputs.push_back(quantised);
  for (const auto& x : inputs)
    for (const auto norm : {chaos::Norm::max, chaos::Norm::euclidean})
      for (const PredictionErrorOptions base : {PredictionErrorOptions{}, PredictionErrorOptions{2, 3, 2, 1, 5},
                                                PredictionErrorOptions{4, 1, 1, 8, 20}}) {
        PredictionErrorOptions o = base;
        o.norm = norm;
        EXPECT_NEAR(chaos::prediction_error(x, o), brute_force_prediction_error(x, o), 1e-12)
            << "m " << o.dimension << " tau " << o.delay << " k " << o.neighbours << " w " << o.theiler;
      }
}

TEST(PredictionError, PeriodicSeriesIsPredictedExactly) {
  // A pattern of period 7 repeated 20 times: in m = 3 every point's nearest neighbours are copies
  // of itself a whole number of periods away (distance 0), whose futures are its own (analytic):
  // the error is exactly 0 while k <= copies outside the Theiler window.
  const std::vector<double> pattern = {0.3, 1.7, -0.4, 2.2, 0.9, -1.1, 0.0};
  std::vector<double> x;
  for (int r = 0; r < 20; ++r) x.insert(x.end(), pattern.begin(), pattern.end());
  PredictionErrorOptions o;
  o.neighbours = 4;
  o.theiler = 6;
  EXPECT_EQ(chaos::prediction_error(x, o), 0.0);
}

TEST(NonlinearityTest, BookkeepingMatchesThePublicPieces) {
  // The surrogates are those of chaos::surrogates(x, K, seed, options.surrogate) and each statistic
  // is the public function applied to one of them (nonlinearity_test.hpp).
  const auto x = chaos::henon(300).components[0];
  NonlinearityTestOptions o;
  o.statistic = NonlinearityStatistic::time_reversal_asymmetry;
  o.surrogates = 9;
  o.seed = 17;
  const auto r = chaos::nonlinearity_test(x, o);
  const auto s = chaos::surrogates(x, 9, 17, o.surrogate);
  ASSERT_EQ(r.surrogate_statistics.size(), 9u);
  EXPECT_EQ(r.data_statistic, chaos::time_reversal_asymmetry(x));
  for (std::size_t k = 0; k < 9; ++k) {
    EXPECT_EQ(r.surrogate_statistics[k], chaos::time_reversal_asymmetry(s[k].values)) << k;
    EXPECT_EQ(r.surrogate_iterations[k], s[k].iterations);
    EXPECT_EQ(r.surrogate_spectral_deviations[k], s[k].spectral_deviation);
  }
  const auto t = chaos::rank_test(r.data_statistic, r.surrogate_statistics, o.alternative);
  EXPECT_EQ(r.test.rank, t.rank);
  EXPECT_EQ(r.test.rejected, t.rejected);
  EXPECT_DOUBLE_EQ(r.test.significance, 2.0 / 10.0);
  EXPECT_EQ(r.options.surrogates, 9u);
}

TEST(NonlinearityTest, EmbeddedTestIsTheOneSidedPredictionTestOnTheEndMatchedHead) {
  // embedded_nonlinearity_test (the pipelines' test) is nonlinearity_test on the end-matched first
  // `length` samples, one-sided (smaller), prediction error in the given embedding (its header).
  const auto x = chaos::henon(1500).components[0];
  const auto e = chaos::embedded_nonlinearity_test(x, 1000, 2, 1, 3, 19, 5);
  const auto head = std::span<const double>(x).first(1000);
  const auto m = chaos::end_match(head);
  EXPECT_EQ(e.segment.offset, m.offset);
  EXPECT_EQ(e.segment.length, m.length);
  NonlinearityTestOptions o;
  o.alternative = Alternative::smaller;
  o.surrogates = 19;
  o.seed = 5;
  o.prediction.dimension = 2;
  o.prediction.delay = 1;
  o.prediction.theiler = 3;
  const auto r = chaos::nonlinearity_test(head.subspan(m.offset, m.length), o);
  EXPECT_EQ(e.result.data_statistic, r.data_statistic);
  EXPECT_EQ(e.result.surrogate_statistics, r.surrogate_statistics);
  EXPECT_EQ(e.result.test.rank, r.test.rank);
  EXPECT_TRUE(e.result.test.rejected);  // Henon: deterministic (HenonIsRejected)
  EXPECT_DOUBLE_EQ(e.result.test.significance, 1.0 / 20.0);
}

TEST(NonlinearityTest, SawtoothIsTimeAsymmetric) {
  // Slow rise, sudden fall (period 16, plus small Gaussian noise): the increments are skewed to the
  // negative side, Q << 0. IAAFT surrogates are time-reversible by construction (random phases),
  // so the data rank lowest among all K + 1 = 40 values (constructed case).
  chaos::Random rng(3);
  std::vector<double> x(1024);
  for (std::size_t t = 0; t < x.size(); ++t) x[t] = static_cast<double>(t % 16) + 0.3 * rng.gaussian();
  NonlinearityTestOptions o;
  o.statistic = NonlinearityStatistic::time_reversal_asymmetry;
  const auto r = chaos::nonlinearity_test(x, o);
  EXPECT_LT(r.data_statistic, -1.0);
  EXPECT_EQ(r.test.rank, 1u);
  EXPECT_TRUE(r.test.rejected);
  EXPECT_DOUBLE_EQ(r.test.significance, 0.05);  // two-sided, K = 39
}

TEST(NonlinearityTest, HenonIsRejected) {
  // The Henon map is deterministic and nonlinear (Henon 1976): its x is predicted far better than
  // any linear-Gaussian surrogate's (Schreiber & Schmitz 2000 use it as their first example), and
  // it is strongly time-asymmetric. Both statistics reject at the two-sided 5% level (K = 39).
  const auto x = chaos::henon(1024).components[0];
  const auto prediction = chaos::nonlinearity_test(x);
  EXPECT_TRUE(prediction.test.rejected);
  EXPECT_EQ(prediction.test.rank, 1u);
  EXPECT_EQ(prediction.surrogates_not_converged, 0u);
  NonlinearityTestOptions o;
  o.statistic = NonlinearityStatistic::time_reversal_asymmetry;
  EXPECT_TRUE(chaos::nonlinearity_test(x, o).test.rejected);
}

TEST(NonlinearityTest, LorenzIsRejected) {
  // Lorenz x sampled at dt = 0.05, embedded with m = 3, tau = 3 samples, Theiler window 10
  // samples: the zeroth-order predictor beats every IAAFT surrogate (Lorenz 1963 is deterministic).
  // Time reversal on x would not do: the Lorenz equations are symmetric under (x, y) -> (-x, -y),
  // so <(dx)^3> vanishes on the attractor; on z, which has no such symmetry, it rejects.
  const auto t = chaos::lorenz(2048, {}, {0.05, 0.005, 100.0});
  NonlinearityTestOptions o;
  o.prediction.delay = 3;
  o.prediction.theiler = 10;
  const auto r = chaos::nonlinearity_test(t.components[0], o);
  EXPECT_TRUE(r.test.rejected);
  EXPECT_EQ(r.test.rank, 1u);
  o.statistic = NonlinearityStatistic::time_reversal_asymmetry;
  EXPECT_TRUE(chaos::nonlinearity_test(t.components[2], o).test.rejected);
}

template <class F>
void expect_refusal(const F& f, chaos::ErrorCode code, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning '" << fragment << "'";
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(NonlinearityTest, SpikeSeriesTiesAndDoesNotReject) {
  // 4,999 ones then one 2, K = 19, two-sided (chaos nonlinearity -n 19). A property: the IAAFT
  // surrogates of a two-valued series are permutations of it (one 2 among ones), and the
  // prediction error does not depend on where the 2 stands, so every surrogate's statistic equals
  // the data's up to rounding (they agree to 13 digits). Compared exactly, the data's ranked first
  // and the test rejected; as ties it cannot.
  std::vector<double> x(5000, 1.0);
  x.back() = 2.0;
  NonlinearityTestOptions o;
  o.surrogates = 19;
  const auto r = chaos::nonlinearity_test(x, o);
  for (const double s : r.surrogate_statistics) EXPECT_NEAR(s, r.data_statistic, 1e-12 * r.data_statistic);
  EXPECT_EQ(r.test.ties, 19u);
  EXPECT_FALSE(r.test.rejected);
}

TEST(NonlinearityTest, Refusals) {
  using chaos::ErrorCode;
  const auto x = chaos::henon(200).components[0];
  NonlinearityTestOptions o;
  o.surrogates = 0;
  expect_refusal([&] { chaos::nonlinearity_test(x, o); }, ErrorCode::invalid_parameter,
                 "at least 1 surrogate is needed (got 0)");
  o = {};
  o.time_reversal_delay = 0;
  expect_refusal([&] { chaos::nonlinearity_test(x, o); }, ErrorCode::invalid_parameter, "time_reversal_delay");
  o = {};
  o.prediction.neighbours = 0;
  expect_refusal([&] { chaos::nonlinearity_test(x, o); }, ErrorCode::invalid_parameter,
                 "neighbours must be at least 1");
  o = {};
  o.prediction.dimension = 0;
  expect_refusal([&] { chaos::nonlinearity_test(x, o); }, ErrorCode::invalid_parameter, "dimension must be at least 1");
  o = {};
  o.surrogate.max_iterations = 0;
  expect_refusal([&] { chaos::nonlinearity_test(x, o); }, ErrorCode::invalid_parameter, "max_iterations");
  o = {};
  o.prediction.theiler = 100;
  expect_refusal([&] { chaos::nonlinearity_test(x, o); }, ErrorCode::too_short,
                 "need N >= (m - 1) tau + horizon + k + 2 theiler + 1");
  const std::vector<double> constant(100, 1.0);
  expect_refusal([&] { chaos::nonlinearity_test(constant); }, ErrorCode::constant, "constant");
  auto bad = x;
  bad[3] = std::nan("");
  expect_refusal([&] { chaos::nonlinearity_test(bad); }, ErrorCode::non_finite, "sample 3 is nan");
  expect_refusal([&] { chaos::time_reversal_asymmetry(x, 0); }, ErrorCode::invalid_parameter, "delay must be");
  expect_refusal([&] { chaos::time_reversal_asymmetry(std::vector<double>{1.0, 2.0}, 2); }, ErrorCode::too_short,
                 "needs N > delay");
  expect_refusal([&] { chaos::rank_test(1.0, std::vector<double>{}, Alternative::smaller); },
                 ErrorCode::invalid_parameter, "no surrogate statistics");
  expect_refusal([&] { chaos::rank_test(std::nan(""), std::vector<double>{1.0}, Alternative::smaller); },
                 ErrorCode::invalid_parameter, "NaN");
}

}  // namespace
