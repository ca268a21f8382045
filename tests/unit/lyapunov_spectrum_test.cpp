// Lyapunov spectrum by tangent dynamics: linear flows and maps whose exponents are known in closed
// form, the Kaplan-Yorke formula on hand-worked cases, the analytic Jacobians of the reference
// systems against finite differences, and refusals of invalid options and systems.
#include "chaos/models/lyapunov_spectrum.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "chaos/error.hpp"

namespace {

using chaos::FlowSpectrumOptions;
using chaos::FlowSystem;
using chaos::MapSpectrumOptions;
using chaos::MapSystem;

// A linear system x -> A x given as a row-major matrix.
using Matrix = std::vector<double>;

Matrix multiply(const Matrix& a, const Matrix& b, std::size_t d) {
  Matrix c(d * d, 0.0);
  for (std::size_t i = 0; i < d; ++i)
    for (std::size_t j = 0; j < d; ++j)
      for (std::size_t k = 0; k < d; ++k) c[i * d + j] += a[i * d + k] * b[k * d + j];
  return c;
}

FlowSystem linear_flow(const Matrix& a, std::size_t d) {
  FlowSystem s;
  s.dimension = d;
  s.field = [a, d](std::span<const double> x, std::span<double> dx) {
    for (std::size_t i = 0; i < d; ++i) {
      dx[i] = 0.0;
      for (std::size_t j = 0; j < d; ++j) dx[i] += a[i * d + j] * x[j];
    }
  };
  s.jacobian = [a](std::span<const double>, std::span<double> j) { std::copy(a.begin(), a.end(), j.begin()); };
  return s;
}

MapSystem linear_map(const Matrix& m, std::size_t d) {
  MapSystem s;
  s.dimension = d;
  s.map = [m, d](std::span<const double> x, std::span<double> next) {
    for (std::size_t i = 0; i < d; ++i) {
      next[i] = 0.0;
      for (std::size_t j = 0; j < d; ++j) next[i] += m[i * d + j] * x[j];
    }
  };
  s.jacobian = [m](std::span<const double>, std::span<double> j) { std::copy(m.begin(), m.end(), j.begin()); };
  return s;
}

// The RK4 step of dx/dt = A x is the matrix polynomial P(hA), P(z) = 1 + z + z^2/2 + z^3/6 + z^4/24,
// whose eigenvalues are P(h mu) for the eigenvalues mu of A. The exponents of the numerical flow are
// therefore ln |P(h mu)| / h exactly (analytic), within h^4 |mu|^5 / 120 of Re(mu).
double rk4_exponent(std::complex<double> mu, double h) {
  const std::complex<double> z = h * mu;
  const std::complex<double> p = 1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0;
  return std::log(std::abs(p)) / h;
}

TEST(LyapunovSpectrum, NonNormalLinearFlowGivesTheRealPartsOfItsEigenvalues) {
  // A = S D S^-1 with D = diag(0.5, -0.2, -1) and a non-orthogonal S, so the tangent vectors must
  // be re-orthonormalised to separate the directions. The state starts at the fixed point 0 and
  // stays there; the tangent dynamics does not depend on it.
  const Matrix s = {1.0, 2.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 1.0};
  // S^-1 for this S (det = 3), worked by hand and checked by the product below.
  const Matrix s_inv = {1.0 / 3, -2.0 / 3, 2.0 / 3, 1.0 / 3, 1.0 / 3, -1.0 / 3, -1.0 / 3, 2.0 / 3, 1.0 / 3};
  const Matrix identity = multiply(s, s_inv, 3);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) ASSERT_NEAR(identity[i * 3 + j], i == j ? 1.0 : 0.0, 1e-15);
  const Matrix d = {0.5, 0, 0, 0, -0.2, 0, 0, 0, -1.0};
  const Matrix a = multiply(multiply(s, d, 3), s_inv, 3);
  FlowSpectrumOptions o;
  o.time = 200.0;
  o.transient = 50.0;
  const std::array<double, 3> x0 = {0.0, 0.0, 0.0};
  const auto r = chaos::flow_spectrum(linear_flow(a, 3), x0, o);
  ASSERT_EQ(r.exponents.size(), 3u);
  const std::array<double, 3> mu = {0.5, -0.2, -1.0};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(r.exponents[i], rk4_exponent(mu[i], o.step), 1e-9) << i;
    EXPECT_NEAR(r.exponents[i], mu[i], 1e-9) << i;  // h^4 |mu|^5 / 120 < 1e-10 here
  }
  // The sum is ln |det P(hA)| / h = sum of the exponents of the numerical map; trace A = -0.7.
  EXPECT_NEAR(r.sum, -0.7, 1e-9);
  EXPECT_EQ(r.renormalisations, 2000u);
  EXPECT_DOUBLE_EQ(r.averaging_length, 200.0);
  ASSERT_TRUE(std::holds_alternative<FlowSpectrumOptions>(r.settings));
  EXPECT_EQ(std::get<FlowSpectrumOptions>(r.settings).time, 200.0);
}

