#pragma once
// The exact correlation-sum counting problem shared by its walks: the norms as policies, the radii
// as accumulator thresholds and their O(1) binning, the problem in the units the loops compute in,
// the histograms the workers fill, and the entry points of the exact and the reference walks.
// docs/reference/correlation_sum.md has the conventions and the proofs of exactness.
//
// Every pair distance is accumulated coordinate by coordinate exactly as DelayEmbedding::distance
// does it (max(acc, |a - b|), or acc + d*d then sqrt), so every mode sees the same doubles and the
// strict comparison d < r gives the same integer counts. A pair is put into a histogram over the
// radius grid (bin g = number of radii <= d); the count for radius k is the sum of bins 0..k.
//
// Two ways of walking the pairs:
//   exact     no cap and no reference subset: every unordered pair i < j, j - i > w, once;
//   reference a cap or a subset: each reference point i with all partners j, |i - j| > w, on both
//             sides (ordered pairs, so a point's count does not depend on which others are
//             reference points), in a seeded random order.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "chaos/correlation_sum.hpp"
#include "chaos/norm.hpp"

namespace chaos::correlation_detail {

using Count = std::uint64_t;

inline constexpr double infinity = std::numeric_limits<double>::infinity();

inline bool in_window(std::size_t i, std::size_t j, std::size_t w) noexcept { return (i > j ? i - j : j - i) <= w; }

// A switch set in the environment (not empty and not "0"): the tests use these to reach every path.
inline bool env_flag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' && *v != '0';
}

// The two norms as compile-time policies; `add` is the step DelayEmbedding::distance takes per
// coordinate and `finish` turns the accumulator into the distance.
struct MaxNorm {
  static double add(double acc, double d) noexcept { return std::max(acc, d); }
  static double finish(double acc) noexcept { return acc; }
};
struct EuclideanNorm {
  static double add(double acc, double d) noexcept { return acc + d * d; }
  static double finish(double acc) noexcept { return std::sqrt(acc); }
};

// Every mode compares the accumulator with a threshold instead of the distance with a radius:
// acc < t(r) exactly when finish(acc) < r. For the maximum norm t(r) = r; for the Euclidean norm
// t(r) is the smallest double a with sqrt(a) >= r (found by bisection over the bit patterns, on
// which sqrt is monotone), so the box-assisted loops need no square root and still agree with
// brute force, which takes the square root and compares with r.
double threshold(Norm norm, double r);

// Bin of an accumulator value in the threshold grid in O(1): non-negative doubles are ordered like
// their bit patterns, so the exponent and the top `bits` mantissa bits index cells no wider than a
// factor 1 + 2^-bits (a cheap, monotone stand-in for the logarithm; up to 1024 cells per octave
// and 4096 in all). A cell that holds no threshold has one bin for all its values, read from the
// table; a cell that holds one is marked, and the bin is fixed up there by comparing with the
// thresholds themselves (with 40 radii over 6 octaves, about 1 cell in 80). The bin is exact in
// both cases.
class AccBins {
 public:
  // The lookup itself, small enough to copy into a loop's locals: held in registers, its fields
  // need not be reloaded after every histogram store (a store through Count* may alias them).
  struct Lookup {
    const std::int32_t* cell;  // g >= 0: the bin of every value in the cell; -1 - g: fix up from g
    const double* t;
    std::uint64_t base;
    int shift;
    double floor;  // lower edge of cell 0, which lies below the first threshold

    std::uint64_t cell_of(double acc) const noexcept {
      return (std::bit_cast<std::uint64_t>(std::max(acc, floor)) >> shift) - base;
    }
    // The exact bin from a marked cell's entry.
    std::size_t fix(std::int32_t entry, double acc) const noexcept {
      auto g = static_cast<std::size_t>(-1 - entry);
      while (t[g] <= acc) ++g;  // stops at t_max > acc at the latest
      return g;
    }
    // Number of thresholds t <= acc, for 0 <= acc < t_max (the survivors of a filter).
    std::size_t inside(double acc) const noexcept {
      const std::int32_t e = cell[cell_of(acc)];
      return e >= 0 ? static_cast<std::size_t>(e) : fix(e, acc);
    }
  };

  explicit AccBins(std::vector<double> t) : t_(std::move(t)) {
    const double lo = t_.front(), hi = t_.back();
    constexpr std::uint64_t max_cells = 4096;
    int shift = 52;
    for (int bits = 10; bits > 0; --bits) {  // as fine as a table of max_cells allows
      shift = 52 - bits;
      if (key(hi, shift) - key(lo, shift) + 2 <= max_cells) break;
    }
    const std::uint64_t base = key(lo, shift) - (key(lo, shift) > 0 ? 1 : 0);
    const std::uint64_t count = key(hi, shift) - base + 1;
    cell_.resize(static_cast<std::size_t>(count));
    for (std::size_t c = 0; c < cell_.size(); ++c) {
      const double edge = std::bit_cast<double>((base + c) << shift);
      const double next_edge = std::bit_cast<double>((base + c + 1) << shift);
      const auto g = std::lower_bound(t_.begin(), t_.end(), edge) - t_.begin();
      const bool marked = g < static_cast<std::ptrdiff_t>(t_.size()) && t_[static_cast<std::size_t>(g)] < next_edge;
      cell_[c] = marked ? static_cast<std::int32_t>(-1 - g) : static_cast<std::int32_t>(g);
    }
    lookup_ = {cell_.data(), t_.data(), base, shift, std::bit_cast<double>(base << shift)};
  }

