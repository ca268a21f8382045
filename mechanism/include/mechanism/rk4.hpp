#pragma once
// Classical fourth-order Runge-Kutta at a fixed step (Kutta 1901; Hairer, Norsett & Wanner, Solving
// Ordinary Differential Equations I, 2nd ed., Springer 1993, Sec. II.1: c = (0, 1/2, 1/2, 1),
// b = (1/6, 1/3, 1/3, 1/6)).
//
// After each step the stepper holds x0 = x(t0), f0 = f(t0, x0), x1 = x(t1), f1 = f(t1, x1) and
// interpolates inside the step with the cubic Hermite polynomial through them (error O(h^4) per
// step, the same order as the method's global error, so dense samples are as good as step ends).
// f1 is computed eagerly: it is both the Hermite slope and the next step's first stage, so a run of
// steps costs 4 evaluations of rhs per step. The reuse happens only when the caller passes back
// exactly (t1, x1) (compared bit for bit) and has not called invalidate().

#include <cstddef>
#include <limits>

#include "mechanism/ode.hpp"

namespace mechanism {

class Rk4 {
 public:
  // Advances t by h and x to the RK4 approximation of x(t + h). h must be finite and > 0
  // (InvalidParameter "h"). The first call for a state size sizes the work vectors once.
  template <OdeSystem S>
  void step(const S& sys, double& t, State& x, double h);

  // The cubic Hermite interpolant of the last step at t in [t_previous(), t_current()]; exact at
  // the ends. Throws InvalidParameter ("t") before the first step or outside the step.
  void interpolate(double t, State& out) const;

  double t_previous() const { return t0_; }  // NaN before the first step
  double t_current() const { return t1_; }

  // The caller changed the system's discrete memory (or wants a fresh start): the next step
  // evaluates its first stage again instead of reusing f(t1, x1). Changing x itself is detected.
  void invalidate() { reuse_ = false; }

  std::size_t rhs_evaluations() const { return rhs_evaluations_; }

 private:
  void resize(Eigen::Index n) {
    for (State* v : {&x0_, &f0_, &x1_, &f1_, &k2_, &k3_, &xs_}) v->resize(n);
    reuse_ = false;
    t0_ = t1_ = std::numeric_limits<double>::quiet_NaN();
  }

  State x0_, f0_, x1_, f1_, k2_, k3_, xs_;
  double t0_ = std::numeric_limits<double>::quiet_NaN();
  double t1_ = std::numeric_limits<double>::quiet_NaN();
  bool reuse_ = false;
  std::size_t rhs_evaluations_ = 0;
};

template <OdeSystem S>
inline void Rk4::step(const S& sys, double& t, State& x, double h) {
  if (!(h > 0.0) || !(h < std::numeric_limits<double>::infinity()))
    detail::throw_invalid("h", h, "the step must be finite and > 0");
  if (x1_.size() != x.size()) resize(x.size());

  const bool reuse = reuse_ && t == t1_ && detail::same_state(x, x1_);
  reuse_ = false;  // stays false if rhs throws part-way through
  if (reuse) {
    // First same as last: the previous step's end point and slope become this step's start.
    x0_.swap(x1_);
    f0_.swap(f1_);
  } else {
    x0_ = x;
    sys.rhs(t, x0_, f0_);
    ++rhs_evaluations_;
  }
  const double half = 0.5 * h;
  xs_ = x0_ + half * f0_;
  sys.rhs(t + half, xs_, k2_);
  xs_ = x0_ + half * k2_;
  sys.rhs(t + half, xs_, k3_);
  xs_ = x0_ + h * k3_;
  const double t1 = t + h;
  sys.rhs(t1, xs_, f1_);  // k4, kept in f1_ until f(t1, x1) overwrites it below
  x1_ = x0_ + (h / 6.0) * (f0_ + 2.0 * k2_ + 2.0 * k3_ + f1_);
  sys.rhs(t1, x1_, f1_);
  rhs_evaluations_ += 4;

  t0_ = t;
  t1_ = t1;
  t = t1;
  x = x1_;
  reuse_ = true;
}

inline void Rk4::interpolate(double t, State& out) const {
  if (!(t >= t0_ && t <= t1_))
    detail::throw_invalid("t", t, "interpolate needs a time inside the last step [t_previous(), t_current()]");
  const double h = t1_ - t0_;
  const double s = (t - t0_) / h;
  const double s2 = s * s, s3 = s2 * s;
  // Hermite basis h00, h01, h10, h11 on [0, 1]; the derivative weights carry the factor h.
  out = (2.0 * s3 - 3.0 * s2 + 1.0) * x0_ + (3.0 * s2 - 2.0 * s3) * x1_ + (h * (s3 - 2.0 * s2 + s)) * f0_ +
        (h * (s3 - s2)) * f1_;
}

}  // namespace mechanism
