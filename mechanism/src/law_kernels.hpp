#pragma once
// Private to the library: the formulas of the contact and friction laws without their parameter
// checks. The public functions (contact_law.cpp, contact_stiffness.cpp, friction_law.cpp) check
// and then call these; the slider-crank checks its scene once and calls them from its right-hand
// side, where the checks cost more than the formulas (tens of millions of calls per run). One
// source for each formula keeps both paths bit-identical.

#include <cmath>

#include "mechanism/friction_law.hpp"

namespace mechanism::detail {

// F = K d^n (1 + chi d_rate / max(|v_impact|, floor)), clamped at 0 (contact_law.hpp); chi from
// hysteresis_factor.
inline double normal_force_kernel(double chi, double exponent, double velocity_floor, double stiffness,
                                  double penetration, double penetration_rate, double impact_velocity) {
  if (penetration <= 0.0) return 0.0;  // NaN goes on and comes out as NaN
  // n = 1.5 (metal on metal) is by far the common case: d sqrt(d) is exact and pow is the
  // costliest call in the simulator's right-hand side.
  const double elastic =
      stiffness * (exponent == 1.5 ? penetration * std::sqrt(penetration) : std::pow(penetration, exponent));
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

}  // namespace mechanism::detail
