#pragma once
// Bifurcation diagrams and their densities: for each parameter value the section points left after
// a transient, and the probability density of those points per parameter value on a common grid
// (the seed's Fig. 4b and 5 plot that grid, parameter x observed variable, as a colour map).
//
//   map_bifurcation  iterates a one-dimensional map family x -> f(r, x) for each r from the same
//                    initial x, drops `transient` iterates and keeps the next `keep`;
//   density_map      samples per parameter value -> densities on common bins, each integrating
//                    to 1 over the range: a histogram (a fixed bin count, or the Freedman-Diaconis
//                    width on the pooled samples, capped) or a Gaussian kernel estimate with
//                    Silverman's bandwidth, averaged over each bin.
//
// The samples may come from anywhere: map_bifurcation, stroboscopic or hyperplane sections of a
// flow (poincare.hpp, section_stream.hpp), or a simulator's sweep.

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace chaos {

struct MapBifurcationOptions {
  double initial = 0.5;         // x0, the same for every parameter value (no continuation)
  std::size_t transient = 1000;  // iterates dropped
  std::size_t keep = 200;        // iterates kept (>= 1)
  void validate() const;
};

struct BifurcationDiagram {
  std::vector<double> parameters;
  std::vector<std::vector<double>> points;  // points[p]: the kept iterates at parameters[p]
};

using MapFamily = std::function<double(double parameter, double x)>;

// Refuses an empty or non-finite parameter list, keep = 0, a non-finite x0, and an orbit that
// leaves the finite numbers (naming the parameter and the iterate).
BifurcationDiagram map_bifurcation(const MapFamily& f, std::span<const double> parameters,
                                   const MapBifurcationOptions& options = {});

enum class DensityEstimator { histogram, kernel };
enum class BinRule {
  fixed,              // `bins` bins
  freedman_diaconis,  // width 2 IQR n^(-1/3) on the pooled samples (Freedman & Diaconis 1981), at most `bins`
};

// More bins than this resolve nothing a plot or a table can show, and each parameter value holds
// a density per bin: the cap keeps a mistyped count (-b -1 read as 2^64-1) from
// allocating gigabytes.
inline constexpr std::size_t max_density_bins = 100000;

struct DensityMapOptions {
  DensityEstimator estimator = DensityEstimator::histogram;
  BinRule bin_rule = BinRule::freedman_diaconis;
  std::size_t bins = 200;           // the count (fixed) or the cap (Freedman-Diaconis); 1..max_density_bins
  std::optional<double> low, high;  // the common range, both or neither; default: pooled min/max, padded
  double padding = 0.05;            // fraction of the pooled span added on each side (>= 0)
  std::optional<double> bandwidth;  // kernel: one bandwidth for all; default Silverman's per parameter value
  void validate() const;
};

struct DensityMap {
  std::vector<double> parameters;
  std::vector<double> edges;                 // bins + 1, equal widths from low to high
  std::vector<double> centres;               // bins
  std::vector<std::vector<double>> density;  // density[p][b]; sum_b density x width = 1 for every p
  std::optional<std::size_t> rule_bins;      // Freedman-Diaconis: the count before the cap (none when IQR = 0)
  std::vector<std::size_t> in_range;         // samples per parameter value inside [low, high]
  std::vector<double> bandwidths;            // kernel: per parameter value
  std::vector<double> kernel_mass;           // kernel: fraction of the estimate inside [low, high] before renormalising
};

// samples[p] belongs to parameters[p]. Refuses mismatched sizes, an empty list or sample set,
// non-finite values, bins = 0, a bad range, and a parameter value with nothing inside a given range.
// A constant pooled sample v (no span to pad) gets the range v -/+ max(|v|, 1) / 2; its histogram
// puts all the mass in one bin, its kernel estimate uses one bin width as the bandwidth.
DensityMap density_map(std::span<const double> parameters, const std::vector<std::vector<double>>& samples,
                       const DensityMapOptions& options = {});

// Silverman's rule of thumb, 0.9 min(s, IQR / 1.34) n^(-1/5) (Silverman 1986, eq. 3.31); when
// that is 0 but s > 0, 0.9 s n^(-1/5); 0 for a constant sample (the caller chooses).
double silverman_bandwidth(std::span<const double> values);

// The q-quantile by linear interpolation between order statistics (Hyndman & Fan 1996, type 7,
// R's default): (n - 1) q is the fractional index into the sorted values.
double quantile(std::span<const double> values, double q);

}  // namespace chaos
