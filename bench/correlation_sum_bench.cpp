// Correlation sums: brute force, kd-tree and box-assisted search on the same job, and the two
// target jobs of docs/validation/performance-correlation-sum.md. Inputs (series, radii) are built before the timed loop.
//
// Search comparison: Lorenz x (sigma 10, rho 28, beta 8/3, dt = 0.01, RK4 step 0.001), tau = 17,
// Theiler window w = 200, 40 log-spaced radii from 0.25 to 5, C(eps, m) for m = 1 .. M in one call
// with M in {2, 5, 10}, one thread, N in {10^3, 10^4, 10^5, 10^6}.
//   brute force: N <= 10^5 only (O(N^2) pairs: about a minute at 10^5, so well over an hour at
//                10^6);
//   kd-tree:     N <= 10^5 (one traversal per point for all radii and dimensions, 1-2 times the
//                box-assisted time: scripts/measure/measure_kd_tree.sh compares the two case by case);
//   box-assisted: every N (at 10^6 one call takes about 3 minutes for M = 2 and more for larger
//                M: the pairs closer than 5 grow as N^2).
// Each benchmark runs one iteration per repetition for N >= 10^5, so the whole file is long; pick
// with --benchmark_filter, e.g. --benchmark_filter='Target' for the two target jobs.
//
// Target jobs (exact counts, no cap):
//   Henon x (a = 1.4, b = 0.3), N = 10^5, tau = 1, m = 1..4, 40 radii 0.005 .. 0.4, w = 10;
//   Lorenz x as above,          N = 10^5, tau = 17, m = 1..6, 40 radii 0.25 .. 5, w = 200;
// each with 1 and 2 threads (real time is reported, as the threads share the work).
// BM_TheilerWindowsLorenz: the Lorenz job at three Theiler windows, one call each against one call
// for all three.
// BM_Floor*: what two parts of a target job cost at the least, for judging how far the exact
// one-thread times can fall (docs/validation/performance-correlation-sum.md, "How far the one-thread time can fall").
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "chaos/correlation_sum.hpp"
#include "chaos/models/systems.hpp"

namespace {

using chaos::CorrelationSearch;

const std::vector<double>& lorenz_x(std::size_t n) {
  static std::map<std::size_t, std::vector<double>> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, chaos::lorenz(n).components[0]).first;
  return it->second;
}

const std::vector<double>& henon_x(std::size_t n) {
  static std::map<std::size_t, std::vector<double>> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, chaos::henon(n).components[0]).first;
  return it->second;
}

void report(benchmark::State& state, const chaos::CorrelationSumResult& r) {
  // Pairs closer than the largest radius in the largest dimension, and the admissible pairs.
  state.counters["pairs_rmax_mmax"] = static_cast<double>(r.pairs.back().back());
  state.counters["admissible"] = static_cast<double>(r.examined.front().front());
}

// One correlation_sum(x, o) per iteration, then the counters of its result.
void time_counts(benchmark::State& state, const std::vector<double>& x, const chaos::CorrelationSumOptions& o) {
  chaos::CorrelationSumResult r;
  for (auto _ : state) {
    r = chaos::correlation_sum(x, o);
    benchmark::DoNotOptimize(r.pairs.data());
  }
  report(state, r);
}

void search(benchmark::State& state, CorrelationSearch mode) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::vector<double>& x = lorenz_x(n);
  chaos::CorrelationSumOptions o;
  o.delay = 17;
  o.min_dimension = 1;
  o.max_dimension = static_cast<std::size_t>(state.range(1));
  o.theiler = 200;
  o.radii = chaos::log_radii(0.25, 5.0, 40);
  o.search = mode;
  time_counts(state, x, o);
}

void BM_BruteForce(benchmark::State& state) { search(state, CorrelationSearch::brute_force); }
void BM_KdTree(benchmark::State& state) { search(state, CorrelationSearch::kd_tree); }
void BM_BoxAssisted(benchmark::State& state) { search(state, CorrelationSearch::box_assisted); }

