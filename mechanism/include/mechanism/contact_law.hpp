#pragma once
// Normal contact laws of the continuous (penalty) family
//
//   F_N = K delta^n (1 + chi(e) * delta_rate / delta_rate_impact),       delta > 0,
//
// with delta the penetration, delta_rate = d(delta)/dt (> 0 while approaching), delta_rate_impact
// the approach speed latched by the caller at contact onset, K the stiffness (see
// contact_stiffness.hpp) and chi the hysteresis factor that makes one free impact rebound with
// roughly the declared restitution e. Only chi differs between the laws:
//   hertz                Hertz 1881, elastic                       chi = 0
//   hunt_crossley        Hunt & Crossley 1975                      chi = 3 (1 - e) / 2
//   lankarani_nikravesh  Lankarani & Nikravesh 1990 (the seed's)   chi = 3 (1 - e^2) / 4
//   flores               Flores et al. 2011                        chi = 8 (1 - e) / (5 e)
//   hu_guo               Hu & Guo 2015                             chi = 3 (1 - e) / (2 e)
//   gonthier             Gonthier et al. 2004                      chi = (1 - e^2) / e
//   exact_restitution    the same force, chi solving                chi - ln(1 + chi) = -chi e - ln(1 - chi e)
// The last is exact: integrating m v dv = -K d^n (1 + chi v / v0) dd over one free impact (v from
// v0 to -e v0 while d goes from 0 and back to 0, so the right side integrates to 0) gives
// int v / (1 + chi v / v0) dv = 0, whose primitive gives the relation above; it holds for every
// exponent n, stiffness, mass and speed (above velocity_floor). The others approximate it (their
// effective restitution drifts from e as e falls: docs/reference/mechanism/contact-and-friction.md).
// Decisions (docs/reference/mechanism/contact-and-friction.md):
//  - The force is clamped at 0: near release the dissipative term can exceed the elastic one
//    (delta_rate < -delta_rate_impact / chi) and would pull the bodies together; contacts only push.
//  - |impact_velocity| is used and raised to velocity_floor, so a grazing onset (latched speed
//    -> 0) gives a finite damping term instead of a division by ~0.
//  - Parameters are validated on every call (a few comparisons) and throw InvalidParameter; the
//    state arguments are not: a NaN penetration (or a NaN rate or impact velocity, for a law with
//    chi != 0, which uses them) propagates to the result so the integrator's non-finite-state
//    check sees it.

#include <optional>
#include <string_view>

namespace mechanism {

enum class NormalContactLaw { hertz, hunt_crossley, lankarani_nikravesh, flores, hu_guo, gonthier, exact_restitution };

struct ContactLawParameters {
  NormalContactLaw law = NormalContactLaw::lankarani_nikravesh;  // the seed's Eq. (10)
  double restitution = 0.9;        // e in (0, 1]; e = 1 means no damping for every law (Flores' benchmarks use 0.9)
  double exponent = 1.5;           // n in F = K delta^n (...); 1.5 for metal-to-metal (Hertz)
  double velocity_floor = 1e-3;    // m/s: a latched impact velocity below this is raised to it (grazing)
  // Throws InvalidParameter naming "restitution" (must be in (0, 1]), "exponent" (finite, > 0) or
  // "velocity_floor" (finite, > 0).
  void validate() const;
};

// chi in F = K d^n (1 + chi * d_rate / d_rate_impact) (table above); throws InvalidParameter
// ("restitution") unless 0 < e <= 1. Every law gives chi = 0 at e = 1.
double hysteresis_factor(NormalContactLaw law, double restitution);

// The chi whose free impact rebounds with exactly e (exact_restitution above): the root of
// chi - ln(1 + chi) + chi e + ln(1 - chi e) = 0 in ((1 - e) / e, 1 / e), where that function falls
// from positive to -infinity (it rises on (0, (1 - e)/e), its only other zero being 0); bisection to
// the last bit. 0 at e = 1. Throws InvalidParameter ("restitution") unless 0 < e <= 1.
double exact_hysteresis_factor(double restitution);

// Normal force magnitude (N) for penetration > 0 (m), penetration_rate (m/s, > 0 approaching) and
// the impact velocity latched at contact onset (its magnitude, floored at velocity_floor).
// 0 for penetration <= 0; never negative (clamped at 0, see above). Throws InvalidParameter for
// invalid parameters or a stiffness that is negative or not finite ("stiffness").
double normal_force(const ContactLawParameters& p, double stiffness, double penetration,
                    double penetration_rate, double impact_velocity);

// Stable lower-case names ("lankarani_nikravesh", ...) for scene files and output headers, and
// the inverse (nullopt for an unknown name).
std::string_view to_string(NormalContactLaw law) noexcept;
std::optional<NormalContactLaw> parse_normal_contact_law(std::string_view name) noexcept;

}  // namespace mechanism
