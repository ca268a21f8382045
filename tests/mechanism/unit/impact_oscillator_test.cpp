// The closed-form benchmark for the exponents of an impacting system (impact_oscillator.hpp): a
// harmonically forced linear oscillator against a rigid stop with Newton's restitution.
//
// Where the expected values come from:
//  - The period-1 orbit and its Floquet multipliers: closed form (the exact flow between impacts,
//    the exact monodromy exp(A T) times the saltation matrix). Checked here against the exact flow
//    itself (the orbit returns to its impact state) and against det S = r^2 (the multipliers'
//    product is r^2 exp(-2 zeta T), analytic).
//  - On that stable orbit, Benettin with the saltation-variational equation and Benettin by finite
//    differences (the method of `mechanism lyapunov`) must give ln|mu_j| / T to 1e-3 relative.
//  - In a chaotic regime (omega = 2.8, found by scanning omega; its period-1 orbit is unstable),
//    both methods run on the same trajectory (bit for bit: the tangents do not enter the step
//    control) and must agree within two standard errors; the saltation run's exponents sum to
//    -2 zeta + 2 ln(r) x (impacts per unit time) exactly (Liouville between impacts, det S = r^2 at
//    each: analytic), and lambda_1 is positive by many standard errors.
#include "mechanism/impact_oscillator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mechanism/error.hpp"

namespace mechanism {
namespace {

ImpactOscillator periodic() { return {}; }  // zeta 0.05, A 1, omega 2, gap 0, r 0.8
ImpactOscillator chaotic() {
  ImpactOscillator o;
  o.omega = 2.8;
  return o;
}

TEST(ImpactOscillator, PeriodOneOrbitReturnsToItselfUnderTheExactFlow) {
  const ImpactOscillator o = periodic();
  const auto orbits = period_one_orbits(o);
  ASSERT_EQ(orbits.size(), 1u);
  const PeriodOneOrbit& p = orbits[0];
  EXPECT_TRUE(p.stable);
  const double T = o.period();
  const auto back = exact_flow(o, p.impact_time, {o.gap, -o.restitution * p.impact_velocity}, p.impact_time + T);
  EXPECT_NEAR(back[0], o.gap, 1e-12);
  EXPECT_NEAR(back[1], p.impact_velocity, 1e-12);
  const auto& m = p.monodromy;
  const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  EXPECT_NEAR(det, o.restitution * o.restitution * std::exp(-2 * o.zeta * T), 1e-14);
  EXPECT_NEAR(p.exponents[0] + p.exponents[1], -2 * o.zeta + 2 * std::log(o.restitution) / T, 1e-13);
  // A stop beyond every amplitude the forcing reaches: no impacting orbit.
  ImpactOscillator far = o;
  far.gap = 10.0;
  EXPECT_TRUE(period_one_orbits(far).empty());
}

TEST(ImpactOscillator, PeriodicOrbitExponentsAgreeThreeWays) {
  const ImpactOscillator o = periodic();
  const PeriodOneOrbit p = period_one_orbits(o).at(0);
  const double T = o.period();
  const auto start = exact_flow(o, p.impact_time, {o.gap, -o.restitution * p.impact_velocity}, T);
  ImpactLyapunovOptions opt;
  opt.periods = 2000;
  opt.perturbation = 1e-8;
  const ImpactLyapunov s = saltation_lyapunov(o, start, opt);
  const ImpactLyapunov f = finite_difference_impact_lyapunov(o, start, opt);
  ASSERT_EQ(s.status, "completed") << s.message;
  ASSERT_EQ(f.status, "completed") << f.message;
  EXPECT_EQ(s.impacts, opt.periods);  // one impact per period: it stayed on the orbit
  for (int j = 0; j < 2; ++j) {
    SCOPED_TRACE("lambda_" + std::to_string(j + 1));
    EXPECT_NEAR(s.exponents[j], p.exponents[j], 1e-3 * std::abs(p.exponents[j]));
    EXPECT_NEAR(f.exponents[j], p.exponents[j], 1e-3 * std::abs(p.exponents[j]));
  }
}

TEST(ImpactOscillator, ChaoticRegimeSaltationAndFiniteDifferencesAgree) {
  const ImpactOscillator o = chaotic();
  const auto orbits = period_one_orbits(o);
  ASSERT_EQ(orbits.size(), 1u);
  EXPECT_FALSE(orbits[0].stable);
  ImpactLyapunovOptions opt;
  opt.periods = 2000;
  opt.perturbation = 1e-8;
  const std::array<double, 2> start{-1.0, 0.0};
  const ImpactLyapunov s = saltation_lyapunov(o, start, opt);
  const ImpactLyapunov f = finite_difference_impact_lyapunov(o, start, opt);
  ASSERT_EQ(s.status, "completed") << s.message;
  ASSERT_EQ(f.status, "completed") << f.message;
  EXPECT_GT(s.exponents[0], 10 * s.standard_error[0]);
  for (int j = 0; j < 2; ++j) {
    SCOPED_TRACE("lambda_" + std::to_string(j + 1));
    EXPECT_LT(std::abs(s.exponents[j] - f.exponents[j]), 2 * std::max(s.standard_error[j], f.standard_error[j]));
  }
  const double rate = static_cast<double>(s.impacts) / (static_cast<double>(s.periods) * o.period());
  EXPECT_NEAR(s.exponents[0] + s.exponents[1], -2 * o.zeta + 2 * std::log(o.restitution) * rate, 1e-9);
}

TEST(ImpactOscillator, RefusesImpossibleParameters) {
  ImpactOscillator o;
  o.zeta = 1.0;
  EXPECT_THROW(o.validate(), InvalidParameter);
  o = {};
  o.restitution = 0.0;
  EXPECT_THROW(period_one_orbits(o), InvalidParameter);
  o = {};
  o.omega = -1.0;
  EXPECT_THROW(o.validate(), InvalidParameter);
  ImpactLyapunovOptions opt;
  opt.periods = 5;
  EXPECT_THROW(saltation_lyapunov({}, {-1.0, 0.0}, opt), InvalidParameter);
}

}  // namespace
}  // namespace mechanism