  const Lookup& lookup() const noexcept { return lookup_; }
  // Number of thresholds t <= acc, for any acc (the slow general form).
  std::size_t operator()(double acc) const noexcept {
    return static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), acc) - t_.begin());
  }

 private:
  static std::uint64_t key(double v, int shift) noexcept { return std::bit_cast<std::uint64_t>(v) >> shift; }

  std::vector<double> t_;
  std::vector<std::int32_t> cell_;
  Lookup lookup_{};
};

// Everything the counting loops need, in the units they compute in.
struct Problem {
  std::span<const double> y;       // the series (times a power of two for the Euclidean norm)
  std::vector<double> radii;       // likewise scaled; brute force compares distances with these
  std::vector<double> thresholds;  // the same radii as accumulator thresholds
  double r_max = 0.0, t_max = 0.0;
  std::size_t tau = 1, w = 0;
  std::size_t points = 0;            // P: the reference set is i < P = N - (max-1) tau
  std::size_t min_m = 1, max_m = 1;  // dimensions counted
  std::size_t nm = 1, nr = 1;        // number of dimensions and of radii
  Norm norm = Norm::max;
  std::size_t threads = 1;
  const AccBins* bins = nullptr;
  const std::function<void(double)>* progress = nullptr;  // CorrelationSumOptions::progress, when set

  double at(std::size_t i, std::size_t k) const noexcept { return y[i + k * tau]; }
};

// Histograms [dimension index][bin], one per worker, summed at the end (integer sums: any split
// and any order give the same totals).
using Histogram = std::vector<Count>;

inline Histogram sum_histograms(const std::vector<Histogram>& parts) {
  Histogram total(parts.front().size(), 0);
  for (const auto& h : parts)
    for (std::size_t k = 0; k < h.size(); ++k) total[k] += h[k];
  return total;
}

// Cumulative counts [mi][k] = pairs closer than radius k, from a histogram over bins.
inline std::vector<std::vector<Count>> cumulate(const Histogram& h, std::size_t nm, std::size_t nr) {
  std::vector<std::vector<Count>> out(nm, std::vector<Count>(nr));
  for (std::size_t mi = 0; mi < nm; ++mi) {
    Count acc = 0;
    for (std::size_t k = 0; k < nr; ++k) out[mi][k] = acc += h[mi * nr + k];
  }
  return out;
}

// The first position in [begin, end) where pred fails, for a pred that holds on a prefix.
template <class Pred>
std::size_t first_failing(std::size_t begin, std::size_t end, Pred pred) {
  std::size_t count = end - begin;
  while (count > 0) {
    const std::size_t half = count / 2;
    if (pred(begin + half)) {
      begin += half + 1;
      count -= half + 1;
    } else {
      count = half;
    }
  }
  return begin;
}

// Chunks of consecutive reference points for the exact walks.
constexpr std::size_t chunk_points = 256;

// The definition, every coordinate of one pair; the bin by binary search.
template <class N>
void brute_pair(const Problem& pb, std::size_t i, std::size_t j, Count* hist) {
  double acc = 0.0;
  for (std::size_t k = 0; k < pb.max_m; ++k) {
    acc = N::add(acc, std::abs(pb.at(i, k) - pb.at(j, k)));
    const double d = N::finish(acc);
    if (!(d < pb.r_max)) return;  // the distance never decreases with m: nothing more to count
    if (k + 1 >= pb.min_m) {
      const auto g = std::upper_bound(pb.radii.begin(), pb.radii.end(), d) - pb.radii.begin();
      ++hist[(k + 1 - pb.min_m) * pb.nr + static_cast<std::size_t>(g)];
    }
  }
}

struct Totals {
  std::vector<std::vector<Count>> pairs, examined;
  std::vector<std::vector<std::vector<Count>>> group_pairs, group_examined;  // reference walks only
};

// ---------------------------------------------------------------------------------------------
// Reference walk: per-point counts, cumulative over radii, for a cap or a subset.
//
// A counter fills cum[mi * nr + k] with the number of partners j of point i (|i - j| > w, either
// side) closer than radius k, for every k < need[mi]; entries from need[mi] on are not used.

class ReferenceCounter {
 public:
  virtual ~ReferenceCounter() = default;
  virtual void count(std::size_t i, const std::vector<std::size_t>& need, Count* cum, Histogram& scratch) const = 0;
};

// The counting problem: the series checked, scaled for the Euclidean norm, the radii as
// accumulator thresholds. Built in place and never copied, as pb points into the other members.
struct Prepared {
  Prepared() = default;
  Prepared(const Prepared&) = delete;
  Prepared& operator=(const Prepared&) = delete;
  CorrelationSumOptions options;
  std::vector<double> scaled;
  std::optional<AccBins> bins;
  Problem pb;
  double range = 0.0;
  ValueTies ties;
};

// Checks the options and the series and builds the problem in `p`.
void prepare(Prepared& p, std::span<const double> x, const CorrelationSumOptions& options);
// Refuses a reference subset [offset, offset + count) that does not fit in `points`.
void require_subset(std::size_t points, std::size_t offset, std::size_t count);
// The result from the counts: sums, pairs and examined pairs per dimension and radius.
CorrelationSumResult assemble(const Prepared& p, Totals totals, std::size_t reference_points);

// Every unordered pair outside the Theiler window, once, by the given search (exact walk).
Totals exact_totals(const Problem& pb, CorrelationSearch search);

// The per-reference-point counter of the options' search mode (its structure is built here, once).
std::unique_ptr<ReferenceCounter> make_counter(const Problem& pb, const CorrelationSumOptions& options);
// Reference points offset .. offset + count - 1 of the seeded order, under the options' cap.
Totals subset_totals(const Problem& pb, const ReferenceCounter& counter, const CorrelationSumOptions& options,
                     std::size_t offset, std::size_t count);

}  // namespace chaos::correlation_detail
