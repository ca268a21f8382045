// Correlation sums: cases worked out by hand, every search mode against an independent brute force
// written here from the definition in correlation_sum.hpp (pairs i < j < P = N - (max-1) tau,
// j - i > w, distance in the chosen norm strictly below the radius), thread counts, the seeded
// reference subset and pair cap (reproduced here step by step from docs/reference/correlation_sum.md),
// log_radii, and every refusal with its ErrorCode and numbers.
#include "chaos/correlation_sum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/random.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::CorrelationSearch;
using chaos::CorrelationSumOptions;
using chaos::CorrelationSumResult;
using chaos::Norm;
using Counts = std::vector<std::vector<std::uint64_t>>;

constexpr CorrelationSearch all_modes[] = {CorrelationSearch::brute_force, CorrelationSearch::kd_tree,
                                           CorrelationSearch::box_assisted};
constexpr Norm both_norms[] = {Norm::max, Norm::euclidean};

// The box-assisted search and the kd-tree have an AVX-512 scan (maximum norm), an AVX2 one and a
// portable one; CHAOS_NO_AVX512=1 selects AVX2 and CHAOS_NO_SIMD=1 the portable path, so every
// path the machine runs is checked against the same expectations. Likewise CHAOS_NO_PLANE=1 makes
// the grid bin m = 2 itself instead of counting it by plane_counts (maximum norm).
class ScopedEnv {
 public:
  explicit ScopedEnv(const char* name) : name_(name) { ::setenv(name_, "1", 1); }
  ~ScopedEnv() { ::unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
};
class PortablePath : public ScopedEnv {
 public:
  PortablePath() : ScopedEnv("CHAOS_NO_SIMD") {}
};
class Avx2Path : public ScopedEnv {
 public:
  Avx2Path() : ScopedEnv("CHAOS_NO_AVX512") {}
};

double distance(const std::vector<double>& x, std::size_t i, std::size_t j, std::size_t m, std::size_t tau, Norm norm) {
  double acc = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    const double d = std::abs(x[i + k * tau] - x[j + k * tau]);
    acc = norm == Norm::max ? std::max(acc, d) : acc + d * d;
  }
  return norm == Norm::max ? acc : std::sqrt(acc);
}

// The definition, term by term: every pair, every dimension, every radius (d <= eps when the
// options ask for inclusive counting).
struct Expected {
  Counts pairs;
  std::uint64_t admissible = 0;
};
Expected brute_force(const std::vector<double>& x, const CorrelationSumOptions& o) {
  const std::size_t tau = o.delay, points = x.size() - (o.max_dimension - 1) * tau;
  Expected e;
  e.pairs.assign(o.max_dimension - o.min_dimension + 1, std::vector<std::uint64_t>(o.radii.size(), 0));
  for (std::size_t i = 0; i < points; ++i)
    for (std::size_t j = i + o.theiler + 1; j < points; ++j) {
      ++e.admissible;
      for (std::size_t m = o.min_dimension; m <= o.max_dimension; ++m) {
        const double d = distance(x, i, j, m, tau, o.norm);
        for (std::size_t k = 0; k < o.radii.size(); ++k)
          if (o.inclusive ? d <= o.radii[k] : d < o.radii[k]) ++e.pairs[m - o.min_dimension][k];
      }
    }
  return e;
}

void expect_matches(const CorrelationSumResult& r, const Expected& e, const std::string& what) {
  ASSERT_EQ(r.pairs, e.pairs) << what;
  for (std::size_t mi = 0; mi < r.pairs.size(); ++mi)
    for (std::size_t k = 0; k < r.pairs[mi].size(); ++k) {
      ASSERT_EQ(r.examined[mi][k], e.admissible) << what;
      ASSERT_EQ(r.correlation_sum[mi][k],
                static_cast<double>(e.pairs[mi][k]) / static_cast<double>(e.admissible))
          << what;
    }
}

std::string describe(const CorrelationSumOptions& o) {
  return std::string(chaos::to_string(o.search)) + " " + chaos::to_string(o.norm) + " w=" + std::to_string(o.theiler) +
         " m=" + std::to_string(o.min_dimension) + ".." + std::to_string(o.max_dimension) +
         " tau=" + std::to_string(o.delay) + " threads=" + std::to_string(o.threads);
}

// Every mode (and the portable box-assisted path) against the brute force above.
void expect_all_modes_exact(const std::vector<double>& x, CorrelationSumOptions o) {
  const Expected e = brute_force(x, o);
  for (const auto mode : all_modes) {
    o.search = mode;
    expect_matches(chaos::correlation_sum(x, o), e, describe(o));
  }
  {
    const Avx2Path avx2;
    for (const auto mode : {CorrelationSearch::kd_tree, CorrelationSearch::box_assisted}) {
      o.search = mode;
      expect_matches(chaos::correlation_sum(x, o), e, describe(o) + " AVX2");
    }
  }
  o.search = CorrelationSearch::box_assisted;
  {
    const ScopedEnv grid_only("CHAOS_NO_PLANE");
    expect_matches(chaos::correlation_sum(x, o), e, describe(o) + " m = 2 on the grid");
  }
  const PortablePath portable;
  expect_matches(chaos::correlation_sum(x, o), e, describe(o) + " portable");
}

std::vector<double> uniform(std::size_t n, std::uint64_t seed) {
  chaos::Random rng(seed);
  std::vector<double> x(n);
  for (auto& v : x) v = rng.uniform();
  return x;
}

CorrelationSumOptions options(std::size_t tau, std::size_t min_m, std::size_t max_m, std::size_t w,
                              std::vector<double> radii, Norm norm = Norm::max) {
  CorrelationSumOptions o;
  o.delay = tau;
  o.min_dimension = min_m;
  o.max_dimension = max_m;
  o.theiler = w;
  o.radii = std::move(radii);
  o.norm = norm;
  return o;
}