TEST(LyapunovSpectrum, DiagonalFlowKeepsItsAxesAndIsSortedDescending) {
  // A diagonal A never mixes its axes: QR returns the diagonal growth in the given order (-1, 2, 0)
  // and the result must still come out descending (analytic: the exponents are the diagonal).
  const Matrix a = {-1.0, 0, 0, 0, 0.25, 0, 0, 0, 0.0};
  FlowSpectrumOptions o;
  o.time = 50.0;
  o.transient = 0.0;
  const std::array<double, 3> x0 = {0.0, 0.0, 0.0};
  const auto r = chaos::flow_spectrum(linear_flow(a, 3), x0, o);
  // Within the RK4 truncation h^4 |mu|^5 / 120 = 8.3e-11 (mu = -1) of the diagonal,
  EXPECT_NEAR(r.exponents[0], 0.25, 1e-10);
  EXPECT_NEAR(r.exponents[1], 0.0, 1e-15);
  EXPECT_NEAR(r.exponents[2], -1.0, 1e-10);
  // and to rounding of the numerical map's exponents ln |P(h mu)| / h.
  EXPECT_NEAR(r.exponents[0], rk4_exponent(0.25, o.step), 1e-13);
  EXPECT_NEAR(r.exponents[2], rk4_exponent(-1.0, o.step), 1e-13);
}

TEST(LyapunovSpectrum, FocusGivesTwoEqualExponents) {
  // dx/dt = A x with eigenvalues -0.1 +- 2i: both exponents equal -0.1 (analytic: Re(mu)), and
  // ln |P(h mu)| / h for the RK4 map.
  const Matrix a = {-0.1, 2.0, -2.0, -0.1};
  FlowSpectrumOptions o;
  o.time = 100.0;
  const std::array<double, 2> x0 = {0.0, 0.0};
  const auto r = chaos::flow_spectrum(linear_flow(a, 2), x0, o);
  const double expected = rk4_exponent({-0.1, 2.0}, o.step);
  EXPECT_NEAR(expected, -0.1, 1e-8);
  EXPECT_NEAR(r.exponents[0], expected, 1e-12);
  EXPECT_NEAR(r.exponents[1], expected, 1e-12);
}

