#include "chaos/models/systems.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "chaos/error.hpp"
#include "chaos/random.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

// Shortest text that reads back as the same double: 0.15, not 0.14999999999999999.
std::string num(double v) { return format_number(v, Precision::shortest); }

void require_samples(std::size_t n, const char* system) {
  if (n == 0) refuse_parameter(std::string(system) + ": the number of samples n must be at least 1 (got n = 0)");
}

void require_positive(double v, const char* system, const char* name) {
  if (!(std::isfinite(v) && v > 0.0))
    refuse_parameter(std::string(system) + ": " + name + " must be finite and positive (got " + name + " = " + num(v) + ")");
}

void require_finite_parameter(double v, const char* system, const char* name) {
  if (!std::isfinite(v))
    refuse_parameter(std::string(system) + ": " + name + " must be finite (got " + name + " = " + num(v) + ")");
}

// Whole number of steps in `interval`, which must be a multiple of `step` within 1e-9 relative;
// `what` names the interval in the message.
// Step counts beyond this would run for days; refusing them also keeps the casts below exact.
constexpr double max_steps = 1e15;

std::size_t whole_steps(double interval, double step, const char* system, const char* what) {
  const double ratio = interval / step;
  const double k = std::round(ratio);
  if (k < 1.0 || std::abs(k * step - interval) > 1e-9 * interval)
    refuse_parameter(std::string(system) + ": " + what + " = " + num(interval) + " must be a whole multiple of the step " +
           num(step) + " (within 1e-9 relative); the ratio is " + num(ratio));
  if (k > max_steps)
    refuse_parameter(std::string(system) + ": " + what + " = " + num(interval) + " is " + num(k) + " steps of " + num(step) +
           "; at most 1e15 steps are allowed");
  return static_cast<std::size_t>(k);
}

// A transient of `time` units is discarded as the nearest whole number of steps.
std::size_t transient_steps(double time, double step, const char* system) {
  const double k = std::round(time / step);
  if (k > max_steps)
    refuse_parameter(std::string(system) + ": transient = " + num(time) + " is " + num(k) + " steps of " + num(step) +
           "; at most 1e15 steps are allowed");
  return static_cast<std::size_t>(k);
}

// Far beyond any attractor of these systems: the integration or the orbit has escaped. `where()`
// names the place ("t = ..." for flows, "iteration ..." for maps); it is only called on failure.
template <class Where>
void require_bounded(double v, const char* system, const Where& where, bool integrated) {
  if (std::isfinite(v) && std::abs(v) <= 1e100) return;
  refuse_parameter(std::string(system) + ": the solution left every bounded region at " + where() + " (value " + num(v) +
         "); the parameters have no bounded attractor from the documented initial condition" +
         (integrated ? ", or the step is too large for the integrator" : ""));
}

using State3 = std::array<double, 3>;

// One classical fourth-order Runge-Kutta step of dx/dt = f(x).
template <class F>
void rk4_step(State3& x, double h, const F& f) {
  State3 k1, k2, k3, k4, y;
  f(x, k1);
  for (int i = 0; i < 3; ++i) y[i] = x[i] + 0.5 * h * k1[i];
  f(y, k2);
  for (int i = 0; i < 3; ++i) y[i] = x[i] + 0.5 * h * k2[i];
  f(y, k3);
  for (int i = 0; i < 3; ++i) y[i] = x[i] + h * k3[i];
  f(y, k4);
  for (int i = 0; i < 3; ++i) x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

// Integrates an autonomous three-dimensional flow from x0 and samples it as FlowSampling says.
template <class F>
Trajectory sample_flow(std::size_t n, State3 x, const FlowSampling& s, const F& f, const char* system) {
  require_samples(n, system);
  try {
    s.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(e.code(), std::string(system) + ": " + e.what());
  }
  const std::size_t per_sample = whole_steps(s.dt, s.step, system, "sampling interval dt");
  const std::size_t skip = transient_steps(s.transient, s.step, system);
  for (std::size_t i = 0; i < skip; ++i) rk4_step(x, s.step, f);
  Trajectory out;
  out.names = {"x", "y", "z"};
  out.dt = s.dt;
  out.components.assign(3, std::vector<double>(n));
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0)
      for (std::size_t i = 0; i < per_sample; ++i) rk4_step(x, s.step, f);
    for (std::size_t c = 0; c < 3; ++c) {
      require_bounded(x[c], system, [&] { return "t = " + num(s.transient + static_cast<double>(k) * s.dt); }, true);
      out.components[c][k] = x[c];
    }
  }
  return out;
}