TEST(CorrelationSum, PointsOnALine) {
  // x[t] = t, t = 0..49, tau = 1, m = 1..2: the reference set has P = 50 - 1 = 49 points and the
  // pair (i, j) is at max-norm distance j - i in both dimensions (both coordinates differ by
  // j - i). With lag d = j - i there are P - d pairs, so the count below r is the sum of P - d
  // over w < d < r: r = 1 (strict) gives 0 pairs, r = 1.5 and r = 2 give the P - 1 = 48 pairs at
  // d = 1, r = 3.5 gives 48 + 47 + 46 = 141. Admissible pairs: P (P - 1) / 2 = 1176.
  std::vector<double> x(50);
  for (std::size_t t = 0; t < x.size(); ++t) x[t] = static_cast<double>(t);
  for (const auto mode : all_modes) {
    auto o = options(1, 1, 2, 0, {1.0, 1.5, 2.0, 3.5});
    o.search = mode;
    const auto r = chaos::correlation_sum(x, o);
    EXPECT_EQ(r.points, 49u);
    EXPECT_EQ(r.dimension, (std::vector<std::size_t>{1, 2}));
    for (std::size_t mi = 0; mi < 2; ++mi) {
      EXPECT_EQ(r.pairs[mi], (std::vector<std::uint64_t>{0, 48, 48, 141})) << chaos::to_string(mode);
      EXPECT_EQ(r.examined[mi], (std::vector<std::uint64_t>(4, 1176)));
      EXPECT_DOUBLE_EQ(r.correlation_sum[mi][3], 141.0 / 1176.0);
    }
    // Theiler window w = 1 drops d = 1: r = 3.5 keeps d = 2, 3: 47 + 46 = 93 of
    // (P - 2)(P - 1) / 2 = 1128 admissible pairs.
    o.theiler = 1;
    const auto t = chaos::correlation_sum(x, o);
    EXPECT_EQ(t.pairs[0], (std::vector<std::uint64_t>{0, 0, 0, 93})) << chaos::to_string(mode);
    EXPECT_EQ(t.examined[0][0], 1128u);
    // Euclidean: in m = 2 the distance is sqrt(2) d, so r = 1.5 keeps d = 1 (1.414...), r = 2
    // too, and r = 3.5 keeps d = 1, 2 (2.83) but not d = 3 (4.24): 48 + 47 = 95 with w = 0.
    o.theiler = 0;
    o.norm = Norm::euclidean;
    const auto e = chaos::correlation_sum(x, o);
    EXPECT_EQ(e.pairs[0], (std::vector<std::uint64_t>{0, 48, 48, 141})) << chaos::to_string(mode);
    EXPECT_EQ(e.pairs[1], (std::vector<std::uint64_t>{0, 48, 48, 95})) << chaos::to_string(mode);
  }
}

TEST(CorrelationSum, TinySeriesEnumerated) {
  // x = 0 1 3 7, tau = 1, m = 1..2: P = 4 - 1 = 3 reference points for both dimensions.
  //   m = 1: points 0, 1, 3; pair distances |0-1| = 1, |0-3| = 3, |1-3| = 2.
  //   m = 2: points (0,1), (1,3), (3,7); max norm: max(1,2) = 2, max(3,6) = 6, max(2,4) = 4;
  //          Euclidean: sqrt(5) = 2.236, sqrt(45) = 6.708, sqrt(20) = 4.472.
  // Radii 1, 2, 4, 6.5, 7 with strict <:
  //   m = 1:     d < 1: none; < 2: {1}; < 4: {1,3,2}; < 6.5, < 7: all 3.
  //   m = 2 max: < 1: none; < 2: none (2 is not < 2); < 4: {2}; < 6.5: {2,6,4}; < 7: 3.
  //   m = 2 Euc: < 1, < 2: none; < 4: {2.236}; < 6.5: {2.236, 4.472}; < 7: 3.
  const std::vector<double> x{0, 1, 3, 7};
  for (const auto mode : all_modes) {
    auto o = options(1, 1, 2, 0, {1, 2, 4, 6.5, 7});
    o.search = mode;
    const auto r = chaos::correlation_sum(x, o);
    EXPECT_EQ(r.pairs[0], (std::vector<std::uint64_t>{0, 1, 3, 3, 3})) << chaos::to_string(mode);
    EXPECT_EQ(r.pairs[1], (std::vector<std::uint64_t>{0, 0, 1, 3, 3})) << chaos::to_string(mode);
    EXPECT_EQ(r.examined[1][0], 3u);
    EXPECT_DOUBLE_EQ(r.correlation_sum[1][2], 1.0 / 3.0);
    o.norm = Norm::euclidean;
    const auto e = chaos::correlation_sum(x, o);
    EXPECT_EQ(e.pairs[0], (std::vector<std::uint64_t>{0, 1, 3, 3, 3})) << chaos::to_string(mode);
    EXPECT_EQ(e.pairs[1], (std::vector<std::uint64_t>{0, 0, 1, 2, 3})) << chaos::to_string(mode);
    // w = 1 leaves only the pair (0, 2): m = 1 distance 3, m = 2 max-norm distance 6.
    o.norm = Norm::max;
    o.theiler = 1;
    const auto t = chaos::correlation_sum(x, o);
    EXPECT_EQ(t.pairs[0], (std::vector<std::uint64_t>{0, 0, 1, 1, 1})) << chaos::to_string(mode);
    EXPECT_EQ(t.pairs[1], (std::vector<std::uint64_t>{0, 0, 0, 1, 1})) << chaos::to_string(mode);
    EXPECT_EQ(t.examined[0][0], 1u);
  }
}