void sizes(benchmark::internal::Benchmark* b, std::int64_t largest) {
  for (std::int64_t n = 1000; n <= largest; n *= 10)
    for (const std::int64_t m : {2, 5, 10}) b->Args({n, m});
  b->ArgNames({"N", "m"})->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_BruteForce)->Apply([](auto* b) { sizes(b, 100'000); })->Iterations(1);
BENCHMARK(BM_KdTree)->Apply([](auto* b) { sizes(b, 100'000); })->Iterations(1);
BENCHMARK(BM_BoxAssisted)->Apply([](auto* b) { sizes(b, 1'000'000); })->Iterations(1);

chaos::CorrelationSumOptions henon_target() {
  chaos::CorrelationSumOptions o;
  o.delay = 1;
  o.min_dimension = 1;
  o.max_dimension = 4;
  o.theiler = 10;
  o.radii = chaos::log_radii(0.005, 0.4, 40);
  return o;
}

chaos::CorrelationSumOptions lorenz_target() {
  chaos::CorrelationSumOptions o;
  o.delay = 17;
  o.min_dimension = 1;
  o.max_dimension = 6;
  o.theiler = 200;
  o.radii = chaos::log_radii(0.25, 5.0, 40);
  return o;
}

// The series and options of a target job: Lorenz (lorenz = true) or Henon, N = 10^5.
const std::vector<double>& target_series(bool lorenz) { return lorenz ? lorenz_x(100'000) : henon_x(100'000); }
chaos::CorrelationSumOptions target_options(bool lorenz) { return lorenz ? lorenz_target() : henon_target(); }

void target(benchmark::State& state, bool lorenz) {
  chaos::CorrelationSumOptions o = target_options(lorenz);
  o.threads = static_cast<std::size_t>(state.range(0));
  time_counts(state, target_series(lorenz), o);
}

void BM_TargetHenon(benchmark::State& state) { target(state, false); }
void BM_TargetLorenz(benchmark::State& state) { target(state, true); }

void targets(benchmark::internal::Benchmark* b) {
  b->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
}
BENCHMARK(BM_TargetHenon)->Apply(targets);
BENCHMARK(BM_TargetLorenz)->Apply(targets);

// The Lorenz target job at three Theiler windows (200, 400, 600: the zoo grid's 1, 2 and 3 times
// w), one correlation_sum per window (range(0) = 0) against correlation_sums_over_theiler_windows
// (range(0) = 1); one thread. docs/reference/correlation_sum.md, "Several Theiler windows".
void BM_TheilerWindowsLorenz(benchmark::State& state) {
  const std::vector<double>& x = lorenz_x(100'000);
  chaos::CorrelationSumOptions o;
  o.delay = 17;
  o.max_dimension = 6;
  o.radii = chaos::log_radii(0.25, 5.0, 40);
  const std::vector<std::size_t> windows{200, 400, 600};
  std::vector<chaos::CorrelationSumResult> r;
  for (auto _ : state) {
    if (state.range(0) == 0) {
      r.clear();
      for (const std::size_t w : windows) {
        o.theiler = w;
        r.push_back(chaos::correlation_sum(x, o));
      }
    } else {
      r = chaos::correlation_sums_over_theiler_windows(x, o, windows);
    }
    benchmark::DoNotOptimize(r.data());
  }
  report(state, r.back());
}
BENCHMARK(BM_TheilerWindowsLorenz)->Arg(0)->Arg(1)->ArgName("together")->Unit(benchmark::kMillisecond)->Iterations(1);

// Floors of the exact target jobs (range(0): 0 Henon, 1 Lorenz; one thread).
//
// BM_FloorIncrements: the histogram increments alone. The box-assisted walk bins every pair closer
// than r_max once in each m >= 3 (m = 2 is counted by the plane sweeps, m = 1 by sorting). This
// makes exactly that many increments, of counters laid out as the walk's (4 interleaved copies of
// a [m][bin] histogram of 64-bit counts), at (m, bin) drawn from the job's own pair counts in a
// seeded random order, replayed from a table of 4096 that stays in the L1 cache. Nothing else: no
// distance, no filter, no bin lookup, and fewer runs of one bin in a row than a trajectory gives
// (a run makes each increment wait for the previous one). So it is a lower bound on the binning
// of any method that bins each close pair once per m.
//
// BM_FloorPlane: the job restricted to m = 2 (min = max = 2), which the library counts with the
// plane sweeps of docs/reference/correlation_sum.md (step 4) and the window subtraction, without the grid.
//
// The job itself (BM_TargetHenon, BM_TargetLorenz) also filters the candidates of the grid; the two
// floors together leave what that filter may cost within a target time.
const chaos::CorrelationSumResult& floor_job(bool lorenz) {
  static std::map<bool, chaos::CorrelationSumResult> cache;
  auto it = cache.find(lorenz);
  if (it == cache.end())
    it = cache.emplace(lorenz, chaos::correlation_sum(target_series(lorenz), target_options(lorenz))).first;
  return it->second;
}

void BM_FloorIncrements(benchmark::State& state) {
  const chaos::CorrelationSumResult& exact = floor_job(state.range(0) == 1);
  const std::size_t nr = exact.radius.size();
  // Weights of (m >= 3, bin): the pairs whose distance lies in [r_{k-1}, r_k).
  std::vector<std::size_t> cell;
  std::vector<double> weight;
  std::uint64_t increments = 0;
  for (std::size_t mi = 0; mi < exact.dimension.size(); ++mi) {
    if (exact.dimension[mi] < 3) continue;
    for (std::size_t k = 0; k < nr; ++k) {
      const std::uint64_t in_bin = exact.pairs[mi][k] - (k > 0 ? exact.pairs[mi][k - 1] : 0);
      cell.push_back(mi * nr + k);
      weight.push_back(static_cast<double>(in_bin));
      increments += in_bin;
    }
  }
  std::mt19937_64 rng(1);
  std::discrete_distribution<std::size_t> draw(weight.begin(), weight.end());
  constexpr std::size_t table = 4096, copies = 4;
  std::vector<std::uint32_t> slot(table);
  for (std::uint32_t& s : slot) s = static_cast<std::uint32_t>(cell[draw(rng)] * copies);
  std::vector<std::uint64_t> h(exact.dimension.size() * nr * copies);
  for (auto _ : state) {
    std::fill(h.begin(), h.end(), 0);
    std::uint64_t done = 0;
    while (done < increments) {
      const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(table, increments - done)) / copies * copies;
      if (n == 0) {
        ++h[slot[0]];
        ++done;
        continue;
      }
      for (std::size_t u = 0; u < n; u += copies) {
        ++h[slot[u]];
        ++h[slot[u + 1] + 1];
        ++h[slot[u + 2] + 2];
        ++h[slot[u + 3] + 3];
      }
      done += n;
    }
    benchmark::DoNotOptimize(h.data());
    benchmark::ClobberMemory();
  }
  state.counters["increments"] = static_cast<double>(increments);
  state.counters["ns_per_increment"] = benchmark::Counter(
      static_cast<double>(increments), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_FloorPlane(benchmark::State& state) {
  const bool lorenz = state.range(0) == 1;
  chaos::CorrelationSumOptions o = target_options(lorenz);
  o.min_dimension = 2;
  o.max_dimension = 2;
  time_counts(state, target_series(lorenz), o);
}

void floors(benchmark::internal::Benchmark* b) {
  b->Arg(0)->Arg(1)->ArgName("lorenz")->Unit(benchmark::kMillisecond)->Iterations(3);
}
BENCHMARK(BM_FloorIncrements)->Apply(floors);
BENCHMARK(BM_FloorPlane)->Apply(floors);

}  // namespace
