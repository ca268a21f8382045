#include "chaos/models/lyapunov_spectrum.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "chaos/error.hpp"
#include "chaos/format.hpp"
#include "chaos/random.hpp"

namespace chaos {

namespace {

std::string num(double v) { return format_number(v, Precision::shortest); }

// Step counts beyond this would run for days; refusing them also keeps the casts exact.
constexpr double max_count = 1e15;

// `interval` must be a whole multiple of `unit` within 1e-9 relative, as in the generators' sampling.
std::size_t whole_multiple(double interval, double unit, const char* what, const char* unit_name) {
  const double ratio = interval / unit;
  const double k = std::round(ratio);
  if (k < 1.0 || std::abs(k * unit - interval) > 1e-9 * interval)
    refuse_parameter(std::string("lyapunov spectrum: ") + what + " = " + num(interval) + " must be a whole multiple of the " +
           unit_name + " " + num(unit) + " (within 1e-9 relative); the ratio is " + num(ratio));
  if (k > max_count)
    refuse_parameter(std::string("lyapunov spectrum: ") + what + " = " + num(interval) + " is " + num(k) + " " + unit_name +
           "s; at most 1e15 are allowed");
  return static_cast<std::size_t>(k);
}

// Far beyond any attractor of the reference systems: the orbit (or the integration) has escaped.
// `where()` names the time or iteration; it is only called on failure, so no string is built per step.
template <class Where>
void require_bounded(double v, const Where& where) {
  if (std::isfinite(v) && std::abs(v) <= 1e100) return;
  refuse_parameter("lyapunov spectrum: the orbit left every bounded region at " + where() + " (value " + num(v) +
         "); the parameters have no bounded attractor from this initial condition, or the step is too large");
}

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
// Tangent vectors are the columns of Y; the Jacobian is row-major so user callbacks can write it
// in the documented layout directly.
template <int D>
using Mat = Eigen::Matrix<double, D, D>;
template <int D>
using RowMat = Eigen::Matrix<double, D, D, (D == 1 ? Eigen::ColMajor : Eigen::RowMajor)>;

// Factorises Y = Q R, replaces Y by Q and, when `accumulate`, adds ln |R_ii| to the sums. Signs of
// R_ii are irrelevant: a column of Q with the opposite sign spans the same direction.
template <int D>
void reorthonormalise(Mat<D>& y, Eigen::HouseholderQR<Mat<D>>& qr, Vec<D>& sums, bool accumulate) {
  qr.compute(y);
  if (accumulate)
    for (Eigen::Index i = 0; i < y.cols(); ++i) sums[i] += std::log(std::abs(qr.matrixQR()(i, i)));
  y = qr.householderQ();
}

// Sums of ln |R_ii| overflow only if the tangent vectors did within one interval; -inf is a
// legitimate answer (a Jacobian with a zero singular value), inf or NaN is not.
template <int D>
void require_finite_growth(const Vec<D>& sums) {
  for (Eigen::Index i = 0; i < sums.size(); ++i)
    if (std::isnan(sums[i]) || sums[i] == std::numeric_limits<double>::infinity())
      refuse_parameter("lyapunov spectrum: the tangent vectors overflowed within one renormalisation interval (sum of ln|R_" +
             std::to_string(i + 1) + "| = " + num(sums[i]) + "); shorten the renormalisation interval");
}

template <int D>
LyapunovSpectrum finish(const Vec<D>& sums, double length, std::size_t renormalisations, std::vector<double> start) {
  LyapunovSpectrum out;
  out.exponents.resize(static_cast<std::size_t>(sums.size()));
  for (Eigen::Index i = 0; i < sums.size(); ++i) out.exponents[static_cast<std::size_t>(i)] = sums[i] / length;
  // QR orders the exponents by construction once the vectors are aligned; sorting guards the
  // cases where they never mix (a diagonal linear system keeps its axes, in their given order).
  std::sort(out.exponents.begin(), out.exponents.end(), std::greater<>());
  out.sum = 0.0;
  for (const double l : out.exponents) out.sum += l;
  out.kaplan_yorke_dimension = kaplan_yorke_dimension(out.exponents);
  out.renormalisations = renormalisations;
  out.averaging_length = length;
  out.initial_state = std::move(start);
  return out;
}

struct FlowPlan {
  std::size_t steps_per_interval;
  std::size_t transient_intervals;
  std::size_t intervals;
  double interval;  // steps_per_interval * step, the exact time between factorisations
};

FlowPlan plan_flow(const FlowSpectrumOptions& o) {
  o.validate();
  FlowPlan p{};
  p.steps_per_interval = whole_multiple(o.renormalisation_interval, o.step, "renormalisation_interval", "step");
  p.interval = static_cast<double>(p.steps_per_interval) * o.step;
  p.intervals = whole_multiple(o.time, o.renormalisation_interval, "time", "renormalisation interval");
  const double transient = std::round(o.transient / o.renormalisation_interval);
  if (transient > max_count) refuse_parameter("lyapunov spectrum: transient = " + num(o.transient) + " is too many intervals");
  p.transient_intervals = static_cast<std::size_t>(transient);
  if (static_cast<double>(p.intervals + p.transient_intervals) * static_cast<double>(p.steps_per_interval) > max_count)
    refuse_parameter("lyapunov spectrum: time + transient = " + num(o.time + o.transient) + " is more than 1e15 steps of " +
           num(o.step));
  return p;
}

// RK4 on the pair (x, Y) with dx/dt = f(x), dY/dt = J(x) Y: every stage evaluates the Jacobian at
// the stage's state, which makes Y exactly the derivative of the RK4 step map.
template <int D, class Field, class Jacobian>
LyapunovSpectrum integrate_flow(Eigen::Index d, const Field& field, const Jacobian& jacobian, Vec<D> x,
                                const FlowSpectrumOptions& o) {
  const FlowPlan plan = plan_flow(o);
  std::vector<double> start(x.data(), x.data() + d);
  const double h = o.step;
  Mat<D> y = Mat<D>::Identity(d, d);
  Vec<D> k1(d), k2(d), k3(d), k4(d), xs(d), sums = Vec<D>::Zero(d);
  Mat<D> c1(d, d), c2(d, d), c3(d, d), c4(d, d), ys(d, d);
  RowMat<D> j(d, d);
  Eigen::HouseholderQR<Mat<D>> qr(d, d);
  const auto stage = [&](const Vec<D>& xi, const Mat<D>& yi, Vec<D>& k, Mat<D>& c) {
    field(xi, k);
    jacobian(xi, j);
    c.noalias() = j * yi;
  };
  const std::size_t total = plan.transient_intervals + plan.intervals;
  for (std::size_t interval = 0; interval < total; ++interval) {
    for (std::size_t s = 0; s < plan.steps_per_interval; ++s) {
      stage(x, y, k1, c1);
      xs = x + 0.5 * h * k1;
      ys = y + 0.5 * h * c1;
      stage(xs, ys, k2, c2);
      xs = x + 0.5 * h * k2;
      ys = y + 0.5 * h * c2;
      stage(xs, ys, k3, c3);
      xs = x + h * k3;
      ys = y + h * c3;
      stage(xs, ys, k4, c4);
      x += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      y += h / 6.0 * (c1 + 2.0 * c2 + 2.0 * c3 + c4);
    }
    for (Eigen::Index i = 0; i < d; ++i)
      require_bounded(x[i], [&] { return "t = " + num(static_cast<double>(interval + 1) * plan.interval); });
    reorthonormalise<D>(y, qr, sums, interval >= plan.transient_intervals);
  }
  require_finite_growth<D>(sums);
  auto out = finish<D>(sums, static_cast<double>(plan.intervals) * plan.interval, plan.intervals, std::move(start));
  out.settings = o;
  return out;
}

template <int D, class Map, class Jacobian>
LyapunovSpectrum iterate_map(Eigen::Index d, const Map& map, const Jacobian& jacobian, Vec<D> x,
                             const MapSpectrumOptions& o) {
  o.validate();
  std::vector<double> start(x.data(), x.data() + d);
  const std::size_t per = o.renormalisation_interval;
  const std::size_t transient_intervals = (o.transient + per / 2) / per;  // rounded to whole intervals
  const std::size_t intervals = o.iterations / per;
  Mat<D> y = Mat<D>::Identity(d, d), next_y(d, d);
  Vec<D> next(d), sums = Vec<D>::Zero(d);
  RowMat<D> j(d, d);
  Eigen::HouseholderQR<Mat<D>> qr(d, d);
  std::size_t iteration = 0;
  for (std::size_t interval = 0; interval < transient_intervals + intervals; ++interval) {
    for (std::size_t s = 0; s < per; ++s) {
      jacobian(x, j);
      next_y.noalias() = j * y;
      y = next_y;
      map(x, next);
      x = next;
      ++iteration;
      for (Eigen::Index i = 0; i < d; ++i)
        require_bounded(x[i], [&] { return "iteration " + std::to_string(iteration); });
    }
    reorthonormalise<D>(y, qr, sums, interval >= transient_intervals);
  }
  require_finite_growth<D>(sums);
  auto out = finish<D>(sums, static_cast<double>(intervals * per), intervals, std::move(start));
  out.settings = o;
  return out;
}

void require_finite_parameter(double v, const char* system, const char* name) {
  if (!std::isfinite(v))
    refuse_parameter(std::string(system) + " spectrum: " + name + " must be finite (got " + name + " = " + num(v) + ")");
}

void check_system(std::size_t dimension, bool has_field, bool has_jacobian, std::span<const double> initial_state,
                  const char* kind) {
  if (dimension == 0) refuse_parameter(std::string("lyapunov spectrum: the ") + kind + " needs dimension >= 1 (got 0)");
  if (!has_field || !has_jacobian)
    refuse_parameter(std::string("lyapunov spectrum: the ") + kind + " needs both its equations and its Jacobian");
  if (initial_state.size() != dimension)
    refuse_parameter("lyapunov spectrum: the initial state has " + std::to_string(initial_state.size()) +
           " components but the " + kind + " has dimension " + std::to_string(dimension));
  for (std::size_t i = 0; i < initial_state.size(); ++i)
    if (!std::isfinite(initial_state[i]))
      refuse_parameter("lyapunov spectrum: initial state component " + std::to_string(i) + " is " + num(initial_state[i]) +
             "; it must be finite");
}

}  // namespace

void FlowSpectrumOptions::validate() const {
  const auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0))
      refuse_parameter(std::string("lyapunov spectrum: ") + name + " must be finite and positive (got " + name + " = " + num(v) +
             ")");
  };
  positive(step, "step");
  positive(renormalisation_interval, "renormalisation_interval");
  positive(time, "time");
  if (!(std::isfinite(transient) && transient >= 0.0))
    refuse_parameter("lyapunov spectrum: transient must be finite and >= 0 (got transient = " + num(transient) + ")");
  whole_multiple(renormalisation_interval, step, "renormalisation_interval", "step");
  whole_multiple(time, renormalisation_interval, "time", "renormalisation interval");
}

