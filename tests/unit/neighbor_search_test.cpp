// The neighbour searches `chaos neighbors` measures, against brute force (the definition): the
// kd-tree's k nearest (KdTree::k_nearest), the box-assisted grid (BoxGrid) and nanoflann through
// its adaptor (NanoflannSearch). Expected values: k_nearest_brute_force and
// count_within_brute_force on the same points, for every point of small data sets (uniform noise,
// Hénon, Lorenz, Lorenz rounded to integers and a five-level series, the last two full of exact
// ties), m = 1, 2, 3, 5, both norms, Theiler windows 0, 3, 20 and k = 1, 4, 12.
//   ours:      exact equality: the same indices in the same order and bit-identical distances, and
//              the same counts (radii equal to an existing distance included: strictness);
//   nanoflann: Euclidean only; the same distances rank by rank (its indices may differ where
//              distances tie: docs/reference/neighbors.md), every index admissible, the same counts.
#include "chaos/box_grid.hpp"
#include "chaos/neighbors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/models/systems.hpp"
// nanoflann, the outside reference, is compared where it is built (CHAOS_WITH_NANOFLANN, on by
// default: tests/support/nanoflann_search.hpp); brute force is the expected value either way.
#if CHAOS_WITH_NANOFLANN
#include "nanoflann_search.hpp"
#endif

