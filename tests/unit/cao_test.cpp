// Cao's method (Cao 1997) on cases with known answers: a six-sample series worked out by hand, and
// small Hénon and Lorenz series against an independent O(N^2) transcription of the definition in
// cao.hpp written here (no kd-tree, no rescaling); plus every refusal, checked for its ErrorCode
// and for the numbers in its message.
#include "chaos/cao.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::CaoOptions;
using chaos::Norm;

// The definition, transcribed independently: for m = min .. max + 1, points i < N - m tau; the
// nearest j (same range, |i - j| > w, distance > 0, ties to the smaller j) in m dimensions;
// a = d_{m+1} / d_m and |x[i + m tau] - x[j + m tau]| averaged over the points that have a j.
struct Reference {
  std::vector<double> E, E_star;
  std::vector<std::size_t> without;
};

double distance(const std::vector<double>& x, std::size_t i, std::size_t j, std::size_t m, std::size_t tau, Norm norm) {
  double acc = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    const double d = std::abs(x[i + k * tau] - x[j + k * tau]);
    acc = norm == Norm::max ? std::max(acc, d) : acc + d * d;
  }
  return norm == Norm::max ? acc : std::sqrt(acc);
}

Reference reference_cao(const std::vector<double>& x, const CaoOptions& o) {
  Reference r;
  for (std::size_t m = o.min_dimension; m <= o.max_dimension + 1; ++m) {
    const std::size_t points = x.size() - m * o.delay;
    double sum_a = 0.0, sum_star = 0.0;
    std::size_t used = 0, without = 0;
    for (std::size_t i = 0; i < points; ++i) {
      std::size_t best = points;
      double best_d = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < points; ++j) {
        if ((i > j ? i - j : j - i) <= o.theiler) continue;
        const double d = distance(x, i, j, m, o.delay, o.norm);
        if (d > 0.0 && d < best_d) {
          best_d = d;
          best = j;
        }
      }
      if (best == points) {
        ++without;
        continue;
      }
      sum_a += distance(x, i, best, m + 1, o.delay, o.norm) / best_d;
      sum_star += std::abs(x[i + m * o.delay] - x[best + m * o.delay]);
      ++used;
    }
    r.E.push_back(sum_a / static_cast<double>(used));
    r.E_star.push_back(sum_star / static_cast<double>(used));
    r.without.push_back(without);
  }
  return r;
}

void expect_matches_reference(const std::vector<double>& x, const CaoOptions& o) {
  const auto got = chaos::cao(x, o);
  const auto want = reference_cao(x, o);
  const std::size_t count = o.max_dimension - o.min_dimension + 1;
  ASSERT_EQ(got.dimension.size(), count);
  for (std::size_t k = 0; k < count; ++k) {
    EXPECT_EQ(got.dimension[k], o.min_dimension + k);
    // Same sums in the same order; only the exact power-of-two rescaling differs: ~1 ulp at most.
    EXPECT_NEAR(got.E[k], want.E[k], 1e-13 * want.E[k]) << "m = " << got.dimension[k];
    EXPECT_NEAR(got.E_star[k], want.E_star[k], 1e-13 * want.E_star[k]) << "m = " << got.dimension[k];
    EXPECT_NEAR(got.E1[k], want.E[k + 1] / want.E[k], 1e-13) << "m = " << got.dimension[k];
    EXPECT_NEAR(got.E2[k], want.E_star[k + 1] / want.E_star[k], 1e-13) << "m = " << got.dimension[k];
    EXPECT_EQ(got.points_without_neighbor[k], want.without[k]) << "m = " << got.dimension[k];
  }
}

