#pragma once
// A kinematic jet: a scalar quantity of the mechanism (a coordinate of a point, an angle) written
// as a function of the generalised coordinates q and of time through the driven crank angle. It
// carries what the equations of motion need and nothing more:
//   value  the quantity itself,
//   rate   its time derivative,
//   grad   its gradient with respect to (q, theta_crank): the row of the velocity Jacobian, so
//          that rate = grad . (q_dot, omega),
//   bias   the part of its second time derivative not proportional to q_ddot (centripetal and
//          Coriolis terms; the crank turns at constant speed, so theta_crank_ddot = 0).
// Its acceleration is then grad . (q_ddot, 0) + bias. The arithmetic below is forward-mode
// differentiation to second order along the motion, so any pose built from the mechanism's
// lengths and angles (sums, products, sin, cos, asin) comes with exact Jacobians and bias terms,
// and the equations of motion follow from the principle of virtual power (Kane's form of
// Lagrange's equations, seed Eq. 20-21) without deriving them by hand per joint topology.

#include <cmath>

#include <Eigen/Core>

namespace mechanism {

// At most 8 free coordinates (crank pivot 2, conrod end 2, conrod angle, slider pin 2, slider
// angle) plus the driven crank angle. A jet's row has a fixed size (unused columns stay zero):
// fixed-size arithmetic is unrolled and vectorised, and was about twice as fast as a dynamic row of
// the same capacity. The simulator instantiates the width its scene needs (3 columns for the seed
// scene's two coordinates plus the crank: the jets then cost a third of the full width);
// Jet is the full width.
inline constexpr int max_jet_columns = 9;
template <int N>
using BasicJetRow = Eigen::Matrix<double, 1, N>;
using JetRow = BasicJetRow<max_jet_columns>;

template <int N>
struct BasicJet {
  double value = 0.0;
  double rate = 0.0;
  double bias = 0.0;
  BasicJetRow<N> grad;

  // A constant (zero gradient).
  static BasicJet constant(double value) {
    BasicJet j;
    j.value = value;
    j.grad.setZero();
    return j;
  }
  // The coordinate in column `index` with its current value and rate.
  static BasicJet coordinate(int index, double value, double rate) {
    BasicJet j = constant(value);
    j.rate = rate;
    j.grad(index) = 1.0;
    return j;
  }
};
using Jet = BasicJet<max_jet_columns>;

template <int N>
inline BasicJet<N> operator+(const BasicJet<N>& a, const BasicJet<N>& b) {
  return {a.value + b.value, a.rate + b.rate, a.bias + b.bias, a.grad + b.grad};
}
template <int N>
inline BasicJet<N> operator-(const BasicJet<N>& a, const BasicJet<N>& b) {
  return {a.value - b.value, a.rate - b.rate, a.bias - b.bias, a.grad - b.grad};
}
template <int N>
inline BasicJet<N> operator-(const BasicJet<N>& a) {
  return {-a.value, -a.rate, -a.bias, -a.grad};
}
template <int N>
inline BasicJet<N> operator*(double s, const BasicJet<N>& a) {
  return {s * a.value, s * a.rate, s * a.bias, s * a.grad};
}
template <int N>
inline BasicJet<N> operator*(const BasicJet<N>& a, const BasicJet<N>& b) {
  // (ab)'' = a'' b + 2 a' b' + a b''; only the q_ddot-free parts go into the bias.
  return {a.value * b.value, a.rate * b.value + a.value * b.rate,
          a.bias * b.value + 2.0 * a.rate * b.rate + a.value * b.bias,
          b.value * a.grad + a.value * b.grad};
}

// f(a) for a scalar function with derivatives d1 = f'(a), d2 = f''(a).
template <int N>
inline BasicJet<N> chain(const BasicJet<N>& a, double f, double d1, double d2) {
  return {f, d1 * a.rate, d1 * a.bias + d2 * a.rate * a.rate, d1 * a.grad};
}
template <int N>
inline BasicJet<N> sin(const BasicJet<N>& a) {
  const double s = std::sin(a.value), c = std::cos(a.value);
  return chain(a, s, c, -s);
}
template <int N>
inline BasicJet<N> cos(const BasicJet<N>& a) {
  const double s = std::sin(a.value), c = std::cos(a.value);
  return chain(a, c, -s, -c);
}
// asin on (-1, 1); the caller guarantees |a| < 1 (a conrod shorter than the crank offset is
// refused when the scene is read).
template <int N>
inline BasicJet<N> asin(const BasicJet<N>& a) {
  const double r = 1.0 - a.value * a.value;
  const double d1 = 1.0 / std::sqrt(r);
  return chain(a, std::asin(a.value), d1, a.value * d1 / r);
}

// A point of the plane as two jets.
template <int N>
struct BasicJetPoint {
  BasicJet<N> x, y;
};
using JetPoint = BasicJetPoint<max_jet_columns>;
template <int N>
inline BasicJetPoint<N> operator+(const BasicJetPoint<N>& a, const BasicJetPoint<N>& b) {
  return {a.x + b.x, a.y + b.y};
}
template <int N>
inline BasicJetPoint<N> operator-(const BasicJetPoint<N>& a, const BasicJetPoint<N>& b) {
  return {a.x - b.x, a.y - b.y};
}

// A body's orientation: the cosine and sine of its angle, computed once per angle (one sincos).
template <int N>
struct BasicJetRotation {
  BasicJet<N> c, s;
  explicit BasicJetRotation(const BasicJet<N>& angle) {
    const double sn = std::sin(angle.value), cs = std::cos(angle.value);
    c = chain(angle, cs, -sn, -cs);
    s = chain(angle, sn, cs, -sn);
  }
};
using JetRotation = BasicJetRotation<max_jet_columns>;

// p + R (ox, oy): a point fixed in a body whose reference point is p and whose orientation is R,
// at body-frame offset (ox, oy).
template <int N>
inline BasicJetPoint<N> offset(const BasicJetPoint<N>& p, const BasicJetRotation<N>& r, double ox, double oy) {
  return {p.x + ox * r.c - oy * r.s, p.y + ox * r.s + oy * r.c};
}
template <int N>
inline BasicJetPoint<N> offset(const BasicJetPoint<N>& p, const BasicJet<N>& angle, double ox, double oy) {
  return offset(p, BasicJetRotation<N>(angle), ox, oy);
}

}  // namespace mechanism
