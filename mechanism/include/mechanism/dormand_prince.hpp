#pragma once
// Dormand-Prince 5(4), the explicit embedded Runge-Kutta pair of J. R. Dormand and P. J. Prince,
// "A family of embedded Runge-Kutta formulae", J. Comput. Appl. Math. 6 (1980) 19-26, as used in the
// code DOPRI5 of Hairer, Norsett & Wanner, Solving Ordinary Differential Equations I, 2nd ed.,
// Springer 1993 (HNW), Sec. II.5 (tableau, Table 5.2) and Sec. II.6 (dense output of order 4 with the
// coefficients of L. F. Shampine, "Some practical Runge-Kutta formulas", Math. Comp. 46 (1986) 135-150).
//
// - Local extrapolation: the step is advanced with the 5th-order weights b; the 4th-order embedded
//   solution only serves the error estimate err = h * sum_i (b_i - bhat_i) k_i.
// - FSAL: the 7th stage is f(t + h, x_new), so an accepted step hands its last stage to the next
//   step as k1: 6 evaluations of rhs per step after the first.
// - Error norm (HNW Sec. II.4, automatic step size control): ||err|| = sqrt( (1/n) sum_i (err_i / sc_i)^2 ) with
//   sc_i = absolute_tolerance + relative_tolerance * max(|x_i|, |x_new_i|); accepted when <= 1.
// - Step-size controller (HNW Sec. II.4; PI control: K. Gustafsson, ACM TOMS 17 (1991) 533-554, and
//   Hairer & Wanner, Solving ODEs II, Sec. IV.2; the constants of DOPRI5): with
//   a = 1/5 - 0.75 beta,  h_new = h * clamp(safety * err^-a * err_old^beta, min_factor, max_factor),
//   err_old the error of the previous accepted step (at least 1e-4). beta = 0 is the standard
//   controller h * safety * err^(-1/5); beta = 0.04 (the default) is DOPRI5's Lund-stabilised PI
//   controller. After a rejection the step is h * max(min_factor, safety * err^-a) and the next
//   accepted step may not grow (HNW's rule against oscillating rejections).
// - Dense output (HNW II.6): over the last accepted step [t0, t1], theta = (t - t0)/h,
//   u(theta) = x0 + theta (r2 + (1-theta) (r3 + theta (r4 + (1-theta) r5))) with
//   r2 = x1 - x0, r3 = h k1 - r2, r4 = r2 - h k7 - r3, r5 = h sum_i d_i k_i; it needs no extra
//   evaluation and is kept through rejected attempts.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "mechanism/ode.hpp"

namespace mechanism {

struct AdaptiveOptions {
  double relative_tolerance = 1e-8, absolute_tolerance = 1e-10;  // both > 0
  double initial_step = 0;  // 0: Hairer's automatic initial step (DormandPrince54::initial_step)
  double min_step = 1e-14, max_step = std::numeric_limits<double>::infinity();
  std::size_t max_steps = 100'000'000;  // attempts per advance_to call
  // Controller constants (HNW II.4 and DOPRI5's defaults); see the header comment.
  double safety = 0.9;            // in (0, 1]
  double min_factor = 0.2;        // in (0, 1): the most a step may shrink
  double max_factor = 10.0;       // > 1: the most a step may grow
  double controller_beta = 0.04;  // in [0, 0.2]: 0 = standard controller, 0.04 = DOPRI5's PI controller
  void validate() const;          // throws InvalidParameter naming the key ("relative_tolerance", ...)
};

enum class StepOutcome { accepted, rejected, step_underflow, non_finite };
// How advance_to ended: reached t_end, or the status that stopped it.
enum class AdvanceStatus { reached, step_underflow, non_finite, max_steps };

class DormandPrince54 {
 public:
  explicit DormandPrince54(AdaptiveOptions options = {}) : options_(options) { options_.validate(); }
  const AdaptiveOptions& options() const { return options_; }

