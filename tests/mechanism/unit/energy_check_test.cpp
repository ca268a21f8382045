// The energy check on a finished run (simulate.hpp, max_energy_defect_per_revolution): issue 16's
// case, 1e-6 m clearance at 50 rpm on the scene as printed (face contact, exponent 1.5, absolute
// LuGre with a constant sigma1: the built-in reading before issue 12), reported
// `completed` with energy_balance_relative 0.53 after 3 revolutions. Half a revolution of it is
// measured at 0.075 (counted as one revolution, 2.5 times the limit of 0.03); the same run with
// sigma1 fading (the scene's own warning) measures 3e-11 and must stay completed, so the check
// flags the integration, not the slow speed or the small clearance.
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

}  // namespace
