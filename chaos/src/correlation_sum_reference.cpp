// The reference-point walk of the correlation sum, for a cap on the pairs per radius or a subset
// of reference points: per-point counts on both sides of each reference point, cumulative over the
// radii, taken in a seeded random order and merged in that order.

#include <algorithm>
#include <cmath>
#include <optional>

#include <boost/sort/pdqsort/pdqsort.hpp>

#include "chaos/random.hpp"
#include "correlation_sum_layouts.hpp"
#include "correlation_sum_problem.hpp"
#include "correlation_sum_scan.hpp"
#include "chaos/detail/parallel.hpp"
#include "numeric.hpp"

namespace chaos::correlation_detail {

namespace {

using detail::add_sat;

// Turns a per-point histogram into cumulative counts.
void histogram_to_cumulative(const Histogram& h, std::size_t nm, std::size_t nr, Count* cum) {
  for (std::size_t mi = 0; mi < nm; ++mi) {
    Count acc = 0;
    for (std::size_t k = 0; k < nr; ++k) cum[mi * nr + k] = acc += h[mi * nr + k];
  }
}

template <class N>
class BruteCounter final : public ReferenceCounter {
 public:
  explicit BruteCounter(const Problem& pb) : pb_(pb) {}
  void count(std::size_t i, const std::vector<std::size_t>&, Count* cum, Histogram& h) const override {
    std::fill(h.begin(), h.end(), 0);
    for (std::size_t j = 0; j < pb_.points; ++j)
      if (!in_window(i, j, pb_.w)) brute_pair<N>(pb_, i, j, h.data());
    histogram_to_cumulative(h, pb_.nm, pb_.nr, cum);
  }

 private:
  const Problem& pb_;
};

// The partners of reference point i that can be closer than t in m >= 2, on the grid: they lie
// in i's row or the adjacent ones, inside i's coordinate-0 window (the argument of box_grid), so
// the work per reference point is the exact walk's work per point.
template <class N>
class GridWalk {
 public:
  explicit GridWalk(const Problem& pb) : grid_(build_grid(pb)), position_(pb.points), row_of_(pb.points) {
    for (std::size_t r = 0; r < grid_.rows.size(); ++r)
      for (std::size_t p = grid_.rows[r].begin; p < grid_.rows[r].end; ++p) {
        position_[grid_.index[p]] = p;
        row_of_[p] = r;
      }
  }
  void partners(const Problem& pb, std::size_t i, double t, Survivors& survivors, Simd simd) const {
    const Grid& g = grid_;
    const std::size_t p = position_[i], r = row_of_[p];
    const double* c0 = g.coordinate(0);
    for (std::size_t s = r > 0 ? r - 1 : 0; s <= r + 1 && s < g.rows.size(); ++s) {
      const Grid::Row& row = g.rows[s];
      if (row.id < g.rows[r].id - 1 || row.id > g.rows[r].id + 1) continue;
      const std::size_t lo = first_failing(row.begin, row.end, [&](std::size_t q) {
        return c0[q] <= c0[p] && !(N::add(0.0, c0[p] - c0[q]) < t);
      });
      const std::size_t hi = first_failing(lo, row.end, [&](std::size_t q) {
        return c0[q] <= c0[p] || N::add(0.0, c0[q] - c0[p]) < t;
      });
      scan_candidates<N, false>(pb, g, p, lo, hi, survivors, simd, t);
    }
  }

 private:
  Grid grid_;
  std::vector<std::size_t> position_, row_of_;  // grid position of each point, row of each position
};

// The same on the kd-tree: every leaf within t of i, on both sides.
template <class N>
class KdWalk {
 public:
  explicit KdWalk(const Problem& pb) : tree_(build_kd(pb)) {}
  void partners(const Problem& pb, std::size_t i, double t, Survivors& survivors, Simd simd) const {
    thread_local std::vector<std::size_t> stack;
    kd_partners<N, false>(pb, tree_, tree_.position[i], 0, survivors, simd, t, stack);
  }