TEST(CorrelationSum, EveryModeEqualsBruteForceOnRandomData) {
  // Expected counts: the brute force above. Radii are log-spaced (TISEAN's grid) plus a few
  // arbitrary ones, so the O(1) binning meets uneven spacing too.
  const auto x = uniform(700, 7);
  auto radii = chaos::log_radii(0.01, 0.6, 12);
  radii.insert(radii.begin() + 5, (radii[4] + radii[5]) / 2);
  radii.push_back(0.61);
  for (const auto norm : both_norms)
    for (const std::size_t w : {0u, 1u, 10u}) expect_all_modes_exact(x, options(1, 1, 5, w, radii, norm));
  // m from 3 only (nothing counted for m = 1, 2) and a delay of 3.
  expect_all_modes_exact(x, options(3, 3, 4, 2, radii, Norm::max));
  // m = 2 alone: with the maximum norm only plane_counts runs, no grid scan.
  for (const std::size_t w : {0u, 5u}) expect_all_modes_exact(x, options(2, 2, 2, w, radii, Norm::max));
}

TEST(CorrelationSum, EveryModeEqualsBruteForceOnHenon) {
  // Henon x (a = 1.4, b = 0.3), tau = 1, m = 1..4, radii as in the speed target (0.005 .. 0.4).
  const auto x = chaos::henon(800).components[0];
  const auto radii = chaos::log_radii(0.005, 0.4, 20);
  for (const auto norm : both_norms)
    for (const std::size_t w : {0u, 1u, 10u}) expect_all_modes_exact(x, options(1, 1, 4, w, radii, norm));
}

TEST(CorrelationSum, EveryModeEqualsBruteForceOnLorenz) {
  // Lorenz x sampled at dt = 0.01 (RK4 step 0.001), tau = 17, m = 1..5, radii 0.25 .. 5.
  const auto x = chaos::lorenz(900).components[0];
  const auto radii = chaos::log_radii(0.25, 5.0, 16);
  for (const auto norm : both_norms)
    for (const std::size_t w : {0u, 1u, 10u}) expect_all_modes_exact(x, options(17, 1, 5, w, radii, norm));
  // A window wider than P/8 takes the path that tests the window pair by pair.
  expect_all_modes_exact(x, options(17, 1, 5, 400, radii, Norm::max));
  expect_all_modes_exact(x, options(17, 1, 5, 400, radii, Norm::euclidean));
}

// chaos d2 draws a progress line from this callback. It is called with growing fractions
// below 1, in every exact search mode and on 1 or 2 threads, and the counts do not depend on it.
TEST(CorrelationSum, ProgressIsReportedAndChangesNothing) {
  // max m = 2: the box-assisted search counts m = 2 by plane_counts alone and reports from there.
  const auto x = chaos::lorenz(3000).components[0];
  for (const auto search : {CorrelationSearch::box_assisted, CorrelationSearch::kd_tree, CorrelationSearch::brute_force})
    for (const std::size_t threads : {1u, 2u})
      for (const std::size_t max_m : {2u, 3u}) {
        auto o = options(17, 1, max_m, 10, chaos::log_radii(0.25, 5.0, 8), Norm::max);
        o.search = search;
        o.threads = threads;
        const auto quiet = chaos::correlation_sum(x, o);
        std::vector<double> seen;
        o.progress = [&seen](double f) { seen.push_back(f); };
        const auto reported = chaos::correlation_sum(x, o);
        EXPECT_EQ(reported.pairs, quiet.pairs);
        ASSERT_FALSE(seen.empty()) << chaos::to_string(search) << ", " << threads << " thread(s), max m " << max_m;
        EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
        EXPECT_GT(seen.front(), 0.0);
        EXPECT_LT(seen.back(), 1.0);
      }
}

TEST(CorrelationSum, TiesExactlyAtTheRadiiAreNotCounted) {
  // Integer data and integer radii: many distances equal a radius exactly, and strict < must
  // leave them out (max norm: |dx| = r; Euclidean: e.g. (3, 4) -> 5, (6, 8) -> 10). Expected
  // counts: the brute force above; the first check also pins one count by hand.
  chaos::Random rng(3);
  std::vector<double> x(600);
  for (auto& v : x) v = static_cast<double>(rng.below(13));
  const std::vector<double> radii{1, 2, 3, 4, 5, 6, 8, 10, 12, 13};
  for (const auto norm : both_norms)
    for (const std::size_t w : {0u, 1u, 10u}) expect_all_modes_exact(x, options(1, 1, 4, w, radii, norm));
  // Radius 1 in m = 1 counts exactly the pairs with equal values (distance 0 < 1 <= every other).
  auto o = options(1, 1, 1, 0, {1.0});
  std::uint64_t equal = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size(); ++j) equal += x[i] == x[j];
  EXPECT_EQ(chaos::correlation_sum(x, o).pairs[0][0], equal);
  // The same on a dyadic grid (multiples of 1/8) with radii on that grid.
  std::vector<double> y(x.size()), dyadic_radii(radii.size());
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = x[i] / 8.0 - 0.75;
  for (std::size_t k = 0; k < radii.size(); ++k) dyadic_radii[k] = radii[k] / 8.0;
  for (const auto norm : both_norms) expect_all_modes_exact(y, options(2, 1, 3, 1, dyadic_radii, norm));
}