namespace {

using chaos::BoxGrid;
using chaos::DelayEmbedding;
using chaos::KdTree;
using chaos::Neighbor;
using chaos::NeighborQuery;
using chaos::Norm;

// Uniform in [0, 1) from the raw output of mt19937_64 (the standard distributions are
// implementation-defined).
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

struct DataSet {
  std::string name;
  std::vector<double> x;
  std::size_t delay;
};

std::vector<DataSet> data_sets() {
  constexpr std::size_t n = 400;
  std::vector<DataSet> sets;
  std::mt19937_64 rng(20261125);
  std::vector<double> noise(n);
  for (auto& v : noise) v = uniform(rng);
  sets.push_back({"uniform", noise, 1});
  sets.push_back({"henon", chaos::henon(n).components[0], 1});
  const auto lorenz = chaos::lorenz(n).components[0];
  sets.push_back({"lorenz", lorenz, 3});
  std::vector<double> rounded(lorenz.size());
  for (std::size_t i = 0; i < lorenz.size(); ++i) rounded[i] = std::round(lorenz[i]);
  sets.push_back({"lorenz-rounded", rounded, 3});
  std::vector<double> levels(n);  // five values: ties at every distance
  for (auto& v : levels) v = static_cast<double>(rng() % 5);
  sets.push_back({"five-levels", levels, 1});
  return sets;
}

std::string where(const DataSet& set, std::size_t m, Norm norm, std::size_t w, std::size_t k, std::size_t i) {
  return set.name + " m=" + std::to_string(m) + " norm=" + chaos::to_string(norm) + " w=" + std::to_string(w) +
         " k=" + std::to_string(k) + " point " + std::to_string(i);
}

TEST(NeighborSearch, KNearestEqualsBruteForce) {
  std::size_t checked = 0, tied = 0;
  std::vector<Neighbor> tree_out, grid_out, nano_out;
  for (const auto& set : data_sets())
    for (std::size_t m : {1u, 2u, 3u, 5u}) {
      const DelayEmbedding points(set.x, m, set.delay);
      for (Norm norm : {Norm::max, Norm::euclidean}) {
        const KdTree tree(points, norm);
        const BoxGrid grid(points, norm, BoxGrid::box_for(points));
        const BoxGrid tiny(points, norm, 1e-9);  // enlarged to the cap: many rings per query
        const bool euclidean = norm == Norm::euclidean;
#if CHAOS_WITH_NANOFLANN
        const auto nano = euclidean ? std::make_unique<chaos::cli::NanoflannSearch>(points) : nullptr;
#else
        (void)euclidean;
#endif
        for (std::size_t w : {0u, 3u, 20u})
          for (std::size_t k : {1u, 4u, 12u})
            for (std::size_t i = 0; i < points.size(); ++i) {
              const NeighborQuery query{w, false};
              const auto expected = chaos::k_nearest_brute_force(points, i, k, norm, query);
              tree.k_nearest(i, k, tree_out, query);
              grid.k_nearest(i, k, grid_out, query);
              ASSERT_EQ(tree_out.size(), expected.size()) << where(set, m, norm, w, k, i);
              ASSERT_EQ(grid_out.size(), expected.size()) << where(set, m, norm, w, k, i);
              for (std::size_t r = 0; r < expected.size(); ++r) {
                ASSERT_EQ(tree_out[r].index, expected[r].index) << "kd-tree " << where(set, m, norm, w, k, i);
                ASSERT_EQ(tree_out[r].distance, expected[r].distance) << "kd-tree " << where(set, m, norm, w, k, i);
                ASSERT_EQ(grid_out[r].index, expected[r].index) << "grid " << where(set, m, norm, w, k, i);
                ASSERT_EQ(grid_out[r].distance, expected[r].distance) << "grid " << where(set, m, norm, w, k, i);
              }
              if (i % 7 == 0) {
                tiny.k_nearest(i, k, grid_out, query);
                ASSERT_EQ(grid_out.size(), expected.size());
                for (std::size_t r = 0; r < expected.size(); ++r)
                  ASSERT_EQ(grid_out[r].index, expected[r].index) << "tiny grid " << where(set, m, norm, w, k, i);
              }
              if (k == 1) {  // k = 1 is nearest()'s answer
                const auto one = tree.nearest(i, query);
                ASSERT_TRUE(one);
                ASSERT_EQ(one->index, expected[0].index);
              }
#if CHAOS_WITH_NANOFLANN
              if (nano) {
                nano->k_nearest(i, k, nano_out, w);
                ASSERT_EQ(nano_out.size(), expected.size()) << "nanoflann " << where(set, m, norm, w, k, i);
                for (std::size_t r = 0; r < expected.size(); ++r) {
                  const std::size_t j = nano_out[r].index;
                  ASSERT_GT(j > i ? j - i : i - j, w) << "nanoflann returned a point inside the Theiler window";
                  ASSERT_EQ(nano_out[r].distance, points.distance(i, j, norm)) << "nanoflann's distance is not ours";
                  ASSERT_EQ(nano_out[r].distance, expected[r].distance) << "nanoflann " << where(set, m, norm, w, k, i);
                  if (nano_out[r].index != expected[r].index) ++tied;
                }
              }
#endif
              ++checked;
            }
      }
    }
  EXPECT_GT(checked, 100000u);
#if CHAOS_WITH_NANOFLANN
  // The tie rule matters: nanoflann picks other indices among equal distances on the quantised sets.
  EXPECT_GT(tied, 0u);
#else
  (void)tied;
#endif
}

TEST(NeighborSearch, CountsEqualBruteForce) {
  std::size_t checked = 0;
  for (const auto& set : data_sets())
    for (std::size_t m : {1u, 3u}) {
      const DelayEmbedding points(set.x, m, set.delay);
      for (Norm norm : {Norm::max, Norm::euclidean}) {
        const KdTree tree(points, norm);
#if CHAOS_WITH_NANOFLANN
        const auto nano = norm == Norm::euclidean ? std::make_unique<chaos::cli::NanoflannSearch>(points) : nullptr;
#endif
        // Radii: a quantile of the distances, and an existing distance exactly (strictness).
        const double scale = points.distance(0, points.size() / 2, norm);
        for (double r : {0.05 * scale, 0.3 * scale, points.distance(1, 7, norm)}) {
          if (!(r > 0.0)) continue;
          const BoxGrid grid(points, norm, r);  // box = radius, as TISEAN
          for (std::size_t w : {0u, 20u})
            for (std::size_t i = 0; i < points.size(); ++i) {
              const NeighborQuery query{w, false};
              const std::size_t expected = chaos::count_within_brute_force(points, i, r, norm, query);
              ASSERT_EQ(tree.count_within(i, r, query), expected) << where(set, m, norm, w, 0, i);
              ASSERT_EQ(grid.count_within(i, r, query), expected) << where(set, m, norm, w, 0, i);
#if CHAOS_WITH_NANOFLANN
              if (nano) {
                ASSERT_EQ(nano->count_within(i, r, w), expected) << "nanoflann " << where(set, m, norm, w, 0, i);
              }
#endif
              ++checked;
            }
        }
      }
    }
  EXPECT_GT(checked, 10000u);
}

// The Theiler window, by hand: on 0, 1, ..., 9 (m = 1) the neighbours of point 5 in order are
// 4 and 6 (distance 1, index order), 3 and 7, ...; w = 2 removes 3..7.
TEST(NeighborSearch, TheilerWindowByHand) {
  std::vector<double> x(10);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = static_cast<double>(i);
  const DelayEmbedding points(x, 1, 1);
  std::vector<Neighbor> out;
  for (Norm norm : {Norm::max, Norm::euclidean}) {
    const KdTree tree(points, norm);
    const BoxGrid grid(points, norm, 1.0);
#if CHAOS_WITH_NANOFLANN
    const chaos::cli::NanoflannSearch nano(points);
    for (const auto* name : {"tree", "grid", "nanoflann"}) {
#else
    for (const auto* name : {"tree", "grid"}) {
#endif
      const std::string s(name);
      const auto run = [&](std::size_t w) {
        if (s == "tree") tree.k_nearest(5, 3, out, {w, false});
        else if (s == "grid") grid.k_nearest(5, 3, out, {w, false});
#if CHAOS_WITH_NANOFLANN
        else nano.k_nearest(5, 3, out, w);
#endif
      };
      run(0);
      ASSERT_EQ(out.size(), 3u) << s;
      EXPECT_EQ(out[0].index, 4u) << s;
      EXPECT_EQ(out[1].index, 6u) << s;
      EXPECT_EQ(out[2].distance, 2.0) << s;
      run(2);
      ASSERT_EQ(out.size(), 3u) << s;
      EXPECT_EQ(out[0].distance, 3.0) << s;  // 2 or 8
      EXPECT_EQ(out[2].distance, 4.0) << s;  // 1 or 9
      run(9);  // everything is inside the window
      EXPECT_TRUE(out.empty()) << s;
    }
    EXPECT_EQ(grid.count_within(5, 2.0, {0, false}), 2u);  // 4 and 6; 3 and 7 are at exactly 2
#if CHAOS_WITH_NANOFLANN
    EXPECT_EQ(nano.count_within(5, 2.0, 0), 2u);
#endif
    EXPECT_EQ(tree.count_within(5, 2.0, {0, false}), 2u);
  }
}

// Fewer admissible points than k: all of them, in order (the definition).
TEST(NeighborSearch, FewerThanK) {
  const std::vector<double> x{0.0, 3.0, 1.0, 7.0};
  const DelayEmbedding points(x, 1, 1);
  std::vector<Neighbor> out;
  const auto expected = chaos::k_nearest_brute_force(points, 0, 10, Norm::max, {});
  ASSERT_EQ(expected.size(), 3u);
  EXPECT_EQ(expected[0].index, 2u);
  KdTree(points, Norm::max).k_nearest(0, 10, out, {});
  ASSERT_EQ(out.size(), 3u);
  BoxGrid(points, Norm::max, 0.5).k_nearest(0, 10, out, {});
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[2].index, 3u);
}

TEST(NeighborSearch, RefusesBadParameters) {
  const std::vector<double> x{0.0, 3.0, 1.0, 7.0};
  const DelayEmbedding points(x, 1, 1);
  std::vector<Neighbor> out;
  EXPECT_THROW(KdTree(points, Norm::max).k_nearest(0, 0, out), chaos::InvalidInput);
  EXPECT_THROW(chaos::k_nearest_brute_force(points, 0, 0, Norm::max), chaos::InvalidInput);
  EXPECT_THROW(BoxGrid(points, Norm::max, 0.0), chaos::InvalidInput);
  EXPECT_THROW(BoxGrid(points, Norm::max, std::nan("")), chaos::InvalidInput);
  EXPECT_THROW(BoxGrid(points, Norm::max, 1.0).count_within(0, std::nan("")), chaos::InvalidInput);
  EXPECT_THROW(BoxGrid(points, Norm::max, 1.0).k_nearest(9, 1, out), chaos::InvalidInput);
}

#if CHAOS_WITH_NANOFLANN
// The threshold behind nanoflann's strict counts: sqrt(s) < r exactly when s < threshold(r).
TEST(NeighborSearch, SquaredThreshold) {
  std::mt19937_64 rng(7);
  for (int n = 0; n < 2000; ++n) {
    const double r = 1e-3 + 10.0 * uniform(rng);
    const double t = chaos::cli::squared_threshold(r);
    EXPECT_GE(std::sqrt(t), r);
    EXPECT_LT(std::sqrt(std::nextafter(t, 0.0)), r);
  }
  EXPECT_EQ(chaos::cli::squared_threshold(0.0), 0.0);
  EXPECT_EQ(chaos::cli::squared_threshold(2.0), 4.0);
}
#endif

}  // namespace