 private:
  KdLayout tree_;
};

// Per reference point on a spatial structure (GridWalk or KdWalk): a subset of R points costs
// about R/P of the exact job (twice that, as each point counts its partners on both sides). The
// candidates are scanned without the index test, as in the exact walk; i itself and its partners
// inside the Theiler window are then enumerated and taken out again with the same accumulators,
// so exactly the same bins. m = 1 is counted on the sorted values: the partners within t of a
// value form a run found by two binary searches.
template <class N, class Walk>
class SpatialCounter final : public ReferenceCounter {
 public:
  explicit SpatialCounter(const Problem& pb) : pb_(pb), simd_(simd_level()) {
    if (pb.max_m >= 2) walk_.emplace(pb);
    if (pb.min_m == 1) {
      sorted_.assign(pb.y.begin(), pb.y.begin() + static_cast<std::ptrdiff_t>(pb.points));
      boost::sort::pdqsort(sorted_.begin(), sorted_.end());  // branchless for doubles: half std::sort's time
    }
  }

  void count(std::size_t i, const std::vector<std::size_t>& need, Count* cum, Histogram& h) const override {
    std::fill(h.begin(), h.end(), 0);
    const std::size_t nr = pb_.nr;
    // Search only as far as the largest radius still open in a dimension m >= 2 (under a cap the
    // largest radii close first, and with them most of the candidates).
    std::size_t top = 0;
    for (std::size_t mi = pb_.min_m == 1 ? 1 : 0; mi < pb_.nm; ++mi) top = std::max(top, need[mi]);
    if (top > 0) {
      const double t = pb_.thresholds[top - 1];
      {
        Survivors survivors(pb_, h.data(), pb_.min_m > 2 ? pb_.min_m - 2 : 0, simd_);
        walk_->partners(pb_, i, t, survivors, simd_);
      }
      // i itself and the window partners, as the scan saw them (acc < t in the first two
      // coordinates, and in the first min_m before anything is binned).
      const AccBins::Lookup bins = pb_.bins->lookup();
      const std::size_t first = i > pb_.w ? i - pb_.w : 0, last = std::min(pb_.points - 1, add_sat(i, pb_.w));
      for (std::size_t j = first; j <= last; ++j) {
        double acc = N::add(N::add(0.0, std::abs(pb_.at(i, 0) - pb_.at(j, 0))), std::abs(pb_.at(i, 1) - pb_.at(j, 1)));
        for (std::size_t m = 2; m <= pb_.max_m; ++m) {
          if (m > 2) acc = N::add(acc, std::abs(pb_.at(i, m - 1) - pb_.at(j, m - 1)));
          if (!(acc < t)) break;
          if (m >= pb_.min_m) --h[(m - pb_.min_m) * nr + bins.inside(acc)];
        }
      }
    }
    histogram_to_cumulative(h, pb_.nm, nr, cum);
    if (pb_.min_m == 1) {
      // Partners within t_k in coordinate 0: the run of sorted values around a0, less i itself and
      // the window partners that pass the same test. Those are binned once (acc < t_k exactly
      // when the bin, the number of thresholds <= acc, is at most k) rather than tested per radius.
      const double a0 = pb_.at(i, 0);
      const std::size_t first = i > pb_.w ? i - pb_.w : 0, last = std::min(pb_.points - 1, add_sat(i, pb_.w));
      Count* window = h.data();  // the m >= 2 histogram is spent: reuse its first nr entries
      std::fill(window, window + nr, 0);
      const AccBins::Lookup bins = pb_.bins->lookup();
      for (std::size_t j = first; j <= last; ++j) {
        const double acc = N::add(0.0, std::abs(a0 - pb_.at(j, 0)));
        if (acc < pb_.t_max) ++window[bins.inside(acc)];
      }
      // The runs are nested (a smaller radius's run lies inside a larger one's), so the searches go
      // from the largest radius down, each inside the previous run: they stay near a0 in memory.
      auto lo = sorted_.begin(), hi = sorted_.end();
      for (std::size_t k = need[0]; k-- > 0;) {
        const double t = pb_.thresholds[k];
        lo = std::partition_point(lo, hi, [&](double v) { return v <= a0 && !(N::add(0.0, a0 - v) < t); });
        hi = std::partition_point(lo, hi, [&](double v) { return v <= a0 || N::add(0.0, v - a0) < t; });
        cum[k] = static_cast<Count>(hi - lo);
      }
      Count taken_out = 0;
      for (std::size_t k = 0; k < need[0]; ++k) cum[k] -= taken_out += window[k];
    }
  }

