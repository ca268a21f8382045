// Embedding-dimension workloads on Lorenz x (sigma 10, rho 28, beta 8/3, dt = 0.01, tau = 17,
// Theiler window 100), single thread, at N = 10^4, 10^5, 10^6:
//   KdTreeAllNearest  build the tree on the m-dimensional delay embedding and find every point's
//                     nearest admissible neighbour, searching in index order;
//   AllNearest        the same through chaos::all_nearest, which searches in the tree's leaf order
//                     (what Cao and FNN do once per m);
//   Cao               the whole of cao() for m = 1..10 (11 trees, since E1(10) needs E(11));
//   KdTreeBuild       the tree alone on 1 or 2 threads (the same tree for any number).
// The series is generated once per N, outside the timed loop.
#include <benchmark/benchmark.h>

#include <map>
#include <vector>

#include "chaos/cao.hpp"
#include "chaos/embedding.hpp"
#include "chaos/neighbors.hpp"
#include "chaos/models/systems.hpp"

namespace {

constexpr std::size_t tau = 17;
constexpr std::size_t theiler = 100;

const std::vector<double>& lorenz_x(std::size_t n) {
  static std::map<std::size_t, std::vector<double>> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, chaos::lorenz(n).components[0]).first;
  return it->second;
}

// Builds the tree on the m-dimensional embedding and hands it to `search` once per iteration.
template <class Search>
void nearest_of_every_point(benchmark::State& state, const Search& search) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto m = static_cast<std::size_t>(state.range(1));
  const auto& x = lorenz_x(n);
  for (auto _ : state) {
    const chaos::DelayEmbedding points(x, m, tau);
    const chaos::KdTree tree(points, chaos::Norm::max);
    search(points, tree);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}

void KdTreeAllNearest(benchmark::State& state) {
  nearest_of_every_point(state, [](const chaos::DelayEmbedding& points, const chaos::KdTree& tree) {
    double sum = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) sum += tree.nearest(i, {theiler, true})->distance;
    benchmark::DoNotOptimize(sum);
  });
}

void AllNearest(benchmark::State& state) {
  nearest_of_every_point(state, [](const chaos::DelayEmbedding&, const chaos::KdTree& tree) {
    const auto nearest = chaos::all_nearest(tree, {theiler, true});
    benchmark::DoNotOptimize(nearest.data());
  });
}

void Cao(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto& x = lorenz_x(n);
  chaos::CaoOptions options;
  options.delay = tau;
  options.theiler = theiler;
  options.max_dimension = 10;
  for (auto _ : state) {
    const auto result = chaos::cao(x, options);
    benchmark::DoNotOptimize(result.E1.data());
  }
}

void KdTreeBuild(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto m = static_cast<std::size_t>(state.range(1));
  const auto threads = static_cast<std::size_t>(state.range(2));
  const auto& x = lorenz_x(n);
  const chaos::DelayEmbedding points(x, m, tau);
  for (auto _ : state) {
    const chaos::KdTree tree(points, chaos::Norm::max, 8, threads);
    benchmark::DoNotOptimize(tree.leaf_order().data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}

}  // namespace

BENCHMARK(KdTreeBuild)->ArgNames({"N", "m", "threads"})->Args({100000, 3, 1})->Args({100000, 3, 2})
    ->Args({1000000, 3, 1})->Args({1000000, 3, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(KdTreeAllNearest)->ArgNames({"N", "m"})->Args({10000, 3})->Args({100000, 3})->Args({10000, 10})
    ->Args({100000, 10})->Unit(benchmark::kMillisecond);
BENCHMARK(KdTreeAllNearest)->ArgNames({"N", "m"})->Args({1000000, 3})->Args({1000000, 10})
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(AllNearest)->ArgNames({"N", "m"})->Args({10000, 3})->Args({100000, 3})->Args({10000, 10})
    ->Args({100000, 10})->Unit(benchmark::kMillisecond);
BENCHMARK(AllNearest)->ArgNames({"N", "m"})->Args({1000000, 3})->Args({1000000, 10})
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(Cao)->ArgName("N")->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(Cao)->ArgName("N")->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(1);
