// Lyapunov spectra of the reference systems against cited values. Exponents are base e, per time
// unit for flows and per iteration for maps (shared/docs/reference-values.md).
//   literature: J. C. Sprott, Chaos and Time-Series Analysis (Oxford University Press, 2003), and
//               his exponent tables (values quoted in shared/docs/reference-values.md);
//   analytic:   the sum of the exponents is the mean of ln |det| of the Jacobian (of the flow: its
//               trace), known exactly for Lorenz, Henon and Ikeda; ln 2 for the logistic map at r = 4.
// Runtimes are kept to about a second each (Rossler, whose small lambda1 converges slowly, is the
// longest).
#include "chaos/models/lyapunov_spectrum.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

TEST(LyapunovSpectrumReference, LorenzSprott) {
  // Sprott (2003): lambda = (0.9056, 0, -14.5723), tolerance 0.005 (sources differ in the third
  // decimal of lambda1, reference-values.md); D_KY = 2.06215 (Sprott), tolerance 0.001.
  const auto s = chaos::lorenz_spectrum();  // default options: step 0.01, 10^4 time units
  ASSERT_EQ(s.exponents.size(), 3u);
  EXPECT_NEAR(s.exponents[0], 0.9056, 0.005);
  EXPECT_NEAR(s.exponents[1], 0.0, 0.005);
  EXPECT_NEAR(s.exponents[2], -14.5723, 0.005);
  EXPECT_NEAR(s.kaplan_yorke_dimension, 2.06215, 0.001);
  // Analytic: the trace of the Lorenz Jacobian is -(sigma + 1 + beta) everywhere, so the exponents
  // sum to -13.6667. The RK4 map's Jacobian determinant differs from exp(h trace) by O(h^5) per
  // step, so at the default step 0.01 the sum is off by about 1e-4; 1e-3 is the tolerance.
  EXPECT_NEAR(s.sum, -(10.0 + 1.0 + 8.0 / 3.0), 1e-3);
}

TEST(LyapunovSpectrumReference, LorenzSumConvergesAtFourthOrderInTheStep) {
  // Analytic: the sum's error is the RK4 truncation of ln det, O(h^4) per unit time; halving the
  // step twice (0.01 -> 0.0025) divides it by about 256. At h = 0.0025 it is within 1e-6 of
  // -(sigma + 1 + beta), the check reference-values.md asks of any spectrum code. The sum needs no
  // long average (it is a time mean of a bounded per-step error), so 10^3 time units suffice.
  chaos::FlowSpectrumOptions coarse;
  coarse.time = 1000.0;
  chaos::FlowSpectrumOptions fine = coarse;
  fine.step = 0.0025;
  const double exact = -(10.0 + 1.0 + 8.0 / 3.0);
  const double coarse_error = std::abs(chaos::lorenz_spectrum({}, coarse).sum - exact);
  const double fine_error = std::abs(chaos::lorenz_spectrum({}, fine).sum - exact);
  EXPECT_LT(fine_error, 1e-6);
  EXPECT_GT(coarse_error / fine_error, 100.0);  // 4^4 = 256 for a fourth-order error
}

TEST(LyapunovSpectrumReference, RosslerSprott) {
  // Sprott (2003): lambda = (0.0714, 0, -5.3943) at a = b = 0.2, c = 5.7, tolerance 0.005 for
  // lambda1 (issue), 0.01 for lambda3. lambda1 is small and converges slowly: 10^5 time units.
  chaos::FlowSpectrumOptions o;
  o.time = 100'000.0;
  const auto s = chaos::rossler_spectrum({}, o);
  EXPECT_NEAR(s.exponents[0], 0.0714, 0.005);
  EXPECT_NEAR(s.exponents[1], 0.0, 0.001);
  EXPECT_NEAR(s.exponents[2], -5.3943, 0.01);
}

TEST(LyapunovSpectrumReference, HenonSprott) {
  // Sprott (2003): lambda = (0.41922, -1.62319), tolerance 0.002; D_KY = 1.25827 (Sprott),
  // tolerance 0.002.
  const auto s = chaos::henon_spectrum();  // 10^6 iterations
  ASSERT_EQ(s.exponents.size(), 2u);
  EXPECT_NEAR(s.exponents[0], 0.41922, 0.002);
  EXPECT_NEAR(s.exponents[1], -1.62319, 0.002);
  EXPECT_NEAR(s.kaplan_yorke_dimension, 1.25827, 0.002);
  // Analytic: det J = -b at every point, so lambda1 + lambda2 = ln b; with a factorisation every
  // iteration ln|R11| + ln|R22| = ln|b| to rounding, hence 1e-9.
  EXPECT_NEAR(s.sum, std::log(0.3), 1e-9);
}

TEST(LyapunovSpectrumReference, IkedaSprott) {
  // Sprott (2003): lambda = (0.5075, -0.7182) for mu = 0.9, a = 0.4, b = 6, tolerance 0.005;
  // D_KY = 1.7066 (Sprott), tolerance 0.005.
  const auto s = chaos::ikeda_spectrum();
  EXPECT_NEAR(s.exponents[0], 0.5075, 0.005);
  EXPECT_NEAR(s.exponents[1], -0.7182, 0.005);
  EXPECT_NEAR(s.kaplan_yorke_dimension, 1.7066, 0.005);
  // Analytic: the rotation angle depends on |z| only, so |det J| = mu^2 and the sum is 2 ln mu.
  EXPECT_NEAR(s.sum, 2.0 * std::log(0.9), 1e-9);
}

TEST(LyapunovSpectrumReference, LogisticAtFourIsLnTwo) {
  // Analytic: the logistic map at r = 4 is conjugate to the tent map of slope 2, lambda = ln 2;
  // tolerance 0.002 (issue).
  const auto s = chaos::logistic_spectrum({4.0});
  ASSERT_EQ(s.exponents.size(), 1u);
  EXPECT_NEAR(s.exponents[0], std::log(2.0), 0.002);
  EXPECT_DOUBLE_EQ(s.kaplan_yorke_dimension, 1.0);
}

TEST(LyapunovSpectrumReference, LogisticSuperstableAndStableCycles) {
  // Analytic: at r = 3.2 the attracting 2-cycle has multiplier r^2 (1 - 2x1)(1 - 2x2) =
  // -r^2 + 2r + 4 = 0.16, so lambda = ln(0.16) / 2 = -0.9163; at r = 2.5 the fixed point
  // 1 - 1/r has derivative 2 - r, lambda = ln 0.5.
  chaos::MapSpectrumOptions o;
  o.iterations = 10'000;
  EXPECT_NEAR(chaos::logistic_spectrum({3.2}, o).exponents[0], std::log(0.16) / 2.0, 1e-9);
  EXPECT_NEAR(chaos::logistic_spectrum({2.5}, o).exponents[0], std::log(0.5), 1e-9);
}

}  // namespace
