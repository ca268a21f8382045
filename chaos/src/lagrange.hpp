#pragma once
// What both Poincaré section paths (whole series, streamed) share (private): whether two samples
// straddle the level in the chosen direction, Lagrange interpolation weights on arbitrary nodes
// (streamed samples need not be uniform in time), and the bisection that finds where the
// interpolant crosses the level.

#include <cstddef>

#include "chaos/poincare.hpp"

namespace chaos::detail {

// a and b are the samples minus the level: a crossing lies between them in direction d.
inline bool crosses(double a, double b, CrossingDirection d) {
  const bool up = a < 0.0 && b >= 0.0, down = a > 0.0 && b <= 0.0;
  switch (d) {
    case CrossingDirection::upward: return up;
    case CrossingDirection::downward: return down;
    case CrossingDirection::both: return up || down;
  }
  return false;
}

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

// The root in [0, 1] of f, a function with f(0) = f0 and a value of the opposite sign (or zero)
// at 1: 60 bisections, below the spacing of doubles in [0, 1].
template <class F>
double bisect_unit_interval(F&& f, double f0) {
  double low = 0.0, high = 1.0, f_low = f0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (low + high), f_mid = f(mid);
    if ((f_mid < 0.0) == (f_low < 0.0) && f_mid != 0.0) {
      low = mid;
      f_low = f_mid;
    } else {
      high = mid;
    }
  }
  return 0.5 * (low + high);
}

}  // namespace chaos::detail
