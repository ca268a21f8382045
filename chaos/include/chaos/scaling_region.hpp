#pragma once
// Finding the straight part of one or more curves y_c(x) on a shared grid, without a hand-picked
// range: the widest interval of x on which every curve's local slope dy/dx stays within a stated
// tolerance of one common value. Used for the correlation dimension (ln C against ln eps across the
// highest embedding dimensions) and, later, for the linear region of Lyapunov divergence curves.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace chaos {

// dy/dx at each grid point by a least-squares line through the 2*half_width + 1 points centred on
// it (fewer at the ends). nullopt where the fit has fewer than 2 defined points. Undefined y values
// (nullopt, e.g. ln C where C = 0) are left out of the fits.
std::vector<std::optional<double>> local_slopes(std::span<const double> x, std::span<const std::optional<double>> y,
                                                std::size_t half_width = 1);

// A closed range [low, high]: the interval of an estimate, or a range of radii.
struct Interval {
  double low = 0.0, high = 0.0;
};

struct ScalingRegionOptions {
  // Every local slope in the region lies within tolerance * |mean slope| of the mean slope
  // (relative), or within tolerance (absolute, when relative is false).
  double tolerance = 0.05;
  bool relative = true;
  std::size_t min_points = 5;  // grid points in the region
  std::size_t half_width = 1;  // of the local-slope fits
  // With a support (find_scaling_region): the support must gain at least this much across a
  // region, support[last] - support[first] >= min_support_gain (and always more than 0).
  double min_support_gain = 0.0;
  // A region must span at least this much in x, x[last] - x[first] >= min_width (0: any width).
  double min_width = 0.0;
  void validate() const;
};

struct ScalingRegion {
  std::size_t first = 0, last = 0;  // grid indices, inclusive
  double slope = 0.0;               // mean of the local slopes over the region and the curves
  double slope_min = 0.0, slope_max = 0.0;  // their range: the plateau's actual flatness
};

// The region shared by all curves that scores highest; ties go to the flatter region. nullopt when
// no interval of at least min_points satisfies the tolerance. Without `support` the score is the
// width in x (the widest region). With it, support[k] is a non-decreasing measure of the evidence
// accumulated up to grid point k (for correlation sums: ln of the pairs closer than eps_k) and the
// score is what is gained across the region, support[last] - support[first]: a stretch where
// nothing enters gains 0 and is never chosen.
std::optional<ScalingRegion> find_scaling_region(std::span<const double> x,
                                                 const std::vector<std::vector<std::optional<double>>>& slopes,
                                                 const ScalingRegionOptions& options = {},
                                                 std::span<const double> support = {});

// Least-squares slope of y against x over [first, last], skipping undefined y; nullopt if fewer
// than 2 defined points.
std::optional<double> fit_slope(std::span<const double> x, std::span<const std::optional<double>> y, std::size_t first,
                                std::size_t last);

}  // namespace chaos
