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

// Found by a sweep at --periods 3 --keep 1: at 5000 rpm (T = 0.012 s) a transient of
// 2 T plus a duration of T sum to 0.036000000000000004 s, while RK4's last step ended at
// 36000 h = 0.036 s, just short of it: the run stopped there and the last revolution (t = 3 T,
// the only one kept) was never written. Expected: the run ends at its end time and writes
// revolutions 2 and 3 (the transient's end and the run's), as the definition says.
TEST(OutputTimes, Rk4LastStepLandsOnTheEnd) {
  mechanism::Scene scene = mechanism::read_scene("", {});
  const double period = scene.driver.period();
  scene.run.transient = 2 * period;
  scene.run.duration = 1 * period;
  scene.run.output_interval = 0;
  scene.run.stroboscopic = true;
  ASSERT_GT(scene.run.transient + scene.run.duration, 36000.0 * (period / 12000.0));  // the rounding above
  mechanism::SliderCrank system(scene);
  std::vector<std::size_t> revolutions;
  mechanism::SimulationObserver observer;
  observer.stroboscopic = [&](std::size_t rev, double, const mechanism::State&, const mechanism::Evaluation&) {
    revolutions.push_back(rev);
  };
  const mechanism::SimulationSummary s = mechanism::simulate(system, observer);
  EXPECT_EQ(s.end_time, scene.run.transient + scene.run.duration);
  EXPECT_EQ(revolutions, (std::vector<std::size_t>{2, 3}));
}
