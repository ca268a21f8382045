// Reference systems: integrator order, hand-iterated maps, analytic identities of the flows,
// documented initial conditions, determinism and parameter validation.
#include "chaos/models/systems.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/random.hpp"

namespace {

using chaos::FlowSampling;

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v) s += x;
  return s / static_cast<double>(v.size());
}

// Expects InvalidInput with the invalid_parameter code and every fragment in the message.
template <class F>
void expect_refused(F&& f, const std::vector<std::string>& fragments) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning " << fragments.front();
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), chaos::ErrorCode::invalid_parameter);
    const std::string message = e.what();
    for (const auto& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << message;
  }
}

TEST(Systems, Rk4HasObservedOrderFourOnLorenz) {
  // Classical RK4 has global error C h^4, so halving the step divides the error by 2^4 = 16 once h
  // is in the asymptotic range. Horizon t = 0.4 from the documented initial condition; the
  // reference solution uses h = 1e-5, whose own error is below 1e-13 by the same law.
  const double horizon = 0.4;
  const auto reference = chaos::lorenz(2, {}, FlowSampling{horizon, 1e-5, 0.0});
  std::vector<double> errors;
  for (const double h : {0.01, 0.005, 0.0025, 0.00125}) {
    const auto t = chaos::lorenz(2, {}, FlowSampling{horizon, h, 0.0});
    double e = 0.0;
    for (std::size_t c = 0; c < 3; ++c) e = std::max(e, std::abs(t.components[c][1] - reference.components[c][1]));
    errors.push_back(e);
  }
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) EXPECT_NEAR(errors[i] / errors[i + 1], 16.0, 2.0) << i;
}

TEST(Systems, FlowStartsAtTheDocumentedInitialConditionAndSamplesTheSameSteps) {
  // Documented: Lorenz and Rossler start from (1, 1, 1); with no transient that is sample 0.
  const auto l = chaos::lorenz(3, {}, FlowSampling{0.01, 0.001, 0.0});
  const auto r = chaos::rossler(3, {}, FlowSampling{0.1, 0.01, 0.0});
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(l.components[c][0], 1.0);
    EXPECT_EQ(r.components[c][0], 1.0);
  }
  EXPECT_EQ(l.names, (std::vector<std::string>{"x", "y", "z"}));
  EXPECT_EQ(l.dt, 0.01);
  EXPECT_EQ(r.dt, 0.1);
  // Sampling every 10 steps takes the same RK4 steps as sampling every step and keeping one in 10,
  // and a transient of 0.5 time units is 500 of those steps.
  const auto every_step = chaos::lorenz(1001, {}, FlowSampling{0.001, 0.001, 0.0});
  const auto sampled = chaos::lorenz(51, {}, FlowSampling{0.01, 0.001, 0.5});
  for (std::size_t k = 0; k < 51; ++k)
    for (std::size_t c = 0; c < 3; ++c) ASSERT_EQ(sampled.components[c][k], every_step.components[c][500 + 10 * k]);
}

TEST(Systems, LorenzTimeAveragesObeyTheFlowIdentitiesAndTheKnownMeanOfZ) {
  // Time averages of derivatives of bounded functions vanish. From d(x^2/2)/dt = sigma (xy - x^2)
  // and dz/dt = xy - beta z: <x^2> = <xy> = beta <z> (analytic, Lorenz 1963 equations). Also
  // dx/dt = sigma (y - x) gives <x> = <y>.
  const auto t = chaos::lorenz(1'000'000);  // 10^4 time units, dt 0.01, RK4 step 0.001
  const auto& x = t.components[0];
  const auto& y = t.components[1];
  const auto& z = t.components[2];
  double xx = 0, xy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    xx += x[i] * x[i];
    xy += x[i] * y[i];
  }
  xx /= static_cast<double>(x.size());
  xy /= static_cast<double>(x.size());
  const double beta = 8.0 / 3.0, mz = mean(z);
  EXPECT_NEAR(xx / (beta * mz), 1.0, 2e-3);
  EXPECT_NEAR(xy / (beta * mz), 1.0, 2e-3);
  // <x> and <y> are both near 0 by the x -> -x, y -> -y symmetry; their difference is bounded
  // by the boundary term |x(T) - x(0)| / (sigma T) < 40 / 1e5.
  EXPECT_NEAR(mean(x) - mean(y), 0.0, 1e-3);
  // The mean of z on the attractor is the value quoted in the literature as about 23.5 (a numerical
  // value, not analytic; the fixed points sit at z = rho - 1 = 27). Band +-0.3 for a 10^4 time-unit
  // average.
  EXPECT_NEAR(mz, 23.5, 0.3);
}

