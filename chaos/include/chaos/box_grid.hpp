#pragma once
// Box-assisted neighbour search in a delay embedding (Grassberger 1990; the boxes of TISEAN,
// Hegger, Kantz & Schreiber 1999): the points are sorted into square boxes over their first two
// coordinates (the first alone for m = 1), and a query looks at the boxes around its own, ring by
// ring. A point ρ + 1 rings away differs from the query by at least ρ boxes in one coordinate, a
// lower bound of its distance in the maximum and the Euclidean norm alike, so the rings stop once
// that bound passes the radius (counts) or the k-th best distance (k nearest).
// Same conventions as neighbors.hpp (Theiler window, strict radius, ties to the smaller index),
// and the distances are those of DelayEmbedding::distance bit for bit, so the answers equal brute
// force exactly (docs/reference/neighbors.md).

#include <cstddef>
#include <memory>
#include <vector>

#include "chaos/embedding.hpp"
#include "chaos/neighbors.hpp"
#include "chaos/norm.hpp"

namespace chaos {

class BoxGrid {
 public:
  // Boxes of side `box` (finite and positive, else InvalidInput), enlarged when the grid would have
  // more than max(4 N, 1024) boxes: a tiny box only costs memory, since the rings adapt to it.
  BoxGrid(const DelayEmbedding& points, Norm norm, double box);
  ~BoxGrid();
  BoxGrid(BoxGrid&&) noexcept;
  BoxGrid& operator=(BoxGrid&&) noexcept;

  // A box for k-nearest queries: about `per_box` points per box over the square the points span
  // (1 when they all coincide in the grid's coordinates).
  static double box_for(const DelayEmbedding& points, double per_box = 4.0);

  // As KdTree::count_within and KdTree::k_nearest (neighbors.hpp).
  std::size_t count_within(std::size_t i, double radius, const NeighborQuery& query = {}) const;
  void k_nearest(std::size_t i, std::size_t k, std::vector<Neighbor>& out, const NeighborQuery& query = {}) const;

  double box() const noexcept;  // the side used, after any enlargement
  std::size_t boxes() const noexcept;
  // Bytes the grid holds besides the series it views (box starts, the point order, the coordinate copy).
  std::size_t memory_bytes() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace chaos