void MapSpectrumOptions::validate() const {
  if (renormalisation_interval == 0)
    refuse_parameter("lyapunov spectrum: renormalisation_interval must be at least 1 iteration (got 0)");
  if (iterations == 0 || iterations % renormalisation_interval != 0)
    refuse_parameter("lyapunov spectrum: iterations must be a positive whole multiple of renormalisation_interval (got "
           "iterations = " + std::to_string(iterations) + ", renormalisation_interval = " +
           std::to_string(renormalisation_interval) + ")");
  // As for flows' steps: a count no run could finish is refused rather than started.
  if (static_cast<double>(iterations) + static_cast<double>(transient) > max_count)
    refuse_parameter("lyapunov spectrum: iterations + transient = " + num(static_cast<double>(iterations) + static_cast<double>(transient)) +
           " is more than 1e15 iterations");
}

double kaplan_yorke_dimension(std::span<const double> exponents) {
  if (exponents.empty()) refuse_parameter("kaplan_yorke_dimension: no exponents given");
  std::vector<double> l(exponents.begin(), exponents.end());
  for (std::size_t i = 0; i < l.size(); ++i)
    if (std::isnan(l[i]) || l[i] == std::numeric_limits<double>::infinity())
      refuse_parameter("kaplan_yorke_dimension: exponent " + std::to_string(i) + " is " + num(l[i]) +
             "; exponents must be finite or -inf");
  std::sort(l.begin(), l.end(), std::greater<>());
  double partial = 0.0;
  for (std::size_t j = 0; j < l.size(); ++j) {
    if (partial + l[j] < 0.0) return static_cast<double>(j) + partial / std::abs(l[j]);
    partial += l[j];
  }
  return static_cast<double>(l.size());
}