TEST(Systems, RosslerTimeAveragesObeyTheFlowIdentities) {
  // dx/dt = -y - z and dy/dt = x + a y with x, y bounded: <y> + <z> = 0 and <x> + a <y> = 0.
  const auto t = chaos::rossler(200'000);  // 2*10^4 time units
  const double mx = mean(t.components[0]), my = mean(t.components[1]), mz = mean(t.components[2]);
  EXPECT_NEAR(my + mz, 0.0, 5e-3);
  EXPECT_NEAR(mx + 0.2 * my, 0.0, 5e-3);
  EXPECT_GT(*std::max_element(t.components[2].begin(), t.components[2].end()), 10.0);  // the z spikes
}

TEST(Systems, HenonMatchesHandIteration) {
  // From (0, 0) with a = 1.4, b = 0.3: x' = 1 - 1.4 x^2 + y, y' = 0.3 x, computed by hand.
  const auto t = chaos::henon(5, {}, 0);
  const double xs[] = {0.0, 1.0, -0.4, 1.076, -0.7408864};
  const double ys[] = {0.0, 0.0, 0.3, -0.12, 0.3228};
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(t.components[0][k], xs[k], 1e-14) << k;
    EXPECT_NEAR(t.components[1][k], ys[k], 1e-14) << k;
  }
  EXPECT_EQ(t.names, (std::vector<std::string>{"x", "y"}));
  // The transient drops exactly that many iterations.
  const auto later = chaos::henon(3, {}, 2);
  EXPECT_EQ(later.components[0][0], t.components[0][2]);
  EXPECT_EQ(later.components[0][2], t.components[0][4]);
}

// Signed area test: the point is left of (or on) the directed edge a -> b.
bool left_of(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax) >= 0.0;
}

TEST(Systems, HenonOrbitStaysInHenonsTrappingRegion) {
  // Henon (1976) shows that the quadrilateral A(-1.33, 0.42), B(1.32, 0.133), C(1.245, -0.14),
  // D(-1.06, -0.5) is mapped into itself; the attractor lies inside it.
  const auto t = chaos::henon(100'000);
  const double ax = -1.33, ay = 0.42, bx = 1.32, by = 0.133, cx = 1.245, cy = -0.14, dx = -1.06, dy = -0.5;
  double lo = 0.0, hi = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double x = t.components[0][k], y = t.components[1][k];
    // Clockwise vertex order A, B, C, D: inside means right of every edge.
    ASSERT_FALSE(left_of(ax, ay, bx, by, x, y)) << k;
    ASSERT_FALSE(left_of(bx, by, cx, cy, x, y)) << k;
    ASSERT_FALSE(left_of(cx, cy, dx, dy, x, y)) << k;
    ASSERT_FALSE(left_of(dx, dy, ax, ay, x, y)) << k;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  // And it is spread over the attractor (x spans about [-1.28, 1.27]), not caught on a cycle.
  EXPECT_LT(lo, -1.2);
  EXPECT_GT(hi, 1.2);
}

TEST(Systems, IkedaIsSprottsFormWithDeterminantMuSquared) {
  // Sprott's Ikeda map z' = 1 + mu z exp(i (a - b / (1 + |z|^2))), written here independently.
  const chaos::IkedaParameters p;
  const auto map = [&p](std::complex<double> z) {
    return 1.0 + p.mu * z * std::exp(std::complex<double>(0.0, p.a - p.b / (1.0 + std::norm(z))));
  };
  const auto t = chaos::ikeda(2000, p, 0);
  std::complex<double> z = 0.0;
  for (std::size_t k = 0; k < 20; ++k) {
    EXPECT_NEAR(t.components[0][k], z.real(), 1e-9) << k;
    EXPECT_NEAR(t.components[1][k], z.imag(), 1e-9) << k;
    z = map(z);
  }
  // Each step of the library's orbit is one application of the map (to rounding).
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    const auto next = map({t.components[0][k], t.components[1][k]});
    ASSERT_NEAR(t.components[0][k + 1], next.real(), 1e-12);
    ASSERT_NEAR(t.components[1][k + 1], next.imag(), 1e-12);
  }
  // The convention fixed by the reference exponents (lambda1 + lambda2 = 2 ln mu, Sprott 2003):
  // |det J| = mu^2 everywhere; checked by central differences at orbit points.
  const double h = 1e-6;
  for (std::size_t k = 100; k < 2000; k += 97) {
    const std::complex<double> z0(t.components[0][k], t.components[1][k]);
    const auto dx = (map(z0 + h) - map(z0 - h)) / (2 * h);
    const auto dy = (map(z0 + std::complex<double>(0, h)) - map(z0 - std::complex<double>(0, h))) / (2 * h);
    const double det = dx.real() * dy.imag() - dx.imag() * dy.real();
    EXPECT_NEAR(det, p.mu * p.mu, 1e-7) << k;
  }
}

