#pragma once
// Correlation sums C(eps, m) for every embedding dimension m = min..max in one pass over the pairs
// (Grassberger & Procaccia 1983; seed Eq. 32). Convention, the same for every search mode:
//   C(eps, m) = (number of pairs i < j with j - i > w and |X_i(m) - X_j(m)| < eps) / (admissible pairs),
// (<= eps with `inclusive`),
// over the same reference set of points for every m, namely i < N - (max-1) tau, so the curves for
// different m are comparable. With the maximum norm the distance in m + 1 dimensions extends the
// one in m by one coordinate, which is what makes the single pass possible.
//
// Search modes give identical counts (a test): brute force (the definition), a kd-tree, and a
// box-assisted grid in the spirit of TISEAN's d2 (Grassberger 1990; Hegger, Kantz & Schreiber 1999).
// Speed for accuracy: a cap on the pairs counted per radius (TISEAN -N) and a random subset of
// reference points, both off by default and reported in the result.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "chaos/norm.hpp"
#include "chaos/series.hpp"

namespace chaos {

enum class CorrelationSearch { brute_force, kd_tree, box_assisted };

const char* to_string(CorrelationSearch search) noexcept;

struct CorrelationSumOptions {
  std::size_t delay = 1;           // -d
  std::size_t min_dimension = 1;   // -m
  std::size_t max_dimension = 10;  // -M
  std::size_t theiler = 0;         // -t: pairs with |i - j| <= theiler are excluded
  Norm norm = Norm::max;
  std::vector<double> radii;       // strictly increasing, positive (log_radii makes TISEAN's grid)
  // false (default): count d < eps, the convention of Grassberger & Procaccia's Theta(eps - d) with
  // Theta(0) = 0. true: count d <= eps, as TISEAN's d2 does (up to the rounding of its logarithmic
  // binning), for comparing counts on quantised data where distances equal a radius exactly.
  bool inclusive = false;
  CorrelationSearch search = CorrelationSearch::box_assisted;
  // TISEAN's -N: once this many pairs are closer than a radius, stop counting for that radius and
  // normalise by the pairs examined until then (reference points are visited in a seeded random
  // order so the examined pairs are not biased in time). 0: no cap, exact counts.
  std::uint64_t pairs_per_radius = 0;
  // Use only this many reference points i (a seeded random subset); partners j range over all
  // points. 0: every point is a reference point.
  // With a cap or a subset each reference point counts its partners on both sides (|i - j| > w),
  // so `pairs` and `examined` count ordered pairs: with all P points as reference points and no
  // cap reached, both are exactly twice the exact counts and C is the same.
  std::size_t reference_points = 0;
  // With a subset: skip this many points of the seeded order first, so that calls with the same
  // seed and consecutive offsets count disjoint subsets (an adaptive budget adds them up).
  std::size_t reference_offset = 0;
  std::uint64_t seed = 1;
  // With a cap or a subset, the counts are also kept in this many groups of reference points
  // (consecutive in the seeded order), so that the statistical error of C and of its local slopes
  // can be estimated by leaving one group out (a delete-a-group jackknife): the pairs around one
  // reference point are not independent, so the pair count alone overstates the evidence.
  std::size_t jackknife_groups = 16;
  std::size_t threads = 1;  // results are identical for any thread count
  // Called from the calling thread with the fraction of the counting done (in thousandths, below
  // 1), for a progress display; the counts do not depend on it. Not called under a pairs cap.
  std::function<void(double)> progress;
  void validate() const;
};

struct CorrelationSumResult {
  std::vector<std::size_t> dimension;               // m = min .. max
  std::vector<double> radius;                       // as given
  std::vector<std::vector<double>> correlation_sum; // [m index][radius index], in [0, 1]
  std::vector<std::vector<std::uint64_t>> pairs;    // pairs closer than the radius
  std::vector<std::vector<std::uint64_t>> examined; // admissible pairs examined (all of them without a cap)
  // A cap or a subset only (empty for exact counts): pairs and examined split by group of
  // reference points, [group][m index][radius index]; the groups add up to `pairs` and `examined`.
  std::vector<std::vector<std::vector<std::uint64_t>>> group_pairs, group_examined;
  std::size_t points = 0;                           // embedded points in the reference set
  double range = 0.0;  // max - min of the series: the max-norm diameter of the embedded points is at most this
  ValueTies ties;      // of the series (series.hpp): D2's explanation says so when most pairs tie
};

// n radii from r_min to r_max, equally spaced in log (TISEAN -r -R -#).
std::vector<double> log_radii(double r_min, double r_max, std::size_t n);

CorrelationSumResult correlation_sum(std::span<const double> x, const CorrelationSumOptions& options);

// Exact correlation sums at several Theiler windows: element q equals correlation_sum(x, options)
// with options.theiler = theilers[q], count for count (options.theiler is not used). The pairs are
// walked once, at the smallest window; for each larger window the pairs with lags between the two
// are enumerated and subtracted: P (w_max - w_min) pairs instead of a walk of every close pair per
// window. For checking that D2 holds over a neighbourhood of w (docs/reference/correlation_sum.md). Exact
// counts only: refuses a pair cap or a reference subset, and whatever correlation_sum refuses at
// any of the windows.
std::vector<CorrelationSumResult> correlation_sums_over_theiler_windows(std::span<const double> x,
                                                                        const CorrelationSumOptions& options,
                                                                        std::span<const std::size_t> theilers);

// Correlation sums of one series over several reference subsets, with the search structure (grid
// or kd-tree, and the sorted values for m = 1) built once instead of once per subset: `chaos d2
// --fast` counts disjoint subsets of one series round after round. count(offset, points) equals
// correlation_sum(x, options) with options.reference_offset = offset and options.reference_points
// = points, count for count; options.reference_offset and reference_points are not used. `x` must
// outlive the object. Refuses (InvalidInput) what correlation_sum refuses.
class CorrelationSumSubsets {
 public:
  CorrelationSumSubsets(std::span<const double> x, const CorrelationSumOptions& options);
  ~CorrelationSumSubsets();
  CorrelationSumSubsets(const CorrelationSumSubsets&) = delete;
  CorrelationSumSubsets& operator=(const CorrelationSumSubsets&) = delete;

  std::size_t points() const noexcept;  // P = N - (max-1) tau, the embedded points
  CorrelationSumResult count(std::size_t reference_offset, std::size_t reference_points) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace chaos
