// Property: the kd-tree is an exact replacement for brute force. For every point of several data
// sets (uniform noise, Hénon and Lorenz delay embeddings, and quantised series with many exact
// ties), every dimension m = 1..10, Theiler windows 0, 1, 10, 50, skip_zero_distance on and off,
// both norms and two leaf sizes, KdTree::nearest must return the same index and the bit-identical
// distance as nearest_brute_force (the definition), count_within the same count as
// count_within_brute_force, and within the same points as within_brute_force, including radii
// equal to an existing distance (strictness).
#include "chaos/neighbors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "chaos/models/systems.hpp"

namespace {

using chaos::DelayEmbedding;
using chaos::KdTree;
using chaos::Norm;
using chaos::NeighborQuery;

// Uniform in [0, 1) from the raw 64-bit output of mt19937_64 (specified by the standard); the
// standard distributions are implementation-defined, so they are not used.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

struct DataSet {
  std::string name;
  std::vector<double> x;
  std::size_t delay;
};

std::vector<DataSet> data_sets() {
  constexpr std::size_t n = 300;
  std::vector<DataSet> sets;
  std::mt19937_64 rng(20240601);
  std::vector<double> noise(n);
  for (auto& v : noise) v = uniform(rng);
  sets.push_back({"uniform", noise, 1});
  sets.push_back({"henon", chaos::henon(n).components[0], 1});
  const auto lorenz = chaos::lorenz(n + 200).components[0];
  sets.push_back({"lorenz", lorenz, 3});
  std::vector<double> rounded(lorenz.size());
  for (std::size_t i = 0; i < lorenz.size(); ++i) rounded[i] = std::round(lorenz[i]);
  sets.push_back({"lorenz-rounded", rounded, 3});
  std::vector<double> levels(n);  // five values only: ties everywhere, in every dimension
  for (auto& v : levels) v = static_cast<double>(rng() % 5);
  sets.push_back({"five-levels", levels, 1});
  return sets;
}

TEST(KdTreeProperty, EqualsBruteForce) {
  std::size_t queries = 0, counts_checked = 0;
  std::vector<std::size_t> found;
  for (const auto& set : data_sets()) {
    for (std::size_t m = 1; m <= 10; ++m) {
      const DelayEmbedding e(set.x, m, set.delay);
      for (const Norm norm : {Norm::max, Norm::euclidean}) {
        const KdTree fine(e, norm, 1), coarse(e, norm, 8);  // every point its own leaf, and the default
        for (const std::size_t w : {0u, 1u, 10u, 50u}) {
          for (const bool skip : {false, true}) {
            const NeighborQuery q{w, skip};
            for (std::size_t i = 0; i < e.size(); ++i) {
              const auto want = chaos::nearest_brute_force(e, i, norm, q);
              for (const KdTree* tree : {&fine, &coarse}) {
                const auto got = tree->nearest(i, q);
                ++queries;
                ASSERT_EQ(got.has_value(), want.has_value()) << set.name << " m=" << m << " i=" << i;
                if (!want) continue;
                ASSERT_EQ(got->index, want->index) << set.name << " m=" << m << " w=" << w << " skip=" << skip
                                                   << " norm=" << chaos::to_string(norm) << " i=" << i;
                ASSERT_EQ(got->distance, want->distance) << set.name << " m=" << m << " i=" << i;
              }
              if (!want || i % 5 != 0) continue;  // counts on a subset keep brute force cheap
              // The nearest distance itself (strict: excludes points at exactly that distance),
              // just above it, a larger radius, zero and infinity.
              const double inf = std::numeric_limits<double>::infinity();
              for (const double r : {want->distance, std::nextafter(want->distance, inf), 4.0 * want->distance + 0.1,
                                     0.0, inf}) {
                const std::size_t expected = chaos::count_within_brute_force(e, i, r, norm, q);
                ASSERT_EQ(fine.count_within(i, r, q), expected) << set.name << " m=" << m << " w=" << w << " i=" << i;
                ASSERT_EQ(coarse.count_within(i, r, q), expected) << set.name << " m=" << m << " w=" << w << " i=" << i;
                // The points themselves, in index order: the same set the count counts (on a
                // third of these queries, to keep the test quick).
                if (i % 15 != 0) continue;
                const auto members = chaos::within_brute_force(e, i, r, norm, q);
                ASSERT_EQ(members.size(), expected);
                for (const KdTree* tree : {&fine, &coarse}) {
                  tree->within(i, r, found, q);
                  ASSERT_EQ(found, members) << set.name << " m=" << m << " w=" << w << " skip=" << skip << " i=" << i
                                            << " r=" << r;
                }
              }
              ++counts_checked;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(queries, 200000u);
  EXPECT_GT(counts_checked, 10000u);
}

TEST(KdTreeProperty, LargeWindowLeavesNothingOrTheFarEnds) {
  // With w >= N - 1 nothing is admissible; with w = N - 2 only the pair (0, N-1) is, for those two
  // points alone. Follows from the window definition |i - j| <= w.
  const auto x = chaos::henon(60).components[0];
  const DelayEmbedding e(x, 2, 1);
  const KdTree tree(e, Norm::max);
  const std::size_t n = e.size();
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_FALSE(tree.nearest(i, {n - 1, false}).has_value());
    const auto got = tree.nearest(i, {n - 2, false});
    if (i == 0 || i == n - 1) {
      ASSERT_TRUE(got.has_value());
      EXPECT_EQ(got->index, n - 1 - i);
    } else {
      EXPECT_FALSE(got.has_value());
    }
  }
}

TEST(KdTreeProperty, CountGrowsWithRadiusAndShrinksWithWindow) {
  // Monotonicity straight from the definition: more radius counts more, more window counts less.
  const auto x = chaos::lorenz(3000).components[0];
  const DelayEmbedding e(x, 3, 10);
  const KdTree tree(e, Norm::max);
  for (std::size_t i = 0; i < e.size(); i += 97) {
    std::size_t previous = 0;
    for (const double r : {0.5, 1.0, 2.0, 4.0, 8.0}) {
      const std::size_t c = tree.count_within(i, r, {10, false});
      EXPECT_GE(c, previous);
      previous = c;
    }
    EXPECT_LE(tree.count_within(i, 4.0, {100, false}), tree.count_within(i, 4.0, {10, false}));
  }
}

TEST(KdTreeProperty, NearestDistanceGrowsWithWindow) {
  // A larger Theiler window only removes candidates, so the nearest admissible distance never
  // decreases (and once no candidate is left, none comes back).
  const auto x = chaos::lorenz(4000).components[0];
  const DelayEmbedding e(x, 3, 17);
  const KdTree tree(e, Norm::euclidean);
  for (std::size_t i = 0; i < e.size(); i += 13) {
    double previous = 0.0;
    for (const std::size_t w : {0u, 1u, 10u, 50u, 100u, 1000u, 3000u, 4000u}) {
      const auto n = tree.nearest(i, {w, false});
      if (!n) {
        previous = std::numeric_limits<double>::infinity();
        continue;
      }
      EXPECT_GE(n->distance, previous) << "i=" << i << " w=" << w;
      previous = n->distance;
    }
  }
}

}  // namespace