TEST(Systems, LogisticFollowsTheMapAndStartsFromTheSeed) {
  const auto t = chaos::logistic(1000, {3.9}, 0, 11);
  chaos::Random rng(11);
  EXPECT_EQ(t.components[0][0], rng.uniform_open());  // documented: x0 = uniform_open() of the seed
  for (std::size_t k = 0; k + 1 < t.size(); ++k)
    ASSERT_EQ(t.components[0][k + 1], 3.9 * t.components[0][k] * (1.0 - t.components[0][k]));
}

TEST(Systems, LogisticAtFourNeverCollapsesOverAMillionIterations) {
  // The r = 4 invariant density 1 / (pi sqrt(x (1 - x))) has mean 1/2 and variance 1/8 (analytic).
  for (const std::uint64_t seed : {1ULL, 2ULL, 3ULL}) {
    const auto t = chaos::logistic(1'000'000, {4.0}, 1000, seed);
    const auto& x = t.components[0];
    double s = 0.0, s2 = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      ASSERT_GT(x[k], 0.0) << k;
      ASSERT_LT(x[k], 1.0) << k;
      if (k > 0) {
        ASSERT_NE(x[k], x[k - 1]) << k;
      }
      s += x[k];
      s2 += x[k] * x[k];
    }
    const double m = s / 1e6;
    // Chaotic samples are correlated only weakly here; the bounds are loose (about 20 sigma of iid).
    EXPECT_NEAR(m, 0.5, 0.01);
    EXPECT_NEAR(s2 / 1e6 - m * m, 0.125, 0.005);
  }
}

TEST(Systems, LogisticKeepsAttractingFixedPoints) {
  // At r = 2.5 the fixed point 1 - 1/r = 0.6 attracts: the orbit must settle there, not be redrawn.
  const auto t = chaos::logistic(10, {2.5}, 1000, 4);
  for (const double x : t.components[0]) EXPECT_NEAR(x, 0.6, 1e-12);
}

TEST(Systems, MackeyGlassStartsOnTheLinearSolutionOfTheFirstDelay) {
  // For 0 <= t <= tau the delayed value is the constant history 1.2, so
  // dx/dt = c - gamma x with c = beta 1.2 / (1 + 1.2^n): x(t) = c/gamma + (1.2 - c/gamma) e^{-gamma t}.
  // RK4 at h = 0.1 errs by about (gamma h)^5 / 120 = 8e-13 relative per step: under 1e-10 by t = 17.
  const chaos::MackeyGlassParameters p;
  const auto t = chaos::mackey_glass(18, p, 1.0, 170, 0.0);
  const double c = p.beta * 1.2 / (1.0 + std::pow(1.2, p.n));
  for (std::size_t k = 0; k <= 17; ++k) {
    const double exact = c / p.gamma + (1.2 - c / p.gamma) * std::exp(-p.gamma * static_cast<double>(k));
    EXPECT_NEAR(t.components[0][k], exact, 1e-10) << k;
  }
}