  // options().initial_step when > 0, else Hairer's estimate (HNW II.4, "Starting step size", the
  // routine HINIT of DOPRI5): one Euler probe, 2 evaluations of rhs, the first reused by the first
  // attempt from (t, x). Always finite and > 0.
  template <OdeSystem S>
  double initial_step(const S& sys, double t, const State& x);

  // One attempt from (t, x) with step h (finite, > 0, else InvalidParameter "h"; capped at max_step):
  //   accepted:       t, x advanced; h = the next suggested step;
  //   rejected:       t, x unchanged; h reduced;
  //   step_underflow: h < min_step (on entry or after the reduction), or t + h == t; t, x unchanged;
  //   non_finite:     a stage or the error estimate is NaN/Inf; t, x, h unchanged.
  template <OdeSystem S>
  StepOutcome try_step(const S& sys, double& t, State& x, double& h);

  // One step of the 5th-order formula without error control (order checks, stepping exactly to an
  // event). Counts as an accepted step and becomes the dense-output step. A non-finite result is
  // left in x for the caller to see.
  template <OdeSystem S>
  void step_fixed(const S& sys, double& t, State& x, double h);
  // The same with the step end given as a time: t becomes exactly t_end (> t).
  template <OdeSystem S>
  void step_fixed_to(const S& sys, double& t, State& x, double t_end);

  // Repeated try_step up to exactly t_end (the last step is stretched or cut to land on it, as
  // DOPRI5 does); h in: the first step to try, out: the next suggested step.
  template <OdeSystem S>
  AdvanceStatus advance_to(const S& sys, double& t, State& x, double t_end, double& h);

  // Dense output over the last accepted step, t in [t_previous(), t_current()] (InvalidParameter
  // "t" outside it or before the first accepted step). Exact at both ends.
  void interpolate(double t, State& out) const;
  double t_previous() const { return t0_; }  // NaN before the first accepted step
  double t_current() const { return t1_; }

  // The caller changed the system's discrete memory: the next attempt evaluates k1 afresh instead of
  // reusing a stored f(t, x). (A changed x or t is detected without it.) The dense output stays.
  void invalidate() { end_valid_ = start_valid_ = work_valid_ = false; }

  std::size_t accepted_steps() const { return accepted_; }
  std::size_t rejected_steps() const { return rejected_; }
  std::size_t rhs_evaluations() const { return rhs_evaluations_; }
  double last_error() const { return last_error_; }  // scaled error norm of the last try_step

 private:
  // Published coefficients: Dormand & Prince (1980); HNW Table 5.2 (tableau) and the DOPRI5
  // dense-output constants d_i (Shampine 1986). The e_i = b_i - bhat_i.
  static constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
  static constexpr double a21 = 1.0 / 5;
  static constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
  static constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
  static constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
  static constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                          a65 = -5103.0 / 18656;
  static constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84;
  static constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                          e6 = 22.0 / 525, e7 = -1.0 / 40;
  static constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                          d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                          d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;

  State* work() { return k_[1 - accepted_set_]; }
  const State* work() const { return k_[1 - accepted_set_]; }
  void prepare(const State& x) {
    if (x.size() != x1_.size() || !sized_) resize(x.size());
  }
  void resize(Eigen::Index n);
  template <OdeSystem S>
  void first_stage(const S& sys, double t, const State& x);
  template <OdeSystem S>
  void stages(const S& sys, double t, const State& x, double h, double t_new);
  double error_norm(const State& x, double h, const State* weights = nullptr) const;
  void accept(double& t, State& x, double t_new);
  template <OdeSystem S>
  StepOutcome controlled(const S& sys, double& t, State& x, double& h, double t_new);

