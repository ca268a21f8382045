// Leading Lyapunov exponents of the Mackey-Glass delay equation, discretised exactly as
// chaos::mackey_glass does it (systems.cpp): RK4 at h = tau / M on the step grid, grid values as
// the delayed values at whole steps, cubic Hermite midpoints (x_a + x_b)/2 + h (f_a - f_b)/8 at
// the half steps, constant history 1.2. The state of that scheme is the last M + 1 grid values and
// their stored slopes; its tangent dynamics is the same scheme run on dual numbers whose K
// derivative slots are K tangent vectors (Farmer, Physica D 4, 366 (1982) treats the history on a
// grid the same way). Every renormalisation interval the K vectors are orthonormalised by
// modified Gram-Schmidt and the logarithms of the norms are accumulated, as in flow_spectrum.

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "chaos/error.hpp"
#include "zoo_model.hpp"

namespace chaos::detail {

namespace {

constexpr int kSlots = 8;  // at most 8 exponents
using D = Dual<kSlots>;

template <class T>
struct MackeyGlassScheme {
  double beta, gamma, n, h;
  std::size_t m;
  std::vector<T> xs, fs;  // ring buffers: slot k mod (m + 1) holds step k
  std::size_t k = 0;
  T x;
  static constexpr double history = 1.2;

