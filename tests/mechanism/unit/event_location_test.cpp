// Event location: locate_crossing / bracket_crossing on functions with known roots (sin t at pi and
// 2 pi, a thrown ball's landing time 2 v0 / g), the degenerate cases (zero at an end, a triple root,
// grazing), and the hybrid loop the simulator uses: adaptive steps, gap checked at the step ends,
// the crossing located on the dense output, a re-step exactly to it with step_fixed_to, the impact
// law applied, invalidate(). Expected impact times are the closed-form sequences of a bouncing ball
// with restitution and of a spring-loaded mass hitting a wall.
#include "mechanism/event_location.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "mechanism/dormand_prince.hpp"
#include "mechanism/error.hpp"
#include "mechanism/rk4.hpp"

namespace {

using mechanism::bracket_crossing;
using mechanism::CrossingBracket;
using mechanism::DormandPrince54;
using mechanism::InvalidParameter;
using mechanism::locate_crossing;
using mechanism::Rk4;
using mechanism::State;
using mechanism::StepOutcome;

constexpr double pi = std::numbers::pi;

// Checks the documented contract of the bracket and returns it.
CrossingBracket located(const std::function<double(double)>& g, double t0, double t1, double root, double tol) {
  const CrossingBracket b = bracket_crossing(g, t0, t1, g(t0), g(t1), tol);
  EXPECT_LE(b.after - b.before, tol);
  EXPECT_LE(b.before, root + 1e-15);  // the crossing lies inside the final bracket
  EXPECT_GE(b.after, root - 1e-15);
  EXPECT_NEAR(b.after, root, tol);
  EXPECT_EQ(locate_crossing(g, t0, t1, g(t0), g(t1), tol), b.after);
  // after carries g1's sign (or is a zero), before carries g0's.
  EXPECT_TRUE(b.g_after == 0.0 || (b.g_after > 0.0) == (g(t1) > 0.0));
  EXPECT_TRUE(b.g_before == 0.0 || (b.g_before > 0.0) == (g(t0) > 0.0));
  EXPECT_EQ(g(b.after), b.g_after);
  return b;
}

TEST(LocateCrossing, SineAtPiBothDirections) {
  const auto s = [](double t) { return std::sin(t); };
  const auto minus_s = [](double t) { return -std::sin(t); };
  for (const double tol : {1e-6, 1e-10, 1e-13}) {
    const auto down = located(s, 3.0, 3.5, pi, tol);       // + to -
    const auto up = located(minus_s, 3.0, 3.5, pi, tol);   // - to +
    const auto up2 = located(s, 6.0, 6.5, 2.0 * pi, tol);  // - to +
    // Bisection would need ceil(log2(0.5 / tol)) evaluations (20, 33, 43); the Illinois method
    // converges superlinearly (order ~1.44, Dowell & Jarratt 1971).
    const double bisection = std::ceil(std::log2(0.5 / tol));
    for (const auto& b : {down, up, up2}) EXPECT_LE(static_cast<double>(b.evaluations), 0.5 * bisection) << tol;
    std::printf("[crossing] sin, tol %.0e: %zu, %zu, %zu evaluations (bisection %.0f)\n", tol, down.evaluations,
                up.evaluations, up2.evaluations, bisection);
  }
}

TEST(LocateCrossing, ThrownBallLandsAtTwoV0OverG) {
  const double v0 = 3.0, g = 9.81;
  const auto height = [&](double t) { return v0 * t - 0.5 * g * t * t; };
  // From the apex (v0/g) to beyond the landing: the root is 2 v0 / g.
  located(height, v0 / g, 3.0 * v0 / g, 2.0 * v0 / g, 1e-12);
  // A rising crossing: the mirror image, from below the ground up.
  located([&](double t) { return -height(t); }, v0 / g, 3.0 * v0 / g, 2.0 * v0 / g, 1e-12);
}

TEST(LocateCrossing, PlainRegulaFalsiTrapIsAvoided) {
  // t^10 - 0.5 on [0, 1] is convex: plain regula falsi keeps the right end forever and creeps in
  // from the left (hundreds of evaluations); the Illinois halving moves the kept end.
  const auto g = [](double t) { return std::pow(t, 10) - 0.5; };
  const double root = std::pow(0.5, 0.1);
  const auto b = located(g, 0.0, 1.0, root, 1e-12);
  EXPECT_LE(b.evaluations, 25u);
  std::printf("[crossing] t^10 - 1/2: %zu evaluations\n", b.evaluations);
}

TEST(LocateCrossing, ZeroAtAnEndIsReturnedWithoutEvaluations) {
  int calls = 0;
  const auto g = [&](double t) {
    ++calls;
    return t - 1.0;
  };
  EXPECT_EQ(locate_crossing(g, 1.0, 2.0, 0.0, 1.0, 1e-9), 1.0);
  EXPECT_EQ(locate_crossing(g, 0.0, 1.0, -1.0, 0.0, 1e-9), 1.0);
  EXPECT_EQ(calls, 0);
}

TEST(LocateCrossing, TangentialAndGrazingCases) {
  // A triple root (tangent crossing, g' = 0 there): the secant is useless near the root; the
  // bisection safeguard still brackets it to the tolerance in bounded work.
  const auto cubic = [](double t) { return (t - 1.0) * (t - 1.0) * (t - 1.0); };
  const auto b = located(cubic, 0.0, 3.0, 1.0, 1e-10);
  EXPECT_LE(static_cast<double>(b.evaluations), 4.0 * std::ceil(std::log2(3.0 / 1e-10)));

  // Near-grazing with a sign change: (t-1)^2 - eps^2 on [1, 2] starts at -eps^2 = -1e-12 and
  // crosses at 1 + eps.
  const double eps = 1e-6;
  located([&](double t) { return (t - 1.0) * (t - 1.0) - eps * eps; }, 1.0, 2.0, 1.0 + eps, 1e-13);

  // Grazing without a sign change: the gap (t-1)^2 touches zero at t = 1 but is positive at both
  // ends. The end-point test cannot see it; locate_crossing refuses instead of inventing a time.
  const auto graze = [](double t) { return (t - 1.0) * (t - 1.0); };
  try {
    locate_crossing(graze, 0.0, 3.0, graze(0.0), graze(3.0), 1e-9);
    ADD_FAILURE() << "a same-sign bracket was accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "g1");
    EXPECT_NE(e.rule().find("same sign"), std::string::npos) << e.what();
  }
}

TEST(LocateCrossing, ToleranceBelowTheTimeResolutionStops) {
  // Around t = 1e6 adjacent doubles are 1.2e-10 apart: a 1e-13 tolerance cannot be met, and the
  // search must stop at adjacent doubles rather than loop.
  const double root = 1e6 + 0.1;
  const auto b = bracket_crossing([&](double t) { return t - root; }, 1e6, 1e6 + 1.0, -0.1, 0.9, 1e-13);
  EXPECT_LE(b.after - b.before, 2.4e-10);
  EXPECT_NEAR(b.after, root, 2.4e-10);
}

TEST(LocateCrossing, InvalidArgumentsNameTheKey) {
  const auto g = [](double t) { return t; };
  const auto key_of = [&](double t0, double t1, double g0, double g1, double tol) -> std::string {
    try {
      locate_crossing(g, t0, t1, g0, g1, tol);
    } catch (const InvalidParameter& e) {
      EXPECT_NE(std::string(e.what()).find(e.key()), std::string::npos);
      return e.key();
    }
    return "";
  };
  EXPECT_EQ(key_of(1.0, 1.0, -1.0, 1.0, 1e-9), "t1");
  EXPECT_EQ(key_of(1.0, 0.5, -1.0, 1.0, 1e-9), "t1");
  EXPECT_EQ(key_of(0.0, 1.0, -1.0, 1.0, 0.0), "time_tolerance");
  EXPECT_EQ(key_of(0.0, 1.0, -1.0, 1.0, -1e-9), "time_tolerance");
  EXPECT_EQ(key_of(NAN, 1.0, -1.0, 1.0, 1e-9), "t0");
  EXPECT_EQ(key_of(0.0, 1.0, NAN, 1.0, 1e-9), "g0");
  EXPECT_EQ(key_of(0.0, 1.0, -1.0, INFINITY, 1e-9), "g1");
  EXPECT_EQ(key_of(0.0, 1.0, 1.0, 2.0, 1e-9), "g1");
  try {
    locate_crossing([](double t) { return t < 0.25 ? -1.0 : NAN; }, 0.0, 1.0, -1.0, 1.0, 1e-9);
    ADD_FAILURE();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "g");
  }
}