TEST(Cao, SixSamplesByHand) {
  // x = 0 2 5 1 8 3, tau = 1, w = 0, max norm, m = 1 (so E(1) and E(2) are needed).
  // m = 1, points 0..4 (values 0 2 5 1 8): nearest j and d: 0->3 (1), 1->3 (1), 2->1 (3, tie with 4),
  // 3->0 (1, tie with 1), 4->2 (3). Next-coordinate gaps |x[i+1] - x[j+1]|: 6, 3, 4, 6, 2, so
  // a = 6, 3, 4/3, 6, 1: E(1) = 52/15, E*(1) = 21/5.
  // m = 2, points 0..3 ((0,2) (2,5) (5,1) (1,8)): 0->1 (3), 1->0 (3, tie with 3), 2->1 (4),
  // 3->1 (3); gaps |x[i+2] - x[j+2]|: 4, 4, 7, 2, so a = 4/3, 4/3, 7/4, 1: E(2) = 65/48,
  // E*(2) = 17/4. Hence E1(1) = (65/48)/(52/15) = 25/64 and E2(1) = (17/4)/(21/5) = 85/84.
  const std::vector<double> x{0, 2, 5, 1, 8, 3};
  CaoOptions o;
  o.max_dimension = 1;
  const auto r = chaos::cao(x, o);
  ASSERT_EQ(r.dimension, std::vector<std::size_t>{1});
  EXPECT_NEAR(r.E[0], 52.0 / 15.0, 1e-15);
  EXPECT_NEAR(r.E_star[0], 21.0 / 5.0, 1e-15);
  EXPECT_NEAR(r.E1[0], 25.0 / 64.0, 1e-15);
  EXPECT_NEAR(r.E2[0], 85.0 / 84.0, 1e-15);
  EXPECT_NEAR(r.max_E2_deviation, 1.0 / 84.0, 1e-15);
  EXPECT_EQ(r.points_without_neighbor[0], 0u);
  EXPECT_FALSE(r.embedding_dimension.has_value());  // one dimension: no later E1 step to show saturation
  expect_matches_reference(x, o);
}

TEST(Cao, PointWithOnlyZeroDistanceCandidatesIsLeftOut) {
  // x = 1 5 2 1 5 7 1 4, w = 2, m = 1: point 3 (value 1) may only use j = 0 and j = 6, both equal
  // to 1, so it has no neighbour at a positive distance; in m = 2, (x3, x4) = (1, 5) may only use
  // j = 0, (x0, x1) = (1, 5). Every other point has one (worked through in the reference).
  const std::vector<double> x{1, 5, 2, 1, 5, 7, 1, 4};
  CaoOptions o;
  o.max_dimension = 1;
  o.theiler = 2;
  const auto r = chaos::cao(x, o);
  EXPECT_EQ(r.points_without_neighbor[0], 1u);
  expect_matches_reference(x, o);
}

TEST(Cao, MatchesDefinitionOnHenon) {
  // Hénon x, N = 400: the kd-tree implementation against the O(N^2) transcription above.
  const auto x = chaos::henon(400).components[0];
  for (const Norm norm : {Norm::max, Norm::euclidean}) {
    CaoOptions o;
    o.max_dimension = 6;
    o.norm = norm;
    expect_matches_reference(x, o);
    o.min_dimension = 3;
    o.theiler = 5;
    expect_matches_reference(x, o);
  }
}

TEST(Cao, MatchesDefinitionOnLorenzAndQuantisedLorenz) {
  // Lorenz x (dt = 0.01), tau = 5, w = 20, and the same series rounded to integers (many exact
  // ties and zero distances), against the O(N^2) transcription above.
  auto x = chaos::lorenz(1200).components[0];
  CaoOptions o;
  o.delay = 5;
  o.theiler = 20;
  o.max_dimension = 5;
  expect_matches_reference(x, o);
  for (auto& v : x) v = std::round(v);
  expect_matches_reference(x, o);
  o.norm = Norm::euclidean;
  expect_matches_reference(x, o);
}

