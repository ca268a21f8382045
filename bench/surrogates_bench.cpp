// Surrogates (FT, AAFT, IAAFT) of Lorenz x (dt = 0.05) at N = 10^4, 10^5, 10^6 with the generator
// (FFTW plans, sorted values, amplitudes) built outside the timed loop; the IAAFT counters give the
// iterations to the fixed point and the final spectral deviation. Also the Lorenz, Rossler and
// Henon spectra at their default settings, and one nonlinearity test (N = 1024, K = 39).
// Single thread.
#include <benchmark/benchmark.h>

#include <map>
#include <vector>

#include "chaos/models/lyapunov_spectrum.hpp"
#include "chaos/nonlinearity_test.hpp"
#include "chaos/surrogates.hpp"
#include "chaos/models/systems.hpp"

namespace {

const std::vector<double>& lorenz_x(std::size_t n) {
  static std::map<std::size_t, std::vector<double>> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, chaos::lorenz(n, {}, {0.05, 0.005, 100.0}).components[0]).first;
  return it->second;
}

void surrogate(benchmark::State& state, chaos::SurrogateMethod method) {
  const auto& x = lorenz_x(static_cast<std::size_t>(state.range(0)));
  chaos::SurrogateGenerator generator(x, {method});
  std::uint64_t seed = 1;
  double iterations = 0.0, deviation = 0.0;
  for (auto _ : state) {
    const auto s = generator.generate(seed++);
    iterations += static_cast<double>(s.iterations);
    deviation += s.spectral_deviation;
    benchmark::DoNotOptimize(s.values.data());
  }
  state.counters["iterations"] = benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
  state.counters["deviation"] = benchmark::Counter(deviation, benchmark::Counter::kAvgIterations);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

// Plans, sorting and the data's spectrum: the part a generator saves when reused.
void surrogate_generator_setup(benchmark::State& state) {
  const auto& x = lorenz_x(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(chaos::SurrogateGenerator(x));
}

void lorenz_spectrum(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(chaos::lorenz_spectrum());
}
void rossler_spectrum(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(chaos::rossler_spectrum());
}
void henon_spectrum(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(chaos::henon_spectrum());
}

void nonlinearity_test(benchmark::State& state, chaos::NonlinearityStatistic statistic) {
  const auto x = chaos::henon(1024).components[0];
  chaos::NonlinearityTestOptions o;
  o.statistic = statistic;
  for (auto _ : state) benchmark::DoNotOptimize(chaos::nonlinearity_test(x, o));
}

BENCHMARK_CAPTURE(surrogate, fourier, chaos::SurrogateMethod::fourier)
    ->RangeMultiplier(10)->Range(10'000, 1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(surrogate, aaft, chaos::SurrogateMethod::aaft)
    ->RangeMultiplier(10)->Range(10'000, 1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(surrogate, iaaft, chaos::SurrogateMethod::iaaft)
    ->Arg(10'000)->Arg(100'000)->Unit(benchmark::kMillisecond);
// One IAAFT surrogate of 10^6 points takes seconds: timed once.
BENCHMARK_CAPTURE(surrogate, iaaft, chaos::SurrogateMethod::iaaft)
    ->Arg(1'000'000)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(surrogate_generator_setup)->RangeMultiplier(10)->Range(10'000, 1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(lorenz_spectrum)->Unit(benchmark::kMillisecond);
BENCHMARK(rossler_spectrum)->Unit(benchmark::kMillisecond);
BENCHMARK(henon_spectrum)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(nonlinearity_test, prediction_error, chaos::NonlinearityStatistic::prediction_error)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(nonlinearity_test, time_reversal, chaos::NonlinearityStatistic::time_reversal_asymmetry)
    ->Unit(benchmark::kMillisecond);

}  // namespace