LyapunovSpectrum flow_spectrum(const FlowSystem& system, std::span<const double> initial_state,
                               const FlowSpectrumOptions& options) {
  check_system(system.dimension, bool(system.field), bool(system.jacobian), initial_state, "flow");
  const auto d = static_cast<Eigen::Index>(system.dimension);
  const auto field = [&](const Vec<Eigen::Dynamic>& x, Vec<Eigen::Dynamic>& dx) {
    system.field(std::span<const double>(x.data(), system.dimension), std::span<double>(dx.data(), system.dimension));
  };
  const auto jacobian = [&](const Vec<Eigen::Dynamic>& x, RowMat<Eigen::Dynamic>& j) {
    system.jacobian(std::span<const double>(x.data(), system.dimension),
                    std::span<double>(j.data(), system.dimension * system.dimension));
  };
  const Vec<Eigen::Dynamic> x0 = Eigen::Map<const Vec<Eigen::Dynamic>>(initial_state.data(), d);
  return integrate_flow<Eigen::Dynamic>(d, field, jacobian, x0, options);
}

LyapunovSpectrum map_spectrum(const MapSystem& system, std::span<const double> initial_state,
                              const MapSpectrumOptions& options) {
  check_system(system.dimension, bool(system.map), bool(system.jacobian), initial_state, "map");
  const auto d = static_cast<Eigen::Index>(system.dimension);
  const auto map = [&](const Vec<Eigen::Dynamic>& x, Vec<Eigen::Dynamic>& next) {
    system.map(std::span<const double>(x.data(), system.dimension), std::span<double>(next.data(), system.dimension));
  };
  const auto jacobian = [&](const Vec<Eigen::Dynamic>& x, RowMat<Eigen::Dynamic>& j) {
    system.jacobian(std::span<const double>(x.data(), system.dimension),
                    std::span<double>(j.data(), system.dimension * system.dimension));
  };
  const Vec<Eigen::Dynamic> x0 = Eigen::Map<const Vec<Eigen::Dynamic>>(initial_state.data(), d);
  return iterate_map<Eigen::Dynamic>(d, map, jacobian, x0, options);
}

// Lorenz (1963) as in chaos::lorenz: J = [[-sigma, sigma, 0], [rho - z, -1, -x], [y, x, -beta]].
LyapunovSpectrum lorenz_spectrum(const LorenzParameters& p, const FlowSpectrumOptions& options) {
  require_finite_parameter(p.sigma, "lorenz", "sigma");
  require_finite_parameter(p.rho, "lorenz", "rho");
  require_finite_parameter(p.beta, "lorenz", "beta");
  const auto field = [&p](const Vec<3>& x, Vec<3>& d) {
    d[0] = p.sigma * (x[1] - x[0]);
    d[1] = x[0] * (p.rho - x[2]) - x[1];
    d[2] = x[0] * x[1] - p.beta * x[2];
  };
  const auto jacobian = [&p](const Vec<3>& x, RowMat<3>& j) {
    j << -p.sigma, p.sigma, 0.0,
         p.rho - x[2], -1.0, -x[0],
         x[1], x[0], -p.beta;
  };
  return integrate_flow<3>(3, field, jacobian, Vec<3>(1.0, 1.0, 1.0), options);
}

// Rossler (1976) as in chaos::rossler: J = [[0, -1, -1], [1, a, 0], [z, 0, x - c]].
LyapunovSpectrum rossler_spectrum(const RosslerParameters& p, const FlowSpectrumOptions& options) {
  require_finite_parameter(p.a, "rossler", "a");
  require_finite_parameter(p.b, "rossler", "b");
  require_finite_parameter(p.c, "rossler", "c");
  const auto field = [&p](const Vec<3>& x, Vec<3>& d) {
    d[0] = -x[1] - x[2];
    d[1] = x[0] + p.a * x[1];
    d[2] = p.b + x[2] * (x[0] - p.c);
  };
  const auto jacobian = [&p](const Vec<3>& x, RowMat<3>& j) {
    j << 0.0, -1.0, -1.0,
         1.0, p.a, 0.0,
         x[2], 0.0, x[0] - p.c;
  };
  return integrate_flow<3>(3, field, jacobian, Vec<3>(1.0, 1.0, 1.0), options);
}

// Henon (1976) as in chaos::henon: J = [[-2 a x, 1], [b, 0]], |det J| = |b|.
LyapunovSpectrum henon_spectrum(const HenonParameters& p, const MapSpectrumOptions& options) {
  require_finite_parameter(p.a, "henon", "a");
  require_finite_parameter(p.b, "henon", "b");
  const auto map = [&p](const Vec<2>& x, Vec<2>& next) {
    next[0] = 1.0 - p.a * x[0] * x[0] + x[1];
    next[1] = p.b * x[0];
  };
  const auto jacobian = [&p](const Vec<2>& x, RowMat<2>& j) {
    j << -2.0 * p.a * x[0], 1.0,
         p.b, 0.0;
  };
  return iterate_map<2>(2, map, jacobian, Vec<2>(0.0, 0.0), options);
}

// Ikeda in Sprott's form, as in chaos::ikeda: z' = 1 + mu z e^{i t}, t = a - b / (1 + |z|^2). With
// u = x cos t - y sin t, v = x sin t + y cos t and dt/dx = 2 b x / (1 + |z|^2)^2 (likewise y):
//   dx'/dx = mu (cos t - v dt/dx),  dx'/dy = mu (-sin t - v dt/dy),
//   dy'/dx = mu (sin t + u dt/dx),  dy'/dy = mu (cos t + u dt/dy),
// whose determinant is mu^2 (the rotation angle depends on |z| only).
LyapunovSpectrum ikeda_spectrum(const IkedaParameters& p, const MapSpectrumOptions& options) {
  require_finite_parameter(p.mu, "ikeda", "mu");
  require_finite_parameter(p.a, "ikeda", "a");
  require_finite_parameter(p.b, "ikeda", "b");
  const auto map = [&p](const Vec<2>& z, Vec<2>& next) {
    const double t = p.a - p.b / (1.0 + z[0] * z[0] + z[1] * z[1]);
    const double c = std::cos(t), s = std::sin(t);
    next[0] = 1.0 + p.mu * (z[0] * c - z[1] * s);
    next[1] = p.mu * (z[0] * s + z[1] * c);
  };
  const auto jacobian = [&p](const Vec<2>& z, RowMat<2>& j) {
    const double r = 1.0 + z[0] * z[0] + z[1] * z[1];
    const double t = p.a - p.b / r;
    const double c = std::cos(t), s = std::sin(t);
    const double u = z[0] * c - z[1] * s, v = z[0] * s + z[1] * c;
    const double tx = 2.0 * p.b * z[0] / (r * r), ty = 2.0 * p.b * z[1] / (r * r);
    j << p.mu * (c - v * tx), p.mu * (-s - v * ty),
         p.mu * (s + u * tx), p.mu * (c + u * ty);
  };
  return iterate_map<2>(2, map, jacobian, Vec<2>(0.0, 0.0), options);
}