TEST(Cao, AnyNumberOfThreadsGivesTheSameResult) {
  // A property of the design (cao.hpp): each point's neighbour is its own, and the sums run in index
  // order, so 2 or 3 threads give the result of 1 bit for bit. N = 12000 makes three search tasks of
  // 4096 points (all_nearest) at every m; the quantised copy has ties at distance 0.
  auto x = chaos::lorenz(12000).components[0];
  for (int pass = 0; pass < 2; ++pass) {
    CaoOptions o;
    o.delay = 5;
    o.theiler = 20;
    o.max_dimension = 4;
    const auto one = chaos::cao(x, o);
    for (const std::size_t threads : {2u, 3u}) {
      o.threads = threads;
      const auto many = chaos::cao(x, o);
      EXPECT_EQ(many.E, one.E) << threads << " threads";
      EXPECT_EQ(many.E_star, one.E_star) << threads << " threads";
      EXPECT_EQ(many.points_without_neighbor, one.points_without_neighbor) << threads << " threads";
    }
    for (auto& v : x) v = std::round(v);
  }
  CaoOptions none;
  none.threads = 0;
  EXPECT_THROW(none.validate(), chaos::InvalidInput);
}

TEST(Cao, HenonSaturatesAtTwo) {
  // Hénon x[n+1] = 1 - 1.4 x[n]^2 + 0.3 x[n-1] is exactly two-dimensional in delay coordinates
  // (references.tsv: henon.x.cao.embedding_dimension = 2, N = 10000, tau = 1, w = 0, m = 1..8).
  const auto x = chaos::henon(10000).components[0];
  CaoOptions o;
  o.max_dimension = 8;
  const auto r = chaos::cao(x, o);
  ASSERT_TRUE(r.embedding_dimension.has_value());
  EXPECT_EQ(*r.embedding_dimension, 2u);
  EXPECT_GT(r.max_E2_deviation, 0.2);  // deterministic (references.tsv: henon.x.cao.max_E2_deviation)
}

std::string message_of(const std::vector<double>& x, const CaoOptions& o, chaos::ErrorCode code) {
  try {
    static_cast<void>(chaos::cao(x, o));
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no InvalidInput thrown";
  return {};
}

TEST(Cao, RefusesSeriesTooShort) {
  // max m = 10 needs m = 11; with tau = 17 and w = 100: N >= 11*17 + 2*100 + 2 = 389 (cao.hpp).
  std::vector<double> x(388);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.1 * static_cast<double>(i));
  CaoOptions o;
  o.delay = 17;
  o.theiler = 100;
  const std::string msg = message_of(x, o, chaos::ErrorCode::too_short);
  for (const char* part : {"N = 388", "389", "m = 11", "tau = 17", "w = 100"})
    EXPECT_NE(msg.find(part), std::string::npos) << part << " missing from: " << msg;
  x.push_back(std::sin(38.8));  // N = 389 is enough
  EXPECT_NO_THROW(static_cast<void>(chaos::cao(x, o)));
}

TEST(Cao, RefusesBadInputAndOptions) {
  // Each rule of CaoOptions::validate and of the input checks, with the number it names.
  std::vector<double> x(100);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.7 * static_cast<double>(i));
  CaoOptions o;
  o.max_dimension = 3;

  std::vector<double> constant(100, 2.5);
  EXPECT_NE(message_of(constant, o, chaos::ErrorCode::constant).find("constant"), std::string::npos);

  auto with_nan = x;
  with_nan[42] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message_of(with_nan, o, chaos::ErrorCode::non_finite).find("sample 42"), std::string::npos);
  auto with_inf = x;
  with_inf[7] = std::numeric_limits<double>::infinity();
  EXPECT_NE(message_of(with_inf, o, chaos::ErrorCode::non_finite).find("sample 7"), std::string::npos);

  CaoOptions bad = o;
  bad.delay = 0;
  EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("tau = 0"), std::string::npos);
  bad = o;
  bad.min_dimension = 0;
  EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("m = 0"), std::string::npos);
  bad = o;
  bad.min_dimension = 5;
  bad.max_dimension = 4;
  const std::string order = message_of(x, bad, chaos::ErrorCode::invalid_parameter);
  EXPECT_NE(order.find("min m = 5"), std::string::npos) << order;
  EXPECT_NE(order.find("max m = 4"), std::string::npos) << order;
  for (const double v : {0.0, 1.0, -0.1, std::numeric_limits<double>::quiet_NaN()}) {
    bad = o;
    bad.saturation_level = v;
    EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("saturation level"), std::string::npos);
    bad = o;
    bad.saturation_change = v;
    EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("saturation change"), std::string::npos);
  }
  for (const double v : {0.0, -1.0, std::numeric_limits<double>::infinity()}) {
    bad = o;
    bad.stochastic_sigmas = v;
    EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("stochastic_sigmas"), std::string::npos);
  }
  EXPECT_THROW(bad.validate(), chaos::InvalidInput) << "validate() refuses on its own, before any data";
}