TEST(CorrelationSum, InclusiveCountsTiesAtTheRadii) {
  // `inclusive` counts d <= eps (TISEAN's convention). Expected counts: the brute force
  // above with <=, on integer data with integer radii (ties at every radius, both norms) and on a
  // dyadic grid, in every search mode and the portable path.
  chaos::Random rng(5);
  std::vector<double> x(500);
  for (auto& v : x) v = static_cast<double>(rng.below(9));
  const std::vector<double> radii{1, 2, 3, 4, 5, 8};
  for (const auto norm : both_norms)
    for (const std::size_t w : {0u, 3u}) {
      auto o = options(1, 1, 3, w, radii, norm);
      o.inclusive = true;
      expect_all_modes_exact(x, o);
    }
  std::vector<double> y(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = x[i] / 16.0 + 0.5;
  auto o = options(2, 2, 4, 1, {0.0625, 0.125, 0.25}, Norm::max);
  o.inclusive = true;
  expect_all_modes_exact(y, o);
  // By hand: radius 1 in m = 1 counts the pairs at distance 0 or 1 when inclusive, at 0 when not.
  o = options(1, 1, 1, 0, {1.0});
  std::uint64_t zero = 0, one = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size(); ++j) {
      zero += x[i] == x[j];
      one += std::abs(x[i] - x[j]) == 1.0;
    }
  EXPECT_EQ(chaos::correlation_sum(x, o).pairs[0][0], zero);
  o.inclusive = true;
  EXPECT_EQ(chaos::correlation_sum(x, o).pairs[0][0], zero + one);
  // The radii are reported as given, not as the next double used inside.
  EXPECT_EQ(chaos::correlation_sum(x, o).radius, std::vector<double>{1.0});
  // A reference subset and a pair cap count the same way: with all P points as reference points
  // and no cap reached, every pair is seen from both ends (docs/reference/correlation_sum.md).
  o = options(1, 1, 3, 2, radii, Norm::max);
  o.inclusive = true;
  const Expected e = brute_force(x, o);
  o.reference_points = x.size() - 2;
  const auto twice = chaos::correlation_sum(x, o);
  for (std::size_t mi = 0; mi < e.pairs.size(); ++mi)
    for (std::size_t k = 0; k < radii.size(); ++k) EXPECT_EQ(twice.pairs[mi][k], 2 * e.pairs[mi][k]);
}

TEST(CorrelationSum, ThreadCountDoesNotChangeAnything) {
  // Integer counts summed over deterministic chunks: 1, 2 and 3 threads must agree bit for bit,
  // in the exact walk and in the reference walk (subset and cap).
  const auto x = chaos::lorenz(900).components[0];
  auto o = options(17, 1, 4, 20, chaos::log_radii(0.25, 5.0, 10));
  for (const auto mode : all_modes) {
    o.search = mode;
    for (const auto norm : both_norms) {
      o.norm = norm;
      for (const auto& [subset, cap] : {std::pair<std::size_t, std::uint64_t>{0, 0}, {300, 0}, {0, 2000}, {400, 500}}) {
        o.reference_points = subset;
        o.pairs_per_radius = cap;
        o.threads = 1;
        const auto one = chaos::correlation_sum(x, o);
        for (const std::size_t threads : {2u, 3u}) {
          o.threads = threads;
          const auto many = chaos::correlation_sum(x, o);
          EXPECT_EQ(many.pairs, one.pairs) << describe(o) << " subset " << subset << " cap " << cap;
          EXPECT_EQ(many.examined, one.examined) << describe(o) << " subset " << subset << " cap " << cap;
        }
      }
    }
  }
}

// The reference order of docs/reference/correlation_sum.md: a partial Fisher-Yates shuffle of 0 .. P-1 with
// chaos::Random(seed), position t swapped with t + below(P - t).
std::vector<std::size_t> reference_order(std::size_t points, std::size_t count, std::uint64_t seed) {
  std::vector<std::size_t> order(points);
  for (std::size_t i = 0; i < points; ++i) order[i] = i;
  chaos::Random rng(seed);
  for (std::size_t t = 0; t < count; ++t) std::swap(order[t], order[t + rng.below(points - t)]);
  order.resize(count);
  return order;
}

// The reference walk by the documented rules: each reference point i in order, with its partners
// j on both sides (|i - j| > w); after each point, a radius whose count has reached the cap is
// closed for that dimension, and its `examined` stops growing.
// A refusal (InvalidInput, invalid_parameter) whose message contains `fragment`.
bool refused_with(const std::vector<double>& x, const CorrelationSumOptions& o, const std::string& fragment) {
  try {
    (void)chaos::correlation_sum(x, o);
  } catch (const chaos::InvalidInput& e) {
    return e.code() == chaos::ErrorCode::invalid_parameter && std::string(e.what()).find(fragment) != std::string::npos;
  }
  return false;
}

// The jackknife groups (correlation_sum.hpp): position u of the R reference points in the order is
// in group u * G / R, so the groups are G consecutive stretches of the order.
struct Walk {
  Counts pairs, examined;
  std::vector<Counts> group_pairs, group_examined;
};
Walk reference_walk(const std::vector<double>& x, const CorrelationSumOptions& o) {
  const std::size_t tau = o.delay, points = x.size() - (o.max_dimension - 1) * tau;
  const std::size_t nm = o.max_dimension - o.min_dimension + 1, nr = o.radii.size();
  const Counts zero(nm, std::vector<std::uint64_t>(nr, 0));
  Walk walk{zero, zero, {}, {}};
  std::vector<std::vector<bool>> closed(nm, std::vector<bool>(nr, false));
  const std::size_t count = o.reference_points > 0 ? o.reference_points : points;
  std::vector<std::size_t> order = reference_order(points, o.reference_offset + count, o.seed);
  order.erase(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(o.reference_offset));
  const std::size_t groups = std::min(o.jackknife_groups, order.size());
  walk.group_pairs.assign(groups, zero);
  walk.group_examined.assign(groups, zero);
  for (std::size_t u = 0; u < order.size(); ++u) {
    const std::size_t i = order[u], g = u * groups / order.size();
    std::uint64_t partners = 0;
    Counts found(nm, std::vector<std::uint64_t>(nr, 0));
    for (std::size_t j = 0; j < points; ++j) {
      if ((i > j ? i - j : j - i) <= o.theiler) continue;
      ++partners;
      for (std::size_t m = o.min_dimension; m <= o.max_dimension; ++m)
        for (std::size_t k = 0; k < nr; ++k)
          found[m - o.min_dimension][k] += o.inclusive ? distance(x, i, j, m, tau, o.norm) <= o.radii[k]
                                                       : distance(x, i, j, m, tau, o.norm) < o.radii[k];
    }
    for (std::size_t mi = 0; mi < nm; ++mi)
      for (std::size_t k = 0; k < nr; ++k) {
        if (closed[mi][k]) continue;
        walk.pairs[mi][k] += found[mi][k];
        walk.examined[mi][k] += partners;
        walk.group_pairs[g][mi][k] += found[mi][k];
        walk.group_examined[g][mi][k] += partners;
      }
    for (std::size_t mi = 0; mi < nm; ++mi)
      for (std::size_t k = 0; k < nr; ++k)
        if (o.pairs_per_radius > 0 && walk.pairs[mi][k] >= o.pairs_per_radius) closed[mi][k] = true;
  }
  return walk;
}

TEST(CorrelationSum, ReferenceSubsetFollowsTheDocumentedWalk) {
  // Expected: the walk above over the seeded subset; every mode must reproduce it exactly.
  const auto x = chaos::henon(900).components[0];
  auto o = options(1, 1, 3, 5, chaos::log_radii(0.01, 0.5, 10));
  o.reference_points = 120;
  o.seed = 11;
  const Walk want = reference_walk(x, o);
  for (const auto mode : all_modes) {
    o.search = mode;
    const auto r = chaos::correlation_sum(x, o);
    EXPECT_EQ(r.pairs, want.pairs) << chaos::to_string(mode);
    EXPECT_EQ(r.examined, want.examined) << chaos::to_string(mode);
    EXPECT_EQ(r.points, 120u);
  }
  // Same seed: the same result; another seed: another subset and other counts.
  o.search = CorrelationSearch::box_assisted;
  EXPECT_EQ(chaos::correlation_sum(x, o).pairs, chaos::correlation_sum(x, o).pairs);
  auto other = o;
  other.seed = 12;
  EXPECT_NE(chaos::correlation_sum(x, other).pairs, want.pairs);
}

TEST(CorrelationSum, JackknifeGroupsSplitTheReferenceWalk) {
  // Expected: the documented walk above, split into its groups (consecutive stretches of the
  // order), with and without a cap, 16 and 5 groups, 1 and 3 threads; exact counts have no groups.
  const auto x = chaos::henon(900).components[0];
  auto o = options(1, 1, 3, 5, chaos::log_radii(0.01, 0.5, 10));
  o.reference_points = 120;
  o.seed = 11;
  for (const std::size_t groups : {16u, 5u})
    for (const std::uint64_t cap : {0u, 4000u})
      for (const std::size_t threads : {1u, 3u}) {
        o.jackknife_groups = groups;
        o.pairs_per_radius = cap;
        o.threads = threads;
        const Walk want = reference_walk(x, o);
        const auto r = chaos::correlation_sum(x, o);
        const std::string what = "groups " + std::to_string(groups) + " cap " + std::to_string(cap) + " threads " +
                                 std::to_string(threads);
        EXPECT_EQ(r.group_pairs, want.group_pairs) << what;
        EXPECT_EQ(r.group_examined, want.group_examined) << what;
        EXPECT_EQ(r.pairs, want.pairs) << what;
      }
  auto exact = options(1, 1, 3, 5, chaos::log_radii(0.01, 0.5, 10));
  const auto r = chaos::correlation_sum(x, exact);
  EXPECT_TRUE(r.group_pairs.empty());
  EXPECT_TRUE(r.group_examined.empty());
  exact.jackknife_groups = 1;
  EXPECT_TRUE(refused_with(x, exact, "2 to 1024 groups of reference points (got 1)"));
}

TEST(CorrelationSum, ReferenceOffsetCountsTheNextPointsOfTheOrder) {
  // Two calls with the same seed and consecutive offsets count disjoint stretches of one order, so
  // their counts add up exactly to those of the stretch they cover together (integer counts; the
  // walk above reproduces each).
  const auto x = chaos::lorenz(1500).components[0];
  auto o = options(17, 1, 4, 30, chaos::log_radii(0.3, 5.0, 12));
  o.seed = 4;
  o.reference_points = 200;
  const auto both = chaos::correlation_sum(x, o);
  o.reference_points = 80;
  const auto first = chaos::correlation_sum(x, o);
  o.reference_offset = 80;
  o.reference_points = 120;
  const auto second = chaos::correlation_sum(x, o);
  EXPECT_EQ(second.pairs, reference_walk(x, o).pairs);
  for (std::size_t mi = 0; mi < both.pairs.size(); ++mi)
    for (std::size_t k = 0; k < both.pairs[mi].size(); ++k) {
      EXPECT_EQ(first.pairs[mi][k] + second.pairs[mi][k], both.pairs[mi][k]);
      EXPECT_EQ(first.examined[mi][k] + second.examined[mi][k], both.examined[mi][k]);
    }
  const std::size_t points = x.size() - 3 * 17;  // P = N - (max - 1) tau = 1449
  o.reference_points = 0;
  EXPECT_TRUE(refused_with(x, o, "got offset 80, reference_points 0"));
  o.reference_points = points - 79;
  EXPECT_TRUE(refused_with(x, o, "offset + reference_points <= the 1449 embedded points (got offset 80, reference_points 1370)"));
}

