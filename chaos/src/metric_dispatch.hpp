#pragma once
// The norms as compile-time policies for the neighbour searches (neighbors.cpp's kd-tree and
// box_grid.cpp's grid), and the two small pieces both searches run every query through: the
// dispatch from the run-time norm and dimension to a specialised inner loop, and the query point's
// coordinates read once from the delay view.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/norm.hpp"

namespace chaos::detail {

// `add` accumulates one coordinate difference in the order DelayEmbedding::distance uses, `finish`
// turns the accumulator into the distance. For the maximum norm the accumulator is already a lower
// bound of the distance after any prefix of coordinates, so a loop may stop as soon as it exceeds
// the best distance; for the Euclidean norm that would need the square root, so it runs to the end.
struct MaxMetric {
  static constexpr bool early_exit = true;
  static double add(double acc, double d) noexcept { return std::max(acc, d); }
  static double finish(double acc) noexcept { return acc; }
};
struct EuclideanMetric {
  static constexpr bool early_exit = false;
  static double add(double acc, double d) noexcept { return acc + d * d; }
  static double finish(double acc) noexcept { return std::sqrt(acc); }
};

// Runs f.template operator()<Metric, D>() with the norm's policy and D = dim for 1..MaxD, so the
// coordinate loops unroll; D = 0 (the dimension read at run time) above that.
template <std::size_t MaxD, std::size_t D = 1, class Metric, class F>
auto dispatch_dimension(std::size_t dim, F& f) {
  if constexpr (D > MaxD) {
    return f.template operator()<Metric, 0>();
  } else {
    if (dim == D) return f.template operator()<Metric, D>();
    return dispatch_dimension<MaxD, D + 1, Metric>(dim, f);
  }
}
template <std::size_t MaxD, class F>
auto dispatch_metric(Norm norm, std::size_t dim, F&& f) {
  if (norm == Norm::max) return dispatch_dimension<MaxD, 1, MaxMetric>(dim, f);
  return dispatch_dimension<MaxD, 1, EuclideanMetric>(dim, f);
}

// Calls f(q) with point i's coordinates in q (on the stack for usual dimensions). A point outside
// the embedding is refused (InvalidInput) with the numbers.
template <class F>
auto with_point(const DelayEmbedding& points, std::size_t i, F&& f) {
  if (i >= points.size())
    throw InvalidInput(ErrorCode::invalid_parameter, "neighbour query for point " + std::to_string(i) +
                                                         " but the embedding has only " +
                                                         std::to_string(points.size()) + " points");
  constexpr std::size_t stack_dim = 32;
  const std::size_t dim = points.dimension();
  double stack[stack_dim];
  std::vector<double> heap;
  double* q = stack;
  if (dim > stack_dim) {
    heap.resize(dim);
    q = heap.data();
  }
  for (std::size_t k = 0; k < dim; ++k) q[k] = points(i, k);
  return f(static_cast<const double*>(q));
}

}  // namespace chaos::detail
