// The largest Lyapunov exponent from a series (chaos/lyapunov.hpp). Expected values come from:
//   - the definitions of Rosenstein et al. 1993 and Kantz 1994 as written in lyapunov.hpp, coded
//     here a second time by brute force (every pair examined, sums in index order): the library's
//     kd-tree version must agree on Hénon, Lorenz and quantised data, every norm, window and subset;
//   - hand-worked cases: a geometric series x_n = a^n, on which every separation grows by exactly a
//     per step (slope ln a), and a four-sample series worked out in the comments, with ties;
//   - constructed divergence curves whose straight part is known by construction (the fit);
//   - the documented refusals and conventions (per time unit = per sample / dt; thread count and
//     block size do not change a bit).
#include "chaos/lyapunov.hpp"
#include "chaos/lyapunov_local_maps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "chaos/automatic_analysis.hpp"
#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/neighbors.hpp"
#include "chaos/models/systems.hpp"
#include "chaos/time_scales.hpp"
#include "chaos/models/zoo.hpp"

namespace {

using chaos::LyapunovMethod;
using chaos::LyapunovOptions;
using chaos::LyapunovStatus;
using chaos::Norm;

struct BruteCurve {
  std::vector<std::optional<double>> y;
  std::vector<std::size_t> terms, zeros;
  std::size_t used = 0;
};

double distance(const std::vector<double>& x, std::size_t i, std::size_t j, std::size_t m, std::size_t tau, Norm norm) {
  double acc = 0.0;
  for (std::size_t l = 0; l < m; ++l) {
    const double d = std::abs(x[i + l * tau] - x[j + l * tau]);
    acc = norm == Norm::max ? std::max(acc, d) : acc + d * d;
  }
  return norm == Norm::max ? acc : std::sqrt(acc);
}

// Kantz's neighbourhood as lyapunov.hpp states it: members (ascending) at one exact distance from i
// form a group; a group of more than max_tied_neighbours is represented by that many of its
// members, ordered by delay vector (lexicographically) and then index, at ranks floor(r |G| / cap),
// each weighted |G| / cap; then a list longer than max_neighbours by that many of its entries at
// positions floor(r n / max_neighbours). Returns (j, weight) in index order.
std::vector<std::pair<std::size_t, double>> kantz_followed(const std::vector<double>& x, std::size_t i,
                                                           const std::vector<std::size_t>& partners,
                                                           const LyapunovOptions& o) {
  const std::size_t m = o.dimension, tau = o.delay, cap = o.max_tied_neighbours;
  const auto vector_less = [&](std::size_t a, std::size_t b) {  // lexicographic, coordinates by <
    for (std::size_t l = 0; l < m; ++l) {
      if (x[a + l * tau] < x[b + l * tau]) return true;
      if (x[b + l * tau] < x[a + l * tau]) return false;
    }
    return false;
  };
  std::vector<std::pair<std::size_t, double>> followed;
  if (cap == 0 || partners.size() <= cap) {
    for (const std::size_t j : partners) followed.emplace_back(j, 1.0);
  } else {
    std::vector<std::pair<double, std::size_t>> by_distance;
    for (const std::size_t j : partners) by_distance.emplace_back(distance(x, i, j, m, tau, o.norm), j);
    std::sort(by_distance.begin(), by_distance.end());
    for (std::size_t g = 0, end = 0; g < by_distance.size(); g = end) {
      std::vector<std::size_t> group;
      for (end = g; end < by_distance.size() && by_distance[end].first == by_distance[g].first; ++end)
        group.push_back(by_distance[end].second);
      if (group.size() <= cap) {
        for (const std::size_t j : group) followed.emplace_back(j, 1.0);
        continue;
      }
      std::stable_sort(group.begin(), group.end(), vector_less);  // equal vectors keep index order
      for (std::size_t r = 0; r < cap; ++r)
        followed.emplace_back(group[r * group.size() / cap], static_cast<double>(group.size()) / static_cast<double>(cap));
    }
    std::sort(followed.begin(), followed.end());
  }
  if (o.max_neighbours != 0 && followed.size() > o.max_neighbours) {
    std::vector<std::pair<std::size_t, double>> kept;
    for (std::size_t r = 0; r < o.max_neighbours; ++r) kept.push_back(followed[r * followed.size() / o.max_neighbours]);
    followed = kept;
  }
  return followed;
}

// The definitions, by brute force: reference points and neighbours among the first
// P = N - (m-1) tau - K points; neighbours need |i - j| > w and a positive distance; the nearest
// one (smallest index among equals) for Rosenstein, all closer than eps for Kantz.
BruteCurve brute_force(const std::vector<double>& x, const LyapunovOptions& o) {
  const std::size_t m = o.dimension, tau = o.delay, K = o.steps;
  const std::size_t p = x.size() - (m - 1) * tau - K;
  const std::size_t n = o.reference_points == 0 ? p : std::min(o.reference_points, p);
  const double eps = o.radius.value_or(0.0);
  BruteCurve c;
  std::vector<double> sum(K + 1, 0.0);
  c.terms.assign(K + 1, 0);
  c.zeros.assign(K + 1, 0);
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = r * p / n;
    std::vector<std::size_t> partners;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < p; ++j) {
      if ((i > j ? i - j : j - i) <= o.theiler) continue;
      const double d = distance(x, i, j, m, tau, o.norm);
      if (d == 0.0) continue;
      if (o.method == LyapunovMethod::kantz) {
        if (d < eps) partners.push_back(j);
      } else if (d < best) {
        best = d;
        partners = {j};
      }
    }
    if (partners.empty() || partners.size() < (o.method == LyapunovMethod::kantz ? o.min_neighbours : 1)) continue;
    ++c.used;
    const auto followed = o.method == LyapunovMethod::kantz ? kantz_followed(x, i, partners, o)
                                                             : std::vector<std::pair<std::size_t, double>>{};
    for (std::size_t k = 0; k <= K; ++k) {
      if (o.method == LyapunovMethod::rosenstein) {
        const double d = distance(x, i + k, partners[0] + k, m, tau, o.norm);
        if (d > 0.0) {
          sum[k] += std::log(d);
          ++c.terms[k];
        } else {
          ++c.zeros[k];
        }
      } else {
        double mean = 0.0, weight = 0.0;
        for (const auto& [j, w] : followed) {
          mean += w * distance(x, i + k, j + k, m, tau, o.norm);
          weight += w;
        }
        if (mean > 0.0) {
          sum[k] += std::log(mean / weight);
          ++c.terms[k];
        } else {
          ++c.zeros[k];
        }
      }
    }
  }
  for (std::size_t k = 0; k <= K; ++k)
    c.y.push_back(c.terms[k] > 0 ? std::optional<double>(sum[k] / static_cast<double>(c.terms[k])) : std::nullopt);
  return c;
}