  AdaptiveOptions options_;
  // Two stage sets: the accepted step's stages (dense output, FSAL source) and the work set of the
  // current attempt, swapped on acceptance so that a rejected attempt never spoils the dense output.
  State k_[2][7];
  int accepted_set_ = 0;
  State ys_, x_new_, x0_, x1_, work_x_, weights_;
  double t0_ = std::numeric_limits<double>::quiet_NaN(), t1_ = std::numeric_limits<double>::quiet_NaN();
  double work_t_ = 0;
  bool sized_ = false, have_step_ = false;
  bool end_valid_ = false;    // k_[acc][6] == f(t1_, x1_)
  bool start_valid_ = false;  // k_[acc][0] == f(t0_, x0_): re-stepping from the step start to an event
  bool work_valid_ = false;   // work()[0] == f(work_t_, work_x_): after a rejection or initial_step
  bool last_rejected_ = false;
  static constexpr double log_error_floor = -9.210340371976184;  // log(1e-4): DOPRI5's floor on err_old
  double log_error_old_ = log_error_floor;
  double last_error_ = std::numeric_limits<double>::quiet_NaN();
  std::size_t accepted_ = 0, rejected_ = 0, rhs_evaluations_ = 0;
};

inline void DormandPrince54::resize(Eigen::Index n) {
  for (auto& set : k_)
    for (State& k : set) k.resize(n);
  for (State* v : {&ys_, &x_new_, &x0_, &x1_, &work_x_, &weights_}) v->resize(n);
  sized_ = true;
  have_step_ = end_valid_ = start_valid_ = work_valid_ = false;
  t0_ = t1_ = std::numeric_limits<double>::quiet_NaN();
}

template <OdeSystem S>
inline void DormandPrince54::first_stage(const S& sys, double t, const State& x) {
  State* k = work();
  if (end_valid_ && t == t1_ && detail::same_state(x, x1_)) {
    k[0] = k_[accepted_set_][6];  // FSAL
  } else if (start_valid_ && t == t0_ && detail::same_state(x, x0_)) {
    k[0] = k_[accepted_set_][0];  // re-step from the start of the last step (to an event time)
  } else if (!(work_valid_ && t == work_t_ && detail::same_state(x, work_x_))) {
    sys.rhs(t, x, k[0]);
    ++rhs_evaluations_;
    work_t_ = t;
    work_x_ = x;
    work_valid_ = true;
  }
}

template <OdeSystem S>
inline void DormandPrince54::stages(const S& sys, double t, const State& x, double h, double t_new) {
  State* k = work();
  ys_ = x + (h * a21) * k[0];
  sys.rhs(t + c2 * h, ys_, k[1]);
  ys_ = x + h * (a31 * k[0] + a32 * k[1]);
  sys.rhs(t + c3 * h, ys_, k[2]);
  ys_ = x + h * (a41 * k[0] + a42 * k[1] + a43 * k[2]);
  sys.rhs(t + c4 * h, ys_, k[3]);
  ys_ = x + h * (a51 * k[0] + a52 * k[1] + a53 * k[2] + a54 * k[3]);
  sys.rhs(t + c5 * h, ys_, k[4]);
  ys_ = x + h * (a61 * k[0] + a62 * k[1] + a63 * k[2] + a64 * k[3] + a65 * k[4]);
  sys.rhs(t_new, ys_, k[5]);
  x_new_ = x + h * (b1 * k[0] + b3 * k[2] + b4 * k[3] + b5 * k[4] + b6 * k[5]);
  if constexpr (WeightedRhsSystem<S>)
    sys.rhs_and_error_weights(t_new, x_new_, k[6], weights_);  // controlled() reads weights_
  else
    sys.rhs(t_new, x_new_, k[6]);
  rhs_evaluations_ += 6;
}

inline double DormandPrince54::error_norm(const State& x, double h, const State* weights) const {
  const Eigen::Index n = x.size();
  if (n == 0) return 0.0;
  const State* k = work();
  const double atol = options_.absolute_tolerance, rtol = options_.relative_tolerance;
  // One fused pass: no temporary vector.
  const auto scaled = (h * (e1 * k[0] + e3 * k[2] + e4 * k[3] + e5 * k[4] + e6 * k[5] + e7 * k[6])).array() /
                      (rtol * x.array().abs().max(x_new_.array().abs()) + atol);
  const double sum = weights ? (scaled * weights->array()).square().sum() : scaled.square().sum();
  return std::sqrt(sum / static_cast<double>(n));
}

inline void DormandPrince54::accept(double& t, State& x, double t_new) {
  accepted_set_ = 1 - accepted_set_;  // the work set becomes the accepted step's set
  x0_ = x;
  x1_.swap(x_new_);
  x = x1_;
  t0_ = t;
  t1_ = t_new;
  t = t_new;
  have_step_ = end_valid_ = start_valid_ = true;
  work_valid_ = false;  // the new work set holds the old step's stages
  ++accepted_;
}

template <OdeSystem S>
inline StepOutcome DormandPrince54::controlled(const S& sys, double& t, State& x, double& h, double t_new) {
  prepare(x);
  first_stage(sys, t, x);
  stages(sys, t, x, h, t_new);
  double err = 0.0;
  if constexpr (ErrorWeightedSystem<S>) {
    if constexpr (!WeightedRhsSystem<S>) sys.error_weights(t_new, x_new_, weights_);  // else stages() did
    err = error_norm(x, h, &weights_);
  } else {
    err = error_norm(x, h);
  }
  last_error_ = err;
  if (!std::isfinite(err) || !x_new_.allFinite()) return StepOutcome::non_finite;

  // err^-a * err_old^beta as one exp of logs (cheaper than two pow); log(0) = -inf gives +inf,
  // which the clamp turns into max_factor.
  const double beta = options_.controller_beta, exponent = 0.2 - 0.75 * beta;
  const double log_err = std::log(err);
  if (err <= 1.0) {
    double factor = options_.safety * std::exp(beta * log_error_old_ - exponent * log_err);
    factor = std::clamp(factor, options_.min_factor, options_.max_factor);
    double h_new = std::min(h * factor, options_.max_step);
    if (last_rejected_) h_new = std::min(h_new, h);
    log_error_old_ = std::max(log_err, log_error_floor);
    last_rejected_ = false;
    accept(t, x, t_new);
    h = h_new;
    return StepOutcome::accepted;
  }
  h *= std::max(options_.min_factor, options_.safety * std::exp(-exponent * log_err));
  last_rejected_ = true;
  ++rejected_;
  if (h < options_.min_step || t + h == t) return StepOutcome::step_underflow;
  return StepOutcome::rejected;
}

template <OdeSystem S>
inline double DormandPrince54::initial_step(const S& sys, double t, const State& x) {
  const double h_max = options_.max_step;
  if (options_.initial_step > 0.0) return std::min(options_.initial_step, h_max);
  prepare(x);
  first_stage(sys, t, x);
  State* k = work();
  const State& f0 = k[0];
  const double atol = options_.absolute_tolerance, rtol = options_.relative_tolerance;
  // HINIT: h0 from |x| / |f0|, then h1 from an estimate of the second derivative, both in the
  // tolerance-scaled norm (sums of squares, as in DOPRI5).
  const double dnf = (f0.array() / (rtol * x.array().abs() + atol)).square().sum();
  const double dny = (x.array() / (rtol * x.array().abs() + atol)).square().sum();
  double h0 = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : 0.01 * std::sqrt(dny / dnf);
  h0 = std::min(h0, h_max);
  ys_ = x + h0 * f0;
  sys.rhs(t + h0, ys_, k[1]);  // k[1] is scratch here; every attempt recomputes it
  ++rhs_evaluations_;
  const double der2 = std::sqrt(((k[1] - f0).array() / (rtol * x.array().abs() + atol)).square().sum()) / h0;
  const double der12 = std::max(std::abs(der2), std::sqrt(dnf));
  const double h1 = der12 <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / der12, 1.0 / 5.0);
  const double h = std::min({100.0 * h0, h1, h_max});
  // A non-finite f0 gives no estimate; a small finite step lets the first attempt report non_finite.
  return std::isfinite(h) && h > 0.0 ? h : std::clamp(1e-6, options_.min_step, h_max);
}