TEST(Systems, MackeyGlassStaysPositiveAndBounded) {
  // x > 0 is invariant, and beta u / (1 + u^10) <= 0.2 * 0.7224 (maximum at u = 9^(-1/10)), so
  // dx/dt < 0 whenever x > 1.4448: x stays in (0, max(1.2, 1.4448)] (analytic).
  const auto t = chaos::mackey_glass(20'000);
  const auto [lo, hi] = std::minmax_element(t.components[0].begin(), t.components[0].end());
  EXPECT_GT(*lo, 0.0);
  EXPECT_LE(*hi, 1.4449);
  EXPECT_LT(*lo, 0.6);  // and it oscillates (tau = 17 is chaotic), it does not settle
  EXPECT_GT(*hi, 1.1);
}

TEST(Systems, MackeyGlassConvergesAsTheStepShrinks) {
  // Over a horizon of 100 time units (about 6 delays) the solutions at M = 17, 34, 68, 136 steps
  // per delay approach the M = 1088 one, each halving of the step dividing the error by about
  // 2^4 (RK4 with an O(h^4) Hermite interpolation of the delayed value).
  const std::size_t n = 101;
  const auto ref = chaos::mackey_glass(n, {}, 1.0, 1088, 0.0).components[0];
  std::vector<double> errors;
  for (const std::size_t m : {17, 34, 68, 136}) {
    const auto x = chaos::mackey_glass(n, {}, 1.0, m, 0.0).components[0];
    double e = 0.0;
    for (std::size_t k = 0; k < n; ++k) e = std::max(e, std::abs(x[k] - ref[k]));
    errors.push_back(e);
  }
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) {
    EXPECT_GT(errors[i] / errors[i + 1], 12.0) << "M = " << (17 << i);
    EXPECT_LT(errors[i] / errors[i + 1], 20.0) << "M = " << (17 << i);
  }
  EXPECT_LT(errors.back(), 1e-6);
}

TEST(Systems, SineAndQuasiPeriodicAreTheFormulas) {
  const auto s = chaos::sine(400, 2.0, 0.01);
  for (std::size_t k = 0; k < 400; ++k)
    EXPECT_NEAR(s.components[0][k], std::sin(2 * std::numbers::pi * 2.0 * 0.01 * static_cast<double>(k)), 1e-13);
  EXPECT_NEAR(s.components[0][12], 1.0 * std::sin(2 * std::numbers::pi * 0.24), 1e-13);
  EXPECT_NEAR(s.components[0][25], 0.0, 1e-13);  // half period at f = 2, dt = 0.01
  const auto q = chaos::quasi_periodic(200, 1.0, 1.6180339887498949, 0.05);
  for (std::size_t k = 0; k < 200; ++k) {
    const double tk = 0.05 * static_cast<double>(k);
    EXPECT_NEAR(q.components[0][k],
                std::sin(2 * std::numbers::pi * tk) + std::sin(2 * std::numbers::pi * 1.6180339887498949 * tk), 1e-12);
  }
  EXPECT_EQ(q.dt, 0.05);
}

TEST(Systems, WhiteNoiseIsTheSeededGaussianStream) {
  const auto w = chaos::white_noise(100'000, 8);
  chaos::Random rng(8);
  for (const double v : w.components[0]) ASSERT_EQ(v, rng.gaussian());
  // N(0, 1): 5 standard errors.
  EXPECT_NEAR(mean(w.components[0]), 0.0, 5.0 / std::sqrt(1e5));
}

TEST(Systems, Ar1HasLagOneCorrelationPhiAndAStationaryStart) {
  // For x[t] = phi x[t-1] + e[t] the lag-1 autocorrelation is phi, with a large-N standard error
  // sqrt((1 - phi^2) / N) (Bartlett); 5 of them.
  const double phi = 0.9;
  const auto t = chaos::ar1(1'000'000, phi, 3);
  const auto& x = t.components[0];
  const double m = mean(x);
  double c0 = 0.0, c1 = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    c0 += (x[i] - m) * (x[i] - m);
    if (i + 1 < x.size()) c1 += (x[i] - m) * (x[i + 1] - m);
  }
  EXPECT_NEAR(c1 / c0, phi, 5.0 * std::sqrt((1 - phi * phi) / 1e6));
  // The first value is drawn from N(0, 1 / (1 - phi^2)) = N(0, 5.263): its variance over 20000
  // seeds lies within 5 standard errors (sd of a sample variance: var * sqrt(2 / K)).
  const int seeds = 20'000;
  double s2 = 0.0;
  for (int s = 0; s < seeds; ++s) {
    const double x0 = chaos::ar1(1, phi, static_cast<std::uint64_t>(s) + 100).components[0][0];
    s2 += x0 * x0;
  }
  const double var = 1.0 / (1.0 - phi * phi);
  EXPECT_NEAR(s2 / seeds, var, 5.0 * var * std::sqrt(2.0 / seeds));
}

