#pragma once
// Nearest-neighbour search in a delay embedding, with a Theiler window: candidates j with
// |i - j| <= theiler are excluded, so temporally correlated points of a flow do not pose as
// neighbours (Theiler 1986). Two interchangeable searchers, tested equal to each other:
//   KdTree      O(N log N) build, fast queries for any dimension and either norm;
//   BoxGrid     (box_grid.hpp) boxes over the first two coordinates, as TISEAN searches;
//   brute force O(N) per query, the definition, kept for tests and tiny inputs.
// The kd-tree prunes with the distance from the query to a node's bounding box, which is a valid
// lower bound for the maximum norm as well as the Euclidean one (nanoflann's additive bound is
// valid only for Euclidean-type norms, hence our own tree).

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "chaos/embedding.hpp"
#include "chaos/norm.hpp"

namespace chaos {

struct Neighbor {
  std::size_t index;
  double distance;
};

struct NeighborQuery {
  std::size_t theiler = 0;     // exclude candidates with |i - j| <= theiler (always excludes j = i)
  bool skip_zero_distance = false;  // ignore candidates at distance exactly 0 (ties in quantised
                                    // data); the nearest candidate at a positive distance is returned
};

class KdTree {
 public:
  // `threads` share the build; the tree, and every answer, is the same for any number.
  KdTree(const DelayEmbedding& points, Norm norm, std::size_t leaf_size = 8, std::size_t threads = 1);
  ~KdTree();
  KdTree(KdTree&&) noexcept;
  KdTree& operator=(KdTree&&) noexcept;

  // The nearest admissible neighbour of point i of the embedding, or nullopt when none exists.
  // Ties in distance are broken by the smaller index, so the answer is unique and equals brute force.
  std::optional<Neighbor> nearest(std::size_t i, const NeighborQuery& query = {}) const;

  // The k nearest admissible neighbours of point i, written to `out` (cleared first) in the order
  // (distance, index): the first k admissible j in that order, fewer when fewer are admissible.
  // The same tie rule as nearest(), so k = 1 gives nearest()'s answer. Throws for k = 0.
  void k_nearest(std::size_t i, std::size_t k, std::vector<Neighbor>& out, const NeighborQuery& query = {}) const;

  // Number of admissible j with distance(i, j) < radius (strict, the correlation-sum convention).
  std::size_t count_within(std::size_t i, double radius, const NeighborQuery& query = {}) const;

  // The admissible j with distance(i, j) < radius, in ascending order of j, written to `out`
  // (cleared first, so one buffer serves many queries): exactly the points count_within counts.
  void within(std::size_t i, double radius, std::vector<std::size_t>& out, const NeighborQuery& query = {}) const;

  const DelayEmbedding& points() const noexcept;
  Norm norm() const noexcept;
  // Every point index once, in the order of the tree's leaves: points close in space are close in
  // this order, so queries made in it reuse the same nodes from cache (a batch of queries in index
  // order jumps across the whole tree for chaotic data).
  std::span<const std::size_t> leaf_order() const noexcept;
  // Bytes the tree holds besides the series it views (indices, the coordinate copy, nodes, boxes).
  std::size_t memory_bytes() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The nearest admissible neighbour of every point of the tree (element i: tree.nearest(i, query)).
// The searches run in the tree's leaf order, so each finds the nodes the one before read still in
// the cache (in index order a chaotic series jumps across the whole tree at every search): 1.6 times
// faster for Cao's method on Lorenz x at N = 10^5, 2.6 times at 10^6. `progress`, if given, is
// called with the fraction done (on the calling thread); `threads` share the searches, each point's
// answer being its own, so any number gives the same result.
std::vector<std::optional<Neighbor>> all_nearest(const KdTree& tree, const NeighborQuery& query = {},
                                                 const std::function<void(double)>& progress = nullptr,
                                                 std::size_t threads = 1);

std::optional<Neighbor> nearest_brute_force(const DelayEmbedding& points, std::size_t i, Norm norm,
                                            const NeighborQuery& query = {});
// The k nearest admissible neighbours in the order (distance, index), by looking at every j.
std::vector<Neighbor> k_nearest_brute_force(const DelayEmbedding& points, std::size_t i, std::size_t k, Norm norm,
                                            const NeighborQuery& query = {});
std::size_t count_within_brute_force(const DelayEmbedding& points, std::size_t i, double radius,
                                     Norm norm, const NeighborQuery& query = {});
std::vector<std::size_t> within_brute_force(const DelayEmbedding& points, std::size_t i, double radius, Norm norm,
                                            const NeighborQuery& query = {});

}  // namespace chaos
