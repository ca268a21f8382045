// The simulator's costs on the seed scene (5000 rpm, translational clearance 0.5 mm, LuGre as the
// seed prints it) and on the same scene without friction:
//   RightHandSide     one evaluation of the equations of motion at a pose in contact (the unit
//                     every integrator pays per stage);
//   RightHandSideJets the same pose through the general kinematic jets, which every topology but
//                     the seed's uses (the seed's takes a closed form); SliderCrank::evaluate_with_jets
//                     also copies into an Evaluation;
//   CrankPeriod       one simulated crank period (12 ms) from the seed's initial conditions, with
//                     RK4 at 1e-6 s and with Dormand-Prince 5(4) at rtol 1e-4 (the cheapest
//                     setting that keeps the seed scene's long-run statistics), 1e-6 and 1e-9.
// Scenes are read outside the timed loop.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "mechanism/scene.hpp"
#include "mechanism/simulate.hpp"

namespace {

std::vector<std::string> friction_override(std::int64_t with_friction) {
  return with_friction ? std::vector<std::string>{} : std::vector<std::string>{"joint.slider.friction.law=none"};
}

void RightHandSide(benchmark::State& state) {
  const mechanism::SliderCrank sys(mechanism::read_scene("", friction_override(state.range(0))));
  mechanism::State x = sys.initial_state();
  x[0] = std::asin(-0.52e-3 / 0.12);  // slider 0.02 mm into the lower surface
  x[1] = 1e-3;
  mechanism::State dx(x.size());
  for (auto _ : state) {
    sys.rhs(0.0, x, dx);
    benchmark::DoNotOptimize(dx.data());
  }
}
BENCHMARK(RightHandSide)->ArgName("friction")->Arg(1)->Arg(0);

void RightHandSideJets(benchmark::State& state) {
  const mechanism::SliderCrank sys(mechanism::read_scene("", friction_override(state.range(0))));
  mechanism::State x = sys.initial_state();
  x[0] = std::asin(-0.52e-3 / 0.12);
  x[1] = 1e-3;
  mechanism::Evaluation ev;
  for (auto _ : state) {
    sys.evaluate_with_jets(0.0, x, ev);
    benchmark::DoNotOptimize(ev.q_ddot.data());
  }
}
BENCHMARK(RightHandSideJets)->ArgName("friction")->Arg(1)->Arg(0);

void CrankPeriod(benchmark::State& state, std::vector<std::string> integrator) {
  auto overrides = friction_override(state.range(0));
  overrides.insert(overrides.end(), integrator.begin(), integrator.end());
  overrides.push_back("run.duration=0.012");
  overrides.push_back("run.output_interval=0");
  const mechanism::Scene scene = mechanism::read_scene("", overrides);
  std::size_t steps = 0;
  for (auto _ : state) {
    mechanism::SliderCrank sys(scene);
    const auto summary = mechanism::simulate(sys);
    steps += summary.steps + summary.rejected_steps;
    benchmark::DoNotOptimize(summary.max_penetration);
  }
  state.counters["steps_per_period"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kAvgIterations);
}
BENCHMARK_CAPTURE(CrankPeriod, rk4_1e-6, {"integrator.method=rk4", "integrator.step=1e-6"})
    ->ArgName("friction")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(CrankPeriod, dopri5_1e-4, {"integrator.method=dopri5", "integrator.relative_tolerance=1e-4"})
    ->ArgName("friction")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(CrankPeriod, dopri5_1e-6,
                  {"integrator.method=dopri5", "integrator.relative_tolerance=1e-6", "integrator.absolute_tolerance=1e-9"})
    ->ArgName("friction")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(CrankPeriod, dopri5_1e-9,
                  {"integrator.method=dopri5", "integrator.relative_tolerance=1e-9", "integrator.absolute_tolerance=1e-12"})
    ->ArgName("friction")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace
