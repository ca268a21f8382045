// The energy check on a finished run (simulate.hpp, max_energy_defect_per_revolution): a hostile-input
// case, 1e-6 m clearance at 50 rpm on the scene as printed (face contact, exponent 1.5, absolute
// LuGre with a constant sigma1: once the built-in reading), reported
// `completed` with energy_balance_relative 0.53 after 3 revolutions. Half a revolution of it is
// measured at 0.075 (counted as one revolution, 2.5 times the limit of 0.03); the same run with
// sigma1 fading (the scene's own warning) measures 3e-11 and must stay completed, so the check
// flags the integration, not the slow speed or the small clearance.
// The per-step check: the built-in scene at 0.5 mm on dopri5 with rtol 3e-2 and steps up to 1e-3 s
// accepts steps that push the slider 7 mm into the guide, yet its balance grows by only 0.022 of the
// (inflated) largest kinetic energy per revolution, under the limit; one of its steps changes the
// balance by 56 times the kinetic energy before it.
#include <gtest/gtest.h>

#include <string>

#include "mechanism/simulate.hpp"

namespace {

mechanism::Scene slow_tight_scene(std::vector<std::string> extra = {}) {
  std::vector<std::string> overrides{"joint.slider.model=face", "joint.slider.contact.exponent=1.5",
                                     "joint.slider.friction.law=lugre_absolute",
                                     "joint.slider.friction.sigma1_velocity=0",
                                     "joint.slider.clearance=1e-6",
                                     "driver.speed_rpm=50",
                                     "run.duration=0.6",
                                     "run.output_interval=0"};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return mechanism::read_scene("", overrides);
}

TEST(EnergyCheck, IssueCaseIsNotCompleted) {
  mechanism::SliderCrank system(slow_tight_scene());
  const mechanism::SimulationSummary s = mechanism::simulate(system);
  EXPECT_EQ(s.status, mechanism::SimulationStatus::energy_defect);
  EXPECT_STREQ(mechanism::to_string(s.status), "energy_defect");
  EXPECT_GT(s.energy_balance_relative, mechanism::max_energy_defect_per_revolution);
  EXPECT_NE(s.message.find("the energy balance is off by"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("above the limit 0.03"), std::string::npos) << s.message;
  // The run still reached its end: the outputs are whole, only their trust is withdrawn.
  EXPECT_DOUBLE_EQ(s.end_time, 0.6);
}

TEST(EnergyCheck, ResolvedRunOfTheSameCaseIsCompleted) {
  mechanism::SliderCrank system(slow_tight_scene({"joint.slider.friction.sigma1_velocity=1e-3"}));
  const mechanism::SimulationSummary s = mechanism::simulate(system);
  EXPECT_EQ(s.status, mechanism::SimulationStatus::completed) << s.message;
  EXPECT_LT(s.energy_balance_relative, 1e-6 * mechanism::max_energy_defect_per_revolution);
}

TEST(EnergyCheck, OneStepBeyondARevolutionsAllowanceIsNotCompleted) {
  mechanism::SliderCrank system(mechanism::read_scene(
      "", {"integrator.method=dopri5", "integrator.relative_tolerance=3e-2", "integrator.max_step=1e-3",
           "run.duration=0.6", "run.output_interval=0"}));
  const mechanism::SimulationSummary s = mechanism::simulate(system);
  const double revolutions = s.end_time / system.scene().driver.period();
  ASSERT_LT(s.energy_balance_relative / revolutions, mechanism::max_energy_defect_per_revolution)
      << "the case no longer shows what the average misses";
  EXPECT_GT(s.max_penetration, 10 * system.scene().slider_guide.clearance);  // what the average let through
  EXPECT_EQ(s.status, mechanism::SimulationStatus::energy_defect);
  EXPECT_GT(s.energy_jump_relative, mechanism::max_energy_defect_per_revolution);
  EXPECT_NE(s.message.find("one step changed the energy balance by"), std::string::npos) << s.message;
}

TEST(EnergyCheck, TheBuiltInSceneOnItsOwnIntegratorHasNoLargeStep) {
  // RK4 at 1e-6 s, 0.5 mm: the largest step change measured over 1.2 s is 8e-9 of the kinetic
  // energy (docs/reference/mechanism/model.md); the band leaves a factor 100 above that, and the limit (0.03)
  // is far above both.
  mechanism::SliderCrank system(mechanism::read_scene("", {"run.duration=0.12", "run.output_interval=0"}));
  const mechanism::SimulationSummary s = mechanism::simulate(system);
  EXPECT_EQ(s.status, mechanism::SimulationStatus::completed) << s.message;
  EXPECT_GT(s.energy_jump_relative, 0.0);
  EXPECT_LT(s.energy_jump_relative, 1e-6);
}

}  // namespace