void expect_matches_definition(const std::vector<double>& x, const LyapunovOptions& o, const std::string& label) {
  const chaos::DivergenceCurve got = chaos::divergence_curve(x, o);
  // Kantz's default radius has its own test (KantzDefaultRadiusRule); here the definition is
  // evaluated at the radius the library chose.
  LyapunovOptions with_radius = o;
  if (o.method == LyapunovMethod::kantz) with_radius.radius = got.radius;
  const BruteCurve want = brute_force(x, with_radius);
  ASSERT_EQ(got.step.size(), o.steps + 1) << label;
  EXPECT_EQ(got.references_used, want.used) << label;
  EXPECT_EQ(got.terms, want.terms) << label;
  EXPECT_EQ(got.zero_distances, want.zeros) << label;
  for (std::size_t k = 0; k <= o.steps; ++k) {
    EXPECT_EQ(got.step[k], k);
    ASSERT_EQ(got.divergence[k].has_value(), want.y[k].has_value()) << label << " k=" << k;
    // Sums in blocks versus one running sum, and the ln of products of 64 mantissas plus the
    // summed exponents times ln 2 versus the sum of ln d: rounding only.
    if (want.y[k]) {
      EXPECT_NEAR(*got.divergence[k], *want.y[k], 1e-12 * (1.0 + std::abs(*want.y[k]))) << label << " k=" << k;
    }
  }
}

std::vector<double> quantised(std::vector<double> x, double q) {
  for (double& v : x) v = q * std::round(v / q);
  return x;
}

TEST(LargestLyapunov, RosensteinEqualsTheDefinition) {
  const auto henon = chaos::henon(700).components[0];
  const auto lorenz = chaos::lorenz(900).components[0];
  const auto rounded = quantised(lorenz, 1.0);  // many exact ties, zero distances at later steps
  struct Case {
    const char* name;
    const std::vector<double>* x;
    std::size_t m, tau, w, steps, references;
    Norm norm;
  };
  const std::vector<Case> cases{
      {"henon m2", &henon, 2, 1, 0, 15, 0, Norm::max},         {"henon m3 w5", &henon, 3, 1, 5, 10, 0, Norm::euclidean},
      {"henon subset", &henon, 2, 2, 3, 12, 97, Norm::max},    {"lorenz", &lorenz, 3, 8, 20, 60, 0, Norm::max},
      {"lorenz euclid", &lorenz, 4, 5, 40, 30, 200, Norm::euclidean},
      {"lorenz rounded", &rounded, 3, 8, 20, 60, 0, Norm::max}, {"rounded m1", &rounded, 1, 1, 0, 20, 0, Norm::max},
  };
  for (const auto& c : cases) {
    LyapunovOptions o;
    o.dimension = c.m;
    o.delay = c.tau;
    o.theiler = c.w;
    o.steps = c.steps;
    o.reference_points = c.references;
    o.norm = c.norm;
    // The definition averages every member; the thinning of large tie groups (tested in
    // hostile_input_test.cpp) is a representation of that mean, so it is off here.
    o.max_tied_neighbours = 0;
    expect_matches_definition(*c.x, o, c.name);
  }
  // The rounded series really exercises the tie rules: zero distances at later steps.
  LyapunovOptions o;
  o.dimension = 1;
  o.steps = 20;
  const auto curve = chaos::divergence_curve(rounded, o);
  std::size_t zeros = 0;
  for (const auto z : curve.zero_distances) zeros += z;
  EXPECT_GT(zeros, 0u);
}

// Kantz's options for the definition tests: embedding, window, steps, radius (nullopt: the
// automatic one) and norm; the rest at their defaults.
LyapunovOptions kantz_options(std::size_t m, std::size_t tau, std::size_t w, std::size_t steps,
                              std::optional<double> radius, Norm norm) {
  LyapunovOptions o;
  o.method = LyapunovMethod::kantz;
  o.dimension = m;
  o.delay = tau;
  o.theiler = w;
  o.steps = steps;
  o.radius = radius;
  o.norm = norm;
  return o;
}

TEST(LargestLyapunov, KantzEqualsTheDefinition) {
  const auto henon = chaos::henon(700).components[0];
  const auto lorenz = chaos::lorenz(900).components[0];
  const auto rounded = quantised(henon, 0.05);
  struct Case {
    const char* name;
    const std::vector<double>* x;
    std::size_t m, tau, w, steps, references, min_neighbours;
    std::optional<double> radius;
    Norm norm;
  };
  const std::vector<Case> cases{
      {"henon default eps", &henon, 2, 1, 0, 15, 0, 1, std::nullopt, Norm::max},
      {"henon eps 0.05", &henon, 2, 1, 2, 12, 0, 1, 0.05, Norm::euclidean},
      {"henon min 3", &henon, 3, 1, 0, 10, 150, 3, 0.1, Norm::max},
      {"lorenz", &lorenz, 3, 8, 20, 50, 0, 1, 1.0, Norm::max},
      {"henon rounded", &rounded, 2, 1, 0, 15, 0, 1, 0.12, Norm::max},
  };
  for (const auto& c : cases) {
    LyapunovOptions o = kantz_options(c.m, c.tau, c.w, c.steps, c.radius, c.norm);
    o.reference_points = c.references;
    o.min_neighbours = c.min_neighbours;
    // The definition averages every member; the thinning of large tie groups (tested in
    // hostile_input_test.cpp) is a representation of that mean, so it is off here.
    o.max_tied_neighbours = 0;
    expect_matches_definition(*c.x, o, c.name);
  }
}

// Ties and the neighbour cap (lyapunov.hpp, max_tied_neighbours and max_neighbours) against the
// definition coded above. Lorenz x on three levels holds 12 distinct delay vectors in m = 3 and
// Hénon rounded to 0.05 about 300 in m = 2, so the library groups the points by vector and never
// lists a neighbourhood; Hénon rounded to 0.005 holds too many, so the kd-tree lists them and the
// groups are thinned from the list. Both must give the definition's members and weights, with and
// without the cap.
TEST(LargestLyapunov, KantzTiesAndCapEqualTheDefinition) {
  std::vector<double> levels = chaos::lorenz(3000).components[0];
  const auto [lo, hi] = std::minmax_element(levels.begin(), levels.end());
  const double low = *lo, span = *hi - *lo;
  for (double& v : levels) v = std::min(2.0, std::floor(3.0 * (v - low) / span));
  const auto henon = chaos::henon(3000).components[0];
  const auto rounded = quantised(henon, 0.05), fine = quantised(henon, 0.005);
  struct Case {
    const char* name;
    const std::vector<double>* x;
    std::size_t m, tau, w, steps, max_neighbours;
    double radius;
    Norm norm;
  };
  const std::vector<Case> cases{
      {"three levels max", &levels, 3, 8, 20, 12, 0, 1.5, Norm::max},
      {"three levels euclid capped", &levels, 3, 8, 20, 12, 10, 1.5, Norm::euclidean},
      {"three levels capped", &levels, 3, 8, 20, 12, 5, 2.5, Norm::max},
      {"rounded henon", &rounded, 2, 1, 3, 10, 0, 0.12, Norm::max},
      {"rounded henon capped", &rounded, 2, 1, 3, 10, 20, 0.12, Norm::euclidean},
      {"finely rounded henon", &fine, 2, 1, 3, 10, 0, 0.03, Norm::max},
      {"finely rounded henon capped", &fine, 2, 1, 3, 10, 12, 0.03, Norm::max},
  };
  for (const auto& c : cases) {
    LyapunovOptions o = kantz_options(c.m, c.tau, c.w, c.steps, c.radius, c.norm);
    o.max_neighbours = c.max_neighbours;
    o.reference_points = 400;
    expect_matches_definition(*c.x, o, c.name);
    const chaos::DivergenceCurve curve = chaos::divergence_curve(*c.x, o);
    EXPECT_GT(curve.tied_neighbourhoods, 0u) << c.name << ": the case does not exercise the thinning";
    if (c.max_neighbours != 0) {
      EXPECT_GT(curve.capped_neighbourhoods, 0u) << c.name << ": nor the cap";
    }
  }
}

