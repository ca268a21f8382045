#include "mechanism/impact_oscillator.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "checks.hpp"
#include "mechanism/dormand_prince.hpp"
#include "mechanism/error.hpp"
#include "mechanism/event_location.hpp"
#include "mechanism/finite_difference_lyapunov.hpp"

namespace mechanism {

using detail::text;

double ImpactOscillator::period() const { return 2.0 * std::numbers::pi / omega; }

void ImpactOscillator::validate() const {
  if (!(zeta >= 0.0 && zeta < 1.0)) throw InvalidParameter("zeta", text(zeta), "must be in [0, 1) (underdamped)");
  if (!(amplitude > 0.0 && std::isfinite(amplitude)))
    throw InvalidParameter("amplitude", text(amplitude), "must be finite and > 0");
  if (!(omega > 0.0 && std::isfinite(omega))) throw InvalidParameter("omega", text(omega), "must be finite and > 0");
  if (!std::isfinite(gap)) throw InvalidParameter("gap", text(gap), "must be finite");
  if (!(restitution > 0.0 && restitution <= 1.0))
    throw InvalidParameter("restitution", text(restitution), "must be in (0, 1]");
}

void ImpactLyapunovOptions::validate() const {
  if (periods < 10) throw InvalidParameter("periods", std::to_string(periods), "must be >= 10 (10 block means)");
  if (!(relative_tolerance > 0.0) || !(absolute_tolerance > 0.0))
    throw InvalidParameter("tolerance", text(relative_tolerance), "both tolerances must be > 0");
  if (!(perturbation > 0.0 && perturbation < 1.0))
    throw InvalidParameter("perturbation", text(perturbation), "must be in (0, 1)");
}

namespace {

using Mat2 = std::array<std::array<double, 2>, 2>;

// exp(A tau) for A = [[0, 1], [-1, -2 zeta]], 0 <= zeta < 1: the underdamped free oscillation.
Mat2 flow_matrix(double zeta, double tau) {
  const double wd = std::sqrt(1.0 - zeta * zeta);
  const double decay = std::exp(-zeta * tau), c = std::cos(wd * tau), s = std::sin(wd * tau);
  return {{{decay * (c + zeta / wd * s), decay * s / wd}, {-decay * s / wd, decay * (c - zeta / wd * s)}}};
}

// The particular (periodic) solution P cos(omega t - phi) and its rate.
struct Particular {
  double p, phi;
};
Particular particular(const ImpactOscillator& o) {
  const double re = 1.0 - o.omega * o.omega, im = 2.0 * o.zeta * o.omega;
  return {o.amplitude / std::hypot(re, im), std::atan2(im, re)};
}
std::array<double, 2> particular_state(const ImpactOscillator& o, const Particular& pp, double t) {
  const double th = o.omega * t - pp.phi;
  return {pp.p * std::cos(th), -pp.p * o.omega * std::sin(th)};
}

Mat2 multiply(const Mat2& a, const Mat2& b) {
  Mat2 c{};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j];
  return c;
}

double forcing(const ImpactOscillator& o, double t) { return o.amplitude * std::cos(o.omega * t); }

// The saltation matrix of an impact at time t with speed v > 0 before it (the header's formula:
// G + (f+ - G f-) n^T / (n^T f-) with G = diag(1, -r), n = (1, 0), f = (x', x'')).
Mat2 saltation(const ImpactOscillator& o, double t, double v) {
  const double r = o.restitution;
  return {{{-r, 0.0}, {(1.0 + r) * (forcing(o, t) - o.gap) / v, -r}}};
}

// The system with k tangent vectors (the variational equation Y' = A Y), as an OdeSystem. The
// tangents have weight 0 in the step's error norm, so the steps, and with them the trajectory, are
// those of the oscillator alone, whatever the tangents hold: the saltation run and the finite
// differences' reference integrate the same trajectory to the last bit.
struct System {
  const ImpactOscillator* o;
  int tangents;
  void rhs(double t, const State& y, State& dy) const {
    const double z = o->zeta;
    dy[0] = y[1];
    dy[1] = forcing(*o, t) - y[0] - 2.0 * z * y[1];
    for (int j = 0; j < tangents; ++j) {
      const int b = 2 + 2 * j;
      dy[b] = y[b + 1];
      dy[b + 1] = -y[b] - 2.0 * z * y[b + 1];
    }
  }
  void error_weights(double, const State& y, State& w) const {
    w.setZero(y.size());
    w[0] = w[1] = 1.0;
  }
};

// Integrates from t to t_end with every impact located and applied (and its saltation matrix to
// the tangents). Returns false with `why` when it cannot continue.
class Integrator {
 public:
  Integrator(const ImpactOscillator& o, int tangents, const ImpactLyapunovOptions& opt)
      : o_(o), sys_{&o_, tangents}, stepper_([&] {
          AdaptiveOptions a;
          a.relative_tolerance = opt.relative_tolerance;
          a.absolute_tolerance = opt.absolute_tolerance;
          a.max_step = o.period() / 20.0;  // an excursion past the stop shorter than a step is not seen
          a.initial_step = o.period() / 100.0;  // fixed, so that every period starts alike
          return a;
        }()) {}

