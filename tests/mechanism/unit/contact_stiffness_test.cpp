// Contact stiffness: the seed's Eq. (11)-(13) and Flores' journal-bearing stiffness, against the
// values of ../shared/docs/reference-values.md, hand-evaluated cases of Eq. (12), the limits and
// monotonicity of Eq. (11), and the parameter checks.
#include "mechanism/expect_invalid.hpp"
#include "mechanism/contact_stiffness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "mechanism/error.hpp"

namespace {

using mechanism::InvalidParameter;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Steel as in reference-values.md: E = 207 GPa, nu = 0.3.
const double kSteel = mechanism::material_compliance(207e9, 0.3);

using mechanism::testing::expect_invalid;

// Eq. (13): (1 - 0.09) / 207e9.
TEST(ContactStiffness, MaterialCompliance) {
  EXPECT_DOUBLE_EQ(kSteel, 0.91 / 207e9);
  EXPECT_DOUBLE_EQ(mechanism::material_compliance(70e9, 0.0), 1.0 / 70e9);
}

// reference-values.md: about 6.6e10 N/m^1.5 at c = 0.5 mm and 4.8e11 at c = 0.01 mm (R_b = 10 mm).
// By hand: (4/3) / (2 * 0.91/207e9) = 1.5165e11; sqrt(0.01 * 0.0095 / 0.0005) = 0.43589 -> 6.61e10;
// sqrt(0.01 * 0.00999 / 0.00001) = 3.1607 -> 4.793e11.
TEST(ContactStiffness, JournalBearingReferenceValues) {
  const double rb = 0.010;
  const double k_05 = mechanism::journal_bearing_stiffness(kSteel, kSteel, rb, rb - 0.5e-3);
  const double k_001 = mechanism::journal_bearing_stiffness(kSteel, kSteel, rb, rb - 0.01e-3);
  EXPECT_NEAR(k_05, 6.6e10, 0.01 * 6.6e10);
  EXPECT_NEAR(k_001, 4.8e11, 0.01 * 4.8e11);
  EXPECT_NEAR(k_05, 6.6103e10, 1e-4 * 6.6103e10);
  EXPECT_NEAR(k_001, 4.7933e11, 1e-4 * 4.7933e11);
  // Stiffer as the clearance closes: K ~ c^-1/2 for c << R.
  EXPECT_NEAR(k_001 / k_05, std::sqrt(0.5 / 0.01) * std::sqrt(0.00999 / 0.0095), 1e-9 * k_001 / k_05);
}

// Eq. (12) cases evaluated by hand for L_s = 0.1 m.
TEST(ContactStiffness, ContactLengthCasesOfEquation12) {
  const double ls = 0.1;
  EXPECT_EQ(mechanism::contact_length(ls, 1e-5, 2e-5), ls);     // both corners in
  EXPECT_EQ(mechanism::contact_length(ls, 1e-12, 1e-2), ls);
  EXPECT_EQ(mechanism::contact_length(ls, 0.0, 0.0), 0.0);      // both out (0 counts as out)
  EXPECT_EQ(mechanism::contact_length(ls, -1e-5, -2e-6), 0.0);
  EXPECT_EQ(mechanism::contact_length(ls, 0.0, -1e-3), 0.0);
  // One in: the straight face crosses the surface at the fraction dA / (dA - dB) of its length.
  EXPECT_DOUBLE_EQ(mechanism::contact_length(ls, 1e-5, -3e-5), ls * 0.25);
  EXPECT_DOUBLE_EQ(mechanism::contact_length(ls, -3e-5, 1e-5), ls * 0.25);  // symmetric in A, B
  EXPECT_DOUBLE_EQ(mechanism::contact_length(ls, 2e-5, 0.0), ls);           // touching at B
  EXPECT_DOUBLE_EQ(mechanism::contact_length(ls, 1e-12, -1e-2), ls * 1e-12 / (1e-2 + 1e-12));
  // Never above L_s, whatever the rounding.
  for (double a = 1e-12; a < 1e-2; a *= 3.7)
    for (double b = -1e-2; b <= 0.0; b += 7.3e-4) EXPECT_LE(mechanism::contact_length(ls, a, b), ls);
  EXPECT_TRUE(std::isnan(mechanism::contact_length(ls, kNan, 1e-5)));  // state: propagates
}

// Eq. (11) at L_c = L_s by hand: sqrt(0.1 * 0.05) / (2 sigma) / (11.15 / 16.72 + 0.2854).
TEST(ContactStiffness, SliderFaceFullContactByHand) {
  const double ls = 0.1, w = 0.05;
  const double expected = std::sqrt(ls * w) / (2 * kSteel) / (11.15 / (1.0 + 15.72) + 0.2854);
  EXPECT_NEAR(mechanism::slider_face_stiffness(kSteel, kSteel, ls, w, ls), expected, 1e-12 * expected);
  // Half contact: L_s / L_c = 2.
  const double half = std::sqrt(0.5 * ls * w) / (2 * kSteel) / (11.15 / (2.0 + 15.72) + 0.2854);
  EXPECT_NEAR(mechanism::slider_face_stiffness(kSteel, kSteel, ls, w, 0.5 * ls), half, 1e-12 * half);
}

// 0 at L_c = 0, continuous there (K ~ sqrt(L_c) / 0.2854 as L_c -> 0) and increasing on (0, L_s]:
// d ln K / d L_c > 0 holds because 11.15 u (s - 2) / s^2 + 0.2854 > 0 with s = 1 + 15.72 u,
// u = L_c / L_s (its minimum over u is 0.2854 - 11.15/(8 * 15.72) = 0.197).
TEST(ContactStiffness, SliderFaceZeroAtNoContactAndMonotone) {
  const double ls = 0.1, w = 0.05;
  EXPECT_EQ(mechanism::slider_face_stiffness(kSteel, kSteel, ls, w, 0.0), 0.0);
  const double tiny = 1e-12 * ls;
  const double k_tiny = mechanism::slider_face_stiffness(kSteel, kSteel, ls, w, tiny);
  EXPECT_NEAR(k_tiny, std::sqrt(tiny * w) / (2 * kSteel) / 0.2854, 1e-9 * k_tiny);
  double previous = 0.0;
  for (int i = 1; i <= 20000; ++i) {
    const double lc = ls * i / 20000.0;
    const double k = mechanism::slider_face_stiffness(kSteel, kSteel, ls, w, lc);
    ASSERT_GT(k, previous) << "L_c = " << lc;
    previous = k;
  }
  // Also on a log grid toward 0.
  previous = 0.0;
  for (double lc = 1e-15; lc <= ls; lc *= 1.5) {
    const double k = mechanism::slider_face_stiffness(kSteel, kSteel, ls, w, lc);
    ASSERT_GT(k, previous) << "L_c = " << lc;
    previous = k;
  }
}

TEST(ContactStiffness, InvalidParametersThrowNamingTheKey) {
  for (const double e : {0.0, -1.0, kNan, kInf})
    expect_invalid("young_modulus", [&] { mechanism::material_compliance(e, 0.3); });
  for (const double nu : {-0.1, 0.5, 0.7, kNan})
    expect_invalid("poisson_ratio", [&] { mechanism::material_compliance(207e9, nu); });

  expect_invalid("sigma_bearing", [] { mechanism::journal_bearing_stiffness(0.0, kSteel, 0.01, 0.009); });
  expect_invalid("sigma_journal", [] { mechanism::journal_bearing_stiffness(kSteel, kNan, 0.01, 0.009); });
  expect_invalid("journal_radius", [] { mechanism::journal_bearing_stiffness(kSteel, kSteel, 0.01, 0.0); });
  expect_invalid("bearing_radius", [] { mechanism::journal_bearing_stiffness(kSteel, kSteel, 0.01, 0.01); });
  expect_invalid("bearing_radius", [] { mechanism::journal_bearing_stiffness(kSteel, kSteel, 0.009, 0.01); });
  expect_invalid("bearing_radius", [] { mechanism::journal_bearing_stiffness(kSteel, kSteel, kInf, 0.01); });

  expect_invalid("slider_length", [] { mechanism::contact_length(0.0, 1e-5, 1e-5); });
  expect_invalid("slider_length", [] { mechanism::contact_length(-0.1, 1e-5, 1e-5); });

  expect_invalid("sigma_slider", [] { mechanism::slider_face_stiffness(-kSteel, kSteel, 0.1, 0.05, 0.1); });
  expect_invalid("sigma_guide", [] { mechanism::slider_face_stiffness(kSteel, 0.0, 0.1, 0.05, 0.1); });
  expect_invalid("slider_length", [] { mechanism::slider_face_stiffness(kSteel, kSteel, 0.0, 0.05, 0.0); });
  expect_invalid("slider_width", [] { mechanism::slider_face_stiffness(kSteel, kSteel, 0.1, kNan, 0.1); });
  expect_invalid("contact_length", [] { mechanism::slider_face_stiffness(kSteel, kSteel, 0.1, 0.05, -1e-9); });
  expect_invalid("contact_length", [] { mechanism::slider_face_stiffness(kSteel, kSteel, 0.1, 0.05, 0.1000001); });
  expect_invalid("contact_length", [] { mechanism::slider_face_stiffness(kSteel, kSteel, 0.1, 0.05, kNan); });
}

}  // namespace
