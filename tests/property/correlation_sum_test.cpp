// Properties of the correlation sum that must hold for any input (correlation_sum.hpp):
//   - pair counts are nonincreasing in the Theiler window w (the reference set does not depend on
//     w, and a wider window only removes pairs); C itself need not be, as its normaliser shrinks;
//   - pair counts (and C: same normaliser for every m) are nonincreasing in m, for both norms,
//     because the distance of a pair only grows when a coordinate is added;
//   - a pair count for a radius does not depend on the other radii asked for;
//   - scaling series and radii by a power of two changes no count (exact in floating point), and
//     by 1e-150 or 1e150 changes none when no pair distance lies within rounding of a radius;
//   - shifting the series changes no count when the shift is exact.
#include "chaos/correlation_sum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::CorrelationSearch;
using chaos::CorrelationSumOptions;
using chaos::Norm;

constexpr CorrelationSearch all_modes[] = {CorrelationSearch::brute_force, CorrelationSearch::kd_tree,
                                           CorrelationSearch::box_assisted};
constexpr Norm both_norms[] = {Norm::max, Norm::euclidean};

CorrelationSumOptions options(std::size_t tau, std::size_t max_m, std::size_t w, std::vector<double> radii,
                              Norm norm = Norm::max) {
  CorrelationSumOptions o;
  o.delay = tau;
  o.min_dimension = 1;
  o.max_dimension = max_m;
  o.theiler = w;
  o.radii = std::move(radii);
  o.norm = norm;
  return o;
}

TEST(CorrelationSumProperty, PairCountsNonincreasingInTheilerWindow) {
  // Same reference set i < P for every w; pairs with w < j - i <= w' are dropped by w'. The
  // admissible count drops too, so C can go either way: only the counts are compared.
  const auto x = chaos::lorenz(2000).components[0];
  for (const auto norm : both_norms) {
    auto o = options(17, 4, 0, chaos::log_radii(0.2, 8.0, 15), norm);
    auto previous = chaos::correlation_sum(x, o);
    for (const std::size_t w : {1u, 5u, 30u, 200u, 900u}) {
      o.theiler = w;
      const auto r = chaos::correlation_sum(x, o);
      EXPECT_EQ(r.points, previous.points);
      for (std::size_t mi = 0; mi < r.pairs.size(); ++mi)
        for (std::size_t k = 0; k < r.pairs[mi].size(); ++k) {
          EXPECT_LE(r.pairs[mi][k], previous.pairs[mi][k]) << "w = " << w;
          EXPECT_LT(r.examined[mi][k], previous.examined[mi][k]) << "w = " << w;
        }
      previous = r;
    }
  }
}

TEST(CorrelationSumProperty, NonincreasingInDimension) {
  // The distance in m + 1 dimensions is max(d_m, |dx|) (maximum norm) or sqrt(d_m^2 + dx^2)
  // (Euclidean): never smaller. Same pairs for every m, so counts and C cannot grow with m.
  const auto henon = chaos::henon(2500).components[0];
  const auto noise = chaos::white_noise(2500, 4).components[0];
  for (const auto* x : {&henon, &noise})
    for (const auto norm : both_norms)
      for (const auto mode : all_modes) {
        auto o = options(1, 6, 3, chaos::log_radii(0.01, 2.0, 12), norm);
        o.search = mode;
        if (mode != CorrelationSearch::box_assisted) o.max_dimension = 4;  // keep the slow modes short
        const auto r = chaos::correlation_sum(*x, o);
        for (std::size_t mi = 0; mi + 1 < r.pairs.size(); ++mi)
          for (std::size_t k = 0; k < r.pairs[mi].size(); ++k) {
            EXPECT_LE(r.pairs[mi + 1][k], r.pairs[mi][k]);
            EXPECT_LE(r.correlation_sum[mi + 1][k], r.correlation_sum[mi][k]);
          }
      }
}

TEST(CorrelationSumProperty, CountForARadiusIgnoresTheOtherRadii) {
  // Each count is a property of its own radius; the binning must not depend on the grid.
  const auto x = chaos::lorenz(1500).components[0];
  const auto grid = chaos::log_radii(0.25, 5.0, 25);
  for (const auto norm : both_norms) {
    const auto all = chaos::correlation_sum(x, options(17, 5, 20, grid, norm));
    for (const std::size_t k : {0u, 7u, 13u, 24u}) {
      const auto one = chaos::correlation_sum(x, options(17, 5, 20, {grid[k]}, norm));
      for (std::size_t mi = 0; mi < all.pairs.size(); ++mi) EXPECT_EQ(one.pairs[mi][0], all.pairs[mi][k]);
    }
  }
}