// lambda = mean of ln |r (1 - 2 x_n)| along the orbit of chaos::logistic. In one dimension the QR
// step is the product of derivatives, so the logarithms are summed every iteration (the same value
// for any renormalisation interval, without overflow).
LyapunovSpectrum logistic_spectrum(const LogisticParameters& p, const MapSpectrumOptions& options,
                                   std::uint64_t seed) {
  options.validate();
  if (!(std::isfinite(p.r) && p.r > 0.0 && p.r <= 4.0))
    refuse_parameter("logistic spectrum: r must lie in (0, 4] so that orbits stay in [0, 1] (got r = " + num(p.r) + ")");
  Random rng(seed);
  // The generator's rule (systems.cpp): an orbit that lands on 0, 1 or the unstable fixed point in
  // floating point, where the real map never stays, continues from a fresh draw of the same stream.
  const auto collapsed = [&p](double previous, double current) {
    if (p.r > 1.0 && (current <= 0.0 || current >= 1.0)) return true;
    return p.r > 3.0 && current == previous;
  };
  double x = rng.uniform_open();
  const double x0 = x;
  const auto step = [&] {
    double next = p.r * x * (1.0 - x);
    while (collapsed(x, next)) next = rng.uniform_open();
    x = next;
  };
  const std::size_t per = options.renormalisation_interval;
  const std::size_t transient = (options.transient + per / 2) / per * per;
  for (std::size_t i = 0; i < transient; ++i) step();
  Vec<1> sums = Vec<1>::Zero();
  for (std::size_t i = 0; i < options.iterations; ++i) {
    sums[0] += std::log(std::abs(p.r * (1.0 - 2.0 * x)));
    step();
  }
  auto out = finish<1>(sums, static_cast<double>(options.iterations), options.iterations / per, {x0});
  out.settings = options;
  return out;
}

bool has_spectrum(SystemKind system) noexcept {
  switch (system) {
    case SystemKind::lorenz:
    case SystemKind::rossler:
    case SystemKind::henon:
    case SystemKind::logistic:
    case SystemKind::ikeda: return true;
    default: return false;
  }
}

bool is_flow(SystemKind system) noexcept { return system == SystemKind::lorenz || system == SystemKind::rossler; }

LyapunovSpectrum spectrum(const SpectrumRequest& request) {
  if (!has_spectrum(request.system))
    refuse_parameter(std::string("lyapunov spectrum: no equations for system '") + to_string(request.system) +
           "' (spectra exist for lorenz, rossler, henon, logistic, ikeda)");
  // The model parameters are the generator's parameters less its sampling settings.
  std::map<std::string, double> p;
  for (const auto& parameter : system_parameters(request.system))
    if (parameter.name != "dt" && parameter.name != "step" && parameter.name != "transient")
      p[parameter.name] = parameter.default_value;
  for (const auto& [name, value] : request.parameters) {
    if (!p.count(name)) {
      std::string valid;
      for (const auto& [known, unused] : p) valid += (valid.empty() ? "" : ", ") + known;
      refuse_parameter(std::string("lyapunov spectrum: system ") + to_string(request.system) + " has no model parameter '" +
             name + "' (valid: " + valid + ")");
    }
    p[name] = value;
  }
  switch (request.system) {
    case SystemKind::lorenz: return lorenz_spectrum({p["sigma"], p["rho"], p["beta"]}, request.flow);
    case SystemKind::rossler: return rossler_spectrum({p["a"], p["b"], p["c"]}, request.flow);
    case SystemKind::henon: return henon_spectrum({p["a"], p["b"]}, request.map);
    case SystemKind::ikeda: return ikeda_spectrum({p["mu"], p["a"], p["b"]}, request.map);
    case SystemKind::logistic: return logistic_spectrum({p["r"]}, request.map, request.seed);
    default: break;
  }
  refuse_parameter("lyapunov spectrum: unknown system");
}

}  // namespace chaos