 private:
  const Problem& pb_;
  Simd simd_;
  std::optional<Walk> walk_;   // m >= 2 only
  std::vector<double> sorted_;  // coordinate 0 of every point, sorted (m = 1)
};

// Partners of point i on both sides outside the Theiler window.
Count admissible_partners(std::size_t i, std::size_t points, std::size_t w) {
  const std::size_t first = i > w ? i - w : 0;
  const std::size_t last = std::min(points - 1, add_sat(i, w));
  return points - (last - first + 1);
}

// The jackknife group of position u of `size` reference points in the seeded order: `groups`
// consecutive stretches of (nearly) equal length.
std::size_t group_of(std::size_t u, std::size_t size, std::size_t groups) noexcept {
  return u * groups / size;  // groups <= 1024 (validated) and u < size < 2^40: no overflow
}

// Reference points in `order`. Without a cap, all of them are counted, split over the workers.
// With a cap the points are taken in waves, the per-point counts merged in `order`: after each
// point, a radius whose count reached the cap is closed for that dimension (its `examined` stops
// there). Counts grow with the radius, so the closed radii of a dimension are always the largest
// ones and need[mi] (the number still open) describes them. The merge is sequential and per
// point, so the outcome does not depend on the wave size or the number of threads.
Totals reference_walk(const Problem& pb, const ReferenceCounter& counter, const std::vector<std::size_t>& order,
                      std::uint64_t cap, std::size_t groups) {
  const std::size_t nm = pb.nm, nr = pb.nr, stride = nm * nr;
  const auto table = [&] { return std::vector<std::vector<Count>>(nm, std::vector<Count>(nr, 0)); };
  Totals out;
  out.pairs = table();
  out.examined = table();
  groups = order.size() >= 2 ? std::min(groups, order.size()) : 0;  // one group has nothing to leave out
  for (std::size_t b = 0; b < groups; ++b) {
    out.group_pairs.push_back(table());
    out.group_examined.push_back(table());
  }
  std::vector<std::size_t> need(nm, nr);
  if (cap == 0) {
    // Integer sums per worker and group: the same totals for any number of threads.
    const std::size_t tasks = (order.size() + chunk_points - 1) / chunk_points;
    const std::size_t workers = detail::worker_count(pb.threads, tasks);
    const std::size_t slots = std::max<std::size_t>(groups, 1);
    std::vector<Histogram> sums(workers, Histogram(slots * stride, 0));
    std::vector<Histogram> scratch(workers, Histogram(stride, 0));
    std::vector<std::vector<Count>> cum(workers, std::vector<Count>(stride, 0));
    detail::parallel_tasks(pb.threads, tasks, [&](std::size_t t, std::size_t worker) {
      const std::size_t end = std::min(order.size(), (t + 1) * chunk_points);
      for (std::size_t u = t * chunk_points; u < end; ++u) {
        counter.count(order[u], need, cum[worker].data(), scratch[worker]);
        Count* sum = sums[worker].data() + (groups > 0 ? group_of(u, order.size(), groups) : 0) * stride;
        for (std::size_t k = 0; k < stride; ++k) sum[k] += cum[worker][k];
      }
    }, pb.progress);
    const Histogram total = sum_histograms(sums);
    std::vector<Count> examined(slots, 0);
    for (std::size_t u = 0; u < order.size(); ++u)
      examined[groups > 0 ? group_of(u, order.size(), groups) : 0] += admissible_partners(order[u], pb.points, pb.w);
    for (std::size_t b = 0; b < slots; ++b)
      for (std::size_t mi = 0; mi < nm; ++mi)
        for (std::size_t k = 0; k < nr; ++k) {
          const Count pairs = total[b * stride + mi * nr + k];
          out.pairs[mi][k] += pairs;
          out.examined[mi][k] += examined[b];
          if (groups > 0) {
            out.group_pairs[b][mi][k] = pairs;
            out.group_examined[b][mi][k] = examined[b];
          }
        }
    return out;
  }

  const std::size_t per_worker = 64;
  const std::size_t wave_size = per_worker * std::max<std::size_t>(1, pb.threads);
  std::vector<Count> cum(std::min(wave_size, order.size()) * stride, 0);
  std::vector<Histogram> scratch(detail::worker_count(pb.threads, wave_size), Histogram(stride, 0));
  for (std::size_t start = 0; start < order.size();) {
    if (std::all_of(need.begin(), need.end(), [](std::size_t n) { return n == 0; })) break;
    const std::size_t wave = std::min(wave_size, order.size() - start);
    detail::parallel_tasks(pb.threads, (wave + per_worker - 1) / per_worker, [&](std::size_t t, std::size_t worker) {
      const std::size_t end = std::min(wave, (t + 1) * per_worker);
      for (std::size_t u = t * per_worker; u < end; ++u)
        counter.count(order[start + u], need, &cum[u * stride], scratch[worker]);
    });
    for (std::size_t u = 0; u < wave; ++u) {
      const Count partners = admissible_partners(order[start + u], pb.points, pb.w);
      const std::size_t b = groups > 0 ? group_of(start + u, order.size(), groups) : 0;
      for (std::size_t mi = 0; mi < nm; ++mi) {
        for (std::size_t k = 0; k < need[mi]; ++k) {
          out.pairs[mi][k] += cum[u * stride + mi * nr + k];
          out.examined[mi][k] += partners;
          if (groups > 0) {
            out.group_pairs[b][mi][k] += cum[u * stride + mi * nr + k];
            out.group_examined[b][mi][k] += partners;
          }
        }
        while (need[mi] > 0 && out.pairs[mi][need[mi] - 1] >= cap) --need[mi];
      }
    }
    start += wave;
  }
  return out;
}

// The reference points: a seeded partial Fisher-Yates shuffle of 0 .. P-1, `count` of them.
std::vector<std::size_t> reference_order(std::size_t points, std::size_t count, std::uint64_t seed) {
  std::vector<std::size_t> order(points);
  for (std::size_t i = 0; i < points; ++i) order[i] = i;
  Random rng(seed);
  for (std::size_t t = 0; t < count; ++t)
    std::swap(order[t], order[t + static_cast<std::size_t>(rng.below(points - t))]);
  order.resize(count);
  return order;
}

template <class N>
std::unique_ptr<ReferenceCounter> make_counter(const Problem& pb, CorrelationSearch search) {
  switch (search) {
    case CorrelationSearch::brute_force: return std::make_unique<BruteCounter<N>>(pb);
    case CorrelationSearch::kd_tree: return std::make_unique<SpatialCounter<N, KdWalk<N>>>(pb);
    case CorrelationSearch::box_assisted: break;
  }
  return std::make_unique<SpatialCounter<N, GridWalk<N>>>(pb);
}


}  // namespace

std::unique_ptr<ReferenceCounter> make_counter(const Problem& pb, const CorrelationSumOptions& options) {
  return options.norm == Norm::max ? make_counter<MaxNorm>(pb, options.search)
                                   : make_counter<EuclideanNorm>(pb, options.search);
}

// Reference points offset .. offset + count - 1 of the seeded order, under the options' cap.
Totals subset_totals(const Problem& pb, const ReferenceCounter& counter, const CorrelationSumOptions& options,
                     std::size_t offset, std::size_t count) {
  std::vector<std::size_t> order = reference_order(pb.points, offset + count, options.seed);
  order.erase(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(offset));
  return reference_walk(pb, counter, order, options.pairs_per_radius, options.jackknife_groups);
}

}  // namespace chaos::correlation_detail
