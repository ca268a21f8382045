#pragma once
// Delay embedding as a view: point i in dimension m is (x[i], x[i+tau], ..., x[i+(m-1)tau])
// (seed Eq. 30). Nothing is copied; the view holds a span of the series, which must outlive it.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

#include "chaos/norm.hpp"

namespace chaos {

class DelayEmbedding {
 public:
  // All N - (m-1)tau points. Throws InvalidInput if m or tau is 0 or the series is too short.
  DelayEmbedding(std::span<const double> series, std::size_t dimension, std::size_t delay);
  // Only the first `points` points; used when a larger dimension must stay inside the series
  // (Cao's method compares the same points in m and m+1 dimensions).
  DelayEmbedding(std::span<const double> series, std::size_t dimension, std::size_t delay,
                 std::size_t points);

  std::size_t size() const noexcept { return points_; }
  std::size_t dimension() const noexcept { return dimension_; }
  std::size_t delay() const noexcept { return delay_; }
  std::span<const double> series() const noexcept { return series_; }

  // Coordinate k of point i.
  double operator()(std::size_t i, std::size_t k) const noexcept { return series_[i + k * delay_]; }

  double distance(std::size_t i, std::size_t j, Norm norm) const noexcept {
    double acc = 0.0;
    for (std::size_t k = 0; k < dimension_; ++k) {
      const double d = std::abs((*this)(i, k) - (*this)(j, k));
      acc = norm == Norm::max ? std::max(acc, d) : acc + d * d;
    }
    return norm == Norm::max ? acc : std::sqrt(acc);
  }

  // Number of points an embedding of this dimension and delay has in a series of length n
  // (0 when it has none).
  static std::size_t points_for(std::size_t n, std::size_t dimension, std::size_t delay) noexcept {
    const std::size_t span = (dimension - 1) * delay;
    return n > span ? n - span : 0;
  }

 private:
  std::span<const double> series_;
  std::size_t dimension_;
  std::size_t delay_;
  std::size_t points_;
};

}  // namespace chaos
