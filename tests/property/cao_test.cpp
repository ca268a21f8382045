// Properties of Cao's method that hold for any input, from its definition (cao.hpp):
//   * E(m), E1, E2 are ratios of distances, so they do not change when the series is multiplied by
//     a constant c != 0 or shifted by a constant, and E*(m) scales with |c|. Exactly so when the
//     transformed series is exact in floating point; otherwise up to the rounding of the
//     transformed input, amplified by the conditioning of the nearest-neighbour distances.
//   * The tie rule makes quantised data (Lorenz rounded to integers) give finite values everywhere.
//   * A larger Theiler window only removes candidates, so a point without an admissible neighbour
//     at a positive distance keeps lacking one: points_without_neighbor never decreases.
#include "chaos/cao.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "chaos/models/systems.hpp"

namespace {

using chaos::CaoOptions;
using chaos::CaoResult;
using chaos::Norm;

constexpr double eps = std::numeric_limits<double>::epsilon();

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

void expect_identical(const CaoResult& a, const CaoResult& b, double e_star_factor, const std::string& what) {
  ASSERT_EQ(a.dimension, b.dimension) << what;
  for (std::size_t k = 0; k < a.dimension.size(); ++k) {
    EXPECT_EQ(a.E[k], b.E[k]) << what << " m=" << a.dimension[k];
    EXPECT_EQ(a.E1[k], b.E1[k]) << what << " m=" << a.dimension[k];
    EXPECT_EQ(a.E2[k], b.E2[k]) << what << " m=" << a.dimension[k];
    EXPECT_EQ(a.E_star[k], e_star_factor * b.E_star[k]) << what << " m=" << a.dimension[k];
  }
  EXPECT_EQ(a.embedding_dimension, b.embedding_dimension) << what;
}

// Smallest positive gap between the values used as 1-D points (x[i], i < N - tau): the 1-D
// nearest-neighbour distances are at least this.
double smallest_gap(std::vector<double> x, std::size_t tau) {
  x.resize(x.size() - tau);
  std::sort(x.begin(), x.end());
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i] > x[i - 1]) gap = std::min(gap, x[i] - x[i - 1]);
  return gap;
}

struct Case {
  std::string name;
  std::vector<double> x;
  CaoOptions options;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  CaoOptions lorenz;
  lorenz.delay = 17;
  lorenz.theiler = 100;
  out.push_back({"lorenz", chaos::lorenz(6000).components[0], lorenz});
  CaoOptions henon;
  henon.max_dimension = 8;
  out.push_back({"henon", chaos::henon(4000).components[0], henon});
  return out;
}

TEST(CaoProperty, ExactTransformationsChangeNothing) {
  // Multiplying by -1 or by a power of two, and shifting data that lie on a 2^-24 grid by 1024,
  // are exact in floating point, so every neighbour and every sum is the same: bitwise equality.
  for (auto c : cases()) {
    for (const Norm norm : {Norm::max, Norm::euclidean}) {
      c.options.norm = norm;
      const auto base = chaos::cao(c.x, c.options);
      for (const double factor : {-1.0, 0x1.0p-500, 0x1.0p+500}) {
        auto y = c.x;
        for (auto& v : y) v *= factor;
        expect_identical(chaos::cao(y, c.options), base, std::abs(factor), c.name + " scaled");
      }
      auto grid = c.x;
      for (auto& v : grid) v = std::ldexp(std::round(std::ldexp(v, 24)), -24);
      const auto on_grid = chaos::cao(grid, c.options);
      for (auto& v : grid) v += 1024.0;
      expect_identical(chaos::cao(grid, c.options), on_grid, 1.0, c.name + " shifted");
    }
  }
}

TEST(CaoProperty, ScaledByExtremeFactorsUnchanged) {
  // x * 1e-150 and x * 1e150 round every sample (relative error <= eps/2), so distances move by at
  // most ~2 eps max|x| in absolute terms. E2 and E* are averages of differences of O(max|x|):
  // 1e-12 relative. E(m), m >= 2, average ratios of distances that are not tiny: 1e-12 too. E(1)
  // is a mean of d2/d1 over 1-D nearest neighbours, some of them only `gap` apart, so its relative
  // error is bounded by ~8 eps max|x| / gap (the conditioning of the input, not an algorithmic loss).
  for (auto c : cases()) {
    double largest = 0.0;
    for (const double v : c.x) largest = std::max(largest, std::abs(v));
    const double tol_1 = std::max(1e-12, 8.0 * eps * largest / smallest_gap(c.x, c.options.delay));
    for (const Norm norm : {Norm::max, Norm::euclidean}) {
      c.options.norm = norm;
      const auto base = chaos::cao(c.x, c.options);
      for (const double factor : {1e-150, 1e150}) {
        auto y = c.x;
        for (auto& v : y) v *= factor;
        const auto r = chaos::cao(y, c.options);
        ASSERT_EQ(r.dimension, base.dimension);
        for (std::size_t k = 0; k < r.dimension.size(); ++k) {
          const double tol = r.dimension[k] == 1 ? tol_1 : 1e-12;
          EXPECT_LE(relative(r.E[k], base.E[k]), tol) << c.name << " x" << factor << " m=" << r.dimension[k];
          EXPECT_LE(relative(r.E1[k], base.E1[k]), tol) << c.name << " x" << factor << " m=" << r.dimension[k];
          EXPECT_LE(relative(r.E2[k], base.E2[k]), 1e-12) << c.name << " x" << factor << " m=" << r.dimension[k];
          EXPECT_LE(relative(r.E_star[k], factor * base.E_star[k]), 1e-12) << c.name << " m=" << r.dimension[k];
        }
        EXPECT_EQ(r.embedding_dimension, base.embedding_dimension) << c.name << " x" << factor;
      }
    }
  }
}

