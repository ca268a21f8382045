// Properties of the mutual-information estimators that hold for any input: non-negativity (a
// plug-in mutual information is the Kullback-Leibler divergence of the joint histogram from the
// product of its own marginals, Gibbs' inequality), the bound I(tau) <= I(0), and invariances:
// equal-width boxes depend only on (x - min) / (max - min), equiprobable boxes only on the order.
#include "chaos/mutual_information.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::MutualInformationEstimator;
using chaos::MutualInformationOptions;

struct Named {
  std::string name;
  std::vector<double> x;
};

std::vector<Named> inputs() {
  std::vector<Named> v;
  v.push_back({"lorenz", chaos::lorenz(20'000).components[0]});
  v.push_back({"henon", chaos::henon(5'000).components[0]});
  v.push_back({"logistic", chaos::logistic(5'000).components[0]});
  v.push_back({"sine", chaos::sine(3'000, 1.0, 0.013).components[0]});
  v.push_back({"ar1", chaos::ar1(5'000, 0.95, 3).components[0]});
  v.push_back({"noise", chaos::white_noise(5'000, 4).components[0]});
  // Short series of few distinct values: many empty cells and ties, where rounding and tie rules
  // would show first.
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    chaos::Random rng(seed);
    std::vector<double> x(40 + seed);
    for (auto& value : x) value = static_cast<double>(rng.below(3 + seed % 4));
    v.push_back({"small" + std::to_string(seed), x});
  }
  return v;
}

constexpr MutualInformationEstimator both[] = {MutualInformationEstimator::equal_width,
                                               MutualInformationEstimator::equiprobable};

TEST(MutualInformationProperty, NonNegativeAndBoundedByTheDelayZeroEntropy) {
  // I(tau) >= 0 (Gibbs), and I(tau) <= H(first coordinate) <= ln(boxes), the largest entropy of a
  // partition into that many boxes. (I(tau) <= I(0) need not hold exactly: the marginals at tau
  // come from N - tau samples.)
  for (const auto& in : inputs())
    for (const std::size_t boxes : {2u, 4u, 16u})
      for (const auto e : both) {
        if (in.x.size() < 10 + boxes) continue;
        const auto r = chaos::mutual_information(in.x, {10, boxes, e});
        for (std::size_t tau = 0; tau <= 10; ++tau) {
          EXPECT_GE(r.information[tau], 0.0) << in.name << " boxes " << boxes << " tau " << tau;
          EXPECT_LE(r.information[tau], std::log(static_cast<double>(boxes)) + 1e-12) << in.name;
        }
      }
}

std::vector<double> transformed(const std::vector<double>& x, double (*f)(double)) {
  std::vector<double> y(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = f(x[i]);
  return y;
}

TEST(MutualInformationProperty, EqualWidthIsExactlyInvariantUnderPowerOfTwoScaling) {
  // Multiplying by 2^k (no overflow or underflow) is exact, and so are min, max, the differences
  // and the quotient (x - min) / (max - min): every box, hence every bit of I, is unchanged.
  for (const auto& in : inputs()) {
    const auto base = chaos::mutual_information(in.x, {10, 16});
    for (const double c : {0x1p-500, 0x1p-3, 0x1p7, 0x1p500, -0x1p4}) {
      std::vector<double> y(in.x.size());
      for (std::size_t i = 0; i < y.size(); ++i) y[i] = c * in.x[i];
      if (c > 0) {
        EXPECT_EQ(chaos::mutual_information(y, {10, 16}).information, base.information) << in.name << " " << c;
      } else {
        // A negative factor mirrors the partition: box b becomes boxes - 1 - b, a relabelling that
        // leaves I unchanged up to summation order, except for samples exactly on a box edge, where
        // floor() is not symmetric; the sampled sine has such samples.
        if (in.name == "sine") continue;
        const auto mirrored = chaos::mutual_information(y, {10, 16}).information;
        for (std::size_t tau = 0; tau <= 10; ++tau)
          EXPECT_NEAR(mirrored[tau], base.information[tau], 1e-12) << in.name << " tau " << tau;
      }
    }
  }
}

TEST(MutualInformationProperty, EqualWidthIsInvariantUnderExtremeScalingAndShifts) {
  // Scaling by 1e-150 or 1e150 or shifting by a constant rounds each sample by at most half an ulp,
  // which moves the box of a sample only if it lies within a few ulps of a box edge. No sample of
  // these chaotic series does (checked: the results are identical), so equality is required; an
  // estimator that squared the data (overflow at 1e150) or used an absolute tolerance would fail.
  const auto lorenz = chaos::lorenz(20'000).components[0];
  const auto base = chaos::mutual_information(lorenz, {20, 16});
  for (const double c : {1e-150, 1e150}) {
    std::vector<double> y(lorenz.size());
    for (std::size_t i = 0; i < y.size(); ++i) y[i] = c * lorenz[i];
    EXPECT_EQ(chaos::mutual_information(y, {20, 16}).information, base.information) << c;
  }
  // Dyadic data (multiples of 2^-10 below 2^16 in magnitude) shifted by 1000 stay exact, so here
  // invariance is exact by construction rather than by the absence of edge cases.
  std::vector<double> dyadic(lorenz.size()), shifted(lorenz.size());
  for (std::size_t i = 0; i < lorenz.size(); ++i) {
    dyadic[i] = std::round(lorenz[i] * 1024.0) / 1024.0;
    shifted[i] = dyadic[i] + 1000.0;
  }
  EXPECT_EQ(chaos::mutual_information(shifted, {20, 16}).information,
            chaos::mutual_information(dyadic, {20, 16}).information);
}

// True when y orders the samples exactly as x does: equal where x is equal, strictly increasing
// where x strictly increases. A strictly increasing real function can fail this in floating point
// by rounding two close values to one.
bool same_order(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<std::size_t> idx(x.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  for (std::size_t k = 0; k + 1 < idx.size(); ++k) {
    const double x0 = x[idx[k]], x1 = x[idx[k + 1]], y0 = y[idx[k]], y1 = y[idx[k + 1]];
    if (x0 == x1 ? y0 != y1 : !(y0 < y1)) return false;
  }
  return true;
}

TEST(MutualInformationProperty, EquiprobableIsInvariantUnderStrictlyIncreasingTransforms) {
  // Ranks, and the index order among ties, are unchanged by a strictly increasing map, so the
  // boxes and every bit of I are too. The precondition, that the map stays strictly increasing
  // after rounding on these samples, is checked first.
  const MutualInformationOptions o{10, 8, MutualInformationEstimator::equiprobable};
  for (const auto& in : inputs()) {
    // The sampled sine repeats values to within an ulp near its extrema; every rounding transform
    // merges some of them, so it cannot serve here.
    if (in.name == "sine") continue;
    const auto base = chaos::mutual_information(in.x, o).information;
    const auto check = [&](const std::vector<double>& y, const char* what) {
      ASSERT_TRUE(same_order(in.x, y)) << in.name << " " << what << " merges samples after rounding";
      EXPECT_EQ(chaos::mutual_information(y, o).information, base) << in.name << " " << what;
    };
    check(transformed(in.x, [](double v) { return std::atan(v); }), "atan");
    check(transformed(in.x, [](double v) { return v * v * v; }), "cube");
    check(transformed(in.x, [](double v) { return 1e150 * v + 7e150; }), "1e150 (x + 7)");
    check(transformed(in.x, [](double v) { return 1e-150 * v - 3e-150; }), "1e-150 x - 3e-150");
    check(transformed(in.x, [](double v) { return std::exp(v); }), "exp");
  }
}

}  // namespace