  MackeyGlassScheme(const std::vector<double>& p, std::size_t steps_per_delay)
      : beta(p[0]), gamma(p[1]), n(p[2]), h(p[3] / static_cast<double>(steps_per_delay)), m(steps_per_delay),
        xs(m + 1), fs(m + 1), x(history) {
    xs[0] = x;
  }
  T rhs(const T& state, const T& delayed) const {
    using std::pow;
    return beta * delayed / (1.0 + pow(delayed, n)) - gamma * state;
  }
  T delayed_at(std::size_t j) const { return j < m ? T(history) : xs[(j - m) % (m + 1)]; }
  void step() {
    const T d0 = delayed_at(k);
    const T k1 = rhs(x, d0);
    fs[k % (m + 1)] = k1;
    const T d1 = delayed_at(k + 1);
    const T dmid = k + 1 <= m ? T(history) : 0.5 * (d0 + d1) + h * (fs[(k - m) % (m + 1)] - fs[(k + 1 - m) % (m + 1)]) / 8.0;
    const T k2 = rhs(x + 0.5 * h * k1, dmid);
    const T k3 = rhs(x + 0.5 * h * k2, dmid);
    const T k4 = rhs(x + h * k3, d1);
    x += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    ++k;
    xs[k % (m + 1)] = x;
  }
};

}  // namespace

LyapunovSpectrum delay_spectrum(const std::vector<double>& p, std::size_t steps_per_delay, std::size_t exponents,
                                const FlowSpectrumOptions& options) {
  options.validate();
  if (exponents < 1 || exponents > static_cast<std::size_t>(kSlots))
    refuse_parameter("delay spectrum: the number of exponents must be 1.." + std::to_string(kSlots) + " (got " +
           std::to_string(exponents) + ")");
  if (steps_per_delay < 2) refuse_parameter("delay spectrum: steps_per_delay must be at least 2 (got " + std::to_string(steps_per_delay) + ")");
  for (std::size_t i = 0; i < 4; ++i)
    if (!(std::isfinite(p[i]) && p[i] > 0.0)) refuse_parameter("delay spectrum: beta, gamma, n and tau must be finite and positive");
  MackeyGlassScheme<D> s(p, steps_per_delay);
  const double h = s.h;
  const auto per = static_cast<std::size_t>(std::lround(options.renormalisation_interval / h));
  if (per < 1) refuse_parameter("delay spectrum: the renormalisation interval is shorter than one step h = " + std::to_string(h));
  const double interval = static_cast<double>(per) * h;
  const auto transient = static_cast<std::size_t>(std::lround(options.transient / interval));
  const auto intervals = static_cast<std::size_t>(std::lround(options.time / interval));
  const std::size_t m = s.m, slots = m + 1, K = exponents;

  // The tangent vectors live in the derivative slots of the grid values and of the stored slopes;
  // the slope slot about to be overwritten (k mod (m + 1)) is not part of the state.
  const auto for_each_component = [&](auto&& fn) {
    for (std::size_t j = 0; j < slots; ++j) fn(s.xs[j]);
    for (std::size_t j = 0; j < slots; ++j)
      if (j != s.k % slots) fn(s.fs[j]);
  };
  std::vector<double> sums(K, 0.0);
  const auto orthonormalise = [&](bool accumulate) {
    for (std::size_t a = 0; a < K; ++a) {
      for (std::size_t b = 0; b < a; ++b) {
        double dot = 0.0;
        for_each_component([&](D& v) { dot += v.d[a] * v.d[b]; });
        for_each_component([&](D& v) { v.d[a] -= dot * v.d[b]; });
      }
      double norm = 0.0;
      for_each_component([&](D& v) { norm += v.d[a] * v.d[a]; });
      norm = std::sqrt(norm);
      if (!(norm > 0.0) || !std::isfinite(norm)) refuse_parameter("delay spectrum: a tangent vector lost all its length or overflowed");
      if (accumulate) sums[a] += std::log(norm);
      for_each_component([&](D& v) { v.d[a] /= norm; });
    }
    s.x = s.xs[s.k % slots];
  };

  // Half the transient on the orbit alone (the buffer fills), then seed the tangent vectors with a
  // fixed pseudo-random pattern and let them align for the other half.
  const std::size_t seed_after = transient / 2 * per;
  for (std::size_t i = 0; i < seed_after; ++i) s.step();
  for (std::size_t j = 0; j < slots; ++j)
    for (std::size_t a = 0; a < K; ++a)
      s.xs[j].d[a] = std::sin(1.0 + 0.7 * static_cast<double>(j) * static_cast<double>(a + 1) + 0.3 * static_cast<double>(a));
  s.x = s.xs[s.k % slots];
  orthonormalise(false);
  for (std::size_t r = transient / 2; r < transient + intervals; ++r) {
    for (std::size_t i = 0; i < per; ++i) s.step();
    if (!std::isfinite(s.x.v) || std::abs(s.x.v) > 1e100)
      refuse_parameter("delay spectrum: the solution left every bounded region at t = " + std::to_string(static_cast<double>(s.k) * h));
    orthonormalise(r >= transient);
  }
  LyapunovSpectrum out;
  for (std::size_t a = 0; a < K; ++a) out.exponents.push_back(sums[a] / (static_cast<double>(intervals) * interval));
  std::sort(out.exponents.begin(), out.exponents.end(), std::greater<>());
  for (const double l : out.exponents) out.sum += l;
  out.kaplan_yorke_dimension = kaplan_yorke_dimension(out.exponents);
  FlowSpectrumOptions used = options;
  used.step = h;
  used.renormalisation_interval = interval;
  out.settings = used;
  out.initial_state = {MackeyGlassScheme<double>::history};
  out.renormalisations = intervals;
  out.averaging_length = static_cast<double>(intervals) * interval;
  return out;
}

// The same scheme on doubles, sampled every `per_sample` steps after `skip` steps: it must equal
// chaos::mackey_glass exactly (tested), which is what makes the tangent dynamics above that of
// the generator's orbit.
std::vector<double> delay_orbit(const std::vector<double>& p, std::size_t steps_per_delay, std::size_t skip,
                                std::size_t per_sample, std::size_t n) {
  MackeyGlassScheme<double> s(p, steps_per_delay);
  for (std::size_t i = 0; i < skip; ++i) s.step();
  std::vector<double> out(n);
  for (std::size_t j = 0; j < n; ++j) {
    if (j > 0)
      for (std::size_t i = 0; i < per_sample; ++i) s.step();
    out[j] = s.x;
  }
  return out;
}

}  // namespace chaos::detail
