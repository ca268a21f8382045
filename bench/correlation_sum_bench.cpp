// Correlation sums: brute force, kd-tree and box-assisted search on the same job, and the two
// target jobs of docs/correlation_sum.md. Inputs (series, radii) are built before the timed loop.
//
// Search comparison: Lorenz x (sigma 10, rho 28, beta 8/3, dt = 0.01, RK4 step 0.001), tau = 17,
// Theiler window w = 200, 40 log-spaced radii from 0.25 to 5, C(eps, m) for m = 1 .. M in one call
// with M in {2, 5, 10}, one thread, N in {10^3, 10^4, 10^5, 10^6}.
//   brute force: N <= 10^5 only (O(N^2) pairs: about a minute at 10^5, so well over an hour at
//                10^6);
//   kd-tree:     N <= 10^5 (one traversal per point for all radii and dimensions, 1-2 times the
//                box-assisted time: scripts/measure_kd_tree.sh compares the two case by case);
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
#include <benchmark/benchmark.h>

#include <cstdint>
#include <map>
#include <vector>

#include "chaos/correlation_sum.hpp"
#include "chaos/systems.hpp"

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
  chaos::CorrelationSumResult r;
  for (auto _ : state) {
    r = chaos::correlation_sum(x, o);
    benchmark::DoNotOptimize(r.pairs.data());
  }
  report(state, r);
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

void BM_TargetHenon(benchmark::State& state) {
  const std::vector<double>& x = henon_x(100'000);
  chaos::CorrelationSumOptions o;
  o.delay = 1;
  o.min_dimension = 1;
  o.max_dimension = 4;
  o.theiler = 10;
  o.radii = chaos::log_radii(0.005, 0.4, 40);
  o.threads = static_cast<std::size_t>(state.range(0));
  chaos::CorrelationSumResult r;
  for (auto _ : state) {
    r = chaos::correlation_sum(x, o);
    benchmark::DoNotOptimize(r.pairs.data());
  }
  report(state, r);
}

void BM_TargetLorenz(benchmark::State& state) {
  const std::vector<double>& x = lorenz_x(100'000);
  chaos::CorrelationSumOptions o;
  o.delay = 17;
  o.min_dimension = 1;
  o.max_dimension = 6;
  o.theiler = 200;
  o.radii = chaos::log_radii(0.25, 5.0, 40);
  o.threads = static_cast<std::size_t>(state.range(0));
  chaos::CorrelationSumResult r;
  for (auto _ : state) {
    r = chaos::correlation_sum(x, o);
    benchmark::DoNotOptimize(r.pairs.data());
  }
  report(state, r);
}

void targets(benchmark::internal::Benchmark* b) {
  b->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
}
BENCHMARK(BM_TargetHenon)->Apply(targets);
BENCHMARK(BM_TargetLorenz)->Apply(targets);

// The Lorenz target job at three Theiler windows (200, 400, 600: the zoo grid's 1, 2 and 3 times
// w), one correlation_sum per window (range(0) = 0) against correlation_sums_over_theiler_windows
// (range(0) = 1); one thread. docs/correlation_sum.md, "Several Theiler windows".
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

}  // namespace