Trajectory scalar(std::vector<double> values, double dt) {
  Trajectory out;
  out.names = {"x"};
  out.components.push_back(std::move(values));
  out.dt = dt;
  return out;
}

}  // namespace

void FlowSampling::validate() const {
  require_positive(dt, "flow sampling", "dt");
  require_positive(step, "flow sampling", "step");
  if (!(std::isfinite(transient) && transient >= 0.0))
    refuse_parameter("flow sampling: transient must be finite and >= 0 (got transient = " + num(transient) + ")");
  whole_steps(dt, step, "flow sampling", "sampling interval dt");
}

// Lorenz (1963): dx/dt = sigma (y - x), dy/dt = x (rho - z) - y, dz/dt = x y - beta z, from (1, 1, 1).
Trajectory lorenz(std::size_t n, const LorenzParameters& p, const FlowSampling& s) {
  require_finite_parameter(p.sigma, "lorenz", "sigma");
  require_finite_parameter(p.rho, "lorenz", "rho");
  require_finite_parameter(p.beta, "lorenz", "beta");
  const auto f = [&p](const State3& x, State3& d) {
    d[0] = p.sigma * (x[1] - x[0]);
    d[1] = x[0] * (p.rho - x[2]) - x[1];
    d[2] = x[0] * x[1] - p.beta * x[2];
  };
  return sample_flow(n, {1.0, 1.0, 1.0}, s, f, "lorenz");
}

// Rossler (1976): dx/dt = -y - z, dy/dt = x + a y, dz/dt = b + z (x - c), from (1, 1, 1).
Trajectory rossler(std::size_t n, const RosslerParameters& p, const FlowSampling& s) {
  require_finite_parameter(p.a, "rossler", "a");
  require_finite_parameter(p.b, "rossler", "b");
  require_finite_parameter(p.c, "rossler", "c");
  const auto f = [&p](const State3& x, State3& d) {
    d[0] = -x[1] - x[2];
    d[1] = x[0] + p.a * x[1];
    d[2] = p.b + x[2] * (x[0] - p.c);
  };
  return sample_flow(n, {1.0, 1.0, 1.0}, s, f, "rossler");
}

// Henon (1976): x' = 1 - a x^2 + y, y' = b x, from (0, 0), which lies in the basin of the
// attractor at the classical parameters.
Trajectory henon(std::size_t n, const HenonParameters& p, std::size_t transient) {
  require_samples(n, "henon");
  require_finite_parameter(p.a, "henon", "a");
  require_finite_parameter(p.b, "henon", "b");
  double x = 0.0, y = 0.0;
  const auto step = [&] {
    const double xn = 1.0 - p.a * x * x + y;
    y = p.b * x;
    x = xn;
  };
  for (std::size_t i = 0; i < transient; ++i) {
    step();
    require_bounded(x, "henon", [&] { return "iteration " + std::to_string(i + 1); }, false);
  }
  Trajectory out;
  out.names = {"x", "y"};
  out.components.assign(2, std::vector<double>(n));
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) step();
    require_bounded(x, "henon", [&] { return "iteration " + std::to_string(transient + k); }, false);
    out.components[0][k] = x;
    out.components[1][k] = y;
  }
  return out;
}