// --- The hybrid loop -------------------------------------------------------------------------

// A ball in free fall above the floor y = 0: state (y, v). The gap is y.
struct Ball {
  double gravity = 9.81;
  void rhs(double, const State& x, State& dxdt) const {
    dxdt[0] = x[1];
    dxdt[1] = -gravity;
  }
};

// A mass on a spring whose rest position -d lies behind a wall at y = 0 (an impact oscillator):
// y'' = -omega^2 (y + d). Between impacts the motion is a cosine arc, not a polynomial, so the
// integrator's own error shows in the impact times.
struct SpringOnWall {
  double omega = 2.0, d = 0.5;
  void rhs(double, const State& x, State& dxdt) const {
    dxdt[0] = x[1];
    dxdt[1] = -omega * omega * (x[0] + d);
  }
};

struct Impacts {
  std::vector<double> times, speeds_before;  // speeds_before: |v| at each impact
};

// The pattern of the simulation loop: after each accepted step, a gap that went from positive to
// non-positive is an impact; locate it on the dense output, go back to the step start (the dense
// output is exact there), re-step exactly to the impact time, apply the impact law, invalidate().
template <class System>
Impacts bounce_adaptive(const System& sys, State x, double restitution, std::size_t count, double tolerance,
                        double max_step) {
  mechanism::AdaptiveOptions options;
  options.relative_tolerance = options.absolute_tolerance = tolerance;
  // Events are seen only as sign changes between step ends, so no step may hold a whole flight
  // (for the free fall the error estimate is zero, DP5 being exact on quadratics, and the step would
  // grow tenfold per step): max_step is the guard, shorter than the shortest flight.
  options.max_step = max_step;
  DormandPrince54 dp(options);
  double t = 0.0, h = dp.initial_step(sys, t, x);
  State u(x.size());
  const auto gap = [&](double s) {
    dp.interpolate(s, u);
    return u[0];
  };
  Impacts impacts;
  double gap0 = x[0];
  for (std::size_t attempts = 0; impacts.times.size() < count && attempts < 100000; ++attempts) {
    const StepOutcome outcome = dp.try_step(sys, t, x, h);
    if (outcome == StepOutcome::rejected) continue;
    if (outcome != StepOutcome::accepted) {
      ADD_FAILURE() << "outcome " << static_cast<int>(outcome) << " at t = " << t;
      break;
    }
    const double gap1 = x[0];
    if (gap0 > 0.0 && gap1 <= 0.0) {
      const double t_hit = mechanism::locate_crossing(gap, dp.t_previous(), dp.t_current(), gap0, gap1, 1e-12);
      t = dp.t_previous();
      dp.interpolate(t, x);
      dp.step_fixed_to(sys, t, x, t_hit);  // t_hit > t_previous: gap0 > 0 there
      impacts.times.push_back(t);
      impacts.speeds_before.push_back(-x[1]);
      x[1] = -restitution * x[1];  // the impact law
      dp.invalidate();             // what the simulator does after changing the system's memory
    }
    gap0 = x[0];
  }
  return impacts;
}

