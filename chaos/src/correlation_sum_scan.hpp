#pragma once
// The candidate scan of the correlation-sum walks: the candidates of one point, a block at a time,
// filtered coordinate by coordinate against a threshold, with the survivors binned per dimension.
// Portable, AVX2 and AVX-512 versions count exactly the same (the same operations lane by lane);
// the widest the processor runs is used unless the environment narrows it (simd_level()).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "correlation_sum_layouts.hpp"
#include "correlation_sum_problem.hpp"

namespace chaos::correlation_detail {

// Which vector instructions the scans and the binning use (simd_level() below).
enum class Simd { none, avx2, avx512 };

// The widest vector scan this processor runs, unless the environment narrows it:
// CHAOS_NO_SIMD=1 selects the portable scan, CHAOS_NO_AVX512=1 the AVX2 one (so the tests check
// every path on a machine that has them all).
Simd simd_level();

// Histogram increments of survivors' accumulators a[0..n) into h, where bin g of copy c is
// h[g * copies + c]: consecutive survivors often share a bin, and back-to-back increments of one
// counter wait for each other, so `copies` interleaved histograms take turns and are added up at
// the end.
constexpr std::size_t histogram_copies = 4;  // the unrolled binning loops assume 4

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

  // Bins what has been collected at every stored level.
  void flush() noexcept;

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

// Candidates q in [qb, qe) of layout position p, kept while their accumulator is below t (at most
// t_max: the exact walk passes t_max, a capped reference walk the largest radius still open).
// check_window: candidates inside p's Theiler window are dropped here (else the caller takes them
// out afterwards). Instantiated for MaxNorm and EuclideanNorm, with and without the window test.
template <class N, bool check_window>
void scan_candidates(const Problem& pb, const PointLayout& g, std::size_t p, std::size_t qb, std::size_t qe, Survivors& s,
                     Simd simd, double t);

// Every leaf within t of the point at position p, from position `from` on, handed to
// scan_candidates. `stack` is the caller's scratch.
template <class N, bool check_window>
void kd_partners(const Problem& pb, const KdLayout& t, std::size_t p, std::size_t from, Survivors& s, Simd simd,
                 double threshold, std::vector<std::size_t>& stack) {
  stack.assign(1, 0);
  while (!stack.empty()) {
    const std::size_t id = stack.back();
    stack.pop_back();
    const spatial::KdTree::Node& node = t.tree.nodes()[id];
    if (node.end <= from || !(t.near<N>(id, p) < threshold)) continue;
    if (node.left == spatial::KdTree::no_child) {
      scan_candidates<N, check_window>(pb, t, p, std::max(node.begin, from), node.end, s, simd, threshold);
    } else {
      stack.push_back(node.left + 1);
      stack.push_back(node.left);
    }
  }
}

}  // namespace chaos::correlation_detail