// correlation_sums_over_theiler_windows walks the pairs once at the smallest window and subtracts
// the extra lags of each larger one. Expected values: the brute force above at each window (the
// definition), and correlation_sum at that window in the same mode. Windows unsorted and repeated;
// one above P/8 (where the grid tests the window in its scan instead of subtracting it); min m 1 and
// 3; quantised data, whose distances tie with each other and with the radii; 1 and 3 threads.
TEST(CorrelationSum, SeveralTheilerWindowsEqualOneCallEach) {
  const auto lorenz = chaos::lorenz(900).components[0];
  auto quantised = chaos::henon(900).components[0];
  for (auto& v : quantised) v = std::round(v * 16.0) / 16.0;
  const std::vector<std::size_t> windows{40, 0, 200, 40, 7};
  for (const auto& [x, tau, radii] :
       {std::tuple{lorenz, std::size_t{9}, chaos::log_radii(0.3, 6.0, 10)},
        std::tuple{quantised, std::size_t{1}, std::vector<double>{0.0625, 0.125, 0.25, 0.5, 0.75}}})
    for (const auto norm : both_norms)
      for (const std::size_t min_m : {1u, 3u}) {
        std::vector<Expected> expected;
        for (const std::size_t w : windows) expected.push_back(brute_force(x, options(tau, min_m, 4, w, radii, norm)));
        for (const auto mode : all_modes)
          for (const std::size_t threads : {1u, 3u}) {
            auto o = options(tau, min_m, 4, 0, radii, norm);
            o.search = mode;
            o.threads = threads;
            const auto all = chaos::correlation_sums_over_theiler_windows(x, o, windows);
            ASSERT_EQ(all.size(), windows.size());
            for (std::size_t q = 0; q < windows.size(); ++q) {
              o.theiler = windows[q];
              const std::string what = describe(o);
              expect_matches(all[q], expected[q], what);
              const auto alone = chaos::correlation_sum(x, o);
              EXPECT_EQ(all[q].correlation_sum, alone.correlation_sum) << what;
              EXPECT_EQ(all[q].dimension, alone.dimension) << what;
              EXPECT_EQ(all[q].radius, alone.radius) << what;
              EXPECT_EQ(all[q].points, alone.points) << what;
              EXPECT_EQ(all[q].range, alone.range) << what;
            }
          }
      }
  const auto refused = [&](CorrelationSumOptions o, std::vector<std::size_t> w, const std::string& fragment) {
    try {
      (void)chaos::correlation_sums_over_theiler_windows(lorenz, o, w);
    } catch (const chaos::InvalidInput& e) {
      return std::string(e.what()).find(fragment) != std::string::npos;
    }
    return false;
  };
  const auto o = options(9, 1, 4, 0, chaos::log_radii(0.3, 6.0, 10));
  EXPECT_TRUE(refused(o, {}, "no window given"));
  auto capped = o;
  capped.pairs_per_radius = 100;
  EXPECT_TRUE(refused(capped, {5}, "exact counts only (got a pair cap of 100 and 0 reference points"));
  auto subset = o;
  subset.reference_points = 50;
  EXPECT_TRUE(refused(subset, {5}, "exact counts only (got a pair cap of 0 and 50 reference points"));
  // The largest window is checked as correlation_sum checks it: 900 - 27 points leave no pair beyond w = 872.
  EXPECT_TRUE(refused(o, {5, 872}, "N >= (m-1)*tau + w + 2 = 3*9 + 872 + 2"));
}

TEST(CorrelationSum, SubsetsShareOneStructureAndGiveTheSameCounts) {
  // CorrelationSumSubsets builds the search structure once; each count(offset, R) must equal the
  // documented walk above over the same stretch of the seeded order, and correlation_sum with that
  // offset and subset, for every mode and norm, with and without a cap, several subsets in turn.
  const auto x = chaos::lorenz(1500).components[0];
  for (const auto mode : all_modes)
    for (const auto norm : both_norms)
      for (const std::uint64_t cap : {0u, 3000u}) {
        auto o = options(17, 1, 4, 30, chaos::log_radii(0.3, 5.0, 12), norm);
        o.search = mode;
        o.seed = 4;
        o.pairs_per_radius = cap;
        const chaos::CorrelationSumSubsets subsets(x, o);
        EXPECT_EQ(subsets.points(), x.size() - 3 * 17);
        for (const auto [offset, count] : {std::pair<std::size_t, std::size_t>{0, 60}, {60, 60}, {120, 240}, {0, 60}}) {
          o.reference_offset = offset;
          o.reference_points = count;
          const std::string what = describe(o) + " cap " + std::to_string(cap) + " offset " + std::to_string(offset);
          const auto got = subsets.count(offset, count);
          const Walk want = reference_walk(x, o);
          EXPECT_EQ(got.pairs, want.pairs) << what;
          EXPECT_EQ(got.examined, want.examined) << what;
          EXPECT_EQ(got.group_pairs, want.group_pairs) << what;
          const auto alone = chaos::correlation_sum(x, o);
          EXPECT_EQ(got.correlation_sum, alone.correlation_sum) << what;
          EXPECT_EQ(got.points, count);
          EXPECT_EQ(got.range, alone.range);
          EXPECT_EQ(got.radius, alone.radius);
        }
      }
  auto o = options(17, 1, 4, 30, chaos::log_radii(0.3, 5.0, 12));
  const chaos::CorrelationSumSubsets subsets(x, o);
  const auto refused = [&](std::size_t offset, std::size_t count, const std::string& fragment) {
    try {
      (void)subsets.count(offset, count);
    } catch (const chaos::InvalidInput& e) {
      return std::string(e.what()).find(fragment) != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(refused(0, 0, "at least one reference point (got 0)"));
  EXPECT_TRUE(refused(0, 1450, "must not exceed the 1449 embedded points N - (m-1)*tau (got 1450)"));
  EXPECT_TRUE(refused(1400, 50, "(got offset 1400, reference_points 50)"));
  // What correlation_sum refuses, the constructor refuses.
  o.delay = 0;
  EXPECT_THROW(chaos::CorrelationSumSubsets(x, o), chaos::InvalidInput);
}

TEST(CorrelationSum, ReferenceSubsetOnTheGridWithTiesBothNormsAndWindows) {
  // The box-assisted reference walk scans the exact walk's grid (only as far as the
  // largest open radius under a cap) and takes i and its Theiler-window partners out afterwards;
  // the kd-tree walk scans the leaves within that radius and does the same. Expected: the
  // documented walk above, on integer data (ties at the radii, so many leaves of equal values),
  // both norms, windows 0 to 9, m from 1, 2 or 3, strict and inclusive counting, with and without
  // a cap, with the AVX2 and the portable scan.
  chaos::Random rng(8);
  std::vector<double> x(700);
  for (auto& v : x) v = static_cast<double>(rng.below(11));
  const std::vector<double> radii{1, 2, 3, 5, 8};
  for (const auto search : {CorrelationSearch::box_assisted, CorrelationSearch::kd_tree})
  for (const auto norm : both_norms)
    for (const std::size_t w : {0u, 2u, 9u})
      for (const std::size_t min_m : {1u, 2u, 3u})
        for (const bool inclusive : {false, true}) {
          auto o = options(2, min_m, 4, w, radii, norm);
          o.search = search;
          o.inclusive = inclusive;
          o.reference_points = 90;
          o.seed = 3 + w;
          for (const std::uint64_t cap : {0u, 2500u}) {
            o.pairs_per_radius = cap;
            const Walk want = reference_walk(x, o);
            const std::string what = describe(o) + (inclusive ? " inclusive" : "") + " cap " + std::to_string(cap);
            const auto got = chaos::correlation_sum(x, o);
            EXPECT_EQ(got.pairs, want.pairs) << what;
            EXPECT_EQ(got.examined, want.examined) << what;
            {
              const Avx2Path avx2;
              EXPECT_EQ(chaos::correlation_sum(x, o).pairs, want.pairs) << what << " AVX2";
            }
            const PortablePath portable;
            EXPECT_EQ(chaos::correlation_sum(x, o).pairs, want.pairs) << what << " portable";
          }
        }
}

TEST(CorrelationSum, FullReferenceSubsetCountsEveryPairTwice) {
  // With all P points as reference points every pair is seen from both ends: pairs and examined
  // are exactly twice those of the exact walk, so C is the same number.
  const auto x = chaos::lorenz(1500).components[0];
  auto o = options(17, 1, 4, 30, chaos::log_radii(0.3, 5.0, 12));
  const auto exact = chaos::correlation_sum(x, o);
  o.reference_points = exact.points;
  for (const auto mode : all_modes) {
    o.search = mode;
    const auto r = chaos::correlation_sum(x, o);
    for (std::size_t mi = 0; mi < r.pairs.size(); ++mi)
      for (std::size_t k = 0; k < r.pairs[mi].size(); ++k) {
        EXPECT_EQ(r.pairs[mi][k], 2 * exact.pairs[mi][k]) << chaos::to_string(mode);
        EXPECT_EQ(r.examined[mi][k], 2 * exact.examined[mi][k]);
        EXPECT_DOUBLE_EQ(r.correlation_sum[mi][k], exact.correlation_sum[mi][k]);
      }
  }
}

TEST(CorrelationSum, PairCapFollowsTheDocumentedWalk) {
  // Expected: the capped walk above (all points in the seeded order, and a seeded subset).
  const auto x = chaos::lorenz(1400).components[0];
  auto o = options(17, 1, 4, 25, chaos::log_radii(0.3, 5.0, 12));
  o.pairs_per_radius = 3000;
  o.seed = 5;
  for (const std::size_t subset : {0u, 500u}) {
    o.reference_points = subset;
    const Walk want = reference_walk(x, o);
    for (const auto mode : all_modes) {
      o.search = mode;
      const auto r = chaos::correlation_sum(x, o);
      EXPECT_EQ(r.pairs, want.pairs) << chaos::to_string(mode) << " subset " << subset;
      EXPECT_EQ(r.examined, want.examined) << chaos::to_string(mode) << " subset " << subset;
    }
    // The cap is what stops a radius: closed ones reached it, and smaller radii (fewer pairs)
    // stay open longer, so they examine at least as many pairs.
    o.search = CorrelationSearch::box_assisted;
    const auto r = chaos::correlation_sum(x, o);
    for (std::size_t mi = 0; mi < r.pairs.size(); ++mi)
      for (std::size_t k = 0; k + 1 < r.pairs[mi].size(); ++k) EXPECT_GE(r.examined[mi][k], r.examined[mi][k + 1]);
    EXPECT_GE(r.pairs[0].back(), o.pairs_per_radius);
    EXPECT_LT(r.examined[0].back(), r.examined[0].front());
    auto other = o;
    other.seed = 6;
    EXPECT_NE(chaos::correlation_sum(x, other).examined, r.examined);
    EXPECT_EQ(chaos::correlation_sum(x, o).examined, r.examined);
  }
}

TEST(CorrelationSum, CapNeverReachedGivesTheExactSums) {
  // A cap above every count closes nothing: the reference walk over all points, i.e. every pair
  // twice, so C equals the exact C.
  const auto x = uniform(800, 2);
  auto o = options(1, 1, 3, 3, chaos::log_radii(0.02, 0.3, 8));
  const auto exact = chaos::correlation_sum(x, o);
  o.pairs_per_radius = 1'000'000'000;
  const auto capped = chaos::correlation_sum(x, o);
  for (std::size_t mi = 0; mi < exact.pairs.size(); ++mi)
    for (std::size_t k = 0; k < exact.pairs[mi].size(); ++k) {
      EXPECT_EQ(capped.pairs[mi][k], 2 * exact.pairs[mi][k]);
      EXPECT_DOUBLE_EQ(capped.correlation_sum[mi][k], exact.correlation_sum[mi][k]);
    }
}

TEST(CorrelationSum, NondecreasingInRadiusAndWithinZeroOne) {
  // Pairs closer than r are also closer than any larger r (definition), and C = pairs/admissible.
  const auto x = chaos::lorenz(3000).components[0];
  for (const auto norm : both_norms) {
    const auto r = chaos::correlation_sum(x, options(17, 1, 6, 100, chaos::log_radii(0.1, 20.0, 30), norm));
    for (const auto& c : r.correlation_sum) {
      EXPECT_TRUE(std::is_sorted(c.begin(), c.end()));
      EXPECT_GE(c.front(), 0.0);
      EXPECT_LE(c.back(), 1.0);
    }
  }
}

TEST(CorrelationSum, LogRadii) {
  // r_k = r_min (r_max / r_min)^(k / (n - 1)): the ends exactly as given, a constant ratio.
  const auto r = chaos::log_radii(0.005, 0.4, 40);
  ASSERT_EQ(r.size(), 40u);
  EXPECT_EQ(r.front(), 0.005);
  EXPECT_EQ(r.back(), 0.4);
  const double ratio = std::pow(0.4 / 0.005, 1.0 / 39.0);
  for (std::size_t k = 1; k < r.size(); ++k) EXPECT_NEAR(r[k] / r[k - 1], ratio, 1e-12);
  EXPECT_EQ(chaos::log_radii(2.0, 2.0, 1), std::vector<double>{2.0});
  EXPECT_THROW(chaos::log_radii(0.0, 1.0, 5), chaos::InvalidInput);
  EXPECT_THROW(chaos::log_radii(1.0, 0.5, 5), chaos::InvalidInput);
  EXPECT_THROW(chaos::log_radii(1.0, 2.0, 0), chaos::InvalidInput);
  EXPECT_THROW(chaos::log_radii(1.0, 2.0, 1), chaos::InvalidInput);
  EXPECT_THROW(chaos::log_radii(1.0, std::nan(""), 3), chaos::InvalidInput);
  EXPECT_THROW(chaos::log_radii(1.0, 1.0 + 1e-16 * 4, 1000), chaos::InvalidInput);  // not distinct
}

TEST(CorrelationSum, SearchNames) {
  EXPECT_STREQ(chaos::to_string(CorrelationSearch::brute_force), "brute_force");
  EXPECT_STREQ(chaos::to_string(CorrelationSearch::kd_tree), "kd_tree");
  EXPECT_STREQ(chaos::to_string(CorrelationSearch::box_assisted), "box_assisted");
}

// The refusal must carry the code and name the rule's numbers.
void expect_refused(const std::vector<double>& x, const CorrelationSumOptions& o, chaos::ErrorCode code,
                    const std::string& fragment) {
  try {
    chaos::correlation_sum(x, o);
    FAIL() << "accepted; expected a refusal containing '" << fragment << "'";
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(CorrelationSum, InvalidOptionsAreRefused) {
  using chaos::ErrorCode;
  const auto x = uniform(200, 1);
  const auto ok = options(1, 1, 3, 0, {0.1, 0.2});
  auto o = ok;
  o.radii = {};
  expect_refused(x, o, ErrorCode::invalid_parameter, "at least one radius");
  o.radii = {0.1, 0.0};
  expect_refused(x, o, ErrorCode::invalid_parameter, "radius[1] = 0");
  o.radii = {-0.5};
  expect_refused(x, o, ErrorCode::invalid_parameter, "radius[0] = -0.5");
  o.radii = {0.1, std::numeric_limits<double>::infinity()};
  expect_refused(x, o, ErrorCode::invalid_parameter, "radius[1] = inf");
  o.radii = {std::nan("")};
  expect_refused(x, o, ErrorCode::invalid_parameter, "finite and positive");
  o.radii = {0.1, 0.3, 0.3};
  expect_refused(x, o, ErrorCode::invalid_parameter, "radius[2] = 0.29999999999999999 after radius[1]");
  o.radii = {0.2, 0.1};
  expect_refused(x, o, ErrorCode::invalid_parameter, "strictly increasing");
  o.radii = {0.1, std::numeric_limits<double>::max()};
  EXPECT_NO_THROW(o.validate());  // d < the largest double is a valid question
  o.inclusive = true;             // d <= it needs a double above it, and there is none
  expect_refused(x, o, ErrorCode::invalid_parameter, "inclusive counting (d <= eps) a radius must be below the largest double (got radius[1] = 1.7976931348623157e+308)");
  o = ok;
  o.min_dimension = 0;
  expect_refused(x, o, ErrorCode::invalid_parameter, "m = 0");
  o = ok;
  o.min_dimension = 4;
  expect_refused(x, o, ErrorCode::invalid_parameter, "min m = 4 > max m = 3");
  o = ok;
  o.delay = 0;
  expect_refused(x, o, ErrorCode::invalid_parameter, "tau = 0");
  o = ok;
  o.threads = 0;
  expect_refused(x, o, ErrorCode::invalid_parameter, "threads");
  o = ok;
  o.reference_points = 199;  // P = 200 - 2 = 198
  expect_refused(x, o, ErrorCode::invalid_parameter, "198 embedded points");
  // The series: finite, not constant, long enough for one admissible pair, N >= (m-1) tau + w + 2.
  auto bad = x;
  bad[7] = std::nan("");
  expect_refused(bad, ok, ErrorCode::non_finite, "sample 7");
  expect_refused(std::vector<double>(50, 2.5), ok, ErrorCode::constant, "2.5");
  o = ok;
  o.delay = 10;
  o.max_dimension = 5;
  o.theiler = 159;  // needs N >= 4*10 + 159 + 2 = 201
  expect_refused(x, o, ErrorCode::too_short, "N = 200");
  expect_refused(x, o, ErrorCode::too_short, "201");
  o.theiler = 158;
  EXPECT_NO_THROW(chaos::correlation_sum(x, o));  // exactly one admissible pair: (0, 159)
  EXPECT_EQ(chaos::correlation_sum(x, o).examined[0][0], 1u);
  expect_refused(std::vector<double>{}, ok, ErrorCode::too_short, "N = 0");
  // validate() alone checks the options without a series.
  o = ok;
  o.radii = {};
  EXPECT_THROW(o.validate(), chaos::InvalidInput);
  EXPECT_NO_THROW(ok.validate());
}

}  // namespace
