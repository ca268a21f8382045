#pragma once
// Tangential (friction) laws of one contact, given its normal force F_N >= 0 and the sliding
// velocity v: the tangential velocity of the body the force acts on relative to the other
// surface, along a tangent chosen by the caller. The returned force is along the same tangent and
// acts on that body, so it opposes v (force * v <= 0 in steady sliding).
//
//   none              F = 0
//   coulomb           F = -mu_k F_N sign(v); 0 at v == 0 exactly (the classical law has no value
//                     there; a regularised law is Ambrosio's)
//   ambrosio          F = -mu_k c_d(|v|) F_N sign(v), Ambrosio 2002: c_d = 0 for |v| <= v0,
//                     (|v| - v0)/(v1 - v0) between, 1 for |v| >= v1
//   lugre_absolute    Canudas de Wit et al. 1995 in forces: F = -(sigma0 z + sigma1 dz/dt + sigma2 v),
//                     dz/dt = v - sigma0 |v| z / g(v), g = F_N mu(v) (N); sigma0 N/m, sigma1, sigma2 N s/m
//   lugre_normalised  the seed's Eq. (15)-(16), coefficients: F = -F_N (sigma0 z + sigma1 dz/dt + sigma2 v),
//                     dz/dt = v - sigma0 |v| z / g(v), g = mu(v); sigma0 1/m, sigma1, sigma2 s/m
// with the Stribeck curve mu(v) = mu_k + (mu_s - mu_k) exp(-|v/v_s|^gamma) (seed Eq. 16).
//
// The bristle deflection z is the state of a LuGre contact (has_state()); the caller keeps one z
// per contact. friction() advances it EXACTLY from z_start over `elapsed` with v and F_N frozen at
// the values passed (a first-order linear ODE with constant coefficients):
//   z(t) = z_ss + (z_start - z_ss) exp(-k t),  k = sigma0 |v| / g(v),  z_ss = g(v) sign(v) / sigma0,
//   dz/dt(t) = k (z_ss - z(t)) = v - sigma0 |v| z(t) / g(v).
// z(t) always lies between z_start and z_ss and moves monotonically toward z_ss, for any k t (the
// explicit Euler map multiplies z - z_ss by 1 - k h and diverges once k h > 2; in the normalised
// form k exceeds 1e6 1/s at the slider's 28 m/s). "Exact" is exact for the frozen v: if v
// changes (even its sign) within the step, each call uses the v it is given as if it had held
// since the start of the step, so the update is first-order accurate in the variation of v and
// unconditionally stable. At v == 0, k = 0: z stays at z_start and dz/dt = 0 (sticking).
// Use within an integrator step: every stage calls friction(..., z_start, c_i h) with the step's
// starting z; after the step, call it with the end state and elapsed = h and keep the returned
// deflection as the next z_start.
//
// F_N == 0 (no contact) carries no load: every law returns force 0, and LuGre returns deflection 0
// and rate 0, so a contact that opens starts again from unloaded bristles (in the absolute form
// z_ss -> 0 as F_N -> 0 anyway). The viscous sigma2 v term is part of the friction force and
// vanishes with it.
// Known LuGre property (not altered here): at a step where z is far from z_ss (contact onset,
// velocity reversal) the sigma1 dz/dt term can reach about 2 sigma1 |v| (absolute form, newtons)
// or 2 sigma1 |v| F_N (normalised form), well above mu F_N.
//
// Parameters throw InvalidParameter (validated on every call); state arguments do not: a NaN in
// normal_force, sliding_velocity or z_start propagates to the result. A negative normal force
// ("normal_force") or a negative or non-finite elapsed ("elapsed") throws.

#include <cmath>
#include <optional>
#include <string_view>