// Smallest |d - r| / r over all pairs, dimensions and radii: the margin within which rounding of
// the scaled values would have to fall to flip a comparison d < r.
double relative_gap(const std::vector<double>& x, const CorrelationSumOptions& o) {
  const std::size_t points = x.size() - (o.max_dimension - 1) * o.delay;
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points; ++i)
    for (std::size_t j = i + o.theiler + 1; j < points; ++j) {
      double acc = 0.0;
      for (std::size_t k = 0; k < o.max_dimension; ++k) {
        const double d = std::abs(x[i + k * o.delay] - x[j + k * o.delay]);
        acc = o.norm == Norm::max ? std::max(acc, d) : acc + d * d;
        const double dist = o.norm == Norm::max ? acc : std::sqrt(acc);
        for (const double r : o.radii) gap = std::min(gap, std::abs(dist - r) / r);
      }
    }
  return gap;
}

TEST(CorrelationSumProperty, ScalingSeriesAndRadiiTogether) {
  const auto x = chaos::henon(1500).components[0];
  for (const auto norm : both_norms)
    for (const auto mode : all_modes) {
      auto o = options(1, 4, 2, chaos::log_radii(0.01, 0.5, 10), norm);
      o.search = mode;
      const auto reference = chaos::correlation_sum(x, o);
      // 1e-150 and 1e150 round every value and radius by half an ulp (relative 1.1e-16), and the
      // distance computation adds a few more; with every distance at least 1e-9 (relative) away
      // from every radius no comparison can flip. The squares of the Euclidean norm would under-
      // or overflow at these scales without the library's internal power-of-two rescaling.
      ASSERT_GT(relative_gap(x, o), 1e-9);
      for (const double s : {1e-150, 1e150}) {
        auto scaled = o;
        std::vector<double> y(x.size());
        for (std::size_t i = 0; i < x.size(); ++i) y[i] = x[i] * s;
        for (auto& r : scaled.radii) r *= s;
        EXPECT_EQ(chaos::correlation_sum(y, scaled).pairs, reference.pairs) << "scale " << s;
      }
      // A power of two is exact: identical counts even with ties at the radii (integer data).
      std::vector<double> q(800);
      chaos::Random rng(9);
      for (auto& v : q) v = static_cast<double>(rng.below(9));
      auto ties = options(1, 3, 1, {1, 2, 3, 4, 5}, norm);
      ties.search = mode;
      const auto base = chaos::correlation_sum(q, ties);
      for (const int e : {-600, 600}) {
        auto scaled = ties;
        std::vector<double> y(q.size());
        for (std::size_t i = 0; i < q.size(); ++i) y[i] = std::ldexp(q[i], e);
        for (auto& r : scaled.radii) r = std::ldexp(r, e);
        EXPECT_EQ(chaos::correlation_sum(y, scaled).pairs, base.pairs) << "2^" << e;
      }
    }
}

TEST(CorrelationSumProperty, ShiftingTheSeries) {
  // Values on the grid k / 1024 with |k| < 2^14, shifted by 1000 or -3.5: every sum and every
  // difference is exact, so each distance is unchanged bit for bit and so is every count, ties at
  // the (grid) radii included.
  chaos::Random rng(21);
  std::vector<double> x(1200);
  for (auto& v : x) v = (static_cast<double>(rng.below(1 << 14)) - 8192.0) / 1024.0;
  for (const auto norm : both_norms)
    for (const auto mode : all_modes) {
      auto o = options(2, 3, 4, {0.5, 1.0, 1.5, 2.0, 4.0, 6.0}, norm);
      o.search = mode;
      const auto base = chaos::correlation_sum(x, o);
      for (const double shift : {1000.0, -3.5}) {
        std::vector<double> y(x.size());
        for (std::size_t i = 0; i < x.size(); ++i) y[i] = x[i] + shift;
        EXPECT_EQ(chaos::correlation_sum(y, o).pairs, base.pairs) << "shift " << shift;
      }
    }
}

}  // namespace