TEST(Systems, SameSeedSameBitsDifferentSeedsDiffer) {
  EXPECT_EQ(chaos::lorenz(1000).components, chaos::lorenz(1000).components);
  EXPECT_EQ(chaos::mackey_glass(500).components, chaos::mackey_glass(500).components);
  EXPECT_EQ(chaos::logistic(1000, {}, 10, 5).components, chaos::logistic(1000, {}, 10, 5).components);
  EXPECT_EQ(chaos::white_noise(1000, 5).components, chaos::white_noise(1000, 5).components);
  EXPECT_EQ(chaos::ar1(1000, 0.5, 5).components, chaos::ar1(1000, 0.5, 5).components);
  EXPECT_NE(chaos::logistic(10, {}, 10, 5).components, chaos::logistic(10, {}, 10, 6).components);
  EXPECT_NE(chaos::white_noise(10, 5).components, chaos::white_noise(10, 6).components);
  EXPECT_NE(chaos::ar1(10, 0.5, 5).components, chaos::ar1(10, 0.5, 6).components);
}

TEST(Systems, InvalidParametersAreRefusedWithTheRuleAndTheNumbers) {
  expect_refused([] { chaos::lorenz(0); }, {"n must be at least 1", "0"});
  expect_refused([] { chaos::lorenz(10, {}, FlowSampling{0.01, 0.003, 0.0}); },
                 {"whole multiple", "0.01", "0.003"});
  expect_refused([] { chaos::lorenz(10, {}, FlowSampling{0.001, 0.01, 0.0}); }, {"whole multiple"});
  expect_refused([] { chaos::lorenz(10, {}, FlowSampling{-0.01, 0.001, 0.0}); }, {"dt", "-0.01"});
  expect_refused([] { chaos::lorenz(10, {}, FlowSampling{0.01, NAN, 0.0}); }, {"step", "nan"});
  expect_refused([] { chaos::rossler(10, {}, FlowSampling{0.1, 0.01, -1.0}); }, {"transient", "-1"});
  expect_refused([] { chaos::lorenz(10, {}, FlowSampling{0.01, 0.001, 1e300}); }, {"transient", "1e+300", "1e15"});
  expect_refused([] { chaos::lorenz(10, {NAN, 28.0, 1.0}); }, {"sigma"});
  expect_refused([] { chaos::henon(0); }, {"n must be at least 1"});
  expect_refused([] { chaos::henon(10, {2.0, 0.3}); }, {"henon", "bounded"});  // a = 2 escapes
  expect_refused([] { chaos::logistic(10, {4.5}); }, {"r must lie in (0, 4]", "4.5"});
  expect_refused([] { chaos::logistic(10, {0.0}); }, {"r must lie in (0, 4]"});
  expect_refused([] { chaos::ikeda(10, {INFINITY, 0.4, 6.0}); }, {"mu", "inf"});
  expect_refused([] { chaos::mackey_glass(10, {}, 1.0, 0); }, {"steps_per_delay", "0"});
  expect_refused([] { chaos::mackey_glass(10, {}, 0.15, 170); }, {"whole multiple", "0.15", "0.1"});
  expect_refused([] { chaos::mackey_glass(10, {0.2, 0.1, 10.0, 0.0}); }, {"tau", "0"});
  expect_refused([] { chaos::mackey_glass(10, {}, 1.0, 170, -5.0); }, {"transient", "-5"});
  expect_refused([] { chaos::sine(10, 0.0); }, {"frequency", "0"});
  expect_refused([] { chaos::sine(10, 1.0, -1.0); }, {"dt", "-1"});
  expect_refused([] { chaos::quasi_periodic(10, 1.0, -2.0); }, {"f2", "-2"});
  expect_refused([] { chaos::white_noise(0); }, {"n must be at least 1"});
  expect_refused([] { chaos::ar1(10, 1.0); }, {"|phi| must be < 1", "1"});
  expect_refused([] { chaos::ar1(10, -1.5); }, {"|phi| must be < 1", "-1.5"});
}

}  // namespace