TEST(LyapunovSpectrum, LinearMapGivesTheLogarithmsOfItsEigenvalues) {
  // M = S diag(2, 0.5) S^-1 with S = [[1, 1], [0, 1]]: exponents ln 2 and ln 0.5 per iteration
  // (analytic), the sum ln |det M| = 0. x0 = 0 is the fixed point.
  const Matrix m = {2.0, -1.5, 0.0, 0.5};
  MapSpectrumOptions o;
  o.iterations = 10'000;
  o.transient = 100;
  const std::array<double, 2> x0 = {0.0, 0.0};
  const auto r = chaos::map_spectrum(linear_map(m, 2), x0, o);
  EXPECT_NEAR(r.exponents[0], std::log(2.0), 1e-12);
  EXPECT_NEAR(r.exponents[1], std::log(0.5), 1e-12);
  EXPECT_NEAR(r.sum, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(r.averaging_length, 10'000.0);
  // Kaplan-Yorke: 1 + ln 2 / |ln 0.5| = 2; the whole sum is 0 >= 0, so D = d = 2 (by the formula's
  // convention).
  EXPECT_DOUBLE_EQ(r.kaplan_yorke_dimension, 2.0);
}

TEST(LyapunovSpectrum, RenormalisationIntervalDoesNotChangeALinearMap) {
  // 0.9 times a rotation by 1 radian: both exponents ln 0.9 (analytic), whatever the number of
  // iterations between factorisations.
  const double c = std::cos(1.0), s = std::sin(1.0);
  const Matrix m = {0.9 * c, -0.9 * s, 0.9 * s, 0.9 * c};
  const std::array<double, 2> x0 = {0.0, 0.0};
  for (const std::size_t per : {1u, 5u, 50u}) {
    MapSpectrumOptions o;
    o.renormalisation_interval = per;
    o.iterations = 5'000;
    const auto r = chaos::map_spectrum(linear_map(m, 2), x0, o);
    EXPECT_NEAR(r.exponents[0], std::log(0.9), 1e-12) << per;
    EXPECT_NEAR(r.exponents[1], std::log(0.9), 1e-12) << per;
    EXPECT_EQ(r.renormalisations, 5'000u / per);
  }
}

TEST(KaplanYorke, HandWorkedCases) {
  // D = j + S_j / |lambda_{j+1}| (Kaplan & Yorke 1979), worked by hand.
  const std::vector<double> henon_like = {1.0, -2.0};
  EXPECT_DOUBLE_EQ(chaos::kaplan_yorke_dimension(henon_like), 1.5);
  const std::vector<double> flow = {0.5, 0.0, -1.0};
  EXPECT_DOUBLE_EQ(chaos::kaplan_yorke_dimension(flow), 2.5);
  const std::vector<double> unsorted = {-1.0, 0.5, 0.0};
  EXPECT_DOUBLE_EQ(chaos::kaplan_yorke_dimension(unsorted), 2.5);
  const std::vector<double> stable = {-0.1, -2.0};
  EXPECT_DOUBLE_EQ(chaos::kaplan_yorke_dimension(stable), 0.0);
  const std::vector<double> expanding = {0.3, 0.1};
  EXPECT_DOUBLE_EQ(chaos::kaplan_yorke_dimension(expanding), 2.0);
  const std::vector<double> superstable = {0.7, -std::numeric_limits<double>::infinity()};
  EXPECT_DOUBLE_EQ(chaos::kaplan_yorke_dimension(superstable), 1.0);
  // Sprott's Lorenz exponents give 2 + 0.9056 / 14.5723 = 2.06214.
  const std::vector<double> lorenz = {0.9056, 0.0, -14.5723};
  EXPECT_NEAR(chaos::kaplan_yorke_dimension(lorenz), 2.06214, 1e-5);
}

TEST(KaplanYorke, RefusesEmptyAndNaN) {
  EXPECT_THROW(chaos::kaplan_yorke_dimension(std::vector<double>{}), chaos::InvalidInput);
  EXPECT_THROW(chaos::kaplan_yorke_dimension(std::vector<double>{0.1, std::nan("")}), chaos::InvalidInput);
  EXPECT_THROW(chaos::kaplan_yorke_dimension(std::vector<double>{std::numeric_limits<double>::infinity()}),
               chaos::InvalidInput);
}

// Central differences with step 1e-6 relative: an independent check of the library's analytic
// Jacobians (error O(1e-10) against O(1) entries).
template <class F>
void finite_difference_jacobian(const F& f, std::span<const double> x, std::span<double> j, std::size_t d) {
  std::vector<double> xp(x.begin(), x.end()), xm(x.begin(), x.end()), fp(d), fm(d);
  for (std::size_t k = 0; k < d; ++k) {
    const double e = 1e-6 * std::max(1.0, std::abs(x[k]));
    xp[k] = x[k] + e;
    xm[k] = x[k] - e;
    f(xp, fp);
    f(xm, fm);
    for (std::size_t i = 0; i < d; ++i) j[i * d + k] = (fp[i] - fm[i]) / (2.0 * e);
    xp[k] = xm[k] = x[k];
  }
}

TEST(LyapunovSpectrum, LorenzAndRosslerJacobiansAgreeWithFiniteDifferences) {
  // The same equations as chaos/models/src/systems.cpp, written out here; the orbit is computed by identical
  // operations, so only the Jacobian differs (analytic in the library, numerical here).
  const chaos::LorenzParameters p;
  const auto lorenz = [&p](std::span<const double> x, std::span<double> d) {
    d[0] = p.sigma * (x[1] - x[0]);
    d[1] = x[0] * (p.rho - x[2]) - x[1];
    d[2] = x[0] * x[1] - p.beta * x[2];
  };
  FlowSystem s{3, lorenz, [&](std::span<const double> x, std::span<double> j) {
                 finite_difference_jacobian(lorenz, x, j, 3);
               }};
  FlowSpectrumOptions o;
  o.time = 100.0;
  o.transient = 10.0;
  const std::array<double, 3> x0 = {1.0, 1.0, 1.0};
  const auto numeric = chaos::flow_spectrum(s, x0, o);
  const auto analytic = chaos::lorenz_spectrum(p, o);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(numeric.exponents[i], analytic.exponents[i], 1e-6) << i;

  const chaos::RosslerParameters q;
  const auto rossler = [&q](std::span<const double> x, std::span<double> d) {
    d[0] = -x[1] - x[2];
    d[1] = x[0] + q.a * x[1];
    d[2] = q.b + x[2] * (x[0] - q.c);
  };
  FlowSystem r{3, rossler, [&](std::span<const double> x, std::span<double> j) {
                 finite_difference_jacobian(rossler, x, j, 3);
               }};
  const auto numeric_r = chaos::flow_spectrum(r, x0, o);
  const auto analytic_r = chaos::rossler_spectrum(q, o);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(numeric_r.exponents[i], analytic_r.exponents[i], 1e-6) << i;
}

TEST(LyapunovSpectrum, HenonAndIkedaJacobiansAgreeWithFiniteDifferences) {
  const chaos::HenonParameters p;
  const auto henon = [&p](std::span<const double> x, std::span<double> n) {
    n[0] = 1.0 - p.a * x[0] * x[0] + x[1];
    n[1] = p.b * x[0];
  };
  const chaos::IkedaParameters q;
  // Sprott's form, as chaos::ikeda: z' = 1 + mu z exp(i (a - b / (1 + |z|^2))).
  const auto ikeda = [&q](std::span<const double> z, std::span<double> n) {
    const double t = q.a - q.b / (1.0 + z[0] * z[0] + z[1] * z[1]);
    const double c = std::cos(t), s = std::sin(t);
    n[0] = 1.0 + q.mu * (z[0] * c - z[1] * s);
    n[1] = q.mu * (z[0] * s + z[1] * c);
  };
  MapSpectrumOptions o;
  o.iterations = 20'000;
  const std::array<double, 2> x0 = {0.0, 0.0};
  const auto h_numeric = chaos::map_spectrum(
      {2, henon, [&](std::span<const double> x, std::span<double> j) { finite_difference_jacobian(henon, x, j, 2); }},
      x0, o);
  const auto h_analytic = chaos::henon_spectrum(p, o);
  const auto i_numeric = chaos::map_spectrum(
      {2, ikeda, [&](std::span<const double> x, std::span<double> j) { finite_difference_jacobian(ikeda, x, j, 2); }},
      x0, o);
  const auto i_analytic = chaos::ikeda_spectrum(q, o);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(h_numeric.exponents[i], h_analytic.exponents[i], 1e-6) << i;
    EXPECT_NEAR(i_numeric.exponents[i], i_analytic.exponents[i], 1e-6) << i;
  }
}

TEST(LyapunovSpectrum, StartsWhereTheGeneratorsStart) {
  // chaos/models/systems.hpp: flows from (1, 1, 1), Henon and Ikeda from (0, 0).
  FlowSpectrumOptions f;
  f.time = 1.0;
  EXPECT_EQ(chaos::lorenz_spectrum({}, f).initial_state, (std::vector<double>{1.0, 1.0, 1.0}));
  MapSpectrumOptions m;
  m.iterations = 10;
  EXPECT_EQ(chaos::henon_spectrum({}, m).initial_state, (std::vector<double>{0.0, 0.0}));
  EXPECT_EQ(chaos::ikeda_spectrum({}, m).initial_state, (std::vector<double>{0.0, 0.0}));
  // The logistic orbit is chaos::logistic's: its first sample after the transient is the state
  // whose derivative enters the average first. Here only the start is compared.
  const auto l = chaos::logistic_spectrum({}, m, 7);
  ASSERT_EQ(l.initial_state.size(), 1u);
  EXPECT_GT(l.initial_state[0], 0.0);
  EXPECT_LT(l.initial_state[0], 1.0);
}

template <class F>
void expect_refusal(const F& f, chaos::ErrorCode code, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning '" << fragment << "'";
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(LyapunovSpectrum, RefusesInvalidOptions) {
  using chaos::ErrorCode;
  const auto flow = [](FlowSpectrumOptions o) { return [o] { chaos::lorenz_spectrum({}, o); }; };
  FlowSpectrumOptions o;
  o.step = 0.0;
  expect_refusal(flow(o), ErrorCode::invalid_parameter, "step must be finite and positive (got step = 0)");
  o = {};
  o.step = std::nan("");
  expect_refusal(flow(o), ErrorCode::invalid_parameter, "step must be finite and positive");
  o = {};
  o.renormalisation_interval = 0.015;
  expect_refusal(flow(o), ErrorCode::invalid_parameter, "renormalisation_interval = 0.015 must be a whole multiple");
  o = {};
  o.time = 100.05;
  expect_refusal(flow(o), ErrorCode::invalid_parameter, "time = 100.05 must be a whole multiple");
  o = {};
  o.transient = -1.0;
  expect_refusal(flow(o), ErrorCode::invalid_parameter, "transient must be finite and >= 0 (got transient = -1)");
  o = {};
  o.time = -5.0;
  expect_refusal(flow(o), ErrorCode::invalid_parameter, "time must be finite and positive");

  const auto map = [](MapSpectrumOptions m) { return [m] { chaos::henon_spectrum({}, m); }; };
  MapSpectrumOptions m;
  m.renormalisation_interval = 0;
  expect_refusal(map(m), ErrorCode::invalid_parameter, "renormalisation_interval must be at least 1");
  m = {};
  m.renormalisation_interval = 3;
  m.iterations = 1000;
  expect_refusal(map(m), ErrorCode::invalid_parameter, "iterations = 1000, renormalisation_interval = 3");
  m = {};
  m.iterations = 0;
  expect_refusal(map(m), ErrorCode::invalid_parameter, "iterations must be a positive whole multiple");
}

TEST(LyapunovSpectrum, RefusesInvalidSystemsAndParameters) {
  using chaos::ErrorCode;
  const std::array<double, 2> x0 = {0.0, 0.0};
  const MapSystem henon_without_jacobian{2, [](std::span<const double>, std::span<double>) {}, {}};
  expect_refusal([&] { chaos::map_spectrum(henon_without_jacobian, x0); }, ErrorCode::invalid_parameter,
                 "needs both its equations and its Jacobian");
  const Matrix a = {0.0, 1.0, -1.0, 0.0};
  const std::array<double, 3> three = {0.0, 0.0, 0.0};
  expect_refusal([&] { chaos::flow_spectrum(linear_flow(a, 2), three); }, ErrorCode::invalid_parameter,
                 "the initial state has 3 components but the flow has dimension 2");
  const std::array<double, 2> bad = {0.0, std::numeric_limits<double>::infinity()};
  expect_refusal([&] { chaos::flow_spectrum(linear_flow(a, 2), bad); }, ErrorCode::invalid_parameter,
                 "initial state component 1 is inf");
  expect_refusal([&] { chaos::flow_spectrum(FlowSystem{}, std::span<const double>{}); },
                 ErrorCode::invalid_parameter, "needs dimension >= 1 (got 0)");
  chaos::LorenzParameters p;
  p.rho = std::nan("");
  expect_refusal([&] { chaos::lorenz_spectrum(p); }, ErrorCode::invalid_parameter, "rho must be finite");
  expect_refusal([&] { chaos::logistic_spectrum({4.5}); }, ErrorCode::invalid_parameter, "r must lie in (0, 4]");
}

TEST(LyapunovSpectrum, RefusesAnEscapingOrbit) {
  // dx/dt = x from x = 1 reaches e^231 > 1e100 at t = 231: the orbit is unbounded, refused with
  // the time of escape (the first renormalisation after it).
  const Matrix a = {1.0};
  const std::array<double, 1> x0 = {1.0};
  FlowSpectrumOptions o;
  o.time = 1000.0;
  o.transient = 0.0;
  expect_refusal([&] { chaos::flow_spectrum(linear_flow(a, 1), x0, o); }, chaos::ErrorCode::invalid_parameter,
                 "left every bounded region at t = 230.");
  // Henon at a = 2 escapes from (0, 0) within a few iterations.
  expect_refusal([] { chaos::henon_spectrum({2.0, 0.3}); }, chaos::ErrorCode::invalid_parameter,
                 "left every bounded region at iteration");
}

}  // namespace