namespace mechanism {

enum class FrictionLaw { none, coulomb, ambrosio, lugre_absolute, lugre_normalised };

struct FrictionLawParameters {
  FrictionLaw law = FrictionLaw::lugre_absolute;
  double static_coefficient = 0.1, kinetic_coefficient = 0.11;   // the seed's printed Table 2 values (mu_s < mu_k: see seed-notes)
  double stribeck_velocity = 1e-3, stribeck_exponent = 2.0;      // v_s, gamma (blank in the seed; common values)
  double sigma0 = 1e5, sigma1 = 400.0, sigma2 = 0.0;              // absolute form: N/m, N s/m, N s/m; normalised form: 1/m, s/m, s/m
  double ambrosio_v0 = 1e-4, ambrosio_v1 = 1e-2;                  // Ambrosio 2002 dynamic-correction velocities (m/s), 0 < v0 < v1
  // LuGre: sigma1 fades with sliding speed as sigma1 exp(-(v / v_d)^2) (Canudas de Wit 2003's remedy
  // for the large sigma1 dz/dt transients at high speed); 0 keeps sigma1 constant, as the seed prints it.
  double sigma1_velocity = 0.0;
  // The sigma1 in effect at that speed (inline: it is on the simulator's hot path).
  double bristle_damping(double sliding_velocity) const {
    if (sigma1_velocity <= 0.0) return sigma1;
    const double r = sliding_velocity / sigma1_velocity;
    const double a = r * r;
    return a > 746.0 ? 0.0 : sigma1 * std::exp(-a);  // exp(-a) rounds to 0 beyond 746: skip libm's underflow path
  }
  // Checks the fields the chosen law uses (an unused field is not checked):
  //   coulomb, ambrosio: kinetic_coefficient finite >= 0; ambrosio: 0 < ambrosio_v0 < ambrosio_v1;
  //   LuGre: static_coefficient, kinetic_coefficient, stribeck_velocity, stribeck_exponent, sigma0
  //   finite > 0 (g(v) > 0 everywhere), sigma1, sigma2 finite >= 0.
  // Throws InvalidParameter naming the field ("static_coefficient", "sigma0", ...).
  void validate() const;
  bool stribeck_peak_missing() const;  // true when static < kinetic (the caller warns)
  bool has_state() const;              // LuGre laws carry a bristle deflection z per contact
};

// mu_k + (mu_s - mu_k) exp(-|v/v_s|^gamma); throws InvalidParameter unless mu_s, mu_k >= 0 and
// v_s, gamma > 0 (all finite), whatever the law.
double stribeck_coefficient(const FrictionLawParameters& p, double sliding_velocity);

// Ambrosio's dynamic correction c_d(|v|) in [0, 1] (see above); throws unless 0 < v0 < v1.
double ambrosio_correction(const FrictionLawParameters& p, double sliding_velocity);

// k = sigma0 |v| / g(v) (1/s), the bristle relaxation rate of a LuGre law at this normal force
// and velocity (for step-size diagnostics); +inf when F_N == 0 in the absolute form.
double bristle_relaxation_rate(const FrictionLawParameters& p, double normal_force,
                               double sliding_velocity);

struct FrictionEvaluation {
  double force = 0;            // N, along the tangent, opposing sliding_velocity
  double deflection = 0;       // z at `elapsed` after the step start (0 for stateless laws)
  double deflection_rate = 0;  // dz/dt at that instant
};

// Friction force along the tangent (signed: it opposes sliding_velocity) for normal_force >= 0.
// LuGre: z advanced exactly from z_start over elapsed (see above). Stateless laws ignore z_start
// and elapsed and return deflection 0.
FrictionEvaluation friction(const FrictionLawParameters& p, double normal_force,
                            double sliding_velocity, double z_start, double elapsed);

// Stable lower-case names ("lugre_absolute", ...) and the inverse (nullopt for an unknown name).
std::string_view to_string(FrictionLaw law) noexcept;
std::optional<FrictionLaw> parse_friction_law(std::string_view name) noexcept;

}  // namespace mechanism