// The same loop with fixed RK4 steps and its Hermite dense output.
template <class System>
Impacts bounce_rk4(const System& sys, State x, double restitution, std::size_t count, double h) {
  Rk4 rk;
  double t = 0.0;
  State u(x.size());
  Impacts impacts;
  double gap0 = x[0];
  while (impacts.times.size() < count && t < 100.0) {
    rk.step(sys, t, x, h);
    const double gap1 = x[0];
    if (gap0 > 0.0 && gap1 <= 0.0) {
      const double t_hit = mechanism::locate_crossing(
          [&](double s) {
            rk.interpolate(s, u);
            return u[0];
          },
          rk.t_previous(), rk.t_current(), gap0, gap1, 1e-12);
      t = rk.t_previous();
      rk.interpolate(t, x);
      rk.step(sys, t, x, t_hit - t);
      impacts.times.push_back(t);
      impacts.speeds_before.push_back(-x[1]);
      x[1] = -restitution * x[1];
      rk.invalidate();
    }
    gap0 = x[0];
  }
  return impacts;
}

// Dropped from rest at height H: t_1 = sqrt(2H/g), impact speed v_1 = g t_1; the k-th rebound
// leaves at e^k v_1 and flies 2 e^k v_1 / g, so t_{k+1} = t_k + 2 e^k v_1 / g, speed e^k v_1.
Impacts ball_analytic(double height, double gravity, double restitution, std::size_t count) {
  Impacts a;
  double t = std::sqrt(2.0 * height / gravity), v = gravity * t;
  for (std::size_t k = 0; k < count; ++k) {
    a.times.push_back(t);
    a.speeds_before.push_back(v);
    v *= restitution;
    t += 2.0 * v / gravity;
  }
  return a;
}

