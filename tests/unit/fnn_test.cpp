// False nearest neighbours (Kennel, Brown & Abarbanel 1992) on a six-sample series worked out by
// hand, on Hénon and Lorenz against an independent O(N^2) transcription of the definition in
// fnn.hpp written here, on the known embedding dimensions of Hénon (2) and Lorenz (3), and every
// refusal with its ErrorCode and the numbers in its message.
#include "chaos/fnn.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::FnnOptions;
using chaos::Norm;

double distance(const std::vector<double>& x, std::size_t i, std::size_t j, std::size_t m, std::size_t tau, Norm norm) {
  double acc = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    const double d = std::abs(x[i + k * tau] - x[j + k * tau]);
    acc = norm == Norm::max ? std::max(acc, d) : acc + d * d;
  }
  return norm == Norm::max ? acc : std::sqrt(acc);
}

// The definition, transcribed independently: points i < N - m tau in m dimensions, nearest j in the
// same range with |i - j| > w at a positive distance (ties to the smaller j); false if
// |x[i+m tau] - x[j+m tau]| / R_m > Rtol or R_{m+1} / R_A > Atol, R_A the population standard
// deviation of x; the fraction is over the points that have such a j.
std::vector<double> reference_fnn(const std::vector<double>& x, const FnnOptions& o) {
  double mean = 0.0;
  for (const double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double var = 0.0;
  for (const double v : x) var += (v - mean) * (v - mean);
  const double ra = std::sqrt(var / static_cast<double>(x.size()));
  std::vector<double> fractions;
  for (std::size_t m = o.min_dimension; m <= o.max_dimension; ++m) {
    const std::size_t points = x.size() - m * o.delay;
    std::size_t tested = 0, false_count = 0;
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
      if (best == points) continue;
      ++tested;
      const double gap = std::abs(x[i + m * o.delay] - x[best + m * o.delay]);
      if (gap / best_d > o.rtol || distance(x, i, best, m + 1, o.delay, o.norm) / ra > o.atol) ++false_count;
    }
    fractions.push_back(static_cast<double>(false_count) / static_cast<double>(tested));
  }
  return fractions;
}

TEST(Fnn, SixSamplesByHand) {
  // x = 0 2 5 1 8 3, tau = 1, w = 0, m = 1: points 0..4 (values 0 2 5 1 8) have nearest neighbours
  // 0->3 (R1 = 1), 1->3 (1), 2->1 (3), 3->0 (1), 4->2 (3); next-coordinate gaps 6, 3, 4, 6, 2, so
  // gap/R1 = 6, 3, 4/3, 6, 2/3 and R2 = sqrt(R1^2 + gap^2) = sqrt 37, sqrt 10, 5, sqrt 37, sqrt 13.
  // R_A = sqrt(257)/6 = 2.6719 (population standard deviation), so R2/R_A = 2.28, 1.18, 1.87, 2.28, 1.35.
  const std::vector<double> x{0, 2, 5, 1, 8, 3};
  FnnOptions o;
  o.max_dimension = 1;
  // Defaults Rtol = 10, Atol = 2: no gap ratio exceeds 10; points 0 and 3 exceed Atol: 2/5.
  EXPECT_DOUBLE_EQ(chaos::false_nearest_neighbors(x, o).false_fraction[0], 0.4);
  // Atol = 3 switches criterion 2 off here: 0/5, and the fraction 0 <= 0.01 gives dimension 1.
  o.atol = 3.0;
  const auto r = chaos::false_nearest_neighbors(x, o);
  EXPECT_DOUBLE_EQ(r.false_fraction[0], 0.0);
  ASSERT_TRUE(r.embedding_dimension.has_value());
  EXPECT_EQ(*r.embedding_dimension, 1u);
  // Rtol = 1.2: gap ratios 6, 3, 4/3, 6 exceed it: 4/5.
  o.rtol = 1.2;
  o.atol = 100.0;
  EXPECT_DOUBLE_EQ(chaos::false_nearest_neighbors(x, o).false_fraction[0], 0.8);
}

TEST(Fnn, MatchesDefinition) {
  // The kd-tree implementation against the O(N^2) transcription above: Hénon (tau = 1), Lorenz
  // (tau = 5, w = 20) and Lorenz rounded to integers (exact ties), both norms, several thresholds.
  struct Case {
    std::vector<double> x;
    std::size_t delay, theiler;
  };
  auto lorenz = chaos::lorenz(1200).components[0];
  auto rounded = lorenz;
  for (auto& v : rounded) v = std::round(v);
  const std::vector<Case> cases{{chaos::henon(500).components[0], 1, 0}, {lorenz, 5, 20}, {rounded, 5, 20}};
  for (const auto& c : cases) {
    for (const Norm norm : {Norm::max, Norm::euclidean}) {
      for (const double rtol : {10.0, 2.0}) {
        FnnOptions o;
        o.delay = c.delay;
        o.theiler = c.theiler;
        o.max_dimension = 6;
        o.norm = norm;
        o.rtol = rtol;
        const auto got = chaos::false_nearest_neighbors(c.x, o);
        const auto want = reference_fnn(c.x, o);
        ASSERT_EQ(got.false_fraction.size(), want.size());
        for (std::size_t k = 0; k < want.size(); ++k) {
          // Counts of the same decisions: fnn.cpp's power-of-two rescaling is exact, so every ratio
          // compared with Rtol and Atol is the same double and the fractions are equal exactly.
          EXPECT_EQ(got.false_fraction[k], want[k]) << "m=" << got.dimension[k] << " rtol=" << rtol;
          EXPECT_EQ(got.dimension[k], k + 1);
        }
      }
    }
  }
}

