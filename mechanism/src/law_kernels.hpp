#pragma once
// Private to the library: the formulas of the contact and friction laws without their parameter
// checks. The public functions (contact_law.cpp, contact_stiffness.cpp, friction_law.cpp) check
// and then call these; the slider-crank checks its scene once and calls them from its right-hand
// side, where the checks cost more than the formulas (tens of millions of calls per run). One
// source for each formula keeps both paths bit-identical.

#include <algorithm>
#include <cmath>
#include <limits>

#include "mechanism/friction_law.hpp"

namespace mechanism::detail {

// x^p for x >= 0. The contact exponents in use are 1 and 1.5 (and the line contact's moments add
// 1 and 2 to them): those powers are products and one square root, within an ulp or two of pow,
// which is the costliest call in the simulator's right-hand side.
inline double power(double x, double p) {
  if (p == 1.0) return x;
  if (p == 2.0) return x * x;
  if (p == 3.0) return x * x * x;
  if (p == 1.5) return x * std::sqrt(x);
  if (p == 2.5) return x * x * std::sqrt(x);
  if (p == 3.5) return x * x * x * std::sqrt(x);
  return std::pow(x, p);
}

// F = K d^n (1 + chi d_rate / max(|v_impact|, floor)), clamped at 0 (contact_law.hpp); chi from
// hysteresis_factor.
inline double normal_force_kernel(double chi, double exponent, double velocity_floor, double stiffness,
                                  double penetration, double penetration_rate, double impact_velocity) {
  if (penetration <= 0.0) return 0.0;  // NaN goes on and comes out as NaN
  const double elastic = stiffness * power(penetration, exponent);
  // Hertz or e = 1 has no rate term; a zero (or underflowed) elastic part makes the product 0 and
  // must not meet an overflowed rate ratio (0 * inf).
  if (chi == 0.0 || elastic == 0.0) return elastic;
  // fmax would drop a NaN impact velocity; keep it so that it reaches the result.
  const double latched =
      std::isnan(impact_velocity) ? impact_velocity : std::fmax(std::fabs(impact_velocity), velocity_floor);
  const double force = elastic * (1.0 + chi * penetration_rate / latched);
  // Contacts only push: the dissipative term may exceed the elastic one near release.
  return force < 0.0 ? 0.0 : force;
}

// Seed Eq. 12 (contact_stiffness.hpp).
inline double contact_length_kernel(double slider_length, double penetration_a, double penetration_b) {
  const double a = penetration_a, b = penetration_b;
  if (std::isnan(a) || std::isnan(b)) return std::nan("");
  if (a > 0.0 && b > 0.0) return slider_length;
  if (a <= 0.0 && b <= 0.0) return 0.0;
  // Exactly one is > 0, so |a - b| >= max(a, b) > 0 (also after rounding): the ratio is in (0, 1].
  return slider_length * (std::fmax(a, b) / std::fabs(a - b));
}

// Seed Eq. 11 with S = L_c W (contact_stiffness.hpp); sigma_sum = sigma_slider + sigma_guide.
inline double slider_face_stiffness_kernel(double sigma_sum, double slider_length, double slider_width,
                                           double contact_length) {
  if (contact_length == 0.0) return 0.0;
  const double area = contact_length * slider_width;  // S = L_c W (our reading of the seed)
  // 11.15 (L_s/L_c + 15.72)^-1 written as 11.15 L_c / (L_s + 15.72 L_c): no overflow of L_s/L_c
  // for a tiny L_c.
  const double shape = 11.15 * contact_length / (slider_length + 15.72 * contact_length) + 0.2854;
  return std::sqrt(area) / sigma_sum / shape;
}

// integral_0^1 d(t)_+^p dt and integral_0^1 t d(t)_+^p dt for d(t) = a + (b - a) t (line_contact.hpp).
inline void linear_power_moments(double p, double a, double b, double& i0, double& i1) {
  if (a <= 0.0 && b <= 0.0) {
    i0 = i1 = 0.0;
    return;
  }
  if (a > 0.0 && b > 0.0) {
    if (p == 1.0) {
      // Linear (Eq. 11 read as N/m): the integrals of a + (b - a) t and t (a + (b - a) t).
      i0 = 0.5 * (a + b);
      i1 = (a + 2.0 * b) / 6.0;
      return;
    }
    // About the mean c: d = c (1 + r tau), tau = 2t - 1 in [-1, 1], |r| < 1;
    //   j0 = (1/2) integral (1 + r tau)^p dtau,  j1 = (1/2) integral tau (1 + r tau)^p dtau,
    //   i0 = c^p j0,  i1 = c^p (j0 + j1) / 2.
    const double c = 0.5 * (a + b), r = 0.5 * (b - a) / c;
    double j0 = 0.0, j1 = 0.0;
    if (std::fabs(r) < 0.05) {
      // Binomial series: j0 = sum over even k of C(p, k) r^k / (k + 1), j1 = sum over odd k of
      // C(p, k) r^k / (k + 2); the first omitted term is below r^14 = 6e-19.
      double coefficient = 1.0, rk = 1.0;
      for (int k = 0; k <= 13; ++k) {
        if (k % 2 == 0) j0 += coefficient * rk / (k + 1);
        else j1 += coefficient * rk / (k + 2);
        coefficient *= (p - k) / (k + 1);
        rk *= r;
      }
    } else {
      // v = 1 + r tau: the closed forms lose at most log10(1 / r^2) < 3 digits here.
      const double up = 1.0 + r, um = 1.0 - r;
      const double d1 = power(up, p + 1.0) - power(um, p + 1.0);
      const double d2 = power(up, p + 2.0) - power(um, p + 2.0);
      j0 = d1 / (2.0 * r * (p + 1.0));
      j1 = (d2 / (p + 2.0) - d1 / (p + 1.0)) / (2.0 * r * r);
    }
    const double cp = power(c, p);
    i0 = cp * j0;
    i1 = cp * 0.5 * (j0 + j1);
    return;
  }
  if (a > 0.0) {
    // Only the left part [0, t0] penetrates, d = a (1 - t / t0); a - b >= a > 0.
    const double t0 = a / (a - b), ap = power(a, p);
    i0 = ap * t0 / (p + 1.0);
    i1 = ap * t0 * t0 / ((p + 1.0) * (p + 2.0));
    return;
  }
  // Only the right part [1 - l, 1] penetrates (or a NaN, which propagates).
  const double l = b / (b - a), bp = power(b, p);
  i0 = bp * l / (p + 1.0);
  i1 = bp * ((1.0 - l) * l / (p + 1.0) + l * l / (p + 2.0));
}

// Corner loads of the line contact (line_contact.hpp): F_a = K (i0 - i1), F_b = K i1 with p = n.
inline void line_contact_kernel(double stiffness, double exponent, double a, double b, double& left, double& right) {
  double i0, i1;
  linear_power_moments(exponent, a, b, i0, i1);
  left = stiffness * (i0 - i1);
  right = stiffness * i1;
}

// exp(-a) for a >= 0 (or NaN). Beyond a = 746 the result rounds to 0 (exp(-745.13...) is the
// smallest subnormal's rounding boundary), so 0 is returned without the call: at the slider's
// 30 m/s with v_s = 1 mm/s the Stribeck argument is about 1e9, and libm's underflow path (errno)
// costs more than the rest of the friction law.
inline double exp_minus(double a) { return a > 746.0 ? 0.0 : std::exp(-a); }

// Seed Eq. 16: mu_k + (mu_s - mu_k) exp(-|v/v_s|^gamma).
inline double stribeck_kernel(const FrictionLawParameters& p, double sliding_velocity) {
  const double ratio = std::fabs(sliding_velocity / p.stribeck_velocity);
  return p.kinetic_coefficient +
         (p.static_coefficient - p.kinetic_coefficient) *
             exp_minus(p.stribeck_exponent == 2.0 ? ratio * ratio : std::pow(ratio, p.stribeck_exponent));
}

// LuGre (friction_law.hpp) with z advanced exactly from z_start over `elapsed` at this sliding
// speed: z' = k (z_ss - z) with k = sigma0 |v| / g(v) and z_ss = g(v) sign(v) / sigma0, where g is
// mu(v) F_N (absolute form, newtons) or mu(v) (normalised form). Used by friction() and, with
// integrator.bristles = "exponential", by the slider-crank's right-hand side.
inline FrictionEvaluation lugre_kernel(const FrictionLawParameters& p, double normal_force, double v, double z_start,
                                       double elapsed) {
  FrictionEvaluation out;
  if (normal_force == 0.0) return out;  // no load on the bristles: force 0, z 0
  if (std::isnan(normal_force)) {         // state, not a parameter: let the caller see it
    out.force = out.deflection = out.deflection_rate = normal_force;
    return out;
  }
  double z = z_start, rate = 0.0;
  if (v != 0.0) {  // at v == 0 the ODE is dz/dt = 0: z holds (sticking); NaN takes this branch
    const double mu = stribeck_kernel(p, v);
    const double g = p.law == FrictionLaw::lugre_absolute ? normal_force * mu : mu;
    const double z_ss = std::copysign(g / p.sigma0, v);
    // g can underflow to 0 for a subnormal F_N: then k overflows. A huge finite k keeps
    // k * 0 and 0 * k away from NaN and changes nothing else (exp(-k t) is 0 either way).
    const double k = std::fmin(p.sigma0 * std::fabs(v) / g, std::numeric_limits<double>::max());
    const double kt = k * elapsed;
    const double gap = z_ss - z_start;
    // z_start + gap (1 - e^{-kt}): expm1 keeps the digits when kt is tiny (presliding).
    z = z_start - gap * std::expm1(-kt);
    // Rounding may put z an ulp past z_ss; the exact solution never overshoots.
    if (!std::isnan(z)) z = std::clamp(z, std::fmin(z_start, z_ss), std::fmax(z_start, z_ss));
    // dz/dt = k (z_ss - z(t)) = k gap e^{-kt}; formed from gap e^{-kt} first, so a huge k meets a
    // 0 (not an inf) once the bristles have settled.
    const double settled = gap * exp_minus(kt);
    rate = settled == 0.0 ? 0.0 : k * settled;
    if (!std::isnan(rate))
      rate = std::clamp(rate, -std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  }
  const double s = p.sigma0 * z + p.bristle_damping(v) * rate + p.sigma2 * v;
  out.force = p.law == FrictionLaw::lugre_absolute ? -s : -normal_force * s;
  out.deflection = z;
  out.deflection_rate = rate;
  return out;
}

}  // namespace mechanism::detail
