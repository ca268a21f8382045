// Mutual information: hand-computed histograms, an independent brute-force estimator, the known
// bias for independent data, the partition entropy at delay 0, the first-minimum rule, refusals,
// and the Lorenz first minimum against the project's acceptance band.
#include "chaos/mutual_information.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::MutualInformationEstimator;
using chaos::MutualInformationOptions;
using chaos::MutualInformationResult;

constexpr MutualInformationEstimator both[] = {MutualInformationEstimator::equal_width,
                                               MutualInformationEstimator::equiprobable};

std::vector<double> uniform_noise(std::size_t n, std::uint64_t seed) {
  chaos::Random rng(seed);
  std::vector<double> x(n);
  for (auto& v : x) v = rng.uniform();
  return x;
}

// Straight from the definitions, sharing no code with the library: boxes by the documented rules,
// probabilities as maps of counts, Eq. 31 summed term by term.
std::vector<int> brute_force_boxes(const std::vector<double>& x, std::size_t boxes, MutualInformationEstimator e) {
  std::vector<int> box(x.size());
  if (e == MutualInformationEstimator::equal_width) {
    const double lo = *std::min_element(x.begin(), x.end()), hi = *std::max_element(x.begin(), x.end());
    for (std::size_t t = 0; t < x.size(); ++t) {
      const int b = static_cast<int>(std::floor((x[t] - lo) / (hi - lo) * static_cast<double>(boxes)));
      box[t] = std::min(b, static_cast<int>(boxes) - 1);
    }
  } else {
    std::vector<std::size_t> idx(x.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
    for (std::size_t r = 0; r < idx.size(); ++r)
      box[idx[r]] = static_cast<int>(r * boxes / x.size());
  }
  return box;
}

double brute_force_information(const std::vector<int>& box, std::size_t tau) {
  std::map<std::pair<int, int>, double> pij;
  std::map<int, double> pi, pj;
  const double m = static_cast<double>(box.size() - tau);
  for (std::size_t t = 0; t + tau < box.size(); ++t) {
    pij[{box[t], box[t + tau]}] += 1.0 / m;
    pi[box[t]] += 1.0 / m;
    pj[box[t + tau]] += 1.0 / m;
  }
  double sum = 0.0;
  for (const auto& [key, p] : pij) sum += p * std::log(p / (pi[key.first] * pj[key.second]));
  return sum;
}

TEST(MutualInformation, PeriodTwoSeriesCarriesOneBitInNatsAtEveryLag) {
  // x alternates between two values: with 2 boxes each value fixes its box and the one tau later,
  // so I(tau) is the entropy of the first coordinate over the M = N - tau pairs (analytic): ln 2
  // (1 bit) when M is even, H(ceil(M/2)/M) = ln 2 - O(1/M^2) when M is odd.
  const std::size_t n = 1000;
  std::vector<double> x(n);
  for (std::size_t t = 0; t < n; ++t) x[t] = t % 2 == 0 ? -3.0 : 5.0;
  for (const auto e : both) {
    const auto r = chaos::mutual_information(x, {10, 2, e});
    ASSERT_EQ(r.information.size(), 11u);
    for (std::size_t tau = 0; tau <= 10; ++tau) {
      EXPECT_EQ(r.delay[tau], tau);
      const double m = static_cast<double>(n - tau), p = std::ceil(m / 2) / m;
      const double expected = tau % 2 == 0 ? std::log(2.0) : -p * std::log(p) - (1 - p) * std::log(1 - p);
      EXPECT_NEAR(r.information[tau], expected, 1e-14) << tau;
      EXPECT_NEAR(r.information[tau], std::log(2.0), 1e-6) << tau;
    }
  }
}

TEST(MutualInformation, HandComputedPeriodFourCase) {
  // x = 0 0 1 1 0 0 1 1 with 2 boxes. Lag 1: pairs 00 01 11 10 00 01 11, M = 7, first-coordinate
  // counts (4, 3), second-coordinate counts (3, 4), joint 00:2 01:2 10:1 11:2, so
  // I(1) = [2 ln(2*7/(4*3)) + 2 ln(2*7/(4*4)) + 1 ln(1*7/(3*3)) + 2 ln(2*7/(3*4))] / 7.
  // Lag 2: pairs 01 01 10 10 01 01, M = 6, a deterministic swap: I(2) is the entropy of the first
  // coordinate, H(4/6, 2/6) = ln 3 - (2/3) ln 2.
  const std::vector<double> x = {0, 0, 1, 1, 0, 0, 1, 1};
  const double i1 = (2 * std::log(14.0 / 12.0) + 2 * std::log(14.0 / 16.0) + std::log(7.0 / 9.0) +
                     2 * std::log(14.0 / 12.0)) / 7.0;
  for (const auto e : both) {
    const auto r = chaos::mutual_information(x, {2, 2, e});
    EXPECT_NEAR(r.information[0], std::log(2.0), 1e-15);
    EXPECT_NEAR(r.information[1], i1, 1e-15);
    EXPECT_NEAR(r.information[2], std::log(3.0) - 2.0 / 3.0 * std::log(2.0), 1e-15);
  }
}

TEST(MutualInformation, MatchesAnIndependentBruteForceEstimator) {
  // Logistic data (strongly dependent at small lags) and AR(1) data, several box counts.
  const auto logistic = chaos::logistic(3000, {3.8}, 100, 4).components[0];
  const auto ar = chaos::ar1(2500, 0.7, 9).components[0];
  for (const auto* x : {&logistic, &ar})
    for (const std::size_t boxes : {2u, 5u, 16u, 37u})
      for (const auto e : both) {
        const auto r = chaos::mutual_information(*x, {12, boxes, e});
        const auto box = brute_force_boxes(*x, boxes, e);
        for (std::size_t tau = 0; tau <= 12; ++tau)
          EXPECT_NEAR(r.information[tau], brute_force_information(box, tau), 1e-12)
              << "boxes " << boxes << " tau " << tau;
      }
}

TEST(MutualInformation, DelayZeroIsTheEntropyOfThePartition) {
  // I(0) = sum_i p_i ln(p_i / p_i^2) = -sum_i p_i ln p_i (analytic). Equiprobable boxes with N a
  // multiple of the box count hold N / boxes samples each: I(0) = ln boxes exactly.
  const auto x = chaos::ar1(4800, 0.5, 2).components[0];
  for (const std::size_t boxes : {2u, 16u, 48u}) {
    const auto r = chaos::mutual_information(x, {3, boxes, MutualInformationEstimator::equiprobable});
    EXPECT_NEAR(r.information[0], std::log(static_cast<double>(boxes)), 1e-13) << boxes;
    // Equal width: the entropy of the box histogram counted here directly.
    const auto w = chaos::mutual_information(x, {3, boxes, MutualInformationEstimator::equal_width});
    const auto box = brute_force_boxes(x, boxes, MutualInformationEstimator::equal_width);
    std::vector<double> count(boxes, 0.0);
    for (const int b : box) count[b] += 1.0;
    double h = 0.0;
    for (const double c : count)
      if (c > 0) h -= c / 4800.0 * std::log(c / 4800.0);
    EXPECT_NEAR(w.information[0], h, 1e-13) << boxes;
    EXPECT_LT(w.information[0], std::log(static_cast<double>(boxes)));  // Gaussian data: not uniform
  }
}

TEST(MutualInformation, IndependentDataShowsOnlyTheKnownBias) {
  // For independent samples 2 M I is asymptotically chi-square with (B - 1)^2 degrees of freedom
  // (the G-test), so I has mean (B - 1)^2 / (2M) and standard deviation (B - 1) sqrt(2) / (2M).
  // Bounds at 5 standard deviations around the bias, for every lag >= 1.
  const std::size_t n = 100'000, boxes = 16;
  const auto x = uniform_noise(n, 77);
  for (const auto e : both) {
    const auto r = chaos::mutual_information(x, {20, boxes, e});
    for (std::size_t tau = 1; tau <= 20; ++tau) {
      const double m = static_cast<double>(n - tau);
      const double bias = 225.0 / (2 * m), sd = 15.0 * std::sqrt(2.0) / (2 * m);
      EXPECT_NEAR(r.information[tau], bias, 5 * sd) << tau;
    }
  }
}

MutualInformationResult curve(std::vector<double> values) {
  MutualInformationResult r;
  r.information = std::move(values);
  r.delay.resize(r.information.size());
  std::iota(r.delay.begin(), r.delay.end(), 0u);
  return r;
}

TEST(MutualInformation, FirstMinimumFollowsTheDocumentedRule) {
  // The rule: smallest d in 1..D-1 with I(d-1) > I(d) <= I(d+1).
  EXPECT_EQ(chaos::first_minimum(curve({3, 2, 1, 2, 3})), 2u);
  EXPECT_EQ(chaos::first_minimum(curve({3, 1, 2, 0.5, 4})), 1u);      // the first, not the deepest
  EXPECT_EQ(chaos::first_minimum(curve({3, 2, 2, 2, 1})), 1u);        // a plateau after a descent
  EXPECT_EQ(chaos::first_minimum(curve({1, 2, 1.5, 3})), 2u);         // a rise before the descent
  EXPECT_EQ(chaos::first_minimum(curve({5, 4, 3, 2, 1})), std::nullopt);  // never the last lag
  EXPECT_EQ(chaos::first_minimum(curve({1, 1, 1, 1})), std::nullopt);     // flat: no descent
  EXPECT_EQ(chaos::first_minimum(curve({1, 2, 3, 4})), std::nullopt);     // rising
  EXPECT_EQ(chaos::first_minimum(curve({2, 1})), std::nullopt);           // no interior delay
  EXPECT_EQ(chaos::first_minimum(curve({})), std::nullopt);
  // The delay reported is the one stored for that position.
  auto shifted = curve({3, 2, 1, 2});
  shifted.delay = {10, 11, 12, 13};
  EXPECT_EQ(chaos::first_minimum(shifted), 12u);
}

TEST(MutualInformation, LorenzFirstMinimumFallsInTheAcceptanceBand) {
  // references.tsv row lorenz.x.mutual_information.first_minimum: a peer reports a minimum near
  // lag 16 for Lorenz x (ruskeepaa2017); the project's band is [14, 20] samples at dt = 0.01,
  // N = 10^5, 16 boxes.
  const auto x = chaos::lorenz(100'000).components[0];
  const auto r = chaos::mutual_information(x, {50, 16, MutualInformationEstimator::equal_width});
  const auto d = chaos::first_minimum(r);
  ASSERT_TRUE(d.has_value());
  EXPECT_GE(*d, 14u);
  EXPECT_LE(*d, 20u);
}

template <class F>
void expect_refused(F&& f, chaos::ErrorCode code, const std::vector<std::string>& fragments) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    for (const auto& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << fragment << " not in " << e.what();
  }
}

TEST(MutualInformation, RefusesInvalidInput) {
  using chaos::ErrorCode;
  const auto x = uniform_noise(100, 1);
  expect_refused([&] { chaos::mutual_information(x, {0, 16}); }, ErrorCode::invalid_parameter, {"max_delay", "0"});
  expect_refused([&] { chaos::mutual_information(x, {5, 1}); }, ErrorCode::invalid_parameter, {"boxes", "1"});
  expect_refused([&] { chaos::mutual_information(x, {5, 5000}); }, ErrorCode::invalid_parameter, {"boxes", "5000"});
  expect_refused([&] { chaos::mutual_information(x, {90, 16}); }, ErrorCode::too_short, {"N = 100", "106"});
  expect_refused([&] { chaos::mutual_information(std::vector<double>{}, {}); }, ErrorCode::too_short, {"N = 0"});
  auto bad = x;
  bad[17] = NAN;
  expect_refused([&] { chaos::mutual_information(bad, {}); }, ErrorCode::non_finite, {"sample 17"});
  bad[17] = INFINITY;
  expect_refused([&] { chaos::mutual_information(bad, {}); }, ErrorCode::non_finite, {"sample 17"});
  expect_refused([&] { chaos::mutual_information(std::vector<double>(100, 2.5), {}); }, ErrorCode::constant, {"2.5"});
  const chaos::MutualInformationResult mismatched{{0, 1, 2}, {1.0, 0.5}};
  expect_refused([&] { chaos::first_minimum(mismatched); }, ErrorCode::invalid_parameter, {"3 delays", "2"});
}

}  // namespace