  bool advance(double& t, State& y, double t_end, std::size_t& impacts, std::string& why) {
    if (h_ <= 0.0) h_ = stepper_.initial_step(sys_, t, y);
    std::size_t in_this_call = 0;
    while (t < t_end) {
      double h = std::min(h_, t_end - t);
      const double t_start = t;
      const double g_start = y[0] - o_.gap;
      const StepOutcome s = stepper_.try_step(sys_, t, y, h);
      if (s == StepOutcome::rejected) {
        h_ = h;
        continue;
      }
      if (s != StepOutcome::accepted) {
        why = s == StepOutcome::non_finite ? "the state became non-finite" : "the step underflowed";
        return false;
      }
      if (t_end - t < 1e-14 * std::max(1.0, std::abs(t_end))) t = t_end;
      h_ = h;
      const double g_end = y[0] - o_.gap;
      if (g_start < 0.0 && g_end >= 0.0) {
        State probe(y.size());
        auto g = [&](double tt) {
          stepper_.interpolate(tt, probe);
          return probe[0] - o_.gap;
        };
        const CrossingBracket b = bracket_crossing(g, t_start, t, g_start, g_end, 1e-15 * std::max(1.0, std::abs(t)));
        const double tc = b.after;
        stepper_.interpolate(tc, y);
        t = tc;
        const double v = y[1];
        if (!(v > 0.0)) {
          why = "an impact with no approach speed (grazing) at t = " + text(tc);
          return false;
        }
        const Mat2 s_mat = saltation(o_, tc, v);
        y[0] = o_.gap;
        y[1] = -o_.restitution * v;
        for (int j = 0; j < sys_.tangents; ++j) {
          const int k = 2 + 2 * j;
          const double a = y[k], c = y[k + 1];
          y[k] = s_mat[0][0] * a + s_mat[0][1] * c;
          y[k + 1] = s_mat[1][0] * a + s_mat[1][1] * c;
        }
        stepper_.invalidate();
        ++impacts;
        // Chattering (impacts accumulating at a point with ever smaller speeds) would need a
        // sticking phase, which this benchmark does not model: stop instead.
        if (++in_this_call > 1000) {
          why = "more than 1000 impacts within one period (chattering) at t = " + text(tc);
          return false;
        }
      }
    }
    return true;
  }

 private:
  ImpactOscillator o_;
  System sys_;
  DormandPrince54 stepper_;
  double h_ = 0.0;
};

// One forcing period of the flow with impacts, as a trajectory of finite_difference_lyapunov.hpp.
class PeriodMap {
 public:
  PeriodMap(const ImpactOscillator& o, std::array<double, 2> start, const ImpactLyapunovOptions& opt)
      : o_(o), opt_(opt), y_(6) {
    y_ << start[0], start[1], 1.0, 0.0, 0.0, 1.0;
  }
  Eigen::VectorXd phase_point() const { return y_.head(2); }
  void set_phase_point(const Eigen::VectorXd& p) { y_.head(2) = p; }
  bool advance() {
    // A fresh stepper every period, as saltation_lyapunov uses, with the tangents it carries (their
    // weight in the error norm is 0): the reference trajectory is the saltation run's.
    Integrator integrator(o_, 2, opt_);
    y_.tail(4) << 1.0, 0.0, 0.0, 1.0;  // unused here; kept bounded
    const double t_end = static_cast<double>(n_ + 1) * o_.period();
    double t = static_cast<double>(n_) * o_.period();
    std::size_t impacts = 0;
    if (!integrator.advance(t, y_, t_end, impacts, failure_)) return false;
    ++n_;
    impacts_ += impacts;
    return true;
  }
  const std::string& failure() const { return failure_; }
  std::size_t impacts() const { return impacts_; }

