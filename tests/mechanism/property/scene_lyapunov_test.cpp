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
//    subspace instead of reporting its transverse growth as the attractor's exponents, also where
//    the level angle is rounding rather than exactly 0.
//  - A perturbation below what the state resolves is refused with the floor named, and a run whose
//    exponents are not all finite is never `completed`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "mechanism/error.hpp"
#include "mechanism/scene.hpp"
#include "mechanism/scene_lyapunov.hpp"
#include "mechanism/simulate.hpp"
#include "mechanism/slider_crank.hpp"

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

TEST(SceneLyapunov, ATiltOfRoundingSizeIsStillAnInvariantSubspace) {
  // The corners model without friction: a level slider stays level, but its four corner forces
  // leave an angle of 1e-18 rad of rounding (measured: 1.9e-18 rad, 1.7e-15 rad/s), where the
  // line model leaves exactly 0. Taken as the angle's scale, a perturbation of 1e-9 was 1e-27 rad,
  // lost in rounding at once: every exponent came out -inf (not_finite). The angle did not move,
  // so the run is the invariant subspace's, with the angle scaled by 1 rad.
  const SceneLyapunov r = run({"joint.slider.model=corners", "joint.slider.friction.law=none"}, 1e-9);
  EXPECT_EQ(r.status, "invariant_subspace") << r.message;
  EXPECT_NE(r.message.find("slider_angle"), std::string::npos) << r.message;
  for (std::size_t i = 0; i < r.coordinates.size(); ++i) {
    if (r.coordinates[i].rfind("slider_angle", 0) == 0) {
      EXPECT_EQ(r.scale[i], 1.0) << r.coordinates[i];
    }
  }
  for (const double v : r.exponents) EXPECT_TRUE(std::isfinite(v));
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

// The floor (scene_lyapunov.hpp, perturbation_digits) is 1e3 epsilon times the steps of one interval
// times the largest |coordinate| / scale; its parts are recomputed here from the result. Below it the
// run is refused and the message names the floor; 1e-16 (which used to complete with every exponent
// -inf) is refused before any integration (1e3 epsilon = 2.2e-13 bounds every scene's floor).
TEST(SceneLyapunov, RefusesAPerturbationBelowTheStateResolutionAndNamesTheFloor) {
  const SceneLyapunov ok = run(tilted("0.5"));
  ASSERT_EQ(ok.status, "completed") << ok.message;
  // RK4 on the scene's fixed grid: 1e-6 s steps, T/50 = 2.4e-4 s per interval.
  EXPECT_EQ(ok.steps_per_interval, 240u);
  // The tilted slider's own coordinates move, so the largest ratio is a coordinate's, above 1.
  EXPECT_GT(ok.largest_scaled_coordinate, 1.0);
  EXPECT_FALSE(ok.largest_scaled_name.empty());
  const double floor = 1e3 * std::numeric_limits<double>::epsilon() * 240.0 * ok.largest_scaled_coordinate;
  EXPECT_DOUBLE_EQ(ok.perturbation_floor, floor);
  EXPECT_LT(ok.perturbation_floor, 1e-8);  // the default stays above it
  try {
    run(tilted("0.5"), 0.5 * floor);
    ADD_FAILURE() << "a perturbation of half the floor ran";
  } catch (const InvalidParameter& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("perturbation"), std::string::npos) << m;
    EXPECT_NE(m.find("below this scene's floor"), std::string::npos) << m;
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", floor);
    EXPECT_NE(m.find(text), std::string::npos) << m << " lacks " << text;
    EXPECT_NE(m.find("240 integrator steps"), std::string::npos) << m;
  }
  for (double tiny : {1e-16, 1e-13}) {
    try {
      run(tilted("0.5"), tiny);
      ADD_FAILURE() << "perturbation " << tiny << " ran";
    } catch (const InvalidParameter& e) {
      EXPECT_NE(std::string(e.what()).find("below the floor 2.22e-13"), std::string::npos) << e.what();
    }
  }
}

// The status rules on results made by hand (property: a run with a non-finite exponent is never
// completed, whatever its other numbers; -inf is what a collapsed direction gives, NaN what a
// failed mean would). The old rule reported -inf exponents as `completed` with a message blaming
// the bristles even where the scene had none (a run at perturbation 1e-16 did).
TEST(SceneLyapunov, ARunWithANonFiniteExponentIsNeverCompleted) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  SceneLyapunov r;
  r.exponents = {734.0, -120.0};
  r.collapsed = {0, 0};
  assign_status(r, "", true);
  EXPECT_EQ(r.status, "completed");
  EXPECT_TRUE(r.message.empty()) << r.message;
  for (const auto& [exponents, collapsed] :
       {std::pair{std::vector<double>{-inf, -inf}, std::vector<std::size_t>{10, 10}},
        std::pair{std::vector<double>{734.0, -inf}, std::vector<std::size_t>{0, 3}},
        std::pair{std::vector<double>{nan, -120.0}, std::vector<std::size_t>{0, 0}}}) {
    for (bool bristles : {true, false}) {
      r = {};
      r.exponents = exponents;
      r.collapsed = collapsed;
      r.largest_separation = 0.5;  // would be `nonlinear` too: not_finite comes first
      assign_status(r, "slider_angle", bristles);
      EXPECT_EQ(r.status, "not_finite") << r.message;
      EXPECT_NE(r.message.find("not finite"), std::string::npos) << r.message;
      const bool blames_bristles = r.message.find("bristle deflections reset") != std::string::npos;
      EXPECT_EQ(blames_bristles, bristles && (collapsed[0] + collapsed[1]) > 0) << r.message;
      if (!bristles && collapsed[1] > 0) {
        EXPECT_NE(r.message.find("rounding"), std::string::npos) << r.message;
      }
    }
  }
  r = {};
  r.exponents = {734.0, -120.0};
  r.largest_separation = 2e-3;
  assign_status(r, "", true);
  EXPECT_EQ(r.status, "nonlinear");
  r.largest_separation = 0.0;
  assign_status(r, "slider_angle", false);
  EXPECT_EQ(r.status, "invariant_subspace");
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

