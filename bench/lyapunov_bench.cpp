// The largest Lyapunov exponent from a series, Rosenstein and Kantz, at N = 10^4, 10^5, 10^6,
// single thread, inputs generated outside the timed loop:
//   map:  Hénon x, m = 2, tau = 1, w = 0, K = 20 steps (the reference row's settings);
//   flow: Lorenz x at dt = 0.01, m = 3, tau = 17, w = 100, K = 500 steps (the reference row's
//         settings), Kantz with the default eps = range / 1000.
// Each run is the whole estimate: kd-tree, neighbour searches, the divergence curve and the fit.
// Counters: the exponent found (per sample) and the neighbours per reference point.
// Tied data: the flow's Lorenz x quantised to 3 levels, beside the same settings on the untied
// series (quantised_lorenz / untied_lorenz at 10^4): tie groups in Kantz's neighbourhoods are
// thinned, so the two cost about the same (pairs: pairs followed per reference point).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "chaos/lyapunov.hpp"
#include "chaos/models/systems.hpp"

namespace {

const std::vector<double>& series(bool flow, std::size_t n) {
  static std::map<std::pair<bool, std::size_t>, std::vector<double>> cache;
  auto it = cache.find({flow, n});
  if (it == cache.end())
    it = cache.emplace(std::make_pair(flow, n), flow ? chaos::lorenz(n).components[0] : chaos::henon(n).components[0]).first;
  return it->second;
}

void largest_lyapunov(benchmark::State& state, chaos::LyapunovMethod method, bool flow) {
  const auto& x = series(flow, static_cast<std::size_t>(state.range(0)));
  chaos::LyapunovOptions o;
  o.method = method;
  if (flow) {
    o.dimension = 3;
    o.delay = 17;
    o.theiler = 100;
    o.steps = 500;
  } else {
    o.dimension = 2;
    o.delay = 1;
    o.steps = 20;
  }
  double lambda = 0.0, neighbours = 0.0;
  for (auto _ : state) {
    const auto r = chaos::largest_lyapunov(x, o);
    lambda = r.fit.lambda.value_or(0.0);
    neighbours = r.curve.mean_neighbours;
    benchmark::DoNotOptimize(r.curve.divergence.data());
  }
  state.counters["lambda_per_sample"] = lambda;
  state.counters["neighbours"] = neighbours;
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK_CAPTURE(largest_lyapunov, rosenstein_henon, chaos::LyapunovMethod::rosenstein, false)
    ->RangeMultiplier(10)->Range(10'000, 1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(largest_lyapunov, kantz_henon, chaos::LyapunovMethod::kantz, false)
    ->RangeMultiplier(10)->Range(10'000, 1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(largest_lyapunov, rosenstein_lorenz, chaos::LyapunovMethod::rosenstein, true)
    ->Arg(10'000)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(largest_lyapunov, kantz_lorenz, chaos::LyapunovMethod::kantz, true)
    ->Arg(10'000)->Arg(100'000)->Unit(benchmark::kMillisecond);
// 5 10^8 pair distances (Rosenstein) and several times that (Kantz): timed once.
BENCHMARK_CAPTURE(largest_lyapunov, rosenstein_lorenz, chaos::LyapunovMethod::rosenstein, true)
    ->Arg(1'000'000)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(largest_lyapunov, kantz_lorenz, chaos::LyapunovMethod::kantz, true)
    ->Arg(1'000'000)->Iterations(1)->Unit(benchmark::kMillisecond);

// Lorenz x (flow settings, K = 100) untied or quantised to 3 levels, floor(3 (x - min) / (max - min)).
void tied_lorenz(benchmark::State& state, chaos::LyapunovMethod method, bool tied) {
  std::vector<double> x = series(true, static_cast<std::size_t>(state.range(0)));
  if (tied) {
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    const double low = *lo, high = *hi;
    for (double& v : x) v = std::min(2.0, std::floor(3.0 * (v - low) / (high - low)));
  }
  chaos::LyapunovOptions o;
  o.method = method;
  o.dimension = 3;
  o.delay = 17;
  o.theiler = 100;
  o.steps = 100;
  double pairs = 0.0;
  for (auto _ : state) {
    const auto c = chaos::divergence_curve(x, o);
    pairs = static_cast<double>(c.pairs_followed) / static_cast<double>(std::max<std::size_t>(1, c.references_used));
    benchmark::DoNotOptimize(c.divergence.data());
  }
  state.counters["pairs"] = pairs;
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK_CAPTURE(tied_lorenz, kantz_untied_lorenz, chaos::LyapunovMethod::kantz, false)
    ->Arg(10'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(tied_lorenz, kantz_quantised_lorenz, chaos::LyapunovMethod::kantz, true)
    ->Arg(10'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(tied_lorenz, rosenstein_untied_lorenz, chaos::LyapunovMethod::rosenstein, false)
    ->Arg(10'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(tied_lorenz, rosenstein_quantised_lorenz, chaos::LyapunovMethod::rosenstein, true)
    ->Arg(10'000)->Unit(benchmark::kMillisecond);

}  // namespace
