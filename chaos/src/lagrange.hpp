#pragma once
// Lagrange interpolation weights on arbitrary nodes (private): the streaming sections interpolate
// between samples whose times need not be uniform.

#include <cstddef>

namespace chaos::detail {

// w[k] = prod_{j != k} (s - u[j]) / (u[k] - u[j]) for the n distinct nodes u (n <= 4).
inline void lagrange_weights(const double* u, std::size_t n, double s, double* w) {
  for (std::size_t k = 0; k < n; ++k) {
    double num = 1.0, den = 1.0;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == k) continue;
      num *= s - u[j];
      den *= u[k] - u[j];
    }
    w[k] = num / den;
  }
}

}  // namespace chaos::detail