TEST(Cao, ValidateAcceptsDefaults) {
  // The documented defaults (cao.hpp) are valid.
  EXPECT_NO_THROW(CaoOptions{}.validate());
}

TEST(Cao, ZeroEStarIsRefusedNotNaN) {
  // x = 0 2 2 2, m = 1: points 0 1 2 have values 0 2 2. Point 0's nearest is 1 (distance 2, tie with
  // 2), point 1's and point 2's is 0 (their twin is at distance 0 and skipped). The next values of
  // every pair are equal (x1 = x2 = x3 = 2), so E*(1) = 0 and E2(1) = E*(2)/E*(1) is 0/0. The rule in
  // cao.hpp/cao.cpp: refuse with InvalidInput(constant) naming m, never return NaN.
  const std::vector<double> x{0, 2, 2, 2};
  CaoOptions o;
  o.max_dimension = 1;
  const std::string msg = message_of(x, o, chaos::ErrorCode::constant);
  EXPECT_NE(msg.find("E*(m) = 0 at m = 1"), std::string::npos) << msg;
}

}  // namespace

TEST(CaoSaturation, RuleOnConstructedCurves) {
  // The rule documented in cao.hpp, applied by hand: level 0.8, change 0.1.
  const std::vector<std::size_t> m{1, 2, 3, 4, 5, 6};
  // A flow like Lorenz: the jump happens between m = 2 and 3, later steps are small.
  EXPECT_EQ(chaos::e1_saturation(m, std::vector<double>{0.0, 0.19, 0.91, 0.94, 0.96, 0.99}, 0.8, 0.1), 3u);
  // Reaches the level but still climbs by more than 0.1 once: saturation starts after that step.
  EXPECT_EQ(chaos::e1_saturation(m, std::vector<double>{0.1, 0.82, 0.95, 0.97, 0.98, 0.99}, 0.8, 0.1), 3u);
  // A slow, steady rise far below 1 never passes as saturation.
  EXPECT_FALSE(chaos::e1_saturation(m, std::vector<double>{0.30, 0.38, 0.46, 0.54, 0.62, 0.70}, 0.8, 0.1));
  // Only the last dimension reaches the level: no later step, so "not saturated".
  EXPECT_FALSE(chaos::e1_saturation(m, std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.5, 0.95}, 0.8, 0.1));
  // A late drop breaks saturation from any earlier start.
  EXPECT_FALSE(chaos::e1_saturation(m, std::vector<double>{0.9, 0.95, 0.97, 0.98, 0.99, 0.7}, 0.8, 0.1));
}

TEST(CaoStochastic, WhiteNoiseHasNoEmbeddingDimensionHenonHasOne) {
  // Cao (1997): for independent samples E2(m) = 1 for every m (the next value does not depend on
  // the neighbour found), so the series is flagged stochastic and gets no embedding dimension, even
  // where E1 alone settles; the deterministic Henon map is not flagged.
  const auto noise = chaos::white_noise(10000, 7).components[0];
  CaoOptions o;
  o.max_dimension = 10;
  const auto r = chaos::cao(noise, o);
  EXPECT_TRUE(r.stochastic);
  EXPECT_FALSE(r.embedding_dimension.has_value());
  for (std::size_t k = 0; k < r.E2.size(); ++k) EXPECT_LE(std::abs(r.E2[k] - 1.0), 4.0 * r.E2_standard_error[k]);
  const auto henon = chaos::henon(10000).components[0];
  const auto h = chaos::cao(henon, o);
  EXPECT_FALSE(h.stochastic);
  EXPECT_EQ(h.embedding_dimension, 2u);
}