 private:
  ImpactOscillator o_;
  ImpactLyapunovOptions opt_;
  State y_;
  std::size_t n_ = 0;
  std::size_t impacts_ = 0;
  std::string failure_;
};

}  // namespace

std::array<double, 2> exact_flow(const ImpactOscillator& o, double t0, std::array<double, 2> y0, double t) {
  o.validate();
  const Particular pp = particular(o);
  const auto p0 = particular_state(o, pp, t0), p1 = particular_state(o, pp, t);
  const Mat2 m = flow_matrix(o.zeta, t - t0);
  const double d0 = y0[0] - p0[0], d1 = y0[1] - p0[1];
  return {p1[0] + m[0][0] * d0 + m[0][1] * d1, p1[1] + m[1][0] * d0 + m[1][1] * d1};
}

std::vector<PeriodOneOrbit> period_one_orbits(const ImpactOscillator& o) {
  o.validate();
  const double T = o.period(), r = o.restitution, gap = o.gap;
  const Particular pp = particular(o);
  const Mat2 m = flow_matrix(o.zeta, T);
  // (I - M) y_p(t_i) = (gap, v) - M (gap, -r v): y_p = s + v w, s = (gap, 0),
  // w = (I - M)^-1 (e2 + r M e2).
  const double a = 1.0 - m[0][0], b = -m[0][1], c = -m[1][0], d = 1.0 - m[1][1];
  const double det = a * d - b * c;
  const double q0 = r * m[0][1], q1 = 1.0 + r * m[1][1];
  const double w0 = (d * q0 - b * q1) / det, w1 = (-c * q0 + a * q1) / det;
  // y_p lies on the ellipse (x / P)^2 + (x' / (P omega))^2 = 1: a quadratic in v.
  const double P = pp.p, Pw = pp.p * o.omega;
  const double qa = w0 * w0 / (P * P) + w1 * w1 / (Pw * Pw), qb = 2.0 * gap * w0 / (P * P), qc = gap * gap / (P * P) - 1.0;
  const double disc = qb * qb - 4.0 * qa * qc;
  std::vector<PeriodOneOrbit> out;
  if (!(disc >= 0.0)) return out;
  const double sq = std::sqrt(disc);
  // The stable form of the two roots.
  const double qq = -0.5 * (qb + std::copysign(sq, qb));
  std::vector<double> roots;
  if (qq != 0.0) roots = {qq / qa, qc / qq};
  else roots = {sq / (2.0 * qa), -sq / (2.0 * qa)};
  std::sort(roots.begin(), roots.end(), std::greater<>());
  for (double v : roots) {
    if (!(v > 0.0)) continue;
    const double xp = gap + v * w0, vp = v * w1;
    const double th = std::atan2(-vp / Pw, xp / P);
    double ti = std::fmod((th + pp.phi) / o.omega, T);
    if (ti < 0.0) ti += T;
    // No other impact in between: the exact solution stays below the stop.
    bool clean = true;
    const int samples = 4000;
    for (int k = 1; k < samples && clean; ++k) {
      const double t = ti + T * k / samples;
      clean = exact_flow(o, ti, {gap, -r * v}, t)[0] < gap;
    }
    if (!clean) continue;
    PeriodOneOrbit orbit;
    orbit.impact_time = ti;
    orbit.impact_velocity = v;
    orbit.monodromy = multiply(m, saltation(o, ti, v));
    const auto& mm = orbit.monodromy;
    const double tr = mm[0][0] + mm[1][1], dt = mm[0][0] * mm[1][1] - mm[0][1] * mm[1][0];
    const std::complex<double> root = std::sqrt(std::complex<double>(tr * tr / 4.0 - dt));
    std::complex<double> mu1 = tr / 2.0 + root, mu2 = tr / 2.0 - root;
    if (std::abs(mu2) > std::abs(mu1)) std::swap(mu1, mu2);
    orbit.multipliers = {mu1, mu2};
    orbit.exponents = {std::log(std::abs(mu1)) / T, std::log(std::abs(mu2)) / T};
    orbit.stable = std::abs(mu1) < 1.0;
    out.push_back(orbit);
  }
  return out;
}