// x' = r x (1 - x) from x0 uniform in (0, 1) drawn with `seed`.
//
// In floating point an orbit can land exactly on a point that the real map leaves only in theory:
// x = 1/2 maps to 1 and then to 0 for ever at r = 4, and 0 is a fixed point for every r; the
// fixed point 1 - 1/r (3/4 at r = 4) is representable and is reproduced exactly. Both are
// unstable for r > 1 and r > 3 respectively, so a real orbit never stays there; the generator
// replaces such a value by a fresh draw from the same seeded stream (a measure-zero event that keeps
// the output deterministic). For r <= 1 (r <= 3) the same points are attracting and are kept.
Trajectory logistic(std::size_t n, const LogisticParameters& p, std::size_t transient, std::uint64_t seed) {
  require_samples(n, "logistic");
  if (!(std::isfinite(p.r) && p.r > 0.0 && p.r <= 4.0))
    refuse_parameter("logistic: r must lie in (0, 4] so that orbits stay in [0, 1] (got r = " + num(p.r) + ")");
  Random rng(seed);
  const auto collapsed = [&p](double previous, double current) {
    if (p.r > 1.0 && (current <= 0.0 || current >= 1.0)) return true;
    return p.r > 3.0 && current == previous;
  };
  double x = rng.uniform_open();
  const auto step = [&] {
    double next = p.r * x * (1.0 - x);
    while (collapsed(x, next)) next = rng.uniform_open();
    x = next;
  };
  for (std::size_t i = 0; i < transient; ++i) step();
  std::vector<double> values(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) step();
    values[k] = x;
  }
  return scalar(std::move(values), 1.0);
}

// Ikeda map in Sprott's form: z' = 1 + mu z exp(i (a - b / (1 + |z|^2))), z = x + i y, from 0.
// The rotation angle depends on |z| only, so the Jacobian determinant is mu^2 and
// lambda1 + lambda2 = 2 ln mu.
Trajectory ikeda(std::size_t n, const IkedaParameters& p, std::size_t transient) {
  require_samples(n, "ikeda");
  require_finite_parameter(p.mu, "ikeda", "mu");
  require_finite_parameter(p.a, "ikeda", "a");
  require_finite_parameter(p.b, "ikeda", "b");
  double x = 0.0, y = 0.0;
  const auto step = [&] {
    const double t = p.a - p.b / (1.0 + x * x + y * y);
    const double c = std::cos(t), s = std::sin(t);
    const double xn = 1.0 + p.mu * (x * c - y * s);
    y = p.mu * (x * s + y * c);
    x = xn;
  };
  for (std::size_t i = 0; i < transient; ++i) {
    step();
    require_bounded(x, "ikeda", [&] { return "iteration " + std::to_string(i + 1); }, false);
  }
  Trajectory out;
  out.names = {"x", "y"};
  out.components.assign(2, std::vector<double>(n));
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) step();
    require_bounded(x, "ikeda", [&] { return "iteration " + std::to_string(transient + k); }, false);
    out.components[0][k] = x;
    out.components[1][k] = y;
  }
  return out;
}

// dx/dt = beta x_tau / (1 + x_tau^n) - gamma x with x_tau = x(t - tau) and x(t) = 1.2 on [-tau, 0].
// RK4 at h = tau / M (M = steps_per_delay) on the grid t_k = k h, so the delayed values at whole
// steps are grid values x_{k-M}. The half-step stages need x(t_k + h/2 - tau), the midpoint of
// [t_{k-M}, t_{k-M+1}]; the cubic Hermite interpolant through the two grid values and their
// derivatives gives (x_a + x_b)/2 + h (f_a - f_b)/8, an O(h^4) error that keeps the method fourth
// order. Inside the initial history the delayed value is exactly 1.2.
Trajectory mackey_glass(std::size_t n, const MackeyGlassParameters& p, double dt, std::size_t steps_per_delay,
                        double transient) {
  require_samples(n, "mackey_glass");
  require_positive(p.beta, "mackey_glass", "beta");
  require_positive(p.gamma, "mackey_glass", "gamma");
  require_positive(p.n, "mackey_glass", "n");
  require_positive(p.tau, "mackey_glass", "tau");
  require_positive(dt, "mackey_glass", "dt");
  if (steps_per_delay == 0) refuse_parameter("mackey_glass: steps_per_delay must be at least 1 (got 0)");
  if (!(std::isfinite(transient) && transient >= 0.0))
    refuse_parameter("mackey_glass: transient must be finite and >= 0 (got transient = " + num(transient) + ")");
  constexpr double history = 1.2;
  const std::size_t m = steps_per_delay;
  const double h = p.tau / static_cast<double>(m);
  const std::size_t per_sample = whole_steps(dt, h, "mackey_glass", "sampling interval dt");
  const std::size_t skip = transient_steps(transient, h, "mackey_glass");

  const auto rhs = [&p](double x, double delayed) {
    return p.beta * delayed / (1.0 + std::pow(delayed, p.n)) - p.gamma * x;
  };
  // Ring buffers of the last m + 1 grid values and their derivatives: slot k mod (m + 1) holds
  // step k, so steps k - m .. k are available when stepping from k.
  std::vector<double> xs(m + 1), fs(m + 1);
  std::size_t k = 0;  // current step index
  double x = history;
  xs[0] = x;
  const auto delayed_at = [&](std::size_t j) {  // x at grid step j - m, for j >= 0
    return j < m ? history : xs[(j - m) % (m + 1)];
  };
  const auto step = [&] {
    const double d0 = delayed_at(k);
    const double k1 = rhs(x, d0);
    fs[k % (m + 1)] = k1;
    const double d1 = delayed_at(k + 1);
    // Midpoint of [t_{k-m}, t_{k-m+1}]: inside the constant history while k + 1 <= m.
    const double dmid = k + 1 <= m ? history
                                   : 0.5 * (d0 + d1) + h * (fs[(k - m) % (m + 1)] - fs[(k + 1 - m) % (m + 1)]) / 8.0;
    const double k2 = rhs(x + 0.5 * h * k1, dmid);
    const double k3 = rhs(x + 0.5 * h * k2, dmid);
    const double k4 = rhs(x + h * k3, d1);
    x += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    ++k;
    xs[k % (m + 1)] = x;
    require_bounded(x, "mackey_glass", [&] { return "t = " + num(static_cast<double>(k) * h); }, true);
  };
  for (std::size_t i = 0; i < skip; ++i) step();
  std::vector<double> values(n);
  for (std::size_t j = 0; j < n; ++j) {
    if (j > 0)
      for (std::size_t i = 0; i < per_sample; ++i) step();
    values[j] = x;
  }
  return scalar(std::move(values), dt);
}

