// Output times that fall within rounding after an inner step's end. Found by a study sweep: at
// 2800 rpm, c_t = 0.3 mm, sigma1 fading and dopri5 at rtol 1e-4, a dopri5 step ended a few
// 1e-12 s before revolution 154 (t = 3.3 s); the loop took the revolution as due in that step and
// asked the dense output for a time past its end, which it refuses. Expected: the run completes
// and writes exactly one stroboscopic sample per revolution, at t = k T (the definition).
#include <gtest/gtest.h>

#include <cmath>

#include "mechanism/simulate.hpp"

namespace {

TEST(OutputTimes, RevolutionJustAfterAStepEndIsWritten) {
  mechanism::Scene scene = mechanism::read_scene(
      "", {"driver.speed_rpm=2800.0", "joint.slider.clearance=0.0003", "joint.slider.friction.sigma1_velocity=1e-3",
           "integrator.method=\"dopri5\"", "integrator.relative_tolerance=1e-4"});
  const double period = scene.driver.period();
  scene.run.transient = 150 * period;
  scene.run.duration = 10 * period;  // revolutions 150 .. 160, t = 3.3 s is revolution 154
  scene.run.output_interval = 0;
  scene.run.stroboscopic = true;
  mechanism::SliderCrank system(scene);
  std::vector<std::size_t> revolutions;
  mechanism::SimulationObserver observer;
  observer.stroboscopic = [&](std::size_t rev, double t, const mechanism::State&, const mechanism::Evaluation&) {
    revolutions.push_back(rev);
    EXPECT_NEAR(t, static_cast<double>(rev) * period, 1e-12 * t);
  };
  const mechanism::SimulationSummary s = mechanism::simulate(system, observer);
  ASSERT_EQ(s.status, mechanism::SimulationStatus::completed) << s.message;
  ASSERT_EQ(revolutions.size(), 11u);
  for (std::size_t k = 0; k < revolutions.size(); ++k) EXPECT_EQ(revolutions[k], 150 + k);
}

}  // namespace
