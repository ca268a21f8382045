// The line contact of a tilted slider face (line_contact.hpp). Expected values: the defining
// integrals by brute-force quadrature, the potential's gradient by finite differences, and the
// closed forms of a uniform and of a half-penetrating face.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mechanism/error.hpp"
#include "mechanism/line_contact.hpp"

namespace mechanism {
namespace {

// integral_0^1 w(t) d(t)_+^n dt by composite Simpson on the penetrated part only (the integrand is
// smooth there), with enough panels for 1e-10 relative.
double quadrature(double a, double b, double n, bool right_weight) {
  double lo = 0.0, hi = 1.0;
  if (a <= 0.0) lo = a / (a - b);
  if (b <= 0.0) hi = a / (a - b);
  const int panels = 200000;
  const double h = (hi - lo) / panels;
  double sum = 0.0;
  for (int i = 0; i <= panels; ++i) {
    const double t = lo + i * h;
    const double d = std::max(0.0, a + (b - a) * t);
    const double w = (i == 0 || i == panels) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * (right_weight ? t : 1.0 - t) * std::pow(d, n);
  }
  return sum * h / 3.0;
}

TEST(LineContact, LoadsAreThePressureIntegrals) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pen(-1e-5, 1e-5);
  for (const double n : {1.0, 1.5}) {
    for (int trial = 0; trial < 40; ++trial) {
      const double a = pen(rng), b = pen(rng);
      if (a <= 0.0 && b <= 0.0) continue;
      const double k = 3e9;
      const LineContactLoads f = line_contact_loads(k, n, a, b);
      const double left = k * quadrature(a, b, n, false), right = k * quadrature(a, b, n, true);
      // Simpson's error near a corner that just reaches the surface (d^1.5 has an unbounded second
      // derivative there) still falls as h^2.5: 1e-9 relative to the total.
      const double scale = left + right;
      EXPECT_NEAR(f.left, left, 1e-9 * scale) << "a=" << a << " b=" << b << " n=" << n;
      EXPECT_NEAR(f.right, right, 1e-9 * scale) << "a=" << a << " b=" << b << " n=" << n;
    }
  }
}

TEST(LineContact, LoadsAreTheGradientOfTheEnergy) {
  // F_a = dU/da, F_b = dU/db: the property that makes the contact conservative.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pen(-1e-5, 1e-5);
  const double k = 2e10, n = 1.5;
  for (int trial = 0; trial < 40; ++trial) {
    const double a = pen(rng), b = pen(rng);
    if (a <= 1e-7 && b <= 1e-7) continue;
    const double h = 1e-10;  // central differences: error ~ h^2 U''' / 6, far below 1e-6 relative
    const double dua = (line_contact_energy(k, n, a + h, b) - line_contact_energy(k, n, a - h, b)) / (2 * h);
    const double dub = (line_contact_energy(k, n, a, b + h) - line_contact_energy(k, n, a, b - h)) / (2 * h);
    const LineContactLoads f = line_contact_loads(k, n, a, b);
    const double scale = f.left + f.right;
    EXPECT_NEAR(f.left, dua, 1e-6 * scale) << "a=" << a << " b=" << b;
    EXPECT_NEAR(f.right, dub, 1e-6 * scale) << "a=" << a << " b=" << b;
  }
}

TEST(LineContact, UniformAndHalfPenetratedFaces) {
  const double k = 1e10, d = 4e-6;
  for (const double n : {1.0, 1.5, 2.0}) {
    // Uniform: K d^n split evenly, energy K d^(n+1) / (n+1) (the point-contact law of the face).
    const LineContactLoads u = line_contact_loads(k, n, d, d);
    EXPECT_NEAR(u.left, 0.5 * k * std::pow(d, n), 1e-14 * k * std::pow(d, n));
    EXPECT_NEAR(u.right, u.left, 1e-14 * k * std::pow(d, n));
    EXPECT_NEAR(line_contact_energy(k, n, d, d), k * std::pow(d, n + 1) / (n + 1), 1e-14 * k * std::pow(d, n + 1));
    // Nearly uniform (the series branch) and just outside it (the closed form) are continuous.
    for (const double r : {1e-12, 1e-6, 0.0499, 0.0501}) {
      const double a = d * (1 - r), b = d * (1 + r);
      const LineContactLoads f = line_contact_loads(k, n, a, b);
      const double left = k * quadrature(a, b, n, false), right = k * quadrature(a, b, n, true);
      EXPECT_NEAR(f.left, left, 1e-10 * (left + right)) << "r=" << r;
      EXPECT_NEAR(f.right, right, 1e-10 * (left + right)) << "r=" << r;
    }
    // Left corner in by d, right corner out by d: the left half carries d(t) = d (1 - 2t), in total
    // K d^n / (2 (n+1)), with its resultant 1/(n+2) of the contact length from the deep corner (a
    // third for n = 1, the triangle's centroid): F_b / (F_a + F_b) = (1/2) / (n + 2).
    const LineContactLoads h = line_contact_loads(k, n, d, -d);
    const double total = k * std::pow(d, n) / (2 * (n + 1));
    EXPECT_NEAR(h.left + h.right, total, 1e-14 * total);
    EXPECT_NEAR(h.right / (h.left + h.right), 0.5 / (n + 2), 1e-14);
    // Mirror image.
    const LineContactLoads m = line_contact_loads(k, n, -d, d);
    EXPECT_NEAR(m.left, h.right, 1e-14 * total);
    EXPECT_NEAR(m.right, h.left, 1e-14 * total);
  }
}

TEST(LineContact, FreeFaceAndBadInput) {
  const LineContactLoads none = line_contact_loads(1e10, 1.5, -1e-6, 0.0);
  EXPECT_EQ(none.left, 0.0);
  EXPECT_EQ(none.right, 0.0);
  EXPECT_EQ(line_contact_energy(1e10, 1.5, 0.0, -1e-6), 0.0);
  EXPECT_TRUE(std::isnan(line_contact_loads(1e10, 1.5, NAN, 1e-6).right));  // state: propagates
  EXPECT_THROW(line_contact_loads(-1.0, 1.5, 1e-6, 1e-6), InvalidParameter);
  EXPECT_THROW(line_contact_loads(1e10, 0.0, 1e-6, 1e-6), InvalidParameter);
  EXPECT_THROW(line_contact_energy(INFINITY, 1.5, 1e-6, 1e-6), InvalidParameter);
}

}  // namespace
}  // namespace mechanism
