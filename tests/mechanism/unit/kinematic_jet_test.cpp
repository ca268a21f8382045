// Kinematic jets against finite differences: along a motion q(t) = q0 + v t (q_ddot = 0) with the
// crank at constant speed, a jet's rate must be d/dt of its value and its bias the second
// derivative (expected values: central differences of the plain-double function, brute force).

#include <gtest/gtest.h>

#include <cmath>

#include "mechanism/kinematic_jet.hpp"

namespace mechanism {
namespace {

constexpr double omega = 3.0;

// A composite expression like the mechanism's poses: a point offset on a rotating body whose
// reference is driven by another, and the dependent angle asin(-y / l).
template <class Angle, class Value>
struct Expr {
  static Value eval(const Value& a, const Value& b, const Value& crank) {
    using std::asin, std::cos, std::sin;
    const Value y = 0.05 * sin(crank) + 0.01 * a;
    const Value th = asin((-1.0 / 0.12) * y);
    return 0.3 * cos(th) + 0.07 * sin(b) * cos(crank) + a * b;
  }
};

double plain(double t, double a0, double va, double b0, double vb) {
  const double a = a0 + va * t, b = b0 + vb * t, c = 0.4 + omega * t;
  return Expr<double, double>::eval(a, b, c);
}

TEST(KinematicJet, RateGradientAndBiasMatchFiniteDifferences) {
  const double a0 = 0.2, va = -1.3, b0 = 0.7, vb = 2.1;
  const Jet a = Jet::coordinate(0, a0, va);
  const Jet b = Jet::coordinate(1, b0, vb);
  const Jet crank = Jet::coordinate(2, 0.4, omega);
  const Jet j = Expr<Jet, Jet>::eval(a, b, crank);

  const double h = 1e-4;
  const double f0 = plain(0, a0, va, b0, vb), fp = plain(h, a0, va, b0, vb), fm = plain(-h, a0, va, b0, vb);
  EXPECT_NEAR(j.value, f0, 1e-15);
  EXPECT_NEAR(j.rate, (fp - fm) / (2 * h), 1e-7);
  // With q_ddot = 0 the whole second derivative is the bias.
  EXPECT_NEAR(j.bias, (fp - 2 * f0 + fm) / (h * h), 1e-4);
  // The gradient column k is the rate's sensitivity to the k-th velocity.
  const double d = 1e-6;
  EXPECT_NEAR(j.grad(0), (plain(d, a0, va + 1, b0, vb) - plain(-d, a0, va + 1, b0, vb)) / (2 * d) - j.rate, 1e-6);
  EXPECT_NEAR(j.rate, j.grad(0) * va + j.grad(1) * vb + j.grad(2) * omega, 1e-12);
}

TEST(KinematicJet, OffsetOfARotatingPointHasCentripetalBias) {
  // A point at radius r on a body turning at omega: acceleration -omega^2 r toward the centre.
  const Jet angle = Jet::coordinate(0, 0.3, omega);
  const Jet zero = Jet::constant(0.0);
  const JetPoint p = offset(JetPoint{zero, zero}, angle, 0.05, 0.0);
  EXPECT_NEAR(p.x.bias, -omega * omega * 0.05 * std::cos(0.3), 1e-14);
  EXPECT_NEAR(p.y.bias, -omega * omega * 0.05 * std::sin(0.3), 1e-14);
  EXPECT_NEAR(p.x.rate, -omega * 0.05 * std::sin(0.3), 1e-14);
}

}  // namespace
}  // namespace mechanism
