// SliderCrank::error_weights: the adaptive stepper's error norm leaves out exactly the bristle
// deflections that commit() would reset (a LuGre site open at the step end). Expected values from
// the geometry: at Eq. 29's initial pose the slider is centred (every site open); tilted by
// 0.05 rad its corners reach 25 mm x 0.05 = 1.25 mm > the 0.5 mm clearance, so both faces touch.
#include <gtest/gtest.h>

#include <algorithm>

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

TEST(ErrorWeights, NoBristlesAllOnes) {
  const mechanism::Scene scene = mechanism::read_scene("", {"joint.slider.friction.law=\"coulomb\""});
  mechanism::SliderCrank system(scene);
  mechanism::State w;
  system.error_weights(0.0, system.initial_state(), w);
  EXPECT_EQ(w, mechanism::State::Ones(system.state_size()));
}

}  // namespace
