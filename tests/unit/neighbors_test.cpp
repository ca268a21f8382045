// KdTree and the brute-force searchers on inputs small enough to work out by hand. Each expected
// value is derived in the comment next to it from the definition in neighbors.hpp: distance in the
// chosen norm, Theiler window |i - j| <= w excluded, ties to the smaller index, strict < radius.
#include "chaos/neighbors.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "chaos/error.hpp"
#include "spatial/kd_tree.hpp"

namespace {

using chaos::DelayEmbedding;
using chaos::KdTree;
using chaos::Norm;
using chaos::NeighborQuery;

// Both searchers must give the hand-derived answer.
void expect_nearest(const DelayEmbedding& e, Norm norm, std::size_t i, const NeighborQuery& q,
                    std::size_t index, double distance) {
  for (std::size_t leaf : {1u, 2u, 8u}) {
    const KdTree tree(e, norm, leaf);
    const auto got = tree.nearest(i, q);
    ASSERT_TRUE(got.has_value()) << "leaf size " << leaf;
    EXPECT_EQ(got->index, index) << "leaf size " << leaf;
    EXPECT_EQ(got->distance, distance) << "leaf size " << leaf;
  }
  const auto brute = chaos::nearest_brute_force(e, i, norm, q);
  ASSERT_TRUE(brute.has_value());
  EXPECT_EQ(brute->index, index);
  EXPECT_EQ(brute->distance, distance);
}

// n uniform values in [0, 1) and n others quantised to 0, 1, 2, drawn alternately from one seeded
// generator: smooth data, and data where most pairs tie.
std::pair<std::vector<double>, std::vector<double>> smooth_and_quantised(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> smooth(n), quantised(n);
  for (std::size_t i = 0; i < n; ++i) {
    smooth[i] = u(rng);
    quantised[i] = std::floor(3.0 * u(rng));
  }
  return {std::move(smooth), std::move(quantised)};
}

TEST(KdTree, OneDimensionalHandCases) {
  // x = 0 1 3 7 8 in m = 1: gaps 1, 2, 4, 1.
  const std::vector<double> x{0, 1, 3, 7, 8};
  const DelayEmbedding e(x, 1, 1);
  expect_nearest(e, Norm::max, 0, {}, 1, 1.0);   // |0 - 1| = 1
  expect_nearest(e, Norm::max, 2, {}, 1, 2.0);   // |3 - 1| = 2 < |3 - 7| = 4
  expect_nearest(e, Norm::max, 3, {}, 4, 1.0);   // |7 - 8| = 1
  expect_nearest(e, Norm::max, 0, {1, false}, 2, 3.0);  // w = 1 drops j = 1; |0 - 3| = 3
  expect_nearest(e, Norm::max, 4, {2, false}, 1, 7.0);  // w = 2 leaves j <= 1; |8 - 1| = 7
}

TEST(KdTree, AllNearestIsEveryPointsNearest) {
  // all_nearest(tree, q)[i] is nearest_brute_force(i) by its definition (neighbors.hpp), whatever
  // order it searches in: on random data, and on data quantised to 3 levels, where ties at distance 0
  // and at equal distances decide; with and without the window and the zero-distance rule, and with
  // a point that has no admissible neighbour (the window covers everything: nullopt).
  const auto [smooth, quantised] = smooth_and_quantised(600, 7);
  for (const auto* x : {&smooth, &quantised})
    for (const Norm norm : {Norm::max, Norm::euclidean})
      for (const NeighborQuery q : {NeighborQuery{0, false}, NeighborQuery{5, true}, NeighborQuery{700, false}}) {
        const DelayEmbedding e(*x, 3, 2);
        const KdTree tree(e, norm, 4);
        const auto all = chaos::all_nearest(tree, q);
        ASSERT_EQ(all.size(), e.size());
        for (std::size_t i = 0; i < e.size(); ++i) {
          const auto brute = chaos::nearest_brute_force(e, i, norm, q);
          ASSERT_EQ(all[i].has_value(), brute.has_value()) << "point " << i;
          if (!brute) continue;
          EXPECT_EQ(all[i]->index, brute->index) << "point " << i;
          EXPECT_EQ(all[i]->distance, brute->distance) << "point " << i;
        }
      }
}

TEST(KdTree, AnyNumberOfThreadsBuildsTheSameTree) {
  // With threads, the subtrees below the top levels are built in parallel and numbered afterwards as
  // one thread numbers them (neighbors.hpp: the tree is the same for any number). Above the size at
  // which the build goes parallel (2^15 points), on smooth random data and on data quantised to 3
  // levels (ties at the median, uniform leaves): the leaf order must be the same permutation, every
  // point's nearest neighbour the same, and, for a sample of points, the one brute force finds.
  const auto [smooth, quantised] = smooth_and_quantised(50000, 11);
  for (const auto* x : {&smooth, &quantised}) {
    const DelayEmbedding e(*x, 3, 2);
    const NeighborQuery q{5, true};
    const KdTree one(e, Norm::max, 8, 1);
    const auto expected = chaos::all_nearest(one, q);
    for (std::size_t i = 0; i < e.size(); i += 997) {
      const auto brute = chaos::nearest_brute_force(e, i, Norm::max, q);
      ASSERT_EQ(expected[i].has_value(), brute.has_value()) << "point " << i;
      if (brute) {
        EXPECT_EQ(expected[i]->index, brute->index) << "point " << i;
      }
    }
    // The internal tree, node for node (chaos/src/spatial/kd_tree.hpp).
    const auto at = [&e](std::size_t i, std::size_t k) { return e(i, k); };
    const chaos::spatial::KdTree serial(e.size(), 3, 8, at, 1);
    for (const std::size_t threads : {2u, 3u, 8u}) {
      const chaos::spatial::KdTree parallel(e.size(), 3, 8, at, threads);
      ASSERT_EQ(parallel.nodes().size(), serial.nodes().size()) << threads << " threads";
      for (std::size_t n = 0; n < serial.nodes().size(); ++n) {
        const auto& a = parallel.nodes()[n];
        const auto& b = serial.nodes()[n];
        ASSERT_TRUE(a.begin == b.begin && a.end == b.end && a.left == b.left && a.parent == b.parent &&
                    a.split_dim == b.split_dim && a.split_value == b.split_value && a.uniform == b.uniform)
            << "node " << n << ", " << threads << " threads";
      }
      EXPECT_EQ(parallel.index(), serial.index()) << threads << " threads";
      EXPECT_EQ(parallel.leaf_of(), serial.leaf_of()) << threads << " threads";

      const KdTree many(e, Norm::max, 8, threads);
      EXPECT_TRUE(std::ranges::equal(many.leaf_order(), one.leaf_order())) << threads << " threads";
      const auto got = chaos::all_nearest(many, q, nullptr, threads);
      ASSERT_EQ(got.size(), expected.size());
      for (std::size_t i = 0; i < got.size(); ++i) {
        ASSERT_EQ(got[i].has_value(), expected[i].has_value()) << "point " << i;
        if (got[i]) {
          ASSERT_EQ(got[i]->index, expected[i]->index) << "point " << i;
          ASSERT_EQ(got[i]->distance, expected[i]->distance) << "point " << i;
        }
      }
      EXPECT_EQ(many.count_within(123, 0.05, q), one.count_within(123, 0.05, q));
    }
  }
}

TEST(KdTree, TieGoesToTheSmallerIndex) {
  // x = 0 1 2: point 1 is at distance 1 from both 0 and 2; the rule picks 0.
  const std::vector<double> x{0, 1, 2};
  expect_nearest(DelayEmbedding(x, 1, 1), Norm::max, 1, {}, 0, 1.0);
  // x = 5 2 5 5 8 2: point 3 (value 5) has distance-0 twins at 0 and 2: index 0 wins.
  // w = 3 excludes every j (|3 - j| <= 3 for j = 0..5): nothing is admissible.
  const std::vector<double> y{5, 2, 5, 5, 8, 2};
  const DelayEmbedding e(y, 1, 1);
  expect_nearest(e, Norm::max, 3, {}, 0, 0.0);
  EXPECT_FALSE(KdTree(e, Norm::max).nearest(3, {3, false}).has_value());
  EXPECT_FALSE(chaos::nearest_brute_force(e, 3, Norm::max, {3, false}).has_value());
  // w = 1 excludes 2 and 4; candidates 0 (d 0), 1 (d 3), 5 (d 3): index 0 at distance 0.
  expect_nearest(e, Norm::max, 3, {1, false}, 0, 0.0);
  // Skipping zero distances leaves 1, 4 and 5, all at distance 3: index 1.
  expect_nearest(e, Norm::max, 3, {0, true}, 1, 3.0);
}

TEST(KdTree, SkipZeroDistance) {
  // x = 5 5 6: point 0 has a twin at 1 (d 0); skipping it leaves 2 at distance 1.
  const std::vector<double> x{5, 5, 6};
  const DelayEmbedding e(x, 1, 1);
  expect_nearest(e, Norm::max, 0, {}, 1, 0.0);
  expect_nearest(e, Norm::max, 0, {0, true}, 2, 1.0);
  // Only twins left: nothing at a positive distance within reach.
  const std::vector<double> twins{4, 4};
  EXPECT_FALSE(KdTree(DelayEmbedding(twins, 1, 1), Norm::max).nearest(0, {0, true}).has_value());
}

TEST(KdTree, TwoDimensionalNorms) {
  // m = 2, tau = 1 on x = 0 3 4 0 0: points (0,3) (3,4) (4,0) (0,0).
  // From point 3 = (0,0): to 0 -> max 3, euclid 3; to 1 -> max 4, euclid 5; to 2 -> max 4, euclid 4.
  const std::vector<double> x{0, 3, 4, 0, 0};
  const DelayEmbedding e(x, 2, 1);
  expect_nearest(e, Norm::max, 3, {}, 0, 3.0);
  expect_nearest(e, Norm::euclidean, 3, {}, 0, 3.0);
  // From point 1 = (3,4): to 0 -> (3,1): max 3, euclid sqrt(10); to 2 -> (1,4): max 4, euclid sqrt(17);
  // to 3 -> max 4, euclid 5.
  expect_nearest(e, Norm::max, 1, {}, 0, 3.0);
  expect_nearest(e, Norm::euclidean, 1, {}, 0, std::sqrt(10.0));
  // w = 1 leaves only point 3 for point 1: max 4, euclid 5.
  expect_nearest(e, Norm::max, 1, {1, false}, 3, 4.0);
  expect_nearest(e, Norm::euclidean, 1, {1, false}, 3, 5.0);
}

TEST(KdTree, TwoPointsAndEmptyWindow) {
  // Two points: each is the other's only candidate; any w >= 1 excludes it.
  const std::vector<double> x{1.5, -2.0};
  const DelayEmbedding e(x, 1, 1);
  expect_nearest(e, Norm::euclidean, 0, {}, 1, 3.5);
  expect_nearest(e, Norm::max, 1, {}, 0, 3.5);
  const KdTree tree(e, Norm::max);
  EXPECT_FALSE(tree.nearest(0, {1, false}).has_value());
  EXPECT_FALSE(chaos::nearest_brute_force(e, 0, Norm::max, {1, false}).has_value());
  EXPECT_EQ(tree.count_within(0, 10.0, {1, false}), 0u);
  EXPECT_EQ(tree.count_within(0, 10.0), 1u);
}

TEST(KdTree, CountWithinIsStrict) {
  // x = 0 1 2 3, point 0: distances 1, 2, 3. Radius 1 counts nothing (1 < 1 is false), 1.5 counts
  // one, 3 counts two, 3.5 counts three; w = 1 removes j = 1 from each count.
  const std::vector<double> x{0, 1, 2, 3};
  const DelayEmbedding e(x, 1, 1);
  const KdTree tree(e, Norm::max, 1);
  const std::vector<std::pair<double, std::size_t>> cases{{1.0, 0}, {1.5, 1}, {3.0, 2}, {3.5, 3}};
  for (const auto& [radius, expected] : cases) {
    EXPECT_EQ(tree.count_within(0, radius), expected) << radius;
    EXPECT_EQ(chaos::count_within_brute_force(e, 0, radius, Norm::max), expected) << radius;
    const std::size_t windowed = expected > 0 ? expected - 1 : 0;
    EXPECT_EQ(tree.count_within(0, radius, {1, false}), windowed) << radius;
  }
  EXPECT_EQ(tree.count_within(0, 0.0), 0u);   // nothing is closer than 0
  EXPECT_EQ(tree.count_within(0, -1.0), 0u);
  EXPECT_EQ(tree.count_within(0, INFINITY), 3u);
}

TEST(KdTree, CountWithinDuplicatesAndSkipZero) {
  // Six copies of 2 and two of 7 (indices 6, 7). From point 0: five twins at 0, two points at 5.
  const std::vector<double> x{2, 2, 2, 2, 2, 2, 7, 7};
  const DelayEmbedding e(x, 1, 1);
  const KdTree tree(e, Norm::max, 2);
  EXPECT_EQ(tree.count_within(0, 1.0), 5u);               // the five twins
  EXPECT_EQ(tree.count_within(0, 1.0, {0, true}), 0u);    // twins skipped
  EXPECT_EQ(tree.count_within(0, 6.0, {0, true}), 2u);    // only 6 and 7
  EXPECT_EQ(tree.count_within(2, 1.0, {1, false}), 3u);   // twins 0, 4, 5 (1 and 3 in the window)
  EXPECT_EQ(tree.count_within(2, 6.0, {3, false}), 2u);   // 0..5 in the window; 6 and 7 at 5 < 6
  expect_nearest(e, Norm::max, 2, {2, false}, 5, 0.0);    // 0,1,3,4 in the window; twin 5 first
  expect_nearest(e, Norm::max, 6, {0, true}, 0, 5.0);     // twin 7 skipped; six 2s tie, index 0
  expect_nearest(e, Norm::max, 6, {5, true}, 0, 5.0);     // w = 5 excludes 1..7 but keeps 0
  EXPECT_FALSE(tree.nearest(6, {6, false}).has_value());  // w = 6 excludes all of 0..7
}

TEST(KdTree, WithinListsTheCountedPointsInIndexOrder) {
  // Same data as above: six 2s (0..5) and two 7s (6, 7). From point 2 with radius 1 and w = 1 the
  // members are the twins 0, 4, 5; with radius 6 and w = 3 they are 6 and 7; skipping zero
  // distances from point 0 leaves only the 7s; radius 0 lists nothing (strict).
  const std::vector<double> x{2, 2, 2, 2, 2, 2, 7, 7};
  const DelayEmbedding e(x, 1, 1);
  std::vector<std::size_t> found{99};  // cleared by the call
  for (std::size_t leaf : {1u, 2u, 8u}) {
    const KdTree tree(e, Norm::max, leaf);
    tree.within(2, 1.0, found, {1, false});
    EXPECT_EQ(found, (std::vector<std::size_t>{0, 4, 5})) << "leaf " << leaf;
    tree.within(2, 6.0, found, {3, false});
    EXPECT_EQ(found, (std::vector<std::size_t>{6, 7})) << "leaf " << leaf;
    tree.within(0, 6.0, found, {0, true});
    EXPECT_EQ(found, (std::vector<std::size_t>{6, 7})) << "leaf " << leaf;
    tree.within(0, 0.0, found);
    EXPECT_TRUE(found.empty());
  }
  EXPECT_EQ(chaos::within_brute_force(e, 2, 1.0, Norm::max, {1, false}), (std::vector<std::size_t>{0, 4, 5}));
  // leaf_order is a permutation of the point indices.
  const KdTree tree(e, Norm::max, 2);
  std::vector<std::size_t> order(tree.leaf_order().begin(), tree.leaf_order().end());
  std::sort(order.begin(), order.end());
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_THROW(KdTree(e, Norm::max).within(0, NAN, found), chaos::InvalidInput);
  EXPECT_THROW(KdTree(e, Norm::max).within(8, 1.0, found), chaos::InvalidInput);
}

TEST(KdTree, DelayGreaterThanOne) {
  // tau = 2, m = 2 on x = 0 10 1 20 5 30: points (x0,x2)=(0,1), (x1,x3)=(10,20), (x2,x4)=(1,5),
  // (x3,x5)=(20,30). Point 0's nearest is 2 at max(1,4) = 4, Euclidean sqrt(17).
  const std::vector<double> x{0, 10, 1, 20, 5, 30};
  const DelayEmbedding e(x, 2, 2);
  expect_nearest(e, Norm::max, 0, {}, 2, 4.0);
  expect_nearest(e, Norm::euclidean, 0, {}, 2, std::sqrt(17.0));
}

TEST(KdTree, PointsSubsetAndAccessors) {
  // Only the first 3 of 5 points are searched: from point 0 of x = 0 9 8 0 0, point 3 (distance 0)
  // is not part of the tree, so the nearest is point 2 at distance 8.
  const std::vector<double> x{0, 9, 8, 0, 0};
  const DelayEmbedding e(x, 1, 1, 3);
  KdTree tree(e, Norm::euclidean);
  EXPECT_EQ(tree.points().size(), 3u);
  EXPECT_EQ(tree.norm(), Norm::euclidean);
  expect_nearest(e, Norm::euclidean, 0, {}, 2, 8.0);
  KdTree moved(std::move(tree));
  EXPECT_EQ(moved.nearest(0)->index, 2u);
}

TEST(KdTree, QueryOutsideTheEmbeddingThrows) {
  // Point 5 does not exist in a 5-point embedding; NaN is not a radius.
  const std::vector<double> x{0, 1, 2, 3, 4};
  const DelayEmbedding e(x, 1, 1);
  const KdTree tree(e, Norm::max);
  EXPECT_THROW(static_cast<void>(tree.nearest(5)), chaos::InvalidInput);
  EXPECT_THROW(static_cast<void>(chaos::nearest_brute_force(e, 5, Norm::max)), chaos::InvalidInput);
  EXPECT_THROW(static_cast<void>(tree.count_within(0, NAN)), chaos::InvalidInput);
}

TEST(KdTree, LargeConstantBlocksStayFast) {
  // 200000 samples taking only 3 values: m = 1 has three groups of identical points. Each query
  // must still be cheap (uniform leaves, binary searches), and the answer is known: with
  // skip_zero_distance the nearest of a 0 is the first 1 (index 1), of a 2 the first 1.
  std::vector<double> x(200000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = static_cast<double>(i % 3);
  const DelayEmbedding e(x, 1, 1);
  const KdTree tree(e, Norm::max);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto n = tree.nearest(i, {0, true});
    ASSERT_TRUE(n.has_value());
    ASSERT_EQ(n->index, x[i] == 1.0 ? 0u : 1u) << i;
    ASSERT_EQ(n->distance, 1.0);
  }
  // Without the skip, a 0 at i finds the twin 0 (or 3 when i = 0) at distance 0; counts of the
  // 66667 zeros within 0.5 exclude the point itself.
  EXPECT_EQ(tree.nearest(0)->index, 3u);
  EXPECT_EQ(tree.nearest(6)->index, 0u);
  EXPECT_EQ(tree.count_within(0, 0.5), 66666u);
  EXPECT_EQ(tree.count_within(0, 0.5, {0, true}), 0u);
}

}  // namespace
