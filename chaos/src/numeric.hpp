#pragma once
// Small private helpers shared by the estimators: saturating index arithmetic for length checks,
// the formatter for numbers in messages, and the exact power-of-two rescaling that keeps sums of
// squares finite for data of any magnitude.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "chaos/format.hpp"

namespace chaos::detail {

inline constexpr std::size_t size_max = std::numeric_limits<std::size_t>::max();

// a * b and a + b, saturating at size_max: absurd options give a clear "too short" instead of a
// wrapped-around requirement.
inline std::size_t mul_sat(std::size_t a, std::size_t b) noexcept { return a != 0 && b > size_max / a ? size_max : a * b; }
inline std::size_t add_sat(std::size_t a, std::size_t b) noexcept { return a > size_max - b ? size_max : a + b; }

// Numbers in messages: the library's one formatter (chaos/format.hpp), all 17 digits by default so
// a message shows the number that was really used.
using chaos::format_number;

// The power of two 2^exponent with max |x| / 2^exponent in [0.5, 1). Dividing by it is exact, so
// neighbours, ratios and comparisons are unchanged bit for bit while squares cannot overflow or
// underflow.
inline int scale_exponent(std::span<const double> x) noexcept {
  double largest = 0.0;
  for (const double v : x) largest = std::max(largest, std::abs(v));
  int exponent = 0;
  std::frexp(largest, &exponent);
  return exponent;
}

// The same exponent where max |x| lies outside [2^-100, 2^100], else 0. Inside, squares, cubes and
// sums of them over any series that fits in memory stay far from overflow and underflow, so the
// series is used as given (its results bit for bit those of the code before any rescaling, even
// through pow or log, which a power of two does not pass through exactly); outside, dividing by the
// power of two is exact and makes the estimate that of the rescaled copy.
inline int standardising_exponent(std::span<const double> x) noexcept {
  const int exponent = scale_exponent(x);
  return exponent < -100 || exponent > 101 ? exponent : 0;
}

inline std::vector<double> scaled_by_power_of_two(std::span<const double> x, int exponent) {
  std::vector<double> y(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = std::ldexp(x[i], -exponent);
  return y;
}

}  // namespace chaos::detail