TEST(Fnn, AnyNumberOfThreadsGivesTheSameResult) {
  // Each point's neighbour is its own and the decisions are counted: 2 or 3 threads give the
  // fractions of 1 exactly (N = 12000: three search tasks of 4096 points at every m).
  const auto x = chaos::lorenz(12000).components[0];
  FnnOptions o;
  o.delay = 5;
  o.theiler = 20;
  o.max_dimension = 4;
  const auto one = chaos::false_nearest_neighbors(x, o);
  for (const std::size_t threads : {2u, 3u}) {
    o.threads = threads;
    EXPECT_EQ(chaos::false_nearest_neighbors(x, o).false_fraction, one.false_fraction) << threads << " threads";
  }
  FnnOptions none;
  none.threads = 0;
  EXPECT_THROW(none.validate(), chaos::InvalidInput);
}

TEST(Fnn, KnownEmbeddingDimensions) {
  // references.tsv: lorenz.x.fnn.embedding_dimension = 3 (N = 20000, tau = 17, w = 100, m = 1..8,
  // Kennel et al. 1992); Hénon is exactly two-dimensional in delay coordinates (x[n+1] = 1 - 1.4
  // x[n]^2 + 0.3 x[n-1]), so no neighbour is false from m = 2 on.
  FnnOptions lorenz;
  lorenz.delay = 17;
  lorenz.theiler = 100;
  lorenz.max_dimension = 8;
  const auto l = chaos::false_nearest_neighbors(chaos::lorenz(20000).components[0], lorenz);
  ASSERT_TRUE(l.embedding_dimension.has_value());
  EXPECT_EQ(*l.embedding_dimension, 3u);
  EXPECT_GT(l.false_fraction[1], 0.01);  // m = 2 does not unfold the attractor

  FnnOptions henon;
  henon.max_dimension = 5;
  const auto h = chaos::false_nearest_neighbors(chaos::henon(5000).components[0], henon);
  ASSERT_TRUE(h.embedding_dimension.has_value());
  EXPECT_EQ(*h.embedding_dimension, 2u);
  EXPECT_GT(h.false_fraction[0], 0.5);
}

std::string message_of(const std::vector<double>& x, const FnnOptions& o, chaos::ErrorCode code) {
  try {
    static_cast<void>(chaos::false_nearest_neighbors(x, o));
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no InvalidInput thrown";
  return {};
}

TEST(Fnn, RefusesSeriesTooShort) {
  // Testing m = 8 with tau = 17 and w = 100 needs N >= 8*17 + 2*100 + 2 = 338 (fnn.hpp).
  std::vector<double> x(337);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.1 * static_cast<double>(i));
  FnnOptions o;
  o.delay = 17;
  o.theiler = 100;
  o.max_dimension = 8;
  const std::string msg = message_of(x, o, chaos::ErrorCode::too_short);
  for (const char* part : {"N = 337", "338", "m = 8", "tau = 17", "w = 100"})
    EXPECT_NE(msg.find(part), std::string::npos) << part << " missing from: " << msg;
  x.push_back(std::sin(33.7));
  EXPECT_NO_THROW(static_cast<void>(chaos::false_nearest_neighbors(x, o)));
}

TEST(Fnn, RefusesBadInputAndOptions) {
  // Each rule of FnnOptions::validate and of the input checks, with the number it names.
  std::vector<double> x(100);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.7 * static_cast<double>(i));
  FnnOptions o;
  o.max_dimension = 3;
  EXPECT_NE(message_of(std::vector<double>(50, -1.0), o, chaos::ErrorCode::constant).find("constant"),
            std::string::npos);
  auto with_nan = x;
  with_nan[13] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message_of(with_nan, o, chaos::ErrorCode::non_finite).find("sample 13"), std::string::npos);

  FnnOptions bad = o;
  bad.delay = 0;
  EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("tau = 0"), std::string::npos);
  bad = o;
  bad.min_dimension = 0;
  EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("m = 0"), std::string::npos);
  bad = o;
  bad.min_dimension = 4;
  const std::string order = message_of(x, bad, chaos::ErrorCode::invalid_parameter);
  EXPECT_NE(order.find("min m = 4 > max m = 3"), std::string::npos) << order;
  for (const double v : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    bad = o;
    bad.rtol = v;
    EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("Rtol"), std::string::npos);
    bad = o;
    bad.atol = v;
    EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("Atol"), std::string::npos);
  }
  for (const double v : {-0.01, 1.0, std::numeric_limits<double>::quiet_NaN()}) {
    bad = o;
    bad.threshold = v;
    EXPECT_NE(message_of(x, bad, chaos::ErrorCode::invalid_parameter).find("threshold"), std::string::npos);
  }
  EXPECT_NO_THROW(FnnOptions{}.validate());  // the documented defaults are valid
}

TEST(Fnn, NoNeighbourAtPositiveDistanceIsRefused) {
  // x = 1 1 1 1 2, m = 1: the points i < N - 1 are all 1, so every candidate is at distance 0 and
  // the fraction would be 0/0; fnn.cpp refuses with InvalidInput(constant) naming m.
  const std::vector<double> x{1, 1, 1, 1, 2};
  FnnOptions o;
  o.max_dimension = 1;
  const std::string msg = message_of(x, o, chaos::ErrorCode::constant);
  EXPECT_NE(msg.find("m = 1"), std::string::npos) << msg;
}

}  // namespace
