// Delay-selection estimators on Lorenz x (dt = 0.01) at N = 10^4, 10^5, 10^6, single thread:
// mutual information (16 boxes, delays 0..20, both estimators) and the FFT autocorrelation
// (lags 0..20 and 0..N/10). Inputs are generated once, outside the timed loops.
#include <benchmark/benchmark.h>

#include <map>
#include <vector>

#include "chaos/autocorrelation.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/models/systems.hpp"

namespace {

const std::vector<double>& lorenz_x(std::size_t n) {
  static std::map<std::size_t, std::vector<double>> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, chaos::lorenz(n).components[0]).first;
  return it->second;
}

void mutual_information(benchmark::State& state, chaos::MutualInformationEstimator estimator) {
  const auto& x = lorenz_x(static_cast<std::size_t>(state.range(0)));
  const chaos::MutualInformationOptions options{20, 16, estimator};
  for (auto _ : state) benchmark::DoNotOptimize(chaos::mutual_information(x, options));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void autocorrelation(benchmark::State& state) {
  const auto& x = lorenz_x(static_cast<std::size_t>(state.range(0)));
  const auto max_lag = static_cast<std::size_t>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(chaos::autocorrelation(x, max_lag));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK_CAPTURE(mutual_information, equal_width, chaos::MutualInformationEstimator::equal_width)
    ->RangeMultiplier(10)->Range(10'000, 1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(mutual_information, equiprobable, chaos::MutualInformationEstimator::equiprobable)
    ->RangeMultiplier(10)->Range(10'000, 1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(autocorrelation)
    ->Args({10'000, 20})->Args({100'000, 20})->Args({1'000'000, 20})
    ->Args({10'000, 1'000})->Args({100'000, 10'000})->Args({1'000'000, 100'000})
    ->Unit(benchmark::kMillisecond);

}  // namespace