TEST(CaoProperty, ShiftedLorenzUnchanged) {
  // Lorenz x (|x| < 25) shifted by -50: each shifted sample is rounded to the ulp of ~75, i.e. a
  // relative error of ~4 eps of the data scale; same argument and tolerances as for scaling.
  auto c = cases().front();
  double largest = 0.0;
  for (const double v : c.x) largest = std::max(largest, std::abs(v - 50.0));
  const double tol_1 = std::max(1e-12, 8.0 * eps * largest / smallest_gap(c.x, c.options.delay));
  const auto base = chaos::cao(c.x, c.options);
  auto y = c.x;
  for (auto& v : y) v -= 50.0;
  const auto r = chaos::cao(y, c.options);
  for (std::size_t k = 0; k < r.dimension.size(); ++k) {
    const double tol = r.dimension[k] == 1 ? tol_1 : 1e-12;
    EXPECT_LE(relative(r.E[k], base.E[k]), tol) << "m=" << r.dimension[k];
    EXPECT_LE(relative(r.E1[k], base.E1[k]), tol) << "m=" << r.dimension[k];
    EXPECT_LE(relative(r.E2[k], base.E2[k]), 1e-12) << "m=" << r.dimension[k];
    EXPECT_LE(relative(r.E_star[k], base.E_star[k]), 1e-12) << "m=" << r.dimension[k];
  }
  EXPECT_EQ(r.embedding_dimension, base.embedding_dimension);
}

TEST(CaoProperty, QuantisedLorenzIsFiniteEverywhere) {
  // references.tsv lorenz.x.quantised.cao.all_finite: Lorenz x rounded to integers (N = 20000,
  // tau = 17, w = 100, m = 1..10) has many zero nearest-neighbour distances; the tie rule (nearest
  // neighbour at a positive distance) keeps every E, E*, E1, E2 finite and positive.
  auto x = chaos::lorenz(20000).components[0];
  for (auto& v : x) v = std::round(v);
  CaoOptions o;
  o.delay = 17;
  o.theiler = 100;
  for (const Norm norm : {Norm::max, Norm::euclidean}) {
    o.norm = norm;
    const auto r = chaos::cao(x, o);
    ASSERT_EQ(r.dimension.size(), 10u);
    for (std::size_t k = 0; k < r.dimension.size(); ++k) {
      for (const double v : {r.E[k], r.E_star[k], r.E1[k], r.E2[k]}) {
        EXPECT_TRUE(std::isfinite(v)) << "m=" << r.dimension[k];
        EXPECT_GT(v, 0.0) << "m=" << r.dimension[k];
      }
      EXPECT_GE(r.E[k], 1.0);  // a(i, m) >= 1: adding a coordinate cannot shrink a distance
    }
    EXPECT_TRUE(std::isfinite(r.max_E2_deviation));
  }
}

TEST(CaoProperty, LargerTheilerWindowNeverGivesMorePointsANeighbour) {
  // Candidates of point i at window w' > w are a subset of those at w, so a point with no
  // admissible candidate at a positive distance at w has none at w' either. The series is 0 outside
  // [100, 1300) and quantised oscillation inside, so with w = 1400 the points near either end can
  // only reach zeros: some points must then have no neighbour.
  std::vector<double> x(3000, 0.0);
  for (std::size_t i = 100; i < 1300; ++i) x[i] = std::round(2.0 * std::sin(0.05 * static_cast<double>(i)));
  CaoOptions o;
  o.max_dimension = 4;
  o.delay = 3;
  std::vector<std::size_t> previous(o.max_dimension, 0);
  for (const std::size_t w : {0u, 10u, 100u, 500u, 1000u, 1400u}) {
    o.theiler = w;
    const auto r = chaos::cao(x, o);
    for (std::size_t k = 0; k < r.dimension.size(); ++k) {
      EXPECT_GE(r.points_without_neighbor[k], previous[k]) << "w=" << w << " m=" << r.dimension[k];
      previous[k] = r.points_without_neighbor[k];
    }
  }
  EXPECT_GT(previous.back(), 0u);  // the largest window does leave points without a neighbour
}

}  // namespace
