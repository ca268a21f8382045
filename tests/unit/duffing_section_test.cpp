// Stroboscopic sections of the forced Duffing oscillator x'' + delta x' + alpha x + beta x^3 =
// gamma cos(omega t), integrated by classical RK4 with a whole number of steps per forcing period
// and sampled by the streaming StroboscopicSampler at t = 2 pi k / omega. Expected values: the
// linear response amplitude gamma / sqrt((alpha - omega^2)^2 + (delta omega)^2) and phase
// (analytic, beta = 0); the first-order harmonic-balance amplitude for a weak cubic term
// (A^2 [(alpha + 3/4 beta A^2 - omega^2)^2 + (delta omega)^2] = gamma^2, Nayfeh & Mook 1979,
// ch. 4); and Ueda's chaotic case x'' + 0.05 x' + x^3 = 7.5 cos t (Ueda 1979), whose section is
// not finitely many points.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "chaos/poincare.hpp"
#include "chaos/section_stream.hpp"

namespace chaos {
namespace {

struct Duffing {
  double delta, alpha, beta, gamma, omega;
};

// The section points (x, v) after `transient` periods, `periods` of them.
std::vector<SectionPoint> section(const Duffing& p, std::size_t transient, std::size_t periods, std::size_t steps_per_period = 200) {
  const double period = 2.0 * std::numbers::pi / p.omega, h = period / static_cast<double>(steps_per_period);
  auto f = [&](double t, const std::array<double, 2>& s) {
    return std::array<double, 2>{s[1], -p.delta * s[1] - p.alpha * s[0] - p.beta * s[0] * s[0] * s[0] + p.gamma * std::cos(p.omega * t)};
  };
  StroboscopicSampler sampler(2, period, 0.0);
  std::vector<SectionPoint> out;
  std::array<double, 2> s = {0.0, 0.0};
  const std::size_t total = (transient + periods) * steps_per_period;
  for (std::size_t n = 0; n < total; ++n) {
    const double t = static_cast<double>(n) * h;  // by multiplication: section times fall on samples
    for (auto& q : sampler.push(t, s)) {
      if (q.time > static_cast<double>(transient) * period - 0.5 * h) out.push_back(q);
    }
    const auto k1 = f(t, s);
    const auto k2 = f(t + h / 2, {s[0] + h / 2 * k1[0], s[1] + h / 2 * k1[1]});
    const auto k3 = f(t + h / 2, {s[0] + h / 2 * k2[0], s[1] + h / 2 * k2[1]});
    const auto k4 = f(t + h, {s[0] + h * k3[0], s[1] + h * k3[1]});
    for (int i = 0; i < 2; ++i) s[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }
  for (auto& q : sampler.finish()) out.push_back(q);
  return out;
}

std::vector<double> component(const std::vector<SectionPoint>& points, std::size_t k) {
  std::vector<double> v;
  for (const auto& q : points) v.push_back(q.point[k]);
  return v;
}

TEST(DuffingSection, LinearResponseIsOnePointAtTheAnalyticAmplitude) {
  // x(t) = A cos(omega t - phi), tan phi = delta omega / (alpha - omega^2): at t = 2 pi k / omega
  // the section point is (A cos phi, A omega sin phi). The transient decays as exp(-delta t / 2):
  // e^-30 after 40 periods of 2 pi / 1.4.
  const Duffing p{0.3, 1.0, 0.0, 0.1, 1.4};
  const auto points = section(p, 40, 20);
  ASSERT_EQ(points.size(), 20u);
  const double a = p.gamma / std::hypot(p.alpha - p.omega * p.omega, p.delta * p.omega);
  const double phi = std::atan2(p.delta * p.omega, p.alpha - p.omega * p.omega);
  for (const auto& q : points) {
    // RK4 at 200 steps per period: a local error of order (omega h)^5 / 120 ~ 2.6e-10 per step
    // relative, kept in the steady state by the damping (measured 1.0e-9 in v).
    EXPECT_NEAR(q.point[0], a * std::cos(phi), 5e-9);
    EXPECT_NEAR(q.point[1], a * p.omega * std::sin(phi), 5e-9);
  }
  EXPECT_EQ(distinct_values(component(points, 0), 1e-9), 1u);
}

TEST(DuffingSection, WeakCubicTermMatchesHarmonicBalance) {
  // beta = 0.5, gamma = 0.3: the first-harmonic amplitude solves the harmonic-balance equation
  // (one root below 1 here, found by bisection); it differs from the linear amplitude by ~0.008,
  // and the neglected third harmonic, beta A^3 / (4 |alpha - 9 omega^2|) ~ 2e-4, bounds the
  // agreement of sqrt(x^2 + (v / omega)^2) at the section.
  const Duffing p{0.3, 1.0, 0.5, 0.3, 1.4};
  auto g = [&](double a) {
    const double detune = p.alpha + 0.75 * p.beta * a * a - p.omega * p.omega;
    return a * a * (detune * detune + p.delta * p.delta * p.omega * p.omega) - p.gamma * p.gamma;
  };
  double lo = 0.0, hi = 1.0;
  ASSERT_LT(g(lo), 0.0);
  ASSERT_GT(g(hi), 0.0);
  for (int i = 0; i < 100; ++i) (g(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
  const double harmonic_balance = 0.5 * (lo + hi);
  const double linear = p.gamma / std::hypot(p.alpha - p.omega * p.omega, p.delta * p.omega);
  ASSERT_GT(std::abs(harmonic_balance - linear), 5e-3);  // the test can tell the two apart

  const auto points = section(p, 60, 20);
  ASSERT_EQ(points.size(), 20u);
  EXPECT_EQ(distinct_values(component(points, 0), 1e-9), 1u);  // period 1
  const double measured = std::hypot(points.back().point[0], points.back().point[1] / p.omega);
  EXPECT_NEAR(measured, harmonic_balance, 1e-3);
}

TEST(DuffingSection, UedaChaoticSectionIsNotFinitelyManyPoints) {
  // Ueda's chaotic attractor: 2000 section points with no two closer than 1e-6 in x, except by
  // chance, where a periodic orbit would give its period's count. Bounded: the system is
  // dissipative (divergence -0.05); |x| < 5 and |v| < 10 is a loose box around the attractor
  // (the free oscillator with x = 5 has energy 5^4 / 4 ~ 156, far above the forcing's reach).
  const Duffing p{0.05, 0.0, 1.0, 7.5, 1.0};
  const auto points = section(p, 100, 2000);
  ASSERT_EQ(points.size(), 2000u);
  const auto x = component(points, 0), v = component(points, 1);
  EXPECT_GT(distinct_values(x, 1e-6), 1000u);
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_LT(std::abs(x[i]), 5.0);
    EXPECT_LT(std::abs(v[i]), 10.0);
  }
}

}  // namespace
}  // namespace chaos
