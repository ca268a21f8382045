// simulate(system, start, observer): a run from a given state (parameter continuation). From the
// seed's initial state it is the plain run, bit for bit (the same code path); a start of the
// wrong size or with non-finite values is refused; the work accumulators restart at zero, so the
// energy balance of a continued run holds from its own start (a property of the balance).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mechanism/expect_invalid.hpp"
#include "mechanism/simulate.hpp"

namespace {

mechanism::Scene short_scene() {
  mechanism::Scene s = mechanism::read_scene("", {"run.duration=0.024", "joint.slider.friction.sigma1_velocity=1e-3",
                                                  "integrator.method=\"dopri5\"", "integrator.relative_tolerance=1e-6"});
  s.run.output_interval = 0;
  return s;
}

TEST(SimulateFromState, InitialStateIsThePlainRun) {
  mechanism::SliderCrank a(short_scene()), b(short_scene());
  const auto plain = mechanism::simulate(a);
  const auto from = mechanism::simulate(b, b.initial_state());
  ASSERT_EQ(plain.status, mechanism::SimulationStatus::completed);
  EXPECT_EQ(plain.steps, from.steps);
  EXPECT_EQ(plain.final_state, from.final_state);
  EXPECT_EQ(plain.final_state.size(), a.state_size());
}

TEST(SimulateFromState, RefusesABadStart) {
  mechanism::SliderCrank system(short_scene());
  mechanism::testing::expect_invalid("start state", [&] { mechanism::simulate(system, mechanism::State::Zero(2)); });
  mechanism::State x = system.initial_state();
  x[0] = std::numeric_limits<double>::quiet_NaN();
  mechanism::testing::expect_invalid("start state", [&] { mechanism::simulate(system, x); });
}

TEST(SimulateFromState, ContinuedRunBalancesItsOwnEnergy) {
  mechanism::SliderCrank first(short_scene());
  const auto one = mechanism::simulate(first);
  mechanism::SliderCrank second(short_scene());
  const auto two = mechanism::simulate(second, one.final_state);
  ASSERT_EQ(two.status, mechanism::SimulationStatus::completed);
  const int n = second.coordinate_count();
  // Had the first run's work been carried over, the balance of the second run would be off by
  // that work; it is a hundred times smaller than it.
  const double carried = std::abs(one.final_state[2 * n] + one.final_state[2 * n + 1]);
  ASSERT_GT(carried, 1e-3);
  EXPECT_LT(two.energy_balance_error, 0.01 * carried);
}

}  // namespace