// Mean neighbour count and the fraction of reference points with at least one neighbour, over
// the 1000 evenly spaced reference points i = r P / 1000 of lyapunov.hpp's default-radius rule,
// counted with the kd-tree (tested equal to brute force in tests/property/neighbors_test.cpp).
struct Census {
  double mean = 0.0, covered = 0.0;
};
Census census(const std::vector<double>& x, const LyapunovOptions& o, double r) {
  const std::size_t p = x.size() - (o.dimension - 1) * o.delay - o.steps;
  const chaos::DelayEmbedding points(x, o.dimension, o.delay, p);
  const chaos::KdTree tree(points, Norm::max);
  Census c;
  for (std::size_t k = 0; k < 1000; ++k) {
    const std::size_t n = tree.count_within(k * p / 1000, r, {o.theiler, true});
    c.mean += static_cast<double>(n) / 1000.0;
    c.covered += n >= 1 ? 1.0 / 1000.0 : 0.0;
  }
  return c;
}

double power_of_two_steps(const std::vector<double>& x, double eps) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double ratio = eps / ((*hi - *lo) / 1000.0);
  const double h = std::round(std::log2(ratio));
  EXPECT_EQ(ratio, std::exp2(h)) << "eps is not range / 1000 times a power of two";
  return h;
}