ImpactLyapunov saltation_lyapunov(const ImpactOscillator& o, std::array<double, 2> start,
                                  const ImpactLyapunovOptions& options) {
  o.validate();
  options.validate();
  const double T = o.period();
  State y(6);
  y << start[0], start[1], 1.0, 0.0, 0.0, 1.0;
  double t = 0.0;
  ImpactLyapunov out;
  std::array<double, 2> sums{}, block{};
  std::array<std::vector<double>, 2> means;
  const std::size_t block_length = options.periods / 10;
  const std::size_t total = options.transient + options.periods;
  for (std::size_t n = 0; n < total; ++n) {
    std::size_t impacts = 0;
    Integrator integrator(o, 2, options);  // a fresh stepper each period, as the finite differences use
    if (!integrator.advance(t, y, static_cast<double>(n + 1) * T, impacts, out.message)) {
      out.status = "failed";
      out.message = "period " + std::to_string(n) + ": " + out.message;
      return out;
    }
    // Gram-Schmidt of the two tangent columns: ln R_jj.
    Eigen::Vector2d u(y[2], y[3]), w(y[4], y[5]);
    const double r11 = u.norm();
    u /= r11;
    w -= u.dot(w) * u;
    const double r22 = w.norm();
    w /= r22;
    y[2] = u[0], y[3] = u[1], y[4] = w[0], y[5] = w[1];
    if (n < options.transient) continue;
    out.impacts += impacts;
    const double l[2] = {std::log(r11), std::log(r22)};
    const std::size_t k = n - options.transient + 1;
    for (int j = 0; j < 2; ++j) {
      sums[j] += l[j];
      block[j] += l[j];
      if (k % block_length == 0 && means[j].size() < 10) {
        means[j].push_back(block[j] / static_cast<double>(block_length) / T);
        block[j] = 0.0;
      }
    }
  }
  out.periods = options.periods;
  for (int j = 0; j < 2; ++j) {
    out.exponents[j] = sums[j] / static_cast<double>(options.periods) / T;
    double mean = 0.0, ss = 0.0;
    for (double v : means[j]) mean += v;
    mean /= static_cast<double>(means[j].size());
    for (double v : means[j]) ss += (v - mean) * (v - mean);
    out.standard_error[j] = std::sqrt(ss / static_cast<double>(means[j].size() - 1) / static_cast<double>(means[j].size()));
  }
  return out;
}

ImpactLyapunov finite_difference_impact_lyapunov(const ImpactOscillator& o, std::array<double, 2> start,
                                                 const ImpactLyapunovOptions& options) {
  o.validate();
  options.validate();
  const double T = o.period();
  PeriodMap reference(o, start, options);
  FiniteDifferenceOptions fd;
  fd.exponents = 2;
  fd.perturbation = options.perturbation;
  fd.transient = options.transient;
  fd.iterations = options.periods;
  fd.blocks = 10;
  fd.seed = options.seed;
  const FiniteDifferenceLyapunov r = finite_difference_lyapunov(reference, fd);
  ImpactLyapunov out;
  if (r.status != FiniteDifferenceLyapunov::Status::completed) {
    out.status = "failed";
    out.message = r.message;
    return out;
  }
  out.periods = r.iterations;
  for (int j = 0; j < 2; ++j) {
    out.exponents[j] = r.exponents[static_cast<std::size_t>(j)] / T;
    out.standard_error[j] = r.standard_error[static_cast<std::size_t>(j)] / T;
  }
  return out;
}

}  // namespace mechanism
