#include "chaos/correlation_sum.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>

#include <boost/sort/pdqsort/pdqsort.hpp>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/random.hpp"
#include "chaos/series.hpp"
#include "numeric.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

// Layout of the computation (docs/correlation_sum.md has the conventions and the proofs of exactness).
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

namespace chaos {

namespace {

using detail::add_sat;
using detail::mul_sat;
const auto& number = detail::format_number;

using Count = std::uint64_t;

constexpr double infinity = std::numeric_limits<double>::infinity();


bool in_window(std::size_t i, std::size_t j, std::size_t w) noexcept { return (i > j ? i - j : j - i) <= w; }

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
double threshold(Norm norm, double r) {
  if (norm == Norm::max) return r;
  std::uint64_t lo = 0, hi = std::bit_cast<std::uint64_t>(infinity);  // sqrt(inf) >= r always
  while (lo < hi) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (std::sqrt(std::bit_cast<double>(mid)) >= r)
      hi = mid;
    else
      lo = mid + 1;
  }
  return std::bit_cast<double>(lo);
}

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

// Runs f(task, worker) for every task on min(threads, tasks) workers that take tasks from a shared
// counter. Which worker runs a task varies; the callers only add integers per worker, so the sums
// do not depend on it.
// With `progress` and more than one worker, the calling thread does not compute: it reports the
// fraction of tasks done as tasks end and at least every 10 ms while the workers run. The progress hook is where a caller
// cancels (the Python package checks for Ctrl-C there, which only the calling thread may do), so
// it must run on the calling thread and often, not only when that thread finishes a task: on a
// loaded machine a task can take a second. A hook that throws stops the workers after their
// current task, and the exception is rethrown.
template <class F>
void parallel_tasks(std::size_t threads, std::size_t tasks, F&& f,
                    const std::function<void(double)>* progress = nullptr) {
  const std::size_t workers = std::max<std::size_t>(1, std::min(threads, tasks));
  std::size_t reported = 0;  // thousandths
  const auto report = [&](std::size_t taken) {
    const std::size_t now = std::min(taken, tasks) * 1000 / std::max<std::size_t>(tasks, 1);
    if (progress && now > reported && now < 1000) (*progress)(static_cast<double>(reported = now) / 1000.0);
  };
  if (workers == 1) {
    for (std::size_t t = 0; t < tasks; ++t) {
      f(t, std::size_t{0});
      report(t + 1);
    }
    return;
  }
  std::atomic<std::size_t> next{0}, done{0};
  std::vector<std::exception_ptr> errors(workers);
  std::mutex mutex;
  std::condition_variable finished;
  std::size_t running = progress ? workers : workers - 1;  // threads started below, guarded by mutex
  const auto body = [&](std::size_t worker) {
    try {
      for (std::size_t t; (t = next.fetch_add(1, std::memory_order_relaxed)) < tasks;) {
        f(t, worker);
        done.fetch_add(1, std::memory_order_relaxed);
        if (progress) finished.notify_one();  // the monitor reports as tasks end (and every 10 ms)
      }
    } catch (...) {
      errors[worker] = std::current_exception();
      next.store(tasks);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers);
  const std::size_t first = progress ? 0 : 1;  // without progress, the caller is worker 0
  for (std::size_t k = first; k < workers; ++k)
    pool.emplace_back([&, k] {
      body(k);
      std::lock_guard<std::mutex> lock(mutex);
      if (--running == 0) finished.notify_one();
    });
  std::exception_ptr hook_error;
  if (progress) {
    std::unique_lock<std::mutex> lock(mutex);
    while (running > 0) {
      finished.wait_for(lock, std::chrono::milliseconds(10));
      if (running == 0 || hook_error) continue;
      lock.unlock();
      try {
        report(done.load(std::memory_order_relaxed));
      } catch (...) {
        hook_error = std::current_exception();
        next.store(tasks);
      }
      lock.lock();
    }
    // A run faster than the monitor still reports once (as the old worker-0 reports did): the
    // last fraction below 1 that was reached.
    if (!hook_error) {
      lock.unlock();
      try {
        report(tasks - 1);
      } catch (...) {
        hook_error = std::current_exception();
      }
    }
  } else {
    body(0);
  }
  for (auto& t : pool) t.join();
  if (hook_error) std::rethrow_exception(hook_error);
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

std::size_t worker_count(std::size_t threads, std::size_t tasks) {
  return std::max<std::size_t>(1, std::min(threads, tasks));
}

// Histograms [dimension index][bin], one per worker, summed at the end (integer sums: any split
// and any order give the same totals).
using Histogram = std::vector<Count>;

Histogram sum_histograms(const std::vector<Histogram>& parts) {
  Histogram total(parts.front().size(), 0);
  for (const auto& h : parts)
    for (std::size_t k = 0; k < h.size(); ++k) total[k] += h[k];
  return total;
}

// Cumulative counts [mi][k] = pairs closer than radius k, from a histogram over bins.
std::vector<std::vector<Count>> cumulate(const Histogram& h, std::size_t nm, std::size_t nr) {
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

// ---------------------------------------------------------------------------------------------
// Brute force: the definition, every pair and every coordinate; the bin by binary search.

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

template <class N>
Histogram brute_exact(const Problem& pb) {
  const std::size_t tasks = (pb.points + chunk_points - 1) / chunk_points;
  std::vector<Histogram> parts(worker_count(pb.threads, tasks), Histogram(pb.nm * pb.nr, 0));
  parallel_tasks(pb.threads, tasks, [&](std::size_t t, std::size_t worker) {
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
  const std::size_t workers = worker_count(pb.threads, pb.nr);
  std::vector<Scratch> scratch(workers);
  std::vector<Count> pairs(pb.nr, 0);
  parallel_tasks(pb.threads, pb.nr, [&](std::size_t k, std::size_t worker) {
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

// Points copied in a search structure's order, one contiguous array per coordinate, which is what
// the candidate scans below read (the grid and the kd-tree each lay the points out their way).
struct PointLayout {
  std::size_t size = 0;
  std::vector<double> coords;  // coordinate k of the point at position p: coords[k * size + p]
  std::vector<std::size_t> index;  // the embedded point at position p
  const double* coordinate(std::size_t k) const noexcept { return coords.data() + k * size; }
};

// m >= 2: a grid over the first two coordinates. Points are grouped into rows by coordinate 1
// (row height h >= r_max) and sorted by coordinate 0 within a row. A pair closer than r_max in any
// m >= 2 has acc(coordinate difference) < t_max in coordinates 0 and 1 (the accumulator only
// grows), hence differs by less than h in coordinate 1 and lies in the same or adjacent rows, and
// it lies inside the coordinate-0 window of the other point. Each unordered pair is visited once,
// from its lower row (same row: from the earlier position).
struct Grid : PointLayout {
  struct Row {
    std::int64_t id;
    std::size_t begin, end;
  };
  std::vector<Row> rows;
  struct Chunk {
    std::size_t row, begin, end;
  };
  std::vector<Chunk> chunks;
};

Grid build_grid(const Problem& pb) {
  const std::size_t n = pb.points;
  double lo = infinity, hi = -infinity;
  for (std::size_t i = 0; i < n; ++i) {
    lo = std::min(lo, pb.at(i, 1));
    hi = std::max(hi, pb.at(i, 1));
  }
  // The row of a value is floor((v - lo) / h), computed in floating point. With at most 2^30 rows
  // the quotient's rounding error is below 2^-22 rows, and the margin 1 + 2^-20 on h keeps two
  // values less than r_max (1 + 2^-50) apart in rows that differ by at most one.
  const double h = std::max(pb.r_max, (hi - lo) * 0x1p-30) * (1.0 + 0x1p-20);
  struct Key {
    std::int64_t row;
    double c0;
    std::size_t i;
  };
  std::vector<Key> keys(n);
  std::int64_t last_row = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double q = (pb.at(i, 1) - lo) / h;  // h may be infinite (a radius beyond all distances): one row
    keys[i] = {static_cast<std::int64_t>(std::isfinite(q) ? q : 0.0), pb.at(i, 0), i};
    last_row = std::max(last_row, keys[i].row);
  }
  // Sorted by (row, c0, i). With no more rows than points (the usual case: h >= r_max), a counting
  // sort by row (stable, so index order within a row) and then each row by (c0, i): the same order
  // in about half the time of sorting the triples, which is most of the grid's build and counts in
  // `chaos d2 --fast` (Lorenz x 10^5: 10 of 100 ms).
  const auto by_c0 = [](const Key& a, const Key& b) { return a.c0 != b.c0 ? a.c0 < b.c0 : a.i < b.i; };
  if (static_cast<std::uint64_t>(last_row) < n) {
    std::vector<std::size_t> start(static_cast<std::size_t>(last_row) + 2, 0);
    for (const Key& k : keys) ++start[static_cast<std::size_t>(k.row) + 1];
    for (std::size_t r = 1; r < start.size(); ++r) start[r] += start[r - 1];
    std::vector<Key> grouped(n);
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (const Key& k : keys) grouped[next[static_cast<std::size_t>(k.row)]++] = k;
    for (std::size_t r = 0; r + 1 < start.size(); ++r)
      boost::sort::pdqsort_branchless(grouped.begin() + static_cast<std::ptrdiff_t>(start[r]),
                                      grouped.begin() + static_cast<std::ptrdiff_t>(start[r + 1]), by_c0);
    keys.swap(grouped);
  } else {
    std::sort(keys.begin(), keys.end(),
              [&](const Key& a, const Key& b) { return a.row != b.row ? a.row < b.row : by_c0(a, b); });
  }
  Grid g;
  g.size = n;
  g.coords.resize(n * pb.max_m);
  g.index.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t i = keys[p].i;
    g.index[p] = i;
    for (std::size_t k = 0; k < pb.max_m; ++k) g.coords[k * n + p] = pb.at(i, k);
    if (g.rows.empty() || g.rows.back().id != keys[p].row) g.rows.push_back({keys[p].row, p, p});
    g.rows.back().end = p + 1;
  }
  for (std::size_t t = 0; t < g.rows.size(); ++t)
    for (std::size_t b = g.rows[t].begin; b < g.rows[t].end; b += chunk_points)
      g.chunks.push_back({t, b, std::min(g.rows[t].end, b + chunk_points)});
  return g;
}

// Which vector instructions the scans and the binning use (simd_level() below).
enum class Simd { none, avx2, avx512 };

// Histogram increments of survivors' accumulators a[0..n) into h, where bin g of copy c is
// h[g * copies + c]: consecutive survivors often share a bin, and back-to-back increments of one
// counter wait for each other, so `copies` interleaved histograms take turns and are added up at
// the end.
constexpr std::size_t histogram_copies = 4;  // the unrolled loops below assume 4

void bin_portable(const AccBins::Lookup& bins, const double* a, std::size_t n, Count* h) noexcept {
  std::size_t u = 0;
  for (; u + histogram_copies <= n; u += histogram_copies) {  // unrolled by hand: the compiler keeps the loop
    ++h[bins.inside(a[u]) * histogram_copies];
    ++h[bins.inside(a[u + 1]) * histogram_copies + 1];
    ++h[bins.inside(a[u + 2]) * histogram_copies + 2];
    ++h[bins.inside(a[u + 3]) * histogram_copies + 3];
  }
  for (; u < n; ++u) ++h[bins.inside(a[u]) * histogram_copies];
}

#if defined(__x86_64__) && defined(__GNUC__)
// The same bins in two passes: the cell numbers computed four at a time (max with the floor, shift
// of the bit pattern, subtraction of the base: the scalar cell_of lane by lane, so the same
// integers) into `cells`, then the table reads, the rare fix-ups and the increments.
__attribute__((target("avx2"))) void bin_avx2(const AccBins::Lookup& bins, const double* a, std::size_t n, Count* h,
                                              std::uint32_t* cells) noexcept {
  const __m256d floor = _mm256_set1_pd(bins.floor);
  const __m128i shift = _mm_cvtsi32_si128(bins.shift);
  const __m256i base = _mm256_set1_epi64x(static_cast<long long>(bins.base));
  // The low 32 bits of each 64-bit lane (cell numbers are below 4096), packed into the low half.
  const __m256i low_halves = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
  const std::size_t vector_end = n / 4 * 4;
  for (std::size_t u = 0; u < vector_end; u += 4) {
    const __m256d v = _mm256_max_pd(_mm256_loadu_pd(a + u), floor);
    const __m256i c = _mm256_sub_epi64(_mm256_srl_epi64(_mm256_castpd_si256(v), shift), base);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(cells + u),
                     _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(c, low_halves)));
  }
  const auto bump = [&](std::size_t u, std::size_t copy) {
    const std::int32_t e = bins.cell[cells[u]];
    ++h[(e >= 0 ? static_cast<std::size_t>(e) : bins.fix(e, a[u])) * histogram_copies + copy];
  };
  for (std::size_t u = 0; u < vector_end; u += 4) {
    bump(u, 0);
    bump(u + 1, 1);
    bump(u + 2, 2);
    bump(u + 3, 3);
  }
  bin_portable(bins, a + vector_end, n - vector_end, h);
}
#endif

// Survivors' accumulators per level (dimension m = 2 .. max at level m - 2), binned in batches.
// Collecting them first keeps the filter loops free of table lookups; the binning loop then runs
// over a short array that stays in the L1 cache.
class Survivors {
 public:
  static constexpr std::size_t block = 256;  // candidates filtered level by level at a time
  static constexpr std::size_t batch = 512;  // survivors per level collected before binning

  // Levels below `first` are filtered but not binned (dimensions below min, or m = 2 when it is
  // counted by plane_counts). `simd`: bin with bin_avx2.
  Survivors(const Problem& pb, Count* hist, std::size_t first, Simd simd)
      : pb_(pb), hist_(hist), levels_(pb.max_m - 1), first_(first), simd_(simd != Simd::none),
        acc_(new double[levels_ * capacity]), cells_(new std::uint32_t[capacity]), n_(levels_, 0),
        wide_(copies * pb.nm * pb.nr, 0) {}
  ~Survivors() {
    flush();
    for (std::size_t k = 0; k < wide_.size(); ++k) hist_[k / copies] += wide_[k];
  }
  Survivors(const Survivors&) = delete;
  Survivors& operator=(const Survivors&) = delete;

  std::size_t levels() const noexcept { return levels_; }
  std::size_t first_stored() const noexcept { return first_; }  // levels below are filtered, not counted
  double* buffer(std::size_t level) noexcept { return acc_.get() + level * capacity; }
  std::size_t& count(std::size_t level) noexcept { return n_[level]; }
  // Room for one more block at every level, else bin what has been collected.
  void make_room() noexcept {
    if (n_[first_] >= batch) flush();
  }

  void flush() noexcept {
    const AccBins::Lookup bins = pb_.bins->lookup();
    for (std::size_t level = first_; level < levels_; ++level) {
      Count* h = wide_.data() + (level + 2 - pb_.min_m) * pb_.nr * copies;
#if defined(__x86_64__) && defined(__GNUC__)
      if (simd_)
        bin_avx2(bins, buffer(level), n_[level], h, cells_.get());
      else
#endif
        bin_portable(bins, buffer(level), n_[level], h);
      n_[level] = 0;
    }
  }

 private:
  static constexpr std::size_t copies = histogram_copies;
  static constexpr std::size_t capacity = batch + block + 8;  // + 8: a packed store writes up to 8 lanes
  const Problem& pb_;
  Count* hist_;
  std::size_t levels_, first_;
  bool simd_;
  std::unique_ptr<double[]> acc_;  // not zeroed: only the entries below n_[level] are read (a reference walk builds one per point)
  std::unique_ptr<std::uint32_t[]> cells_;  // bin_avx2's scratch
  std::vector<std::size_t> n_;
  std::vector<Count> wide_;
};

// Scan of the candidates q in [qb, qe) of grid point p, a block at a time and level by level: the
// accumulator of every candidate in the block takes one more coordinate per level, and those
// below t_max are appended to the level's buffer without a branch. A level with no survivors
// ends the block (the accumulator never decreases). Level-major order keeps each level's count
// in a register; candidate-major order would chain every update through memory.
template <class N, bool check_window>
void scan_scalar(const Problem& pb, const PointLayout& g, std::size_t p, std::size_t qb, std::size_t qe, Survivors& s,
                 double t) {
  const std::size_t levels = s.levels(), first = s.first_stored(), w = pb.w, i = g.index[p];
  const double* c0 = g.coordinate(0);
  const double* c1 = g.coordinate(1);
  double a[Survivors::block];
  for (std::size_t q0 = qb; q0 < qe; q0 += Survivors::block) {
    const std::size_t len = std::min(Survivors::block, qe - q0);
    s.make_room();
    for (std::size_t level = 0; level < levels; ++level) {
      const double* ck = g.coordinate(level + 1) + q0;
      const double ak = g.coordinate(level + 1)[p];
      double* out = s.buffer(level);
      std::size_t n = s.count(level), alive = 0;
      for (std::size_t u = 0; u < len; ++u) {
        double v = level == 0 ? N::add(N::add(0.0, std::abs(c0[p] - c0[q0 + u])), std::abs(c1[p] - ck[u]))
                              : N::add(a[u], std::abs(ak - ck[u]));
        if constexpr (check_window)
          if (level == 0 && in_window(i, g.index[q0 + u], w)) v = infinity;  // never survives
        a[u] = v;
        out[n] = v;
        const bool keep = v < t;
        n += keep && level >= first;
        alive += keep;
      }
      s.count(level) = n;
      if (alive == 0) break;
    }
  }
}

// A switch set in the environment (not empty and not "0"): the tests use these to reach every path.
bool env_flag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' && *v != '0';
}

#if defined(__x86_64__) && defined(__GNUC__)
// For each 4-lane comparison mask, the permutation that moves the kept lanes to the front (AVX2
// has no compress instruction).
struct CompressTable {
  alignas(32) std::int32_t index[16][8];
};
constexpr CompressTable make_compress_table() {
  CompressTable table{};
  for (int mask = 0; mask < 16; ++mask) {
    int out = 0;
    for (int lane = 0; lane < 4; ++lane)
      if (mask & (1 << lane)) {
        table.index[mask][2 * out] = 2 * lane;
        table.index[mask][2 * out + 1] = 2 * lane + 1;
        ++out;
      }
  }
  return table;
}
constexpr CompressTable compress_table = make_compress_table();

// The loops the vector scans share: blocks of candidates, and in each block the levels (one more
// coordinate each) until no candidate of the block survives. `pass(q0, len, level, out, n, store)`
// filters one level of the block [q0, q0 + len), `width` candidates at a time, appends the
// survivors to `out` from position n, advances n by their number where the level is stored, and
// returns that number. Returns where the candidates that fill whole vectors end; the caller scans
// the rest. (The passes carry the target attributes; a lambda would not.)
template <std::size_t width, class Pass>
std::size_t scan_vector_blocks(std::size_t qb, std::size_t qe, Survivors& s, Pass& pass) {
  const std::size_t levels = s.levels(), first = s.first_stored();
  const std::size_t vector_end = qb + (qe - qb) / width * width;
  for (std::size_t q0 = qb; q0 < vector_end; q0 += Survivors::block) {
    const std::size_t len = std::min(Survivors::block, vector_end - q0);
    s.make_room();
    for (std::size_t level = 0; level < levels; ++level)
      if (pass(q0, len, level, s.buffer(level), s.count(level), level >= first) == 0) break;
  }
  return vector_end;
}

// Four candidates at a time with AVX2. The operations are the scalar ones lane by lane (subtract,
// absolute value, max or multiply-then-add without fusing: AVX2 alone does not enable FMA), so the
// accumulators are bit-identical. Survivors are packed with a permutation chosen by the mask.
template <class N>
struct Avx2Pass {
  Avx2Pass(const PointLayout& layout, std::size_t point, double threshold)
      : c0(layout.coordinate(0)), g(layout), p(point), t(threshold) {}
  const double* c0;  // coordinate 0 of every position
  const PointLayout& g;
  std::size_t p;
  double t;
  alignas(32) double a[Survivors::block];  // the block's accumulators, written at level 0 before any read

  __attribute__((target("avx2,popcnt"))) std::size_t operator()(std::size_t q0, std::size_t len, std::size_t level,
                                                                 double* out, std::size_t& count, bool store) {
    const __m256d sign = _mm256_set1_pd(-0.0), tv = _mm256_set1_pd(t), a0 = _mm256_set1_pd(c0[p]);
    const double* ck = g.coordinate(level + 1) + q0;
    const __m256d ak = _mm256_set1_pd(g.coordinate(level + 1)[p]);
    std::size_t n = count, alive = 0;
    for (std::size_t u = 0; u < len; u += 4) {
      const __m256d dk = _mm256_andnot_pd(sign, _mm256_sub_pd(ak, _mm256_loadu_pd(ck + u)));
      __m256d v;
      if (level == 0) {
        const __m256d d0 = _mm256_andnot_pd(sign, _mm256_sub_pd(a0, _mm256_loadu_pd(c0 + q0 + u)));
        if constexpr (std::is_same_v<N, MaxNorm>)
          v = _mm256_max_pd(d0, dk);
        else
          v = _mm256_add_pd(_mm256_mul_pd(d0, d0), _mm256_mul_pd(dk, dk));
      } else {
        const __m256d prev = _mm256_load_pd(a + u);
        if constexpr (std::is_same_v<N, MaxNorm>)
          v = _mm256_max_pd(prev, dk);
        else
          v = _mm256_add_pd(prev, _mm256_mul_pd(dk, dk));
      }
      _mm256_store_pd(a + u, v);
      const int mask = _mm256_movemask_pd(_mm256_cmp_pd(v, tv, _CMP_LT_OQ));
      const __m256i perm = _mm256_load_si256(reinterpret_cast<const __m256i*>(compress_table.index[mask]));
      _mm256_storeu_ps(reinterpret_cast<float*>(out + n), _mm256_permutevar8x32_ps(_mm256_castpd_ps(v), perm));
      const auto k = static_cast<std::size_t>(__builtin_popcount(static_cast<unsigned>(mask)));
      n += store ? k : 0;
      alive += k;
    }
    count = n;
    return alive;
  }
};

template <class N>
void scan_avx2(const Problem& pb, const PointLayout& g, std::size_t p, std::size_t qb, std::size_t qe, Survivors& s,
               double t) {
  Avx2Pass<N> pass(g, p, t);
  const std::size_t vector_end = scan_vector_blocks<4>(qb, qe, s, pass);
  if (vector_end < qe) scan_scalar<N, false>(pb, g, p, vector_end, qe, s, t);
}

// Eight candidates at a time with AVX-512, for the maximum norm only: its lanes take max and
// absolute value, which no compiler contracts, while the Euclidean sum of products could be fused
// into FMA under this target and change the accumulators' last bits. Survivors are packed with the
// compress instruction (into a register, then stored: the memory form is slow on some processors).
__attribute__((target("avx512f"), always_inline)) inline __m512d abs512(__m512d x) {
  return _mm512_castsi512_pd(_mm512_and_si512(_mm512_castpd_si512(x), _mm512_set1_epi64(0x7fffffffffffffff)));
}
struct Avx512MaxPass {
  Avx512MaxPass(const PointLayout& layout, std::size_t point, double threshold)
      : c0(layout.coordinate(0)), g(layout), p(point), t(threshold) {}
  const double* c0;
  const PointLayout& g;
  std::size_t p;
  double t;
  alignas(64) double a[Survivors::block];

  __attribute__((target("avx512f,popcnt"))) std::size_t operator()(std::size_t q0, std::size_t len, std::size_t level,
                                                                   double* out, std::size_t& count, bool store) {
    const __m512d tv = _mm512_set1_pd(t), a0 = _mm512_set1_pd(c0[p]);
    const double* ck = g.coordinate(level + 1) + q0;
    const __m512d ak = _mm512_set1_pd(g.coordinate(level + 1)[p]);
    std::size_t n = count, alive = 0;
    for (std::size_t u = 0; u < len; u += 8) {
      const __m512d dk = abs512(_mm512_sub_pd(ak, _mm512_loadu_pd(ck + u)));
      const __m512d prev = level == 0 ? abs512(_mm512_sub_pd(a0, _mm512_loadu_pd(c0 + q0 + u))) : _mm512_load_pd(a + u);
      const __m512d v = _mm512_maskz_max_pd(0xff, prev, dk);  // maskz: GCC 12's unmasked form warns of an undefined operand
      _mm512_store_pd(a + u, v);
      const __mmask8 mask = _mm512_cmp_pd_mask(v, tv, _CMP_LT_OQ);
      _mm512_storeu_pd(out + n, _mm512_maskz_compress_pd(mask, v));
      const auto k = static_cast<std::size_t>(__builtin_popcount(static_cast<unsigned>(mask)));
      n += store ? k : 0;
      alive += k;
    }
    count = n;
    return alive;
  }
};

void scan_avx512_max(const Problem& pb, const PointLayout& g, std::size_t p, std::size_t qb, std::size_t qe, Survivors& s,
                     double t) {
  Avx512MaxPass pass(g, p, t);
  const std::size_t vector_end = scan_vector_blocks<8>(qb, qe, s, pass);
  if (vector_end < qe) scan_avx2<MaxNorm>(pb, g, p, vector_end, qe, s, t);  // fewer than 8 left
}

// The widest vector scan this processor runs, unless the environment narrows it:
// CHAOS_NO_SIMD=1 selects the portable scan, CHAOS_NO_AVX512=1 the AVX2 one (so the tests check
// every path on a machine that has them all).
Simd simd_level() {
  static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
  static const bool avx512 = avx2 && __builtin_cpu_supports("avx512f");
  if (!avx2 || env_flag("CHAOS_NO_SIMD")) return Simd::none;
  return avx512 && !env_flag("CHAOS_NO_AVX512") ? Simd::avx512 : Simd::avx2;
}
#else
Simd simd_level() { return Simd::none; }
#endif

// CHAOS_NO_PLANE=1 makes the grid bin m = 2 itself, so the tests check both ways against brute force.
bool plane_disabled() { return env_flag("CHAOS_NO_PLANE"); }

template <class N, bool check_window>
// Candidates q in [qb, qe) of layout position p, kept while their accumulator is below t (at most
// t_max: the exact walk passes t_max, a capped reference walk the largest radius still open).
void scan_candidates(const Problem& pb, const PointLayout& g, std::size_t p, std::size_t qb, std::size_t qe, Survivors& s,
                     Simd simd, double t) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (!check_window && simd == Simd::avx512 && std::is_same_v<N, MaxNorm>) return scan_avx512_max(pb, g, p, qb, qe, s, t);
  if (!check_window && simd != Simd::none) return scan_avx2<N>(pb, g, p, qb, qe, s, t);
#endif
  (void)simd;
  scan_scalar<N, check_window>(pb, g, p, qb, qe, s, t);
}

// The pairs 1 <= j - i <= w that the grid counted when it leaves the Theiler window to a
// subtraction: the same accumulators in the same order, so exactly the same bins.
template <class N>
void window_pairs(const Problem& pb, Count* hist) {
  const std::size_t tasks = (pb.points + chunk_points - 1) / chunk_points;
  const AccBins::Lookup bins = pb.bins->lookup();
  std::vector<Histogram> parts(worker_count(pb.threads, tasks), Histogram(pb.nm * pb.nr, 0));
  parallel_tasks(pb.threads, tasks, [&](std::size_t t, std::size_t worker) {
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
  std::vector<Histogram> parts(worker_count(pb.threads, g.chunks.size()), Histogram(pb.nm * pb.nr, 0));
  parallel_tasks(pb.threads, g.chunks.size(), [&](std::size_t c, std::size_t worker) {
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

// ---------------------------------------------------------------------------------------------
// kd-tree: one traversal per point for every radius and every m >= 2.
//
// The tree splits the first c = max(2, min_m) coordinates: a pair that counts in some m >= min_m
// has acc < t_max in those coordinates already (the accumulator only grows). A node splits at the
// median of its widest coordinate until at most `leaf_points` remain; the points are copied in
// leaf order, every coordinate contiguous, as the grid copies them, so a leaf is a run of
// positions that the grid's candidate scan filters level by level and bins for every m at once. A
// point visits the leaves whose box lies within t_max of it in the c coordinates (a lower bound
// of every accumulator inside, as rounding is monotone), and in the exact walk only the positions
// after its own, so each unordered pair is examined once. m = 1 and the Theiler window are done as
// in the box-assisted walk.
struct KdLayout : PointLayout {
  static constexpr std::size_t leaf_points = 128;
  struct Node {
    std::size_t begin, end;
    std::size_t left;  // children left and left + 1; 0 (the root is nobody's child): a leaf
  };
  std::size_t dims = 2;  // c
  std::vector<Node> nodes;
  std::vector<double> box;  // lo and hi of coordinate k of node n: box[2 * (n * dims + k)] and the next
  std::vector<std::size_t> position;  // the position of each embedded point

  // Lower bound of the accumulator in the c split coordinates from the point at position p to
  // any point of node n.
  template <class N>
  double near(std::size_t n, std::size_t p) const noexcept {
    const double* b = box.data() + 2 * n * dims;
    double acc = 0.0;
    for (std::size_t k = 0; k < dims; ++k) {
      const double q = coordinate(k)[p], lo = b[2 * k], hi = b[2 * k + 1];
      acc = N::add(acc, q < lo ? lo - q : (q > hi ? q - hi : 0.0));
    }
    return acc;
  }
};

KdLayout build_kd(const Problem& pb) {
  const std::size_t n = pb.points, c = std::max<std::size_t>(2, pb.min_m);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  KdLayout t;
  t.dims = c;
  t.nodes.push_back({0, n, 0});
  for (std::size_t id = 0; id < t.nodes.size(); ++id) {  // breadth first: children are appended
    const std::size_t begin = t.nodes[id].begin, end = t.nodes[id].end;
    t.box.resize(2 * t.nodes.size() * c);
    double* b = t.box.data() + 2 * id * c;
    std::size_t widest = 0;
    for (std::size_t k = 0; k < c; ++k) {
      double lo = infinity, hi = -infinity;
      for (std::size_t u = begin; u < end; ++u) {
        lo = std::min(lo, pb.at(order[u], k));
        hi = std::max(hi, pb.at(order[u], k));
      }
      b[2 * k] = lo;
      b[2 * k + 1] = hi;
      if (hi - lo > b[2 * widest + 1] - b[2 * widest]) widest = k;
    }
    if (end - begin <= KdLayout::leaf_points) continue;
    // Split by count even where every value is equal (ties, quantised data): leaves stay small.
    const std::size_t mid = begin + (end - begin) / 2;
    std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(mid),
                     order.begin() + static_cast<std::ptrdiff_t>(end), [&](std::size_t x, std::size_t y) {
                       const double vx = pb.at(x, widest), vy = pb.at(y, widest);
                       return vx != vy ? vx < vy : x < y;
                     });
    t.nodes[id].left = t.nodes.size();
    t.nodes.push_back({begin, mid, 0});
    t.nodes.push_back({mid, end, 0});
  }
  t.box.resize(2 * t.nodes.size() * c);
  t.size = n;
  t.coords.resize(n * pb.max_m);
  t.index = std::move(order);
  t.position.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    t.position[t.index[p]] = p;
    for (std::size_t k = 0; k < pb.max_m; ++k) t.coords[k * n + p] = pb.at(t.index[p], k);
  }
  return t;
}

// Every leaf within t of the point at position p, from position `from` on, handed to
// scan_candidates. `stack` is the caller's scratch.
template <class N, bool check_window>
void kd_partners(const Problem& pb, const KdLayout& t, std::size_t p, std::size_t from, Survivors& s, Simd simd,
                 double threshold, std::vector<std::size_t>& stack) {
  stack.assign(1, 0);
  while (!stack.empty()) {
    const std::size_t id = stack.back();
    stack.pop_back();
    const KdLayout::Node& node = t.nodes[id];
    if (node.end <= from || !(t.near<N>(id, p) < threshold)) continue;
    if (node.left == 0) {
      scan_candidates<N, check_window>(pb, t, p, std::max(node.begin, from), node.end, s, simd, threshold);
    } else {
      stack.push_back(node.left + 1);
      stack.push_back(node.left);
    }
  }
}

template <class N, bool check_window>
Histogram kd_counts(const Problem& pb, const KdLayout& t, std::size_t first) {
  const Simd simd = simd_level();
  const std::size_t tasks = (pb.points + chunk_points - 1) / chunk_points;
  std::vector<Histogram> parts(worker_count(pb.threads, tasks), Histogram(pb.nm * pb.nr, 0));
  parallel_tasks(pb.threads, tasks, [&](std::size_t task, std::size_t worker) {
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

struct Totals {
  std::vector<std::vector<Count>> pairs, examined;
  std::vector<std::vector<std::vector<Count>>> group_pairs, group_examined;  // reference walks only
};

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
    const std::size_t workers = worker_count(pb.threads, tasks);
    const std::size_t slots = std::max<std::size_t>(groups, 1);
    std::vector<Histogram> sums(workers, Histogram(slots * stride, 0));
    std::vector<Histogram> scratch(workers, Histogram(stride, 0));
    std::vector<std::vector<Count>> cum(workers, std::vector<Count>(stride, 0));
    parallel_tasks(pb.threads, tasks, [&](std::size_t t, std::size_t worker) {
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
  std::vector<Histogram> scratch(worker_count(pb.threads, wave_size), Histogram(stride, 0));
  for (std::size_t start = 0; start < order.size();) {
    if (std::all_of(need.begin(), need.end(), [](std::size_t n) { return n == 0; })) break;
    const std::size_t wave = std::min(wave_size, order.size() - start);
    parallel_tasks(pb.threads, (wave + per_worker - 1) / per_worker, [&](std::size_t t, std::size_t worker) {
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

// The per-reference-point counter of a search mode (its structure is built here, once).
template <class N>
std::unique_ptr<ReferenceCounter> make_counter(const Problem& pb, CorrelationSearch search) {
  switch (search) {
    case CorrelationSearch::brute_force: return std::make_unique<BruteCounter<N>>(pb);
    case CorrelationSearch::kd_tree: return std::make_unique<SpatialCounter<N, KdWalk<N>>>(pb);
    case CorrelationSearch::box_assisted: break;
  }
  return std::make_unique<SpatialCounter<N, GridWalk<N>>>(pb);
}

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

void require_subset(std::size_t points, std::size_t offset, std::size_t count) {
  if (count > points)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "correlation sum: reference_points must not exceed the " + std::to_string(points) +
                           " embedded points N - (m-1)*tau (got " + std::to_string(count) + ")");
  if (offset > 0 && (count == 0 || offset > points || count > points - offset))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "correlation sum: a reference offset needs a subset that fits after it: offset + reference_points "
                       "<= the " + std::to_string(points) + " embedded points (got offset " + std::to_string(offset) +
                           ", reference_points " + std::to_string(count) + ")");
}

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
};

void prepare(Prepared& p, std::span<const double> x, const CorrelationSumOptions& options) {
  options.validate();
  require_finite(x, "correlation sum");
  require_not_constant(x, "correlation sum");
  const std::size_t tau = options.delay, w = options.theiler, top = options.max_dimension;
  const std::size_t minimum = add_sat(add_sat(mul_sat(top - 1, tau), w), 2);
  require_length(x, minimum, "correlation sum",
                 "the reference set i < N - (m-1)*tau for m up to " + std::to_string(top) + " with tau = " +
                     std::to_string(tau) + " needs at least one pair outside the Theiler window w = " +
                     std::to_string(w) + ": N >= (m-1)*tau + w + 2 = " + std::to_string(top - 1) + "*" +
                     std::to_string(tau) + " + " + std::to_string(w) + " + 2");
  p.options = options;

  // For the Euclidean norm the series and radii are multiplied by a power of two that brings
  // max |x| into [0.5, 1): exact, so every comparison d < r keeps its outcome, while squares can
  // neither overflow nor underflow. The maximum norm needs no squares and is used as given.
  std::vector<double> radii = options.radii;
  std::span<const double> y = x;
  if (options.norm == Norm::euclidean) {
    double largest = 0.0;
    for (const double v : x) largest = std::max(largest, std::abs(v));
    int exponent = 0;
    std::frexp(largest, &exponent);
    p.scaled.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) p.scaled[i] = std::ldexp(x[i], -exponent);
    for (double& r : radii) r = std::ldexp(r, -exponent);
    y = p.scaled;
  }

  // d <= r is d < r+, the next double above r (d is a double): the counting loops keep their strict
  // comparison. For the Euclidean norm this comes after the exact power-of-two scaling above.
  if (options.inclusive)
    for (double& r : radii) r = std::nextafter(r, infinity);

  std::vector<double> thresholds(radii.size());
  for (std::size_t k = 0; k < radii.size(); ++k) thresholds[k] = threshold(options.norm, radii[k]);
  p.bins.emplace(thresholds);
  Problem& pb = p.pb;
  pb.y = y;
  pb.radii = radii;
  pb.thresholds = thresholds;
  pb.r_max = radii.back();
  pb.t_max = thresholds.back();
  pb.tau = tau;
  pb.w = w;
  pb.points = x.size() - (top - 1) * tau;
  pb.min_m = options.min_dimension;
  pb.max_m = top;
  pb.nm = top - options.min_dimension + 1;
  pb.nr = radii.size();
  pb.norm = options.norm;
  pb.threads = options.threads;
  pb.bins = &*p.bins;
  pb.progress = p.options.progress ? &p.options.progress : nullptr;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  p.range = *hi - *lo;
}

CorrelationSumResult assemble(const Prepared& p, Totals totals, std::size_t reference_points) {
  const Problem& pb = p.pb;
  CorrelationSumResult result;
  for (std::size_t m = pb.min_m; m <= pb.max_m; ++m) result.dimension.push_back(m);
  result.radius = p.options.radii;
  result.correlation_sum.assign(pb.nm, std::vector<double>(pb.nr, 0.0));
  for (std::size_t mi = 0; mi < pb.nm; ++mi)
    for (std::size_t k = 0; k < pb.nr; ++k)
      if (totals.examined[mi][k] > 0)
        result.correlation_sum[mi][k] =
            static_cast<double>(totals.pairs[mi][k]) / static_cast<double>(totals.examined[mi][k]);
  result.pairs = std::move(totals.pairs);
  result.examined = std::move(totals.examined);
  result.group_pairs = std::move(totals.group_pairs);
  result.group_examined = std::move(totals.group_examined);
  result.points = reference_points > 0 ? reference_points : pb.points;
  result.range = p.range;
  return result;
}

}  // namespace

const char* to_string(CorrelationSearch search) noexcept {
  switch (search) {
    case CorrelationSearch::brute_force: return "brute_force";
    case CorrelationSearch::kd_tree: return "kd_tree";
    case CorrelationSearch::box_assisted: return "box_assisted";
  }
  return "unknown";
}

void CorrelationSumOptions::validate() const {
  const auto refuse = [](const std::string& message) {
    throw InvalidInput(ErrorCode::invalid_parameter, "correlation sum: " + message);
  };
  if (delay == 0) refuse("delay tau must be at least 1 sample (got tau = 0)");
  if (min_dimension == 0) refuse("minimum embedding dimension must be at least 1 (got m = 0)");
  if (min_dimension > max_dimension)
    refuse("minimum embedding dimension must not exceed the maximum (got min m = " + std::to_string(min_dimension) +
           " > max m = " + std::to_string(max_dimension) + ")");
  if (threads == 0) refuse("the number of threads must be at least 1 (got 0)");
  if (jackknife_groups < 2 || jackknife_groups > 1024)
    refuse("the jackknife needs 2 to 1024 groups of reference points (got " + std::to_string(jackknife_groups) + ")");
  if (norm != Norm::max && norm != Norm::euclidean) refuse("unknown norm");
  if (search != CorrelationSearch::brute_force && search != CorrelationSearch::kd_tree &&
      search != CorrelationSearch::box_assisted)
    refuse("unknown search mode");
  if (radii.empty()) refuse("at least one radius is needed (got none)");
  for (std::size_t k = 0; k < radii.size(); ++k) {
    if (!std::isfinite(radii[k]) || !(radii[k] > 0.0))
      refuse("radii must be finite and positive (got radius[" + std::to_string(k) + "] = " + number(radii[k]) + ")");
    if (inclusive && radii[k] == std::numeric_limits<double>::max())
      refuse("with inclusive counting (d <= eps) a radius must be below the largest double (got radius[" +
             std::to_string(k) + "] = " + number(radii[k]) + ")");
    if (k > 0 && !(radii[k] > radii[k - 1]))
      refuse("radii must be strictly increasing (got radius[" + std::to_string(k) + "] = " + number(radii[k]) +
             " after radius[" + std::to_string(k - 1) + "] = " + number(radii[k - 1]) + ")");
  }
}

std::vector<double> log_radii(double r_min, double r_max, std::size_t n) {
  const auto refuse = [](const std::string& message) {
    throw InvalidInput(ErrorCode::invalid_parameter, "log_radii: " + message);
  };
  if (!(std::isfinite(r_min) && r_min > 0.0 && std::isfinite(r_max) && r_max > 0.0))
    refuse("radii must be finite and positive (got r_min = " + number(r_min) + ", r_max = " + number(r_max) + ")");
  if (n == 0) refuse("the number of radii must be at least 1 (got 0)");
  // A log grid finer than this resolves nothing more in the local slopes; the cap keeps a
  // mistyped count from asking for more memory than there is.
  constexpr std::size_t max_radii = 10000;
  if (n > max_radii)
    refuse("the number of radii must be at most " + std::to_string(max_radii) + " (got " + std::to_string(n) + ")");
  if (n == 1) {
    if (r_min != r_max)
      refuse("one radius needs r_min = r_max (got r_min = " + number(r_min) + ", r_max = " + number(r_max) + ")");
    return {r_min};
  }
  if (!(r_min < r_max))
    refuse("r_min must be smaller than r_max for " + std::to_string(n) + " radii (got r_min = " + number(r_min) +
           ", r_max = " + number(r_max) + ")");
  std::vector<double> r(n);
  const double a = std::log(r_min), step = (std::log(r_max) - a) / static_cast<double>(n - 1);
  for (std::size_t k = 0; k < n; ++k) r[k] = std::exp(a + step * static_cast<double>(k));
  r.front() = r_min;  // the ends exactly as given
  r.back() = r_max;
  for (std::size_t k = 1; k < n; ++k)
    if (!(r[k] > r[k - 1]))
      refuse(std::to_string(n) + " radii between " + number(r_min) + " and " + number(r_max) +
             " are not distinct in double precision");
  return r;
}

CorrelationSumResult correlation_sum(std::span<const double> x, const CorrelationSumOptions& options) {
  Prepared p;
  prepare(p, x, options);
  require_subset(p.pb.points, options.reference_offset, options.reference_points);
  if (options.pairs_per_radius == 0 && options.reference_points == 0) {
    Totals totals = options.norm == Norm::max ? exact_totals<MaxNorm>(p.pb, options.search)
                                              : exact_totals<EuclideanNorm>(p.pb, options.search);
    return assemble(p, std::move(totals), 0);
  }
  // A cap without a subset: every point is a reference point, in the seeded order.
  const std::size_t count = options.reference_points > 0 ? options.reference_points : p.pb.points;
  const std::unique_ptr<ReferenceCounter> counter = make_counter(p.pb, options);
  return assemble(p, subset_totals(p.pb, *counter, options, options.reference_offset, count),
                  options.reference_points);
}

namespace {

// The pairs whose lag j - i falls in (windows[s - 1], windows[s]] for s = 1 .. S - 1 (windows sorted,
// distinct) and that are closer than the largest radius, binned per segment s and dimension:
// h[((s - 1) * nm + mi) * nr + bin] (below t_max a bin is at most nr - 1). The accumulators are those
// of every exact walk (coordinate 0 first, then one more per dimension), so each pair lands in the
// bin the walk gave it. window_pairs enumerates lags 1 .. w the same way for the grid and kd-tree.
template <class N>
Histogram lag_band_pairs(const Problem& pb, const std::vector<std::size_t>& windows) {
  const std::size_t segments = windows.size() - 1;
  const std::size_t tasks = (pb.points + chunk_points - 1) / chunk_points;
  const AccBins::Lookup bins = pb.bins->lookup();
  std::vector<Histogram> parts(worker_count(pb.threads, tasks), Histogram(segments * pb.nm * pb.nr, 0));
  parallel_tasks(pb.threads, tasks, [&](std::size_t t, std::size_t worker) {
    Count* h = parts[worker].data();
    const std::size_t end = std::min(pb.points, (t + 1) * chunk_points);
    for (std::size_t i = t * chunk_points; i < end; ++i)
      for (std::size_t s = 1; s <= segments; ++s) {
        Count* hs = h + (s - 1) * pb.nm * pb.nr;
        for (std::size_t j = i + windows[s - 1] + 1; j <= i + windows[s] && j < pb.points; ++j) {
          double acc = N::add(0.0, std::abs(pb.at(i, 0) - pb.at(j, 0)));
          for (std::size_t m = 1; m <= pb.max_m; ++m) {
            if (m > 1) acc = N::add(acc, std::abs(pb.at(i, m - 1) - pb.at(j, m - 1)));
            if (!(acc < pb.t_max)) break;  // beyond every radius here and in every higher dimension
            if (m >= pb.min_m) ++hs[(m - pb.min_m) * pb.nr + bins.inside(acc)];
          }
        }
      }
  });
  return sum_histograms(parts);
}

}  // namespace

std::vector<CorrelationSumResult> correlation_sums_over_theiler_windows(std::span<const double> x,
                                                                        const CorrelationSumOptions& options,
                                                                        std::span<const std::size_t> theilers) {
  if (theilers.empty())
    throw InvalidInput(ErrorCode::invalid_parameter, "correlation sums over Theiler windows: no window given");
  if (options.pairs_per_radius != 0 || options.reference_points != 0)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "correlation sums over Theiler windows: exact counts only (got a pair cap of " +
                           std::to_string(options.pairs_per_radius) + " and " +
                           std::to_string(options.reference_points) + " reference points; both must be 0)");
  // Each window is checked as correlation_sum checks it (the largest is the strictest on N).
  std::vector<std::unique_ptr<Prepared>> prepared;
  for (const std::size_t w : theilers) {
    CorrelationSumOptions o = options;
    o.theiler = w;
    prepared.push_back(std::make_unique<Prepared>());
    prepare(*prepared.back(), x, o);
  }
  std::vector<std::size_t> windows(theilers.begin(), theilers.end());
  std::sort(windows.begin(), windows.end());
  windows.erase(std::unique(windows.begin(), windows.end()), windows.end());

  // The exact walk at the smallest window, then the pairs of each larger window's extra lags.
  const std::size_t smallest =
      static_cast<std::size_t>(std::find(theilers.begin(), theilers.end(), windows.front()) - theilers.begin());
  const Problem& pb = prepared[smallest]->pb;
  const Totals base = options.norm == Norm::max ? exact_totals<MaxNorm>(pb, options.search)
                                                : exact_totals<EuclideanNorm>(pb, options.search);
  const Histogram band = windows.size() < 2 ? Histogram{}
                         : options.norm == Norm::max ? lag_band_pairs<MaxNorm>(pb, windows)
                                                     : lag_band_pairs<EuclideanNorm>(pb, windows);
  std::vector<CorrelationSumResult> out;
  out.reserve(theilers.size());
  for (std::size_t q = 0; q < theilers.size(); ++q) {
    const std::size_t segment =
        static_cast<std::size_t>(std::lower_bound(windows.begin(), windows.end(), theilers[q]) - windows.begin());
    Totals totals;
    totals.pairs = base.pairs;
    for (std::size_t mi = 0; mi < pb.nm; ++mi)
      for (std::size_t s = 1; s <= segment; ++s) {
        const Count* h = band.data() + ((s - 1) * pb.nm + mi) * pb.nr;
        Count closer = 0;  // pairs of this segment closer than radius k
        for (std::size_t k = 0; k < pb.nr; ++k) totals.pairs[mi][k] -= closer += h[k];
      }
    const std::size_t span = pb.points - theilers[q] - 1;  // validated by prepare: P >= w + 2
    totals.examined.assign(pb.nm, std::vector<Count>(pb.nr, static_cast<Count>(span) * static_cast<Count>(span + 1) / 2));
    out.push_back(assemble(*prepared[q], std::move(totals), 0));
  }
  return out;
}

struct CorrelationSumSubsets::State {
  Prepared prepared;
  std::unique_ptr<ReferenceCounter> counter;
};

CorrelationSumSubsets::CorrelationSumSubsets(std::span<const double> x, const CorrelationSumOptions& options)
    : state_(std::make_unique<State>()) {
  prepare(state_->prepared, x, options);
  state_->counter = make_counter(state_->prepared.pb, options);
}

CorrelationSumSubsets::~CorrelationSumSubsets() = default;

std::size_t CorrelationSumSubsets::points() const noexcept { return state_->prepared.pb.points; }

CorrelationSumResult CorrelationSumSubsets::count(std::size_t reference_offset, std::size_t reference_points) const {
  const Prepared& p = state_->prepared;
  if (reference_points == 0)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "correlation sum subsets: a subset needs at least one reference point (got 0)");
  require_subset(p.pb.points, reference_offset, reference_points);
  return assemble(p, subset_totals(p.pb, *state_->counter, p.options, reference_offset, reference_points),
                  reference_points);
}

}  // namespace chaos