// Leaving the wall at speed V: y + d = d cos(w t) + (V/w) sin(w t) = R cos(w t - phi) with
// phi = atan2(V/w, d); back at y = 0 when w t - phi = phi, i.e. after 2 phi / w, at speed V.
Impacts spring_analytic(const SpringOnWall& s, double speed, double restitution, std::size_t count) {
  Impacts a;
  double t = 0.0, v = speed;
  for (std::size_t k = 0; k < count; ++k) {
    t += 2.0 * std::atan2(v / s.omega, s.d) / s.omega;
    a.times.push_back(t);
    a.speeds_before.push_back(v);
    v *= restitution;
  }
  return a;
}

// Returns the worst impact-time error.
double expect_matches(const char* what, const Impacts& got, const Impacts& want, double time_tol, double speed_tol) {
  EXPECT_EQ(got.times.size(), want.times.size()) << what;
  if (got.times.size() != want.times.size()) return INFINITY;
  double worst_t = 0.0, worst_v = 0.0;
  for (std::size_t k = 0; k < want.times.size(); ++k) {
    EXPECT_NEAR(got.times[k], want.times[k], time_tol) << what << ", impact " << k + 1;
    EXPECT_NEAR(got.speeds_before[k], want.speeds_before[k], speed_tol) << what << ", impact " << k + 1;
    worst_t = std::max(worst_t, std::abs(got.times[k] - want.times[k]));
    worst_v = std::max(worst_v, std::abs(got.speeds_before[k] - want.speeds_before[k]));
  }
  std::printf("[hybrid] %-40s %zu impacts, last at t = %.6f; worst time error %.2e, speed error %.2e\n", what,
              want.times.size(), want.times.back(), worst_t, worst_v);
  return worst_t;
}

TEST(HybridLoop, BouncingBallImpactTimesMatchTheAnalyticSequence) {
  const Ball ball;
  const double height = 1.0, e = 0.8;
  const std::size_t n = 15;
  const auto want = ball_analytic(height, ball.gravity, e, n);
  State x0(2);
  x0 << height, 0.0;
  // Both methods and both interpolants are exact for a quadratic trajectory, so what remains is the
  // location tolerance (1e-12) and round-off, carried along 15 impacts.
  // The 15th flight lasts 2 e^14 v_1 / g = 0.040: max_step 0.01.
  expect_matches("ball, DP5 adaptive (tol 1e-10)", bounce_adaptive(ball, x0, e, n, 1e-10, 0.01), want, 1e-10, 1e-9);
  expect_matches("ball, RK4 h = 0.01", bounce_rk4(ball, x0, e, n, 0.01), want, 1e-10, 1e-9);
}

TEST(HybridLoop, ImpactOscillatorTimesFollowTheTolerance) {
  const SpringOnWall spring;
  const double speed = 1.5, e = 0.7;
  const std::size_t n = 10;
  const auto want = spring_analytic(spring, speed, e, n);
  State x0(2);
  x0 << 0.0, speed;
  // Non-polynomial arcs: the impact times carry the integration error, which tightens with the
  // tolerance (DP5) and as h^4 (RK4). Bounds: 100 tol per impact time, and 10 h^4 for RK4.
  // The 10th flight lasts 2 atan2(e^9 V / w, d) / w = 0.060: max_step 0.03.
  const auto loose = bounce_adaptive(spring, x0, e, n, 1e-8, 0.03);
  const auto tight = bounce_adaptive(spring, x0, e, n, 1e-11, 0.03);
  const double loose_error = expect_matches("spring on wall, DP5 adaptive (tol 1e-8)", loose, want, 1e-6, 1e-6);
  const double tight_error = expect_matches("spring on wall, DP5 adaptive (tol 1e-11)", tight, want, 1e-9, 1e-9);
  EXPECT_LT(tight_error, loose_error / 10.0);
  expect_matches("spring on wall, RK4 h = 0.01", bounce_rk4(spring, x0, e, n, 0.01), want, 1e-7, 1e-7);
}

}  // namespace
