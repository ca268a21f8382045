#include "chaos/scaling_region.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "chaos/error.hpp"

namespace chaos {

std::vector<std::optional<double>> local_slopes(std::span<const double> x, std::span<const std::optional<double>> y,
                                                std::size_t half_width) {
  if (x.size() != y.size())
    throw InvalidInput(ErrorCode::invalid_parameter, "local_slopes: x has " + std::to_string(x.size()) +
                                                         " points but y has " + std::to_string(y.size()));
  std::vector<std::optional<double>> slope(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!y[k]) continue;  // no slope where the curve itself is undefined
    const std::size_t first = k >= half_width ? k - half_width : 0;
    const std::size_t last = std::min(x.size() - 1, k + half_width);
    slope[k] = fit_slope(x, y, first, last);
  }
  return slope;
}

std::optional<double> fit_slope(std::span<const double> x, std::span<const std::optional<double>> y, std::size_t first,
                                std::size_t last) {
  double sx = 0, sy = 0;
  std::size_t n = 0;
  for (std::size_t k = first; k <= last && k < x.size(); ++k)
    if (y[k]) {
      sx += x[k];
      sy += *y[k];
      ++n;
    }
  if (n < 2) return std::nullopt;
  // Centred sums: numerically stable when x is far from 0 (ln eps for tiny eps).
  const double mx = sx / static_cast<double>(n), my = sy / static_cast<double>(n);
  double sxx = 0, sxy = 0;
  for (std::size_t k = first; k <= last && k < x.size(); ++k)
    if (y[k]) {
      sxx += (x[k] - mx) * (x[k] - mx);
      sxy += (x[k] - mx) * (*y[k] - my);
    }
  if (!(sxx > 0.0)) return std::nullopt;
  return sxy / sxx;
}

void ScalingRegionOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw InvalidInput(ErrorCode::invalid_parameter, "scaling-region tolerance must be positive and finite (got " +
                                                         std::to_string(tolerance) + ")");
  if (min_points < 2)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "a scaling region needs at least 2 points (got min_points = " + std::to_string(min_points) + ")");
  if (!(min_support_gain >= 0.0) || !std::isfinite(min_support_gain))
    throw InvalidInput(ErrorCode::invalid_parameter, "scaling-region support gain must be finite and at least 0 (got " +
                                                         std::to_string(min_support_gain) + ")");
  if (!(min_width >= 0.0) || !std::isfinite(min_width))
    throw InvalidInput(ErrorCode::invalid_parameter, "scaling-region minimum width must be finite and at least 0 (got " +
                                                         std::to_string(min_width) + ")");
  if (half_width < 1)
    throw InvalidInput(ErrorCode::invalid_parameter, "local-slope half width must be at least 1 (got 0)");
}

std::optional<ScalingRegion> find_scaling_region(std::span<const double> x,
                                                 const std::vector<std::vector<std::optional<double>>>& slopes,
                                                 const ScalingRegionOptions& options,
                                                 std::span<const double> support) {
  options.validate();
  if (slopes.empty()) return std::nullopt;
  if (!support.empty() && support.size() != x.size())
    throw InvalidInput(ErrorCode::invalid_parameter, "find_scaling_region: the support has " + std::to_string(support.size()) +
                                                         " points but the grid has " + std::to_string(x.size()));
  for (const auto& curve : slopes)
    if (curve.size() != x.size())
      throw InvalidInput(ErrorCode::invalid_parameter, "find_scaling_region: a slope curve has " + std::to_string(curve.size()) +
                                                           " points but the grid has " + std::to_string(x.size()));
  std::optional<ScalingRegion> best;
  double best_width = -1.0;
  for (std::size_t a = 0; a < x.size(); ++a) {
    double lo = INFINITY, hi = -INFINITY, sum = 0.0;
    std::size_t count = 0;
    for (std::size_t b = a; b < x.size(); ++b) {
      bool defined = true;
      for (const auto& curve : slopes) {
        if (!curve[b]) {
          defined = false;
          break;
        }
        lo = std::min(lo, *curve[b]);
        hi = std::max(hi, *curve[b]);
        sum += *curve[b];
        ++count;
      }
      if (!defined) break;  // a region is contiguous and fully defined
      const double mean = sum / static_cast<double>(count);
      const double allowed = options.relative ? options.tolerance * std::abs(mean) : options.tolerance;
      // Once the spread exceeds twice the allowance no mean can bring it back: stop extending.
      if (hi - lo > 2.0 * allowed) break;
      if (hi - mean > allowed || mean - lo > allowed) continue;
      if (b - a + 1 < options.min_points || x[b] - x[a] < options.min_width) continue;
      const double width = support.empty() ? x[b] - x[a] : support[b] - support[a];
      if (!support.empty() && (!(width > 0.0) || width < options.min_support_gain))
        continue;  // too little entered across the region: no evidence of its slope
      const bool wider = width > best_width * (1.0 + 1e-12);
      const bool as_wide_but_flatter = std::abs(width - best_width) <= 1e-12 * std::abs(best_width) && best &&
                                       hi - lo < best->slope_max - best->slope_min;
      if (wider || as_wide_but_flatter) {
        best = ScalingRegion{a, b, mean, lo, hi};
        best_width = width;
      }
    }
  }
  return best;
}

}  // namespace chaos
