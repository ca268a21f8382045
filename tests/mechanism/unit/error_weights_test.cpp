// SliderCrank::error_weights: the adaptive stepper's error norm leaves out exactly the bristle
// deflections that commit() would reset (a LuGre site open at the step end). Expected values from
// the geometry: at Eq. 29's initial pose the slider is centred (every site open); tilted by
// 0.05 rad its corners reach 25 mm x 0.05 = 1.25 mm > the 0.5 mm clearance, so both faces touch.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "mechanism/simulate.hpp"

namespace {

TEST(ErrorWeights, OnlyOpenBristlesAreLeftOut) {
  const mechanism::Scene scene = mechanism::read_scene("");
  mechanism::SliderCrank system(scene);
  ASSERT_GT(system.state_size(), 2 * system.coordinate_count() + 2);  // LuGre: bristle states present
  mechanism::State x = system.initial_state(), w;
  system.error_weights(0.0, x, w);
  ASSERT_EQ(w.size(), x.size());
  for (std::size_t i = 0; i < system.site_count(); ++i) {
    const int k = system.bristle_index(i);
    if (k >= 0) {
      EXPECT_EQ(w[k], 0.0) << "site " << i << " is open at the initial pose";
    }
  }
  for (int k = 0; k < 2 * system.coordinate_count() + 2; ++k) EXPECT_EQ(w[k], 1.0);

  const auto names = system.coordinate_names();
  const auto angle = std::find(names.begin(), names.end(), "slider_angle") - names.begin();
  x[angle] = 0.05;
  mechanism::Evaluation ev;
  system.evaluate(0.0, x, ev);
  system.error_weights(0.0, x, w);
  std::size_t touching = 0;
  for (std::size_t i = 0; i < system.site_count(); ++i) {
    const int k = system.bristle_index(i);
    if (k < 0) continue;
    EXPECT_EQ(w[k], ev.sites[i].penetration > 0.0 ? 1.0 : 0.0);
    touching += ev.sites[i].penetration > 0.0 ? 1 : 0;
  }
  EXPECT_EQ(touching, 2u);
}

// The adaptive stepper's step-end stage takes dx/dt, the weights and the full evaluation from one
// evaluation of the equations (rhs_and_error_weights); each must be bit-identical to what rhs(),
// error_weights() and evaluate() give on their own, or a run would depend on which path it took.
TEST(ErrorWeights, OneEvaluationGivesWhatTheSeparateCallsGive) {
  for (const char* law : {"lugre_normalised", "coulomb"}) {
    const mechanism::Scene scene = mechanism::read_scene(
        "", {std::string("joint.slider.friction.law=\"") + law + "\"", "joint.slider.model=\"line\""});
    mechanism::SliderCrank system(scene);
    mechanism::State x = system.initial_state();
    const auto names = system.coordinate_names();
    const auto angle = std::find(names.begin(), names.end(), "slider_angle") - names.begin();
    for (double tilt : {0.0, 0.05}) {
      x[angle] = tilt;  // 0.05 rad: both faces touch (see above)
      mechanism::State f, w, f2, w2;
      mechanism::Evaluation ev, ev2;
      system.rhs(1e-3, x, f);
      system.error_weights(1e-3, x, w);
      system.evaluate(1e-3, x, ev);
      f2.setConstant(x.size(), -1.0);
      system.rhs_and_error_weights(1e-3, x, f2, w2, ev2);
      EXPECT_EQ(f2, f) << law << " tilt " << tilt;
      EXPECT_EQ(w2, w) << law << " tilt " << tilt;
      ASSERT_EQ(ev2.sites.size(), ev.sites.size());
      for (std::size_t i = 0; i < ev.sites.size(); ++i) {
        EXPECT_EQ(ev2.sites[i].normal_force, ev.sites[i].normal_force);
        EXPECT_EQ(ev2.sites[i].friction_force, ev.sites[i].friction_force);
        EXPECT_EQ(ev2.sites[i].penetration, ev.sites[i].penetration);
      }
      EXPECT_EQ(ev2.q_ddot, ev.q_ddot);
      EXPECT_EQ(ev2.kinetic_energy, ev.kinetic_energy);
      EXPECT_EQ(ev2.driving_torque, ev.driving_torque);
      mechanism::State f3, w3;
      system.rhs_and_error_weights(1e-3, x, f3, w3);
      EXPECT_EQ(f3, f);
      EXPECT_EQ(w3, w);
    }
  }
}

TEST(ErrorWeights, NoBristlesAllOnes) {
  const mechanism::Scene scene = mechanism::read_scene("", {"joint.slider.friction.law=\"coulomb\""});
  mechanism::SliderCrank system(scene);
  mechanism::State w;
  system.error_weights(0.0, system.initial_state(), w);
  EXPECT_EQ(w, mechanism::State::Ones(system.state_size()));
}

}  // namespace