// The saltation method (saltation.hpp) against Benettin's finite differences on the built-in scene,
// the slider's rotation free and locked, 10 periods after 2, two exponents. Both follow one reference
// trajectory, so they differ only in how the tangents are linearised. Expected: the bar of
// docs/reference/mechanism/saltation.md, agreement within two standard errors. With the latched
// velocities' variations dropped at each renormalisation the saltation method computes Benettin's
// product of interval derivatives; with the rotation free that is all that separates them
// (measured: 0.01 and 0.02 standard errors). With it locked the interval maps are less linear at
// the finite differences' scale in a few per cent of the intervals, and the two stay 0.3 and 0.9
// standard errors apart (docs/validation/mechanism/lyapunov-saltation.md).
// The comparisons of the saltation method with Benettin's: lambda_1 and lambda_2 over 10 periods.
SceneLyapunovOptions two_exponents_over_ten_periods() {
  SceneLyapunovOptions o;
  o.periods = 10;
  o.transient_periods = 2;
  o.exponents = 2;
  return o;
}

TEST(SceneLyapunov, SaltationAgreesWithBenettinOnTheSeedScene) {
  for (const char* rotation : {"free", "locked"}) {
    const Scene scene = read_scene("", {std::string("joint.slider.rotation=") + rotation});
    SceneLyapunovOptions o = two_exponents_over_ten_periods();
    const SceneLyapunov b = scene_lyapunov(scene, o);
    o.method = LyapunovMethod::saltation;
    const SceneLyapunov s = scene_lyapunov(scene, o);
    o.carry_latched_variations = false;
    const SceneLyapunov dropped = scene_lyapunov(scene, o);
    EXPECT_EQ(b.method, "benettin");
    EXPECT_EQ(s.method, "saltation");
    EXPECT_TRUE(s.latched_variations_carried);
    EXPECT_FALSE(dropped.latched_variations_carried);
    ASSERT_EQ(s.exponents.size(), 2u) << rotation;
    ASSERT_EQ(b.exponents.size(), 2u) << rotation;
    EXPECT_GT(s.exponents[0], 5.0 * s.standard_error[0]) << rotation << ": chaotic";
    const bool free = std::string(rotation) == "free";
    for (std::size_t j = 0; j < 2; ++j) {
      EXPECT_LT(std::abs(s.exponents[j] - b.exponents[j]), 2.0 * b.standard_error[j]) << rotation << ", lambda_" << j + 1;
      EXPECT_LT(std::abs(dropped.exponents[j] - b.exponents[j]), (free ? 0.1 : 2.0) * b.standard_error[j])
          << rotation << ", lambda_" << j + 1 << " with the latched variations dropped";
    }
  }
}

// With Coulomb's law the saltation method adds the jump at each located reversal of a held sliding
// direction (saltation.hpp), and Benettin's companions locate their own reversals; the two agree
// within two standard errors, rotation free and locked. Before that, Coulomb's law was refused by
// the saltation method. Measured (10 periods, 2 exponents): free 928.6 / 381.8 against 922.4 /
// 369.5 (standard errors 76 and 55), locked 627.0 / -798.5 against 679.7 / -842.7 (49 and 50).
TEST(SceneLyapunov, SaltationAgreesWithBenettinWithCoulombFriction) {
  for (const char* rotation : {"free", "locked"}) {
    const std::vector<std::string> keys = {std::string("joint.slider.rotation=") + rotation,
                                           "joint.slider.friction.law=coulomb"};
    // The transient and the averaged periods cross reversals (the first at 8.5 crank periods).
    Scene span = read_scene("", keys);
    span.integrator.locate_switches = false;
    span.run.transient = 0.0;
    span.run.duration = 12 * span.driver.period();
    span.run.output_interval = span.run.duration;
    SliderCrank sys(span);
    const SimulationSummary run = simulate(sys);
    ASSERT_GT(run.located_reversals, 0u) << rotation;
    const Scene scene = read_scene("", keys);
    SceneLyapunovOptions o = two_exponents_over_ten_periods();
    const SceneLyapunov b = scene_lyapunov(scene, o);
    o.method = LyapunovMethod::saltation;
    const SceneLyapunov s = scene_lyapunov(scene, o);
    ASSERT_EQ(s.status, "completed") << rotation << ": " << s.message;
    ASSERT_EQ(b.exponents.size(), 2u) << rotation;
    ASSERT_EQ(s.exponents.size(), 2u) << rotation;
    for (std::size_t j = 0; j < 2; ++j)
      EXPECT_LT(std::abs(s.exponents[j] - b.exponents[j]), 2.0 * b.standard_error[j]) << rotation << ", lambda_" << j + 1;
  }
}

}  // namespace
}  // namespace mechanism
