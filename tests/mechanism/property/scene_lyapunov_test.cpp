// Lyapunov exponents of a scene from its equations (scene_lyapunov.hpp): properties that hold
// whatever the exponents' values.
//  - Restitution 1, no friction, a conservative slider model: the crank's prescribed motion makes the
//    equations those of a time-periodic Hamiltonian system, so the period map preserves volume in
//    (q, p) and its exponents come in pairs lambda_i = -lambda_(d+1-i) (symplectic). In (q, q_dot)
//    the volume changes only by det M(q_start) / det M(q_end), bounded and returning with the crank
//    every period, so the sum of the exponents is 0 up to that factor over the run (1 / 0.24 s at
//    most for a factor of e) and the finite-difference error.
//  - Restitution 0.5: the contacts dissipate, the sum is negative.
//  - The estimate does not depend on the perturbation inside its linear range.
//  - A level slider without friction stays level: the method says the orbit is in an invariant
//    subspace instead of reporting its transverse growth as the attractor's exponents.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "mechanism/error.hpp"
#include "mechanism/scene.hpp"
#include "mechanism/scene_lyapunov.hpp"

namespace mechanism {
namespace {

SceneLyapunov run(std::vector<std::string> overrides, double perturbation = 1e-8) {
  SceneLyapunovOptions o;
  o.periods = 20;
  o.transient_periods = 5;
  o.perturbation = perturbation;
  return scene_lyapunov(read_scene("", overrides), o);
}

// The audit's generic start: tilted and spinning, the line model (conservative).
std::vector<std::string> tilted(const std::string& restitution) {
  return {"joint.slider.model=line", "joint.slider.friction.law=none", "joint.slider.contact.restitution=" + restitution,
          "initial.slider_angle=0.01", "initial.slider_rate=20"};
}

TEST(SceneLyapunov, ConservativeSceneHasSymplecticPairsAndZeroSum) {
  const SceneLyapunov r = run(tilted("1"));
  ASSERT_EQ(r.status, "completed") << r.message;
  const std::size_t d = r.exponents.size();
  ASSERT_EQ(d, 4u);  // conrod angle, slider angle and their rates
  const double sum = std::accumulate(r.exponents.begin(), r.exponents.end(), 0.0);
  EXPECT_LT(std::abs(sum), 1.0) << "1/s";
  EXPECT_GT(r.exponents[0], 0.0);
  for (std::size_t i = 0; i < d / 2; ++i) {
    const double pair = r.exponents[i] + r.exponents[d - 1 - i];
    // Finite-time QR pairs agree only statistically: two standard errors of the noisier one.
    EXPECT_LT(std::abs(pair), 2.0 * std::max(r.standard_error[i], r.standard_error[d - 1 - i]))
        << "lambda_" << i + 1 << " + lambda_" << d - i;
  }
  EXPECT_LT(r.largest_separation, max_linear_separation);
}

TEST(SceneLyapunov, DissipativeContactsMakeTheSumNegative) {
  const SceneLyapunov r = run(tilted("0.5"));
  ASSERT_EQ(r.status, "completed") << r.message;
  double sum = 0.0, se = 0.0;
  for (std::size_t i = 0; i < r.exponents.size(); ++i) sum += r.exponents[i], se += r.standard_error[i];
  EXPECT_LT(sum, -3.0 * se);
  EXPECT_TRUE(std::isfinite(r.kaplan_yorke));
  EXPECT_NEAR(r.kaplan_yorke, r.kaplan_yorke_section + 1.0, 1e-12);
}

TEST(SceneLyapunov, DoesNotDependOnThePerturbationInTheLinearRange) {
  // Two perturbations 100x apart inside the linear range (docs/reference/mechanism/lyapunov.md measures it:
  // 1e-6 to 1e-8; below 1e-10 round-off in the penetrations, differences of metres-sized positions,
  // takes over and the exponents grow): the reference orbit is the same, only the companions
  // differ, and their effect must stay below half the estimate's own standard error.
  const SceneLyapunov a = run(tilted("0.5"), 1e-6), b = run(tilted("0.5"), 1e-8);
  ASSERT_EQ(a.exponents.size(), b.exponents.size());
  for (std::size_t i = 0; i < a.exponents.size(); ++i)
    EXPECT_NEAR(a.exponents[i], b.exponents[i], 0.5 * a.standard_error[i]) << "lambda_" << i + 1;
}

TEST(SceneLyapunov, ALevelFrictionlessSliderIsReportedAsAnInvariantSubspace) {
  const SceneLyapunov r = run({"joint.slider.model=line", "joint.slider.friction.law=none"});
  EXPECT_EQ(r.status, "invariant_subspace");
  EXPECT_NE(r.message.find("slider_angle"), std::string::npos) << r.message;
}

TEST(SceneLyapunov, RefusesARigidMechanismAndImpossibleOptions) {
  try {
    scene_lyapunov(read_scene("", {"joint.slider.type=ideal"}));
    ADD_FAILURE() << "an ideal mechanism has no phase space";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("rigid"), std::string::npos) << e.what();
  }
  SceneLyapunovOptions o;
  o.periods = 5;
  EXPECT_THROW(scene_lyapunov(read_scene(""), o), InvalidParameter);
  o = {};
  o.intervals_per_period = 0;
  EXPECT_THROW(scene_lyapunov(read_scene(""), o), InvalidParameter);
  o = {};
  o.exponents = 99;
  EXPECT_THROW(scene_lyapunov(read_scene(""), o), InvalidParameter);
}

TEST(SceneLyapunov, KaplanYorkeDimension) {
  // Lorenz's spectrum: 2 + 0.9056 / 14.5723 (Sprott); Henon's 1 + 0.41922 / 1.62319; a contracting
  // fixed point 0; exponents that never sum below 0 do not bound it (NaN); -inf (a collapsed
  // direction) ends the sum.
  EXPECT_NEAR(kaplan_yorke_dimension({0.9056, 0.0, -14.5723}), 2.06214, 1e-5);
  EXPECT_NEAR(kaplan_yorke_dimension({-1.62319, 0.41922}), 1.25827, 1e-5);
  EXPECT_EQ(kaplan_yorke_dimension({-0.1, -0.2}), 0.0);
  EXPECT_TRUE(std::isnan(kaplan_yorke_dimension({0.3, 0.1})));
  EXPECT_EQ(kaplan_yorke_dimension({0.3, -std::numeric_limits<double>::infinity()}), 1.0);
}

}  // namespace
}  // namespace mechanism
