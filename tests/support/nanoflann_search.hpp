#pragma once
// nanoflann (J. L. Blanco, P. K. Rai, 2014; Debian's libnanoflann-dev), the outside reference that
// `chaos neighbors` measures our searches against: its kd-tree over the delay embedding as a view
// (pt(i, k) = x[i + k tau], nothing copied), Euclidean norm only: its pruning bound adds squared
// coordinate gaps, which is not a lower bound for the maximum norm. The Theiler window is applied in
// the result sets (a candidate with |i - j| <= w is not kept), so the tree itself is nanoflann's, as
// shipped.
//
// nanoflann offers a candidate only when its squared distance is strictly below the current worst,
// so among points tied at the k-th distance it keeps the first one it meets, which need not be the
// smallest index: its k nearest equal brute force's as distances, and as indices only up to ties
// (docs/reference/neighbors.md). Its squared distances are accumulated in DelayEmbedding::distance's order, so
// the distances (after the square root) are bit-identical to ours.

#include <cstddef>
#include <memory>
#include <vector>

#include "chaos/embedding.hpp"
#include "chaos/neighbors.hpp"

namespace chaos::cli {

class NanoflannSearch {
 public:
  // nanoflann's default leaf size is 10.
  explicit NanoflannSearch(const DelayEmbedding& points, std::size_t leaf_size = 10);
  ~NanoflannSearch();
  NanoflannSearch(NanoflannSearch&&) noexcept;
  NanoflannSearch& operator=(NanoflannSearch&&) noexcept;

  // Admissible j with Euclidean distance < radius (strict, exactly as brute force decides it).
  std::size_t count_within(std::size_t i, double radius, std::size_t theiler) const;
  // The k nearest admissible j in the order (distance, index); distances are Euclidean.
  void k_nearest(std::size_t i, std::size_t k, std::vector<Neighbor>& out, std::size_t theiler) const;
  // nanoflann's own account (its node pool and index array), besides the series it views.
  std::size_t memory_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The smallest double a >= 0 with sqrt(a) >= r: a squared distance s satisfies sqrt(s) < r exactly
// when s < a, so a count on squared distances decides as brute force does on distances.
double squared_threshold(double r);

}  // namespace chaos::cli
