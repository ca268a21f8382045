// The exact walk of the correlation sum: every unordered pair outside the Theiler window, once, by
// brute force, on the grid of rows or on the kd-tree, with m = 1 and (maximum norm) m = 2 counted
// by sweeps over sorted coordinates instead of pair by pair.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <type_traits>

#include <boost/sort/pdqsort/pdqsort.hpp>

#include "correlation_sum_layouts.hpp"
#include "correlation_sum_problem.hpp"
#include "correlation_sum_scan.hpp"
#include "chaos/detail/parallel.hpp"

namespace chaos::correlation_detail {

namespace {

template <class N>
Histogram brute_exact(const Problem& pb) {
  const std::size_t tasks = (pb.points + chunk_points - 1) / chunk_points;
  std::vector<Histogram> parts(detail::worker_count(pb.threads, tasks), Histogram(pb.nm * pb.nr, 0));
  detail::parallel_tasks(pb.threads, tasks, [&](std::size_t t, std::size_t worker) {
    Count* hist = parts[worker].data();
    const std::size_t end = std::min(pb.points, (t + 1) * chunk_points);
    for (std::size_t i = t * chunk_points; i < end; ++i)
      for (std::size_t j = i + pb.w + 1; j < pb.points; ++j) brute_pair<N>(pb, i, j, hist);
  }, pb.progress);
  return sum_histograms(parts);
}

// ---------------------------------------------------------------------------------------------
// Box-assisted, exact walk. All comparisons are on accumulators against thresholds.
//
// m = 1: the reference values sorted; for each radius a two-pointer sweep counts the pairs of
// positions p < q with acc(v[q] - v[p]) < t (monotone in p and q, so the sweep is exact), then the
// pairs inside the Theiler window, enumerated, are subtracted. O(P (nr + w) + P log P).
template <class N>
std::vector<Count> box_dimension_one(const Problem& pb) {
  std::vector<double> v(pb.y.begin(), pb.y.begin() + static_cast<std::ptrdiff_t>(pb.points));
  boost::sort::pdqsort(v.begin(), v.end());
  const auto acc = [](double a, double b) { return N::add(0.0, std::abs(a - b)); };
  std::vector<Count> pairs(pb.nr, 0);
  for (std::size_t k = 0; k < pb.nr; ++k) {
    const double t = pb.thresholds[k];
    std::size_t hi = 0;
    Count total = 0;
    for (std::size_t p = 0; p < v.size(); ++p) {
      hi = std::max(hi, p + 1);
      while (hi < v.size() && acc(v[hi], v[p]) < t) ++hi;
      total += hi - p - 1;
    }
    pairs[k] = total;
  }
  Histogram window(pb.nr + 1, 0);
  const AccBins::Lookup bins = pb.bins->lookup();
  for (std::size_t lag = 1; lag <= pb.w && lag < pb.points; ++lag)
    for (std::size_t i = 0; i + lag < pb.points; ++i) {
      const double a = acc(pb.y[i], pb.y[i + lag]);
      ++window[a < pb.t_max ? bins.inside(a) : pb.nr];  // the table serves accumulators below t_max
    }
  Count excluded = 0;
  for (std::size_t k = 0; k < pb.nr; ++k) pairs[k] -= excluded += window[k];
  return pairs;
}

// m = 2 with the maximum norm, without enumerating pairs. max(|a0 - b0|, |a1 - b1|) < t holds
// exactly when |a0 - b0| < t and |a1 - b1| < t, and for a fixed point the partners that pass one
// coordinate's test form a contiguous run of that coordinate's sorted order (the test is monotone,
// as in m = 1). So the partners of point i within t are the points whose position in the
// coordinate-0 order lies in i's run [lo0, hi0) and whose position in the coordinate-1 order lies
// in i's run [lo1, hi1): an orthogonal range count, done offline for all points by sweeping the
// coordinate-0 order once and keeping a Fenwick tree over coordinate-1 positions (point i's count
// is F(hi0) - F(lo0), F(k) counting the first k points of the sweep inside [lo1, hi1)).
// O(P log P) per radius instead of one histogram increment per close pair: the Henon target job
// has 8.5e8 pairs closer than r_max in m = 2. Every pair i != j is counted from both ends and each
// point finds itself, so the unordered pairs are (sum - P) / 2; pairs inside the Theiler window
// are included, as in the grid, and subtracted by window_pairs. Returns the pairs closer than each
// radius (cumulative), counted exactly as the accumulator test of the grid counts them. Reports
// progress (radii done) when given, i.e. when no grid scan follows.
std::vector<Count> plane_counts(const Problem& pb, const std::function<void(double)>* progress) {
  const std::size_t n = pb.points;
  std::vector<std::uint32_t> by0(n), by1(n);
  for (std::size_t i = 0; i < n; ++i) by0[i] = by1[i] = static_cast<std::uint32_t>(i);
  std::sort(by0.begin(), by0.end(), [&](std::uint32_t a, std::uint32_t b) { return pb.at(a, 0) < pb.at(b, 0); });
  std::sort(by1.begin(), by1.end(), [&](std::uint32_t a, std::uint32_t b) { return pb.at(a, 1) < pb.at(b, 1); });
  std::vector<double> v0(n), v1(n);
  std::vector<std::uint32_t> rank1(n), sweep1(n);  // position in the coordinate-1 order, by index and by sweep step
  for (std::size_t p = 0; p < n; ++p) {
    v0[p] = pb.at(by0[p], 0);
    v1[p] = pb.at(by1[p], 1);
    rank1[by1[p]] = static_cast<std::uint32_t>(p);
  }
  for (std::size_t p = 0; p < n; ++p) sweep1[p] = rank1[by0[p]];

  // The run of sorted values v within t of v[p], for every p: [lo[p], hi[p]), both nondecreasing in p.
  const auto runs = [n](const std::vector<double>& v, double t, std::vector<std::uint32_t>& lo,
                        std::vector<std::uint32_t>& hi) {
    std::size_t a = 0, b = 0;
    for (std::size_t p = 0; p < n; ++p) {
      while (!(std::abs(v[p] - v[a]) < t)) ++a;  // stops at a = p at the latest
      b = std::max(b, p + 1);
      while (b < n && std::abs(v[b] - v[p]) < t) ++b;
      lo[p] = static_cast<std::uint32_t>(a);
      hi[p] = static_cast<std::uint32_t>(b);
    }
  };
  struct Scratch {
    std::vector<std::uint32_t> lo0, hi0, lo1, hi1, tree;
  };
  const std::size_t workers = detail::worker_count(pb.threads, pb.nr);
  std::vector<Scratch> scratch(workers);
  std::vector<Count> pairs(pb.nr, 0);
  detail::parallel_tasks(pb.threads, pb.nr, [&](std::size_t k, std::size_t worker) {
    Scratch& sc = scratch[worker];
    for (auto* v : {&sc.lo0, &sc.hi0, &sc.lo1, &sc.hi1}) v->resize(n);
    sc.tree.assign(n + 1, 0);
    const double t = pb.thresholds[k];
    runs(v0, t, sc.lo0, sc.hi0);
    runs(v1, t, sc.lo1, sc.hi1);
    std::uint32_t* tree = sc.tree.data();
    const auto prefix = [tree](std::size_t r) {  // points inserted so far at coordinate-1 positions < r
      std::uint64_t c = 0;
      for (; r > 0; r &= r - 1) c += tree[r];
      return c;
    };
    // F(step) for the run [lo1, hi1) of the point at sweep position p.
    const auto inside = [&](std::size_t p) {
      const std::uint32_t r = sweep1[p];
      return prefix(sc.hi1[r]) - prefix(sc.lo1[r]);
    };
    std::uint64_t added = 0, removed = 0;  // both sides as unsigned sums: added >= removed
    std::size_t q_lo = 0, q_hi = 0;
    for (std::size_t step = 0; step <= n; ++step) {
      while (q_lo < n && sc.lo0[q_lo] == step) removed += inside(q_lo++);
      while (q_hi < n && sc.hi0[q_hi] == step) added += inside(q_hi++);
      if (step < n)
        for (std::size_t r = sweep1[step] + 1; r <= n; r += r & (~r + 1)) ++tree[r];
    }
    pairs[k] = (added - removed - n) / 2;
  }, progress);
  return pairs;
}

// CHAOS_NO_PLANE=1 makes the grid bin m = 2 itself, so the tests check both ways against brute force.
bool plane_disabled() { return env_flag("CHAOS_NO_PLANE"); }

// The pairs 1 <= j - i <= w that the grid counted when it leaves the Theiler window to a
// subtraction: the same accumulators in the same order, so exactly the same bins.
template <class N>
void window_pairs(const Problem& pb, Count* hist) {
  const std::size_t tasks = (pb.points + chunk_points - 1) / chunk_points;
  const AccBins::Lookup bins = pb.bins->lookup();
  std::vector<Histogram> parts(detail::worker_count(pb.threads, tasks), Histogram(pb.nm * pb.nr, 0));
  detail::parallel_tasks(pb.threads, tasks, [&](std::size_t t, std::size_t worker) {
    Count* h = parts[worker].data();
    const std::size_t end = std::min(pb.points, (t + 1) * chunk_points);
    for (std::size_t i = t * chunk_points; i < end; ++i)
      for (std::size_t j = i + 1; j <= i + pb.w && j < pb.points; ++j) {
        double acc = N::add(N::add(0.0, std::abs(pb.at(i, 0) - pb.at(j, 0))), std::abs(pb.at(i, 1) - pb.at(j, 1)));
        for (std::size_t m = 2; m <= pb.max_m; ++m) {
          if (m > 2) acc = N::add(acc, std::abs(pb.at(i, m - 1) - pb.at(j, m - 1)));
          if (!(acc < pb.t_max)) break;
          if (m >= pb.min_m) ++h[(m - pb.min_m) * pb.nr + bins.inside(acc)];
        }
      }
  });
  const Histogram total = sum_histograms(parts);
  for (std::size_t k = 0; k < total.size(); ++k) hist[k] -= total[k];
}

template <class N, bool check_window>
Histogram box_grid(const Problem& pb, const Grid& g, std::size_t first) {
  const double t = pb.t_max;
  const Simd simd = simd_level();
  std::vector<Histogram> parts(detail::worker_count(pb.threads, g.chunks.size()), Histogram(pb.nm * pb.nr, 0));
  detail::parallel_tasks(pb.threads, g.chunks.size(), [&](std::size_t c, std::size_t worker) {
    Survivors survivors(pb, parts[worker].data(), first, simd);
    const Grid::Chunk& chunk = g.chunks[c];
    const Grid::Row& row = g.rows[chunk.row];
    const bool has_next = chunk.row + 1 < g.rows.size() && g.rows[chunk.row + 1].id == row.id + 1;
    const Grid::Row next = has_next ? g.rows[chunk.row + 1] : Grid::Row{0, 0, 0};
    const double* c0 = g.coordinate(0);
    // The coordinate-0 window: positions q with acc(c0[q] - c0[p]) < t_max on either side. The
    // tests are monotone in p and q (rounding is monotone), so the pointers only move forward.
    const auto left_of = [&](std::size_t p, std::size_t q) {
      return c0[q] <= c0[p] && !(N::add(0.0, c0[p] - c0[q]) < t);
    };
    const auto not_right_of = [&](std::size_t p, std::size_t q) {
      return c0[q] <= c0[p] || N::add(0.0, c0[q] - c0[p]) < t;
    };
    std::size_t same = chunk.begin + 1;
    std::size_t lo = first_failing(next.begin, next.end, [&](std::size_t q) { return left_of(chunk.begin, q); });
    std::size_t hi = lo;
    for (std::size_t p = chunk.begin; p < chunk.end; ++p) {
      same = std::max(same, p + 1);
      while (same < row.end && not_right_of(p, same)) ++same;
      scan_candidates<N, check_window>(pb, g, p, p + 1, same, survivors, simd, t);
      if (!has_next) continue;
      while (lo < next.end && left_of(p, lo)) ++lo;
      hi = std::max(hi, lo);
      while (hi < next.end && not_right_of(p, hi)) ++hi;
      scan_candidates<N, check_window>(pb, g, p, lo, hi, survivors, simd, t);
    }
  }, pb.progress);
  return sum_histograms(parts);
}

// With a small window (w <= P/8, so at most P^2/8 window pairs) the grid counts every pair and
// the window pairs are subtracted afterwards, which keeps the index test out of the inner loop.
// With the maximum norm and that path, m = 2 is counted by plane_counts and the grid bins only
// m >= 3 (it still filters m = 2, whose survivors carry on to m = 3).
template <class N>
Histogram box_grid(const Problem& pb) {
  const std::size_t first = pb.min_m > 2 ? pb.min_m - 2 : 0;
  if (pb.w > pb.points / 8) return box_grid<N, true>(pb, build_grid(pb), first);
  const bool plane = std::is_same_v<N, MaxNorm> && first == 0 && pb.points < std::numeric_limits<std::uint32_t>::max() &&
                     !plane_disabled();
  // m = 2 alone under the plane count: nothing left for the grid to bin.
  Histogram h = plane && pb.max_m == 2 ? Histogram(pb.nm * pb.nr, 0)
                                       : box_grid<N, false>(pb, build_grid(pb), plane ? 1 : first);
  if (plane) {
    const std::vector<Count> cum = plane_counts(pb, pb.max_m == 2 ? pb.progress : nullptr);  // else the grid reports
    Count* h2 = h.data() + (2 - pb.min_m) * pb.nr;
    for (std::size_t k = 0; k < pb.nr; ++k) h2[k] = cum[k] - (k > 0 ? cum[k - 1] : 0);
  }
  window_pairs<N>(pb, h.data());
  return h;
}

template <class N>
std::vector<std::vector<Count>> box_exact(const Problem& pb) {
  std::vector<std::vector<Count>> pairs(pb.nm);
  if (pb.max_m >= 2) pairs = cumulate(box_grid<N>(pb), pb.nm, pb.nr);
  if (pb.min_m == 1) pairs[0] = box_dimension_one<N>(pb);
  return pairs;
}

template <class N, bool check_window>
Histogram kd_counts(const Problem& pb, const KdLayout& t, std::size_t first) {
  const Simd simd = simd_level();
  const std::size_t tasks = (pb.points + chunk_points - 1) / chunk_points;
  std::vector<Histogram> parts(detail::worker_count(pb.threads, tasks), Histogram(pb.nm * pb.nr, 0));
  detail::parallel_tasks(pb.threads, tasks, [&](std::size_t task, std::size_t worker) {
    Survivors survivors(pb, parts[worker].data(), first, simd);
    std::vector<std::size_t> stack;
    const std::size_t end = std::min(pb.points, (task + 1) * chunk_points);
    for (std::size_t p = task * chunk_points; p < end; ++p)
      kd_partners<N, check_window>(pb, t, p, p + 1, survivors, simd, pb.t_max, stack);
  }, pb.progress);
  return sum_histograms(parts);
}

template <class N>
std::vector<std::vector<Count>> kd_exact(const Problem& pb) {
  std::vector<std::vector<Count>> pairs(pb.nm);
  if (pb.max_m >= 2) {
    const KdLayout t = build_kd(pb);
    const std::size_t first = pb.min_m > 2 ? pb.min_m - 2 : 0;
    Histogram h;
    if (pb.w > pb.points / 8) {  // as box_grid: a wide window is tested in the scan
      h = kd_counts<N, true>(pb, t, first);
    } else {
      h = kd_counts<N, false>(pb, t, first);
      window_pairs<N>(pb, h.data());
    }
    pairs = cumulate(h, pb.nm, pb.nr);
  }
  if (pb.min_m == 1) pairs[0] = box_dimension_one<N>(pb);
  return pairs;
}

template <class N>
Totals exact_totals(const Problem& pb, CorrelationSearch search) {
  std::vector<std::vector<Count>> pairs;
  switch (search) {
    case CorrelationSearch::brute_force: pairs = cumulate(brute_exact<N>(pb), pb.nm, pb.nr); break;
    case CorrelationSearch::kd_tree: pairs = kd_exact<N>(pb); break;
    case CorrelationSearch::box_assisted: pairs = box_exact<N>(pb); break;
  }
  const std::size_t span = pb.points - pb.w - 1;  // validated: P >= w + 2
  const Count all = static_cast<Count>(span) * static_cast<Count>(span + 1) / 2;
  Totals totals;
  totals.pairs = std::move(pairs);
  totals.examined.assign(pb.nm, std::vector<Count>(pb.nr, all));
  return totals;
}

}  // namespace

Totals exact_totals(const Problem& pb, CorrelationSearch search) {
  return pb.norm == Norm::max ? exact_totals<MaxNorm>(pb, search) : exact_totals<EuclideanNorm>(pb, search);
}

}  // namespace chaos::correlation_detail