template <OdeSystem S>
inline StepOutcome DormandPrince54::try_step(const S& sys, double& t, State& x, double& h) {
  if (!(h > 0.0) || !(h < std::numeric_limits<double>::infinity()))
    detail::throw_invalid("h", h, "the step must be finite and > 0");
  h = std::min(h, options_.max_step);
  if (h < options_.min_step || t + h == t) return StepOutcome::step_underflow;
  return controlled(sys, t, x, h, t + h);
}

template <OdeSystem S>
inline void DormandPrince54::step_fixed(const S& sys, double& t, State& x, double h) {
  if (!(h > 0.0) || !(h < std::numeric_limits<double>::infinity()))
    detail::throw_invalid("h", h, "the step must be finite and > 0");
  step_fixed_to(sys, t, x, t + h);
}

template <OdeSystem S>
inline void DormandPrince54::step_fixed_to(const S& sys, double& t, State& x, double t_end) {
  if (!(t_end > t) || !(t_end < std::numeric_limits<double>::infinity()))
    detail::throw_invalid("t_end", t_end, "the step end must be finite and > t");
  prepare(x);
  first_stage(sys, t, x);
  stages(sys, t, x, t_end - t, t_end);
  accept(t, x, t_end);
}

template <OdeSystem S>
inline AdvanceStatus DormandPrince54::advance_to(const S& sys, double& t, State& x, double t_end, double& h) {
  if (!(t_end >= t) || !(t_end < std::numeric_limits<double>::infinity()))
    detail::throw_invalid("t_end", t_end, "must be finite and >= t");
  if (!(h > 0.0) || !(h < std::numeric_limits<double>::infinity()))
    detail::throw_invalid("h", h, "the step must be finite and > 0");
  for (std::size_t attempts = 0; t < t_end; ++attempts) {
    if (attempts >= options_.max_steps) return AdvanceStatus::max_steps;
    h = std::min(h, options_.max_step);
    StepOutcome outcome;
    if (t + 1.01 * h >= t_end) {
      // The last step lands exactly on t_end; it may be shorter than min_step.
      h = t_end - t;
      outcome = controlled(sys, t, x, h, t_end);
    } else {
      if (h < options_.min_step || t + h == t) return AdvanceStatus::step_underflow;
      outcome = controlled(sys, t, x, h, t + h);
    }
    if (outcome == StepOutcome::step_underflow) return AdvanceStatus::step_underflow;
    if (outcome == StepOutcome::non_finite) return AdvanceStatus::non_finite;
  }
  return AdvanceStatus::reached;
}

inline void DormandPrince54::interpolate(double t, State& out) const {
  if (!have_step_ || !(t >= t0_ && t <= t1_))
    detail::throw_invalid("t", t, "interpolate needs a time inside the last accepted step [t_previous(), t_current()]");
  const State* k = k_[accepted_set_];
  const double h = t1_ - t0_;
  const double th = (t - t0_) / h, th1 = 1.0 - th;
  // The nested form of the header comment, expanded into one weighted sum so that Eigen evaluates it
  // in one pass: u = x0 + A r2 + B r3 + C r4 + D r5.
  const double A = th, B = th * th1, C = th * B, D = C * th1;
  out = (1.0 - A + B - 2.0 * C) * x0_ + (A - B + 2.0 * C) * x1_ + (h * (B - C + D * d1)) * k[0] + (h * D * d3) * k[2] +
        (h * D * d4) * k[3] + (h * D * d5) * k[4] + (h * D * d6) * k[5] + (h * (D * d7 - C)) * k[6];
}

}  // namespace mechanism