Trajectory sine(std::size_t n, double frequency, double dt) {
  require_samples(n, "sine");
  require_positive(frequency, "sine", "frequency");
  require_positive(dt, "sine", "dt");
  std::vector<double> values(n);
  const double w = 2.0 * std::numbers::pi * frequency;
  // t = k dt computed afresh for every sample, so no rounding accumulates along the series.
  for (std::size_t k = 0; k < n; ++k) values[k] = std::sin(w * (static_cast<double>(k) * dt));
  return scalar(std::move(values), dt);
}

Trajectory quasi_periodic(std::size_t n, double f1, double f2, double dt) {
  require_samples(n, "quasi_periodic");
  require_positive(f1, "quasi_periodic", "f1");
  require_positive(f2, "quasi_periodic", "f2");
  require_positive(dt, "quasi_periodic", "dt");
  std::vector<double> values(n);
  const double w1 = 2.0 * std::numbers::pi * f1, w2 = 2.0 * std::numbers::pi * f2;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * dt;
    values[k] = std::sin(w1 * t) + std::sin(w2 * t);
  }
  return scalar(std::move(values), dt);
}

Trajectory white_noise(std::size_t n, std::uint64_t seed) {
  require_samples(n, "white_noise");
  Random rng(seed);
  std::vector<double> values(n);
  for (auto& v : values) v = rng.gaussian();
  return scalar(std::move(values), 1.0);
}

Trajectory uniform_noise(std::size_t n, std::uint64_t seed) {
  require_samples(n, "uniform_noise");
  Random rng(seed);
  std::vector<double> values(n);
  for (auto& v : values) v = rng.uniform();
  return scalar(std::move(values), 1.0);
}

Trajectory ar1(std::size_t n, double phi, std::uint64_t seed) {
  require_samples(n, "ar1");
  if (!(std::isfinite(phi) && std::abs(phi) < 1.0))
    refuse_parameter("ar1: |phi| must be < 1 for a stationary process (got phi = " + num(phi) + ")");
  Random rng(seed);
  std::vector<double> values(n);
  // The stationary distribution N(0, 1 / (1 - phi^2)), so there is no transient to discard.
  values[0] = rng.gaussian() / std::sqrt(1.0 - phi * phi);
  for (std::size_t t = 1; t < n; ++t) values[t] = phi * values[t - 1] + rng.gaussian();
  return scalar(std::move(values), 1.0);
}

}  // namespace chaos
