#pragma once
// Forward-mode dual numbers: a value and its N partial derivatives. An equation written once as a
// template over the scalar type and evaluated on Dual<N> variables seeded with unit derivatives
// yields its Jacobian exactly (to rounding), so no hand-written Jacobian can disagree with its
// equations. Private to the library.

#include <array>
#include <cmath>
#include <cstddef>

namespace chaos::detail {

template <int N>
struct Dual {
  double v = 0.0;
  std::array<double, N> d{};

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: constants mix freely with variables
  // The variable number `index` of N: derivative 1 along itself.
  static Dual variable(double value, int index) {
    Dual x(value);
    x.d[static_cast<std::size_t>(index)] = 1.0;
    return x;
  }
  Dual& operator+=(const Dual& b) { return *this = *this + b; }
  Dual& operator-=(const Dual& b) { return *this = *this - b; }
  Dual& operator*=(const Dual& b) { return *this = *this * b; }
  Dual& operator/=(const Dual& b) { return *this = *this / b; }

  // Chain rule for a unary function with value f and derivative df at v.
  Dual chain(double f, double df) const {
    Dual r(f);
    for (int i = 0; i < N; ++i) r.d[i] = df * d[i];
    return r;
  }

  friend Dual operator+(const Dual& a, const Dual& b) {
    Dual r(a.v + b.v);
    for (int i = 0; i < N; ++i) r.d[i] = a.d[i] + b.d[i];
    return r;
  }
  friend Dual operator-(const Dual& a, const Dual& b) {
    Dual r(a.v - b.v);
    for (int i = 0; i < N; ++i) r.d[i] = a.d[i] - b.d[i];
    return r;
  }
  friend Dual operator*(const Dual& a, const Dual& b) {
    Dual r(a.v * b.v);
    for (int i = 0; i < N; ++i) r.d[i] = a.d[i] * b.v + a.v * b.d[i];
    return r;
  }
  friend Dual operator/(const Dual& a, const Dual& b) {
    Dual r(a.v / b.v);
    for (int i = 0; i < N; ++i) r.d[i] = (a.d[i] * b.v - a.v * b.d[i]) / (b.v * b.v);
    return r;
  }
  friend Dual operator+(const Dual& a, double b) { return a + Dual(b); }
  friend Dual operator+(double a, const Dual& b) { return Dual(a) + b; }
  friend Dual operator-(const Dual& a, double b) { return a - Dual(b); }
  friend Dual operator-(double a, const Dual& b) { return Dual(a) - b; }
  friend Dual operator*(const Dual& a, double b) { return a.chain(a.v * b, b); }
  friend Dual operator*(double a, const Dual& b) { return b.chain(a * b.v, a); }
  friend Dual operator/(const Dual& a, double b) { return a.chain(a.v / b, 1.0 / b); }
  friend Dual operator/(double a, const Dual& b) { return Dual(a) / b; }
  friend Dual operator-(const Dual& a) { return a.chain(-a.v, -1.0); }
  friend Dual operator+(const Dual& a) { return a; }

  friend Dual sin(const Dual& a) { return a.chain(std::sin(a.v), std::cos(a.v)); }
  friend Dual cos(const Dual& a) { return a.chain(std::cos(a.v), -std::sin(a.v)); }
  friend Dual exp(const Dual& a) {
    const double e = std::exp(a.v);
    return a.chain(e, e);
  }
  friend Dual log(const Dual& a) { return a.chain(std::log(a.v), 1.0 / a.v); }
  friend Dual tanh(const Dual& a) {
    const double t = std::tanh(a.v);
    return a.chain(t, 1.0 - t * t);
  }
  friend Dual sqrt(const Dual& a) {
    const double s = std::sqrt(a.v);
    return a.chain(s, 0.5 / s);
  }
  // x^p for a constant exponent p.
  friend Dual pow(const Dual& a, double p) { return a.chain(std::pow(a.v, p), p * std::pow(a.v, p - 1.0)); }
  // |x| with derivative sign(x) (0 at x = 0, a set of measure zero on an attractor).
  friend Dual abs(const Dual& a) { return a.chain(std::abs(a.v), a.v > 0.0 ? 1.0 : (a.v < 0.0 ? -1.0 : 0.0)); }
  // x - period floor(x / period): the derivative of a wrap onto [0, period) is 1.
  friend Dual wrap(const Dual& a, double period) { return a.chain(a.v - period * std::floor(a.v / period), 1.0); }
};

inline double wrap(double a, double period) { return a - period * std::floor(a / period); }

// The value of a scalar, whether plain or dual (for branches that only look at values).
inline double value_of(double a) { return a; }
template <int N>
double value_of(const Dual<N>& a) { return a.v; }

}  // namespace chaos::detail