TEST(LargestLyapunov, KantzDefaultRadiusRule) {
  // Halving: Hénon with N = 6 10^4 has about 26 neighbours within range / 1000, so eps is halved
  // until the mean is at most 20 (coverage stays near 1).
  auto x = chaos::henon(60'000).components[0];
  LyapunovOptions o;
  o.method = LyapunovMethod::kantz;
  o.steps = 5;
  double eps = chaos::divergence_curve(x, o).radius;
  EXPECT_LE(power_of_two_steps(x, eps), -1.0);
  EXPECT_LE(census(x, o, eps).mean, 20.0);
  EXPECT_GT(census(x, o, 2.0 * eps).mean, 20.0);
  EXPECT_GE(census(x, o, eps).covered, 0.5);
  // Doubling: Lorenz x with N = 10^4, m = 3, tau = 17, w = 100: within range / 1000 most reference
  // points have no neighbour, so eps is doubled until at least half of them have one.
  x = chaos::lorenz(10'000).components[0];
  o.dimension = 3;
  o.delay = 17;
  o.theiler = 100;
  o.steps = 500;
  eps = chaos::divergence_curve(x, o).radius;
  EXPECT_GE(power_of_two_steps(x, eps), 1.0);
  EXPECT_GE(census(x, o, eps).covered, 0.5);
  EXPECT_LT(census(x, o, eps / 2.0).covered, 0.5);
}

TEST(LargestLyapunov, GeometricSeriesGrowsByExactlyLnAPerStep) {
  // x_n = 1.5^n: every separation |x_{i+k} - x_{j+k}| = 1.5^k |x_i - x_j|, so both curves rise by
  // exactly ln 1.5 per step (Rosenstein: each log; Kantz: the log of each neighbourhood's mean),
  // the local slopes are all ln 1.5 and the linear region is the whole curve.
  std::vector<double> x(60);
  for (std::size_t n = 0; n < x.size(); ++n) x[n] = std::pow(1.5, static_cast<double>(n));
  for (const auto method : {LyapunovMethod::rosenstein, LyapunovMethod::kantz}) {
    LyapunovOptions o;
    o.method = method;
    o.steps = 20;
    o.theiler = 2;
    o.radius = 1e30;  // Kantz: every admissible point is a neighbour
    const auto r = chaos::largest_lyapunov(x, o, {}, 0.5);
    for (std::size_t k = 0; k <= o.steps; ++k)
      EXPECT_NEAR(*r.curve.divergence[k] - *r.curve.divergence[0], static_cast<double>(k) * std::log(1.5), 1e-12)
          << to_string(method) << " k=" << k;
    ASSERT_EQ(r.fit.status, LyapunovStatus::linear_region) << r.fit.explanation;
    EXPECT_NEAR(*r.fit.lambda, std::log(1.5), 1e-12);
    EXPECT_EQ(*r.fit.first_step, 0u);
    EXPECT_EQ(*r.fit.last_step, 20u);
    EXPECT_NEAR(r.fit.lambda_interval->low, std::log(1.5), 1e-12);
    EXPECT_NEAR(r.fit.lambda_interval->high, std::log(1.5), 1e-12);
    // Per time unit: per sample / dt, here dt = 0.5.
    EXPECT_DOUBLE_EQ(*r.lambda_per_time, *r.fit.lambda / 0.5);
    EXPECT_DOUBLE_EQ(r.lambda_per_time_interval->high, r.fit.lambda_interval->high / 0.5);
  }
}

TEST(LargestLyapunov, HandWorkedTies) {
  // x = 0 1 5 5, m = 1, K = 1, w = 0: P = 3 reference points 0, 1, 5 (indices 0..2).
  const std::vector<double> x{0, 1, 5, 5};
  LyapunovOptions o;
  o.dimension = 1;
  o.steps = 1;
  // Rosenstein: 0 -> nearest 1 (d 1), then |1 - 5| = 4; 1 -> nearest 0 (d 1, ties go to the
  // smaller index), then |5 - 1| = 4; 5 -> nearest 1 (d 4; its twin at index 3 is not a
  // candidate: it has no future), then |5 - 5| = 0, left out and counted.
  auto c = chaos::divergence_curve(x, o);
  EXPECT_NEAR(*c.divergence[0], std::log(4.0) / 3.0, 1e-15);
  EXPECT_NEAR(*c.divergence[1], std::log(4.0), 1e-15);
  EXPECT_EQ(c.terms, (std::vector<std::size_t>{3, 2}));
  EXPECT_EQ(c.zero_distances, (std::vector<std::size_t>{0, 1}));
  // Kantz, eps = 10: 0 has {1, 5}: mean 3, then (4 + 4)/2 = 4; 1 has {0, 5}: 2.5, then (4 + 0)/2;
  // 5 has {0, 1}: 4.5, then (4 + 0)/2. A zero inside a neighbourhood only lowers its mean.
  o.method = LyapunovMethod::kantz;
  o.radius = 10.0;
  c = chaos::divergence_curve(x, o);
  EXPECT_NEAR(*c.divergence[0], (std::log(3.0) + std::log(2.5) + std::log(4.5)) / 3.0, 1e-15);
  EXPECT_NEAR(*c.divergence[1], (std::log(4.0) + 2.0 * std::log(2.0)) / 3.0, 1e-15);
  EXPECT_NEAR(c.mean_neighbours, 2.0, 1e-15);
  // eps = 4.5: 0 has {1}: 1, then 4; 1 has {0, 5}: 2.5, then 2; 5 has {1}: 4, then 0 (every
  // distance zero: no logarithm, left out and counted).
  o.radius = 4.5;
  c = chaos::divergence_curve(x, o);
  EXPECT_NEAR(*c.divergence[0], (std::log(1.0) + std::log(2.5) + std::log(4.0)) / 3.0, 1e-15);
  EXPECT_NEAR(*c.divergence[1], (std::log(4.0) + std::log(2.0)) / 2.0, 1e-15);
  EXPECT_EQ(c.terms, (std::vector<std::size_t>{3, 2}));
  EXPECT_EQ(c.zero_distances, (std::vector<std::size_t>{0, 1}));
  // eps = 0.5: nobody has a neighbour; every value is undefined and the fit says so.
  o.radius = 0.5;
  const auto r = chaos::largest_lyapunov(x, o);
  for (const auto& v : r.curve.divergence) EXPECT_FALSE(v.has_value());
  EXPECT_EQ(r.fit.status, LyapunovStatus::no_neighbours);
  EXPECT_FALSE(r.fit.lambda.has_value());
}

TEST(LargestLyapunov, QuantisedDataGiveNoInfinityOrNaN) {
  // Hénon rounded to 0.01 and Lorenz rounded to integers: the nearest neighbour at a positive
  // distance and the leave-out rule keep every value finite (Kantz with eps = 1.5 quanta: the
  // neighbours are the points exactly one quantum away in some coordinate).
  struct Set {
    std::vector<double> x;
    double quantum;
    std::size_t delay;
  };
  const std::vector<Set> sets{{quantised(chaos::henon(3000).components[0], 0.01), 0.01, 1},
                              {quantised(chaos::lorenz(3000).components[0], 1.0), 1.0, 8}};
  for (const auto& set : sets)
    for (const auto method : {LyapunovMethod::rosenstein, LyapunovMethod::kantz}) {
      LyapunovOptions o;
      o.method = method;
      o.dimension = 3;
      o.delay = set.delay;
      o.steps = 40;
      o.radius = 1.5 * set.quantum;
      const auto r = chaos::largest_lyapunov(set.x, o);
      EXPECT_GT(r.curve.references_used, 0u);
      for (const auto& v : r.curve.divergence) EXPECT_TRUE(!v || std::isfinite(*v));
      for (const auto& v : r.fit.local_slope) EXPECT_TRUE(!v || std::isfinite(*v));
      EXPECT_TRUE(!r.fit.lambda || std::isfinite(*r.fit.lambda));
    }
}

TEST(LargestLyapunov, ThreadsDoNotChangeABit) {
  // Partial sums are formed per block of 512 reference points and added in block order, in rounds
  // of 256 blocks: N = 3000 is one round of 6 blocks, N = 1.4 10^5 two rounds.
  for (const auto& [n, method] : {std::pair{3000u, LyapunovMethod::rosenstein}, std::pair{3000u, LyapunovMethod::kantz},
                                  std::pair{140'000u, LyapunovMethod::rosenstein}}) {
    const auto x = chaos::henon(n).components[0];
    LyapunovOptions o;
    o.method = method;
    o.steps = n > 3000 ? 3 : 15;
    const auto one = chaos::divergence_curve(x, o);
    // Every block counted: on Hénon every one of the P = N - (m-1) tau - K = N - 1 - K reference
    // points has a neighbour.
    if (method == LyapunovMethod::rosenstein) {
      EXPECT_EQ(one.terms[0], n - 1 - o.steps);
    }
    for (const std::size_t threads : n > 3000 ? std::vector<std::size_t>{3} : std::vector<std::size_t>{2, 3, 8}) {
      o.threads = threads;
      const auto many = chaos::divergence_curve(x, o);
      ASSERT_EQ(many.divergence.size(), one.divergence.size());
      for (std::size_t k = 0; k < one.divergence.size(); ++k) EXPECT_EQ(*many.divergence[k], *one.divergence[k]);
      EXPECT_EQ(many.terms, one.terms);
    }
  }
}

TEST(LargestLyapunov, WhiteNoiseGivesNoExponent) {
  // Independent samples have no exponential divergence: the curve jumps to its saturation level
  // within m steps and stays flat, so no stretch has local slopes within 10% of a positive mean.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto x = chaos::white_noise(4000, seed).components[0];
    for (const auto method : {LyapunovMethod::rosenstein, LyapunovMethod::kantz}) {
      LyapunovOptions o;
      o.method = method;
      const auto r = chaos::largest_lyapunov(x, o);
      EXPECT_FALSE(r.fit.lambda.has_value()) << "seed " << seed << " " << to_string(method) << ": " << *r.fit.lambda;
      EXPECT_NE(r.fit.status, LyapunovStatus::linear_region);
    }
  }
}

chaos::DivergenceCurve constructed(const std::vector<std::optional<double>>& y) {
  chaos::DivergenceCurve c;
  for (std::size_t k = 0; k < y.size(); ++k) c.step.push_back(k);
  c.divergence = y;
  c.terms.assign(y.size(), 1);
  c.zero_distances.assign(y.size(), 0);
  c.references_used = 1;
  c.reference_points = 1;
  return c;
}

TEST(FitDivergence, StraightPartOfConstructedCurves) {
  // A line of slope 0.3 up to step 15, then flat at its value there (K = 40, so half width 2 and
  // at least 7 steps). Local slopes are exactly 0.3 up to step 13 (their 5-step windows lie on the
  // line); at 14 the window reaches the plateau (slope 0.24, 20% low); the plateau's slopes are 0,
  // which does not rise and is never a candidate (though perfectly straight and wider). Region
  // 0..13, lambda 0.3.
  std::vector<std::optional<double>> y;
  for (std::size_t k = 0; k <= 40; ++k) y.push_back(-5.0 + 0.3 * static_cast<double>(std::min<std::size_t>(k, 15)));
  auto fit = chaos::fit_divergence(constructed(y));
  ASSERT_EQ(fit.status, LyapunovStatus::linear_region) << fit.explanation;
  EXPECT_EQ(fit.half_width, 2u);
  EXPECT_EQ(fit.min_steps, 7u);
  EXPECT_EQ(*fit.first_step, 0u);
  EXPECT_EQ(*fit.last_step, 13u);
  EXPECT_NEAR(*fit.lambda, 0.3, 1e-12);
  EXPECT_NEAR(*fit.local_slope[14], 0.24, 1e-12);

  // A hole (an undefined step 10) splits the line: a region is contiguous and defined, and the
  // side after the hole (11..13) is shorter than 7 steps, so the region is 0..9.
  y[10] = std::nullopt;
  fit = chaos::fit_divergence(constructed(y));
  ASSERT_EQ(fit.status, LyapunovStatus::linear_region);
  EXPECT_EQ(*fit.first_step, 0u);
  EXPECT_EQ(*fit.last_step, 9u);
  EXPECT_NEAR(*fit.lambda, 0.3, 1e-12);

  // Falling: no local slope is positive: not diverging, no number.
  std::vector<std::optional<double>> down;
  for (std::size_t k = 0; k <= 30; ++k) down.push_back(-0.3 * static_cast<double>(k));
  fit = chaos::fit_divergence(constructed(down));
  EXPECT_EQ(fit.status, LyapunovStatus::not_diverging);
  EXPECT_FALSE(fit.lambda.has_value());

  // Flat with an irregular ripple: local slopes scatter around 0, never within 10% of their mean.
  std::vector<std::optional<double>> flat;
  for (std::size_t k = 0; k <= 30; ++k) flat.push_back(0.01 * std::sin(2.3 * static_cast<double>(k * k)));
  fit = chaos::fit_divergence(constructed(flat));
  EXPECT_EQ(fit.status, LyapunovStatus::no_linear_region);
  EXPECT_FALSE(fit.lambda.has_value());

  // Nobody had a neighbour.
  auto empty = constructed(std::vector<std::optional<double>>(21));
  empty.references_used = 0;
  EXPECT_EQ(chaos::fit_divergence(empty).status, LyapunovStatus::no_neighbours);

  // Explicit settings replace the automatic ones; a long curve widens the automatic half width.
  chaos::LyapunovFitOptions wide;
  wide.half_width = 3;
  wide.min_steps = 12;
  fit = chaos::fit_divergence(constructed(y), wide);
  EXPECT_EQ(fit.half_width, 3u);
  EXPECT_EQ(fit.min_steps, 12u);
  std::vector<std::optional<double>> long_line;
  for (std::size_t k = 0; k <= 500; ++k) long_line.push_back(0.01 * static_cast<double>(k));
  fit = chaos::fit_divergence(constructed(long_line));
  EXPECT_EQ(fit.half_width, 20u);  // 500 / 25
  EXPECT_EQ(fit.min_steps, 61u);
  EXPECT_NEAR(*fit.lambda, 0.01, 1e-12);
}

// The rise rule: a straight stretch is only an exponential divergence if the separation grows
// across it by min_rise e-folds (default 2). A line rising 1.5 in total is refused by default and
// accepted when the user lowers the bar to 1.
TEST(FitDivergence, StraightStretchMustRiseEnough) {
  std::vector<std::optional<double>> y;
  for (std::size_t k = 0; k <= 150; ++k) y.push_back(-4.0 + 0.01 * static_cast<double>(k));
  auto fit = chaos::fit_divergence(constructed(y));
  EXPECT_EQ(fit.status, LyapunovStatus::no_linear_region) << fit.explanation;
  EXPECT_FALSE(fit.lambda.has_value());
  chaos::LyapunovFitOptions low;
  low.min_rise = 1.0;
  fit = chaos::fit_divergence(constructed(y), low);
  ASSERT_EQ(fit.status, LyapunovStatus::linear_region) << fit.explanation;
  EXPECT_NEAR(*fit.lambda, 0.01, 1e-12);
}

// A rotating flow modulates the divergence with its period: y = 0.01 k + 0.3 sin(2 pi k / 50). The
// modulation's slope swings by 0.3 * 2 pi / 50 = 0.038, four times the exponent, so short local
// slopes never agree within 10%. With period = 50 the local slopes are secants over one whole
// period, in which the sine cancels exactly: every one is 0.01, and so is the fit (the least-
// squares line over the region keeps a ripple of order 0.3 * 6 / (pi * region length)).
TEST(FitDivergence, OscillatingCurveNeedsWholePeriods) {
  std::vector<std::optional<double>> y;
  for (std::size_t k = 0; k <= 300; ++k) {
    const double t = static_cast<double>(k);
    y.push_back(-4.0 + 0.01 * t + 0.3 * std::sin(2.0 * std::numbers::pi * t / 50.0));
  }
  auto fit = chaos::fit_divergence(constructed(y));
  EXPECT_EQ(fit.status, LyapunovStatus::no_linear_region) << fit.explanation;
  chaos::LyapunovFitOptions periodic;
  periodic.period = 50;
  fit = chaos::fit_divergence(constructed(y), periodic);
  ASSERT_EQ(fit.status, LyapunovStatus::linear_region) << fit.explanation;
  EXPECT_EQ(fit.half_width, 25u);
  EXPECT_GE(fit.min_steps, 51u);
  for (std::size_t k = 25; k + 25 <= 300; ++k) EXPECT_NEAR(*fit.local_slope[k], 0.01, 1e-12) << k;
  EXPECT_NEAR(*fit.lambda, 0.01, 0.0005);
}

// Curves of several embedding dimensions must agree: slopes 0.01 and 0.0104 (4% apart) are fitted
// together to their mean; 0.01 and 0.013 (30% apart) are refused, never averaged into a number.
TEST(FitDivergence, DimensionsMustAgree) {
  const auto line = [](double slope) {
    std::vector<std::optional<double>> y;
    for (std::size_t k = 0; k <= 300; ++k) y.push_back(-4.0 + slope * static_cast<double>(k));
    return constructed(y);
  };
  auto fit = chaos::fit_divergence(std::vector<chaos::DivergenceCurve>{line(0.01), line(0.0104)});
  ASSERT_EQ(fit.status, LyapunovStatus::linear_region) << fit.explanation;
  EXPECT_NEAR(*fit.lambda, 0.0102, 1e-12);
  ASSERT_EQ(fit.lambda_by_curve.size(), 2u);
  fit = chaos::fit_divergence(std::vector<chaos::DivergenceCurve>{line(0.01), line(0.013)});
  EXPECT_EQ(fit.status, LyapunovStatus::no_linear_region) << fit.explanation;
  EXPECT_FALSE(fit.lambda.has_value());
}

template <class F>
void expect_refusal(F&& f, chaos::ErrorCode code, const std::vector<std::string>& fragments) {
  try {
    f();
    ADD_FAILURE() << "accepted";
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    for (const auto& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what() << " lacks '" << fragment << "'";
  }
}

TEST(LargestLyapunov, Refusals) {
  using chaos::ErrorCode;
  const auto x = chaos::henon(200).components[0];
  const auto run = [&](LyapunovOptions o) { return [&x, o] { chaos::largest_lyapunov(x, o); }; };
  LyapunovOptions o;
  // N >= (m-1) tau + K + 2w + 3: with m = 3, tau = 10, K = 100, w = 40 that is 203 > 200.
  o.dimension = 3;
  o.delay = 10;
  o.steps = 100;
  o.theiler = 40;
  expect_refusal(run(o), ErrorCode::too_short, {"N = 200", "203", "m = 3", "tau = 10", "steps = 100", "w = 40"});
  o.theiler = 38;  // 199 <= 200: accepted
  EXPECT_NO_THROW(chaos::largest_lyapunov(x, o));
  o = {};
  o.dimension = 0;
  expect_refusal(run(o), ErrorCode::invalid_parameter, {"m = 0"});
  o = {};
  o.delay = 0;
  expect_refusal(run(o), ErrorCode::invalid_parameter, {"tau = 0"});
  o = {};
  o.steps = 0;
  expect_refusal(run(o), ErrorCode::invalid_parameter, {"steps = 0"});
  o = {};
  o.threads = 0;
  expect_refusal(run(o), ErrorCode::invalid_parameter, {"threads"});
  o = {};
  o.min_neighbours = 0;
  expect_refusal(run(o), ErrorCode::invalid_parameter, {"min_neighbours"});
  for (const double eps : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    o = {};
    o.method = LyapunovMethod::kantz;
    o.radius = eps;
    expect_refusal(run(o), ErrorCode::invalid_parameter, {"eps"});
  }
  std::vector<double> bad = x;
  bad[17] = std::nan("");
  expect_refusal([&] { chaos::largest_lyapunov(bad, {}); }, ErrorCode::non_finite, {"sample 17"});
  const std::vector<double> constant(500, 2.5);
  expect_refusal([&] { chaos::largest_lyapunov(constant, {}); }, ErrorCode::constant, {"constant"});
  expect_refusal([&] { chaos::largest_lyapunov(x, {}, {}, 0.0); }, ErrorCode::invalid_parameter, {"dt"});
  chaos::LyapunovFitOptions fit;
  fit.tolerance = 0.0;
  expect_refusal([&] { chaos::largest_lyapunov(x, {}, fit); }, ErrorCode::invalid_parameter, {"tolerance"});
  fit = {};
  fit.min_steps = 1;
  expect_refusal([&] { chaos::largest_lyapunov(x, {}, fit); }, ErrorCode::invalid_parameter, {"min_steps = 1"});
}

// cross_check's rule, on fits whose values are set by hand (expected outcomes from the rule's
// definition: agreement within tolerance * mean keeps both, anything else withdraws each region).
chaos::LyapunovFit region_fit(double lambda) {
  chaos::LyapunovFit f;
  f.status = LyapunovStatus::linear_region;
  f.lambda = lambda;
  f.lambda_interval = chaos::Interval{0.9 * lambda, 1.1 * lambda};
  f.first_step = 10;
  f.last_step = 40;
  f.lambda_by_curve = {lambda};
  f.explanation = "local slopes agree";
  return f;
}

chaos::LyapunovFit no_region_fit() {
  chaos::LyapunovFit f;
  f.status = LyapunovStatus::no_linear_region;
  f.explanation = "no stretch";
  return f;
}

TEST(LyapunovCrossCheck, TwoEstimatesWithinTheToleranceStandAndAnythingElseIsUnconfirmed) {
  // 0.40 and 0.43 differ by 0.03 <= 0.1 * 0.415: both stand, untouched.
  auto r = region_fit(0.40), k = region_fit(0.43);
  chaos::cross_check(r, k, 0.1);
  EXPECT_EQ(r.status, LyapunovStatus::linear_region);
  EXPECT_EQ(k.status, LyapunovStatus::linear_region);
  EXPECT_EQ(*r.lambda, 0.40);
  EXPECT_EQ(*k.lambda, 0.43);

  // 0.40 and 0.45 differ by 0.05 > 0.1 * 0.425: both withdrawn, both values named.
  r = region_fit(0.40);
  k = region_fit(0.45);
  chaos::cross_check(r, k, 0.1);
  for (const auto* f : {&r, &k}) {
    EXPECT_EQ(f->status, LyapunovStatus::unconfirmed);
    EXPECT_FALSE(f->lambda.has_value());
    EXPECT_FALSE(f->lambda_interval.has_value());
    EXPECT_FALSE(f->first_step.has_value());
    EXPECT_TRUE(f->lambda_by_curve.empty());
    EXPECT_NE(f->explanation.find("0.4 per sample"), std::string::npos) << f->explanation;
    EXPECT_NE(f->explanation.find("0.45 per sample"), std::string::npos) << f->explanation;
  }
  EXPECT_STREQ(chaos::to_string(LyapunovStatus::unconfirmed), "unconfirmed");

  // A region only one estimator finds: that one is withdrawn, the other keeps its own status.
  r = region_fit(0.40);
  k = no_region_fit();
  chaos::cross_check(r, k, 0.1);
  EXPECT_EQ(r.status, LyapunovStatus::unconfirmed);
  EXPECT_FALSE(r.lambda.has_value());
  EXPECT_NE(r.explanation.find("Kantz has no_linear_region"), std::string::npos) << r.explanation;
  EXPECT_EQ(k.status, LyapunovStatus::no_linear_region);
  EXPECT_EQ(k.explanation, "no stretch");

  // Neither: nothing to confirm, nothing changes.
  r = no_region_fit();
  k = no_region_fit();
  chaos::cross_check(r, k, 0.1);
  EXPECT_EQ(r.status, LyapunovStatus::no_linear_region);
  EXPECT_EQ(k.explanation, "no stretch");

  EXPECT_THROW(chaos::cross_check(r, k, 0.0), chaos::InvalidInput);
  EXPECT_THROW(chaos::cross_check(r, k, NAN), chaos::InvalidInput);
}

TEST(LyapunovCrossCheck, HenonIsConfirmedByBothEstimators) {
  // Henon x, N = 5000, m = 2: both estimators have a linear region near lambda_1 = 0.41922 (Sprott;
  // references/references.tsv), within 10% of each other, so the check leaves both standing; the
  // per-time values survive with them.
  const auto x = chaos::henon(5000).components[0];
  LyapunovOptions o;
  o.dimension = 2;
  const chaos::LyapunovFitOptions fit;
  auto r = chaos::largest_lyapunov_rosenstein(x, o, fit, 1.0);
  auto k = chaos::largest_lyapunov_kantz(x, o, fit, 1.0);
  ASSERT_EQ(r.fit.status, LyapunovStatus::linear_region) << r.fit.explanation;
  ASSERT_EQ(k.fit.status, LyapunovStatus::linear_region) << k.fit.explanation;
  chaos::cross_check(r, k);
  EXPECT_EQ(r.fit.status, LyapunovStatus::linear_region) << r.fit.explanation;
  EXPECT_EQ(k.fit.status, LyapunovStatus::linear_region) << k.fit.explanation;
  EXPECT_TRUE(r.lambda_per_time.has_value());
  // Withdrawn on a full result: the per-time values go too.
  auto lonely = chaos::largest_lyapunov_rosenstein(x, o, fit, 1.0);
  chaos::LyapunovResult none;
  none.fit = no_region_fit();
  chaos::cross_check(lonely, none);
  EXPECT_EQ(lonely.fit.status, LyapunovStatus::unconfirmed);
  EXPECT_FALSE(lonely.lambda_per_time.has_value());
  EXPECT_FALSE(lonely.lambda_per_time_interval.has_value());
  EXPECT_FALSE(lonely.fit_range_time.has_value());
}

// The halves rule, on fits whose values are set by hand (expected outcomes from the rule's
// definition: the full record's region stays only when at least one half has one and every half
// that has one agrees with it within tolerance * mean).
TEST(LyapunovHalves, ARegionStaysOnlyWhenAHalfShowsItAndNoHalfContradictsIt) {
  // Halves 0.40 and 0.43 around the full 0.41: each within 0.1 * mean of it, the value stands untouched.
  auto full = region_fit(0.41);
  chaos::require_reproduced_by_halves(full, region_fit(0.40), region_fit(0.43), 0.1);
  EXPECT_EQ(full.status, LyapunovStatus::linear_region);
  EXPECT_EQ(*full.lambda, 0.41);

  // One half silent (no region), the other within the tolerance: the value stands.
  full = region_fit(0.42);
  chaos::require_reproduced_by_halves(full, no_region_fit(), region_fit(0.44), 0.1);
  EXPECT_EQ(full.status, LyapunovStatus::linear_region);

  // A half at 0.48 against the full 0.42: 0.06 > 0.1 * 0.45, withdrawn with both halves named.
  full = region_fit(0.42);
  chaos::require_reproduced_by_halves(full, region_fit(0.40), region_fit(0.48), 0.1);
  EXPECT_EQ(full.status, LyapunovStatus::not_reproduced);
  EXPECT_FALSE(full.lambda.has_value());
  EXPECT_FALSE(full.lambda_interval.has_value());
  EXPECT_FALSE(full.first_step.has_value());
  EXPECT_TRUE(full.lambda_by_curve.empty());
  EXPECT_NE(full.explanation.find("first half gives 0.4 per sample"), std::string::npos) << full.explanation;
  EXPECT_NE(full.explanation.find("second half gives 0.48 per sample"), std::string::npos) << full.explanation;
  EXPECT_STREQ(chaos::to_string(LyapunovStatus::not_reproduced), "not_reproduced");

  // A contradicting half is not excused by a silent one.
  full = region_fit(0.42);
  chaos::require_reproduced_by_halves(full, no_region_fit(), region_fit(0.30), 0.1);
  EXPECT_EQ(full.status, LyapunovStatus::not_reproduced);

  // Neither half has a region: withdrawn, both statuses named.
  full = region_fit(0.42);
  chaos::require_reproduced_by_halves(full, no_region_fit(), no_region_fit(), 0.1);
  EXPECT_EQ(full.status, LyapunovStatus::not_reproduced);
  EXPECT_NE(full.explanation.find("first half has no_linear_region"), std::string::npos) << full.explanation;
  EXPECT_NE(full.explanation.find("second half has no_linear_region"), std::string::npos) << full.explanation;

  // No region in the full record: nothing to reproduce, nothing changes.
  full = no_region_fit();
  chaos::require_reproduced_by_halves(full, region_fit(0.40), region_fit(0.80), 0.1);
  EXPECT_EQ(full.status, LyapunovStatus::no_linear_region);
  EXPECT_EQ(full.explanation, "no stretch");

  EXPECT_THROW(chaos::require_reproduced_by_halves(full, full, full, -0.1), chaos::InvalidInput);
}

// Two results are the same to the last bit: every value of the curves, the fits and the answers.
void expect_identical(const chaos::LyapunovResult& a, const chaos::LyapunovResult& b) {
  ASSERT_EQ(a.curve.divergence.size(), b.curve.divergence.size());
  for (std::size_t k = 0; k < a.curve.divergence.size(); ++k) {
    ASSERT_EQ(a.curve.divergence[k].has_value(), b.curve.divergence[k].has_value()) << "step " << k;
    if (a.curve.divergence[k]) {
      EXPECT_EQ(*a.curve.divergence[k], *b.curve.divergence[k]) << "step " << k;
    }
  }
  EXPECT_EQ(a.curve.terms, b.curve.terms);
  EXPECT_EQ(a.curve.zero_distances, b.curve.zero_distances);
  EXPECT_EQ(a.curve.references_used, b.curve.references_used);
  EXPECT_EQ(a.curve.radius, b.curve.radius);
  EXPECT_EQ(a.curve.mean_neighbours, b.curve.mean_neighbours);
  EXPECT_EQ(a.fit.status, b.fit.status);
  EXPECT_EQ(a.fit.explanation, b.fit.explanation);
  EXPECT_EQ(a.fit.lambda, b.fit.lambda);
  EXPECT_EQ(a.fit.lambda_by_curve, b.fit.lambda_by_curve);
  EXPECT_EQ(a.fit.estimate.value, b.fit.estimate.value);
  EXPECT_EQ(a.fit.estimate.reason, b.fit.estimate.reason);
  EXPECT_EQ(a.dimensions, b.dimensions);
}

TEST(LargestLyapunov, RunsOnSharedEmbeddingsEqualSeparateRuns) {
  // largest_lyapunov_runs embeds each dimension once for Rosenstein and Kantz; the expected values
  // are the separate runs', so any difference in the shared embedding, tree, reference order or
  // Kantz radius shows. Henon x (a map, K = 20) and Lorenz x (a flow, w > 0, a reference subset),
  // quantised Henon (ties, zero distances), both norms; then the halves check on both at once
  // against each on its own.
  const auto henon = chaos::henon(6000).components[0];
  const auto lorenz = chaos::lorenz(8000).components[0];
  std::vector<double> quantised = henon;
  for (double& v : quantised) v = std::round(v * 100.0) / 100.0;
  struct Case {
    const std::vector<double>* x;
    std::size_t m, tau, w, steps, references;
    Norm norm;
  };
  for (const Case& c : {Case{&henon, 2, 1, 0, 20, 0, Norm::max}, Case{&lorenz, 3, 17, 40, 300, 1500, Norm::euclidean},
                        Case{&quantised, 2, 1, 2, 20, 0, Norm::max}}) {
    LyapunovOptions r;
    r.dimension = c.m;
    r.delay = c.tau;
    r.theiler = c.w;
    r.steps = c.steps;
    r.reference_points = c.references;
    r.norm = c.norm;
    LyapunovOptions k = r;
    k.method = LyapunovMethod::kantz;
    chaos::LyapunovFitOptions fit;
    fit.dimensions = 3;
    auto both = chaos::largest_lyapunov_runs(*c.x, {r, k}, fit, 0.01);
    ASSERT_EQ(both.size(), 2u);
    auto alone_r = chaos::largest_lyapunov(*c.x, r, fit, 0.01);
    auto alone_k = chaos::largest_lyapunov(*c.x, k, fit, 0.01);
    expect_identical(both[0], alone_r);
    expect_identical(both[1], alone_k);
    std::vector<chaos::LyapunovResult*> pair{&both[0], &both[1]};
    chaos::check_record_halves(std::span<chaos::LyapunovResult* const>(pair), *c.x, {r, k}, fit);
    chaos::check_record_halves(alone_r, *c.x, r, fit);
    chaos::check_record_halves(alone_k, *c.x, k, fit);
    expect_identical(both[0], alone_r);
    expect_identical(both[1], alone_k);
  }
  // Runs that do not share their embeddings are refused.
  LyapunovOptions a, b;
  b.delay = 2;
  EXPECT_THROW(chaos::largest_lyapunov_runs(henon, {a, b}), chaos::InvalidInput);
}

TEST(LyapunovHalves, HenonIsReproducedAndAShortRotatingFlowIsNot) {
  // Henon x, N = 2 * 10^4, m = 2: each half of 10^4 iterations diverges at lambda_1 = 0.41922 (Sprott;
  // references/references.tsv) as the whole does, so the check keeps the value and its per-time twin.
  const auto h = chaos::henon(20000).components[0];
  LyapunovOptions o;
  o.dimension = 2;
  const chaos::LyapunovFitOptions fit;
  auto r = chaos::largest_lyapunov_rosenstein(h, o, fit, 1.0);
  ASSERT_EQ(r.fit.status, LyapunovStatus::linear_region) << r.fit.explanation;
  const double before = *r.fit.lambda;
  chaos::check_record_halves(r, h, o, fit);
  EXPECT_EQ(r.fit.status, LyapunovStatus::linear_region) << r.fit.explanation;
  EXPECT_EQ(*r.fit.lambda, before);
  EXPECT_TRUE(r.lambda_per_time.has_value());

  // The zoo's Genesio-Tesi x (dt = 0.05), its first 10^4 samples, at the neighbourhood grid's
  // m = 6..8, tau = 31, w = 63: Rosenstein finds a straight stretch at 0.0858 per time unit, 16%
  // below lambda_1 = 0.1019 from the equations (docs/validation/zoo.md; Kantz's 0.0935 confirmed it within
  // 10%), while neither half of 5000 samples has a linear region. The check withdraws it.
  const chaos::ZooEntry* e = chaos::find_zoo_system("genesio_tesi");
  ASSERT_NE(e, nullptr);
  const auto x = chaos::zoo_trajectory(*e, 10000).components[e->component];
  const chaos::TimeScales scales = chaos::time_scales(x);
  const LyapunovOptions g = chaos::choose_lyapunov_options(scales, x.size(), 6, 31, 63, LyapunovMethod::rosenstein);
  const chaos::LyapunovFitOptions gfit = chaos::choose_lyapunov_fit(scales);
  auto gt = chaos::largest_lyapunov(x, g, gfit, e->dt);
  ASSERT_EQ(gt.fit.status, LyapunovStatus::linear_region) << gt.fit.explanation;
  EXPECT_NEAR(*gt.lambda_per_time, 0.0858, 0.0005);
  chaos::check_record_halves(gt, x, g, gfit);
  EXPECT_EQ(gt.fit.status, LyapunovStatus::not_reproduced) << gt.fit.explanation;
  EXPECT_FALSE(gt.lambda_per_time.has_value());
  EXPECT_FALSE(gt.fit_range_time.has_value());
}

// The check against a local-map exponent (expected outcomes from the rule's definition): a
// consistent local-map value keeps a slope within tolerance * mean of it and withdraws one further
// away; any other local-map result (not_deterministic: noise at the neighbours' scale; inconsistent;
// not_positive; not run at all) withdraws every slope; the local-map result itself is never changed
// (it is passed as const).
chaos::LocalMapResult local_map_result(chaos::LocalMapStatus status, std::optional<double> lambda) {
  chaos::LocalMapResult m;
  m.status = status;
  m.lambda = lambda;
  return m;
}

TEST(LyapunovCrossCheck, ASlopeStandsOnlyWhereAConsistentLocalMapExponentConfirmsIt) {
  using chaos::LocalMapStatus;
  const auto consistent = local_map_result(LocalMapStatus::consistent, 0.1017);
  // Genesio-Tesi's zoo row (N = 10^5, m = 4): Rosenstein 0.0915, local maps 0.1017 per time unit;
  // 0.0102 > 0.1 * 0.0966, so the slope is withdrawn and both values are named.
  auto r = region_fit(0.0915);
  chaos::cross_check(r, chaos::LyapunovMethod::rosenstein, consistent, 0.1);
  EXPECT_EQ(r.status, LyapunovStatus::unconfirmed);
  EXPECT_FALSE(r.lambda.has_value());
  EXPECT_FALSE(r.lambda_interval.has_value());
  EXPECT_NE(r.explanation.find("Rosenstein gives 0.0915 per sample"), std::string::npos) << r.explanation;
  EXPECT_NE(r.explanation.find("local maps give 0.1017"), std::string::npos) << r.explanation;
  // Kantz's 0.0949 on the same row: 0.0068 <= 0.1 * 0.0983, it stands untouched.
  auto k = region_fit(0.0949);
  chaos::cross_check(k, chaos::LyapunovMethod::kantz, consistent, 0.1);
  EXPECT_EQ(k.status, LyapunovStatus::linear_region);
  EXPECT_EQ(*k.lambda, 0.0949);
  EXPECT_EQ(k.explanation, "local slopes agree");
  // A slope above the local maps is withdrawn the same way (the rule is symmetric in value).
  k = region_fit(0.115);
  chaos::cross_check(k, chaos::LyapunovMethod::kantz, consistent, 0.1);
  EXPECT_EQ(k.status, LyapunovStatus::unconfirmed);
  EXPECT_NE(k.explanation.find("Kantz gives 0.115"), std::string::npos) << k.explanation;
  // An inconsistent or non-positive local-map result confirms nothing, so the slope is withdrawn:
  // a slope stands only on a positive confirmation (Sprott F x with 1% noise at m = 6: Rosenstein
  // and Kantz agree 15% low beside inconsistent maps; docs/notes/zoo-notes.md, section 4).
  for (const auto status : {LocalMapStatus::inconsistent, LocalMapStatus::not_positive}) {
    r = region_fit(0.0915);
    chaos::cross_check(r, chaos::LyapunovMethod::rosenstein, local_map_result(status, std::nullopt), 0.1);
    EXPECT_EQ(r.status, LyapunovStatus::unconfirmed) << chaos::to_string(status);
    EXPECT_FALSE(r.lambda.has_value());
    EXPECT_NE(r.explanation.find(std::string("they are ") + chaos::to_string(status)), std::string::npos)
        << r.explanation;
    EXPECT_NE(r.explanation.find("Rosenstein gives 0.0915 per sample"), std::string::npos) << r.explanation;
  }
  // Maps that could not be run confirm nothing either; the refusal is quoted.
  r = region_fit(0.0915);
  chaos::cross_check_without_local_maps(r, chaos::LyapunovMethod::kantz, "the series is too short");
  EXPECT_EQ(r.status, LyapunovStatus::unconfirmed);
  EXPECT_FALSE(r.lambda.has_value());
  EXPECT_NE(r.explanation.find("(Kantz): the local linear maps were not run: the series is too short"),
            std::string::npos)
      << r.explanation;
  auto unfitted = no_region_fit();
  chaos::cross_check_without_local_maps(unfitted, chaos::LyapunovMethod::kantz, "too short");
  EXPECT_EQ(unfitted.status, LyapunovStatus::no_linear_region);
  EXPECT_EQ(unfitted.explanation, "no stretch");
  // Maps that explain little of their neighbourhoods (median residual 0.87: Henon x with 1% noise)
  // withdraw any slope, whatever its value: the divergence curves start from those neighbours.
  auto noisy = local_map_result(LocalMapStatus::not_deterministic, std::nullopt);
  noisy.base.median_residual = 0.87;
  for (const auto method : {chaos::LyapunovMethod::rosenstein, chaos::LyapunovMethod::kantz}) {
    r = region_fit(0.3544);
    chaos::cross_check(r, method, noisy, 0.1);
    EXPECT_EQ(r.status, LyapunovStatus::unconfirmed) << chaos::to_string(method);
    EXPECT_FALSE(r.lambda.has_value());
    EXPECT_NE(r.explanation.find("87% of their neighbourhoods' image spread unexplained"), std::string::npos)
        << r.explanation;
  }
  // A fit without a region has nothing to withdraw.
  auto none = no_region_fit();
  chaos::cross_check(none, chaos::LyapunovMethod::kantz, consistent, 0.1);
  EXPECT_EQ(none.status, LyapunovStatus::no_linear_region);
  EXPECT_EQ(none.explanation, "no stretch");
  EXPECT_THROW(chaos::cross_check(none, chaos::LyapunovMethod::kantz, consistent, -0.1), chaos::InvalidInput);

  // On a full result the per-time values go with the slope.
  const auto x = chaos::henon(5000).components[0];
  LyapunovOptions o;
  o.dimension = 2;
  auto full = chaos::largest_lyapunov_rosenstein(x, o, {}, 1.0);
  ASSERT_EQ(full.fit.status, LyapunovStatus::linear_region) << full.fit.explanation;
  chaos::cross_check(full, local_map_result(LocalMapStatus::consistent, 2.0 * *full.fit.lambda));
  EXPECT_EQ(full.fit.status, LyapunovStatus::unconfirmed);
  EXPECT_FALSE(full.lambda_per_time.has_value());
  EXPECT_FALSE(full.fit_range_time.has_value());
}

TEST(LargestLyapunov, NamedEntryPointsSetTheMethod) {
  const auto x = chaos::henon(2000).components[0];
  LyapunovOptions o;
  o.method = LyapunovMethod::kantz;
  EXPECT_EQ(chaos::largest_lyapunov_rosenstein(x, o).curve.method, LyapunovMethod::rosenstein);
  o.method = LyapunovMethod::rosenstein;
  const auto k = chaos::largest_lyapunov_kantz(x, o);
  EXPECT_EQ(k.curve.method, LyapunovMethod::kantz);
  ASSERT_TRUE(k.options.radius.has_value());  // the radius used is recorded
  EXPECT_EQ(*k.options.radius, k.curve.radius);
  EXPECT_STREQ(chaos::to_string(LyapunovMethod::kantz), "kantz");
  EXPECT_STREQ(chaos::to_string(LyapunovStatus::no_linear_region), "no_linear_region");
}

}  // namespace
