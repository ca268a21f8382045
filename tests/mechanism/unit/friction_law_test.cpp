// Friction laws: Coulomb's sign, Ambrosio's correction, the Stribeck curve, and LuGre in both
// forms: the steady-sliding limit, the exact bristle update against a fine RK4 of its ODE written
// here, its stability where explicit Euler diverges, presliding, and stick-slip of a block pulled
// through a spring (an integrator written here, advancing z with the exact update each step).
#include "mechanism/expect_invalid.hpp"
#include "mechanism/friction_law.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "mechanism/error.hpp"

namespace {

using mechanism::FrictionEvaluation;
using mechanism::FrictionLaw;
using mechanism::FrictionLawParameters;
using mechanism::InvalidParameter;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

FrictionLawParameters with_law(FrictionLaw law) {
  FrictionLawParameters p;
  p.law = law;
  return p;
}

// g(v) of the header: newtons (absolute) or a coefficient (normalised).
double g_of(const FrictionLawParameters& p, double normal_force, double v) {
  const double mu = mechanism::stribeck_coefficient(p, v);
  return p.law == FrictionLaw::lugre_absolute ? normal_force * mu : mu;
}

using mechanism::testing::expect_invalid;

TEST(FrictionLaw, CoulombOpposesSlidingAndIsZeroAtRest) {
  const auto p = with_law(FrictionLaw::coulomb);
  EXPECT_DOUBLE_EQ(mechanism::friction(p, 50.0, 0.3, 0, 0).force, -0.11 * 50.0);
  EXPECT_DOUBLE_EQ(mechanism::friction(p, 50.0, -1e-12, 0, 0).force, +0.11 * 50.0);
  EXPECT_EQ(mechanism::friction(p, 50.0, 0.0, 0, 0).force, 0.0);  // documented choice at v == 0
  EXPECT_EQ(mechanism::friction(p, 0.0, 3.0, 0, 0).force, 0.0);
  EXPECT_EQ(mechanism::friction(p, 50.0, 3.0, 0.7, 1.0).deflection, 0.0);  // stateless
  EXPECT_EQ(mechanism::friction(with_law(FrictionLaw::none), 50.0, 3.0, 0, 0).force, 0.0);
}

// Ambrosio 2002: c_d = 0 up to v0, 1 from v1, linear between (v0 = 1e-4, v1 = 1e-2 by default).
TEST(FrictionLaw, AmbrosioCorrectionIsARamp) {
  const auto p = with_law(FrictionLaw::ambrosio);
  const double v0 = p.ambrosio_v0, v1 = p.ambrosio_v1;
  for (const double v : {0.0, 1e-12, 0.5 * v0, v0}) EXPECT_EQ(mechanism::ambrosio_correction(p, v), 0.0) << v;
  for (const double v : {v1, 2 * v1, 100.0}) EXPECT_EQ(mechanism::ambrosio_correction(p, v), 1.0) << v;
  for (const double f : {0.1, 0.25, 0.5, 0.9}) {
    const double v = v0 + f * (v1 - v0);
    EXPECT_NEAR(mechanism::ambrosio_correction(p, v), f, 1e-12);
    EXPECT_NEAR(mechanism::ambrosio_correction(p, -v), f, 1e-12);
    EXPECT_NEAR(mechanism::friction(p, 20.0, -v, 0, 0).force, +0.11 * f * 20.0, 1e-12);
  }
  EXPECT_DOUBLE_EQ(mechanism::friction(p, 20.0, 5.0, 0, 0).force, -0.11 * 20.0);
  EXPECT_EQ(mechanism::friction(p, 20.0, 0.5 * v0, 0, 0).force, 0.0);
}

// Seed Eq. (16): mu_s at rest, mu_k far away, mu_k + (mu_s - mu_k)/e at |v| = v_s.
TEST(FrictionLaw, StribeckCurve) {
  FrictionLawParameters p;
  p.static_coefficient = 0.15;
  p.kinetic_coefficient = 0.1;
  EXPECT_DOUBLE_EQ(mechanism::stribeck_coefficient(p, 0.0), 0.15);
  EXPECT_DOUBLE_EQ(mechanism::stribeck_coefficient(p, 100.0), 0.1);
  EXPECT_DOUBLE_EQ(mechanism::stribeck_coefficient(p, 1e-3), 0.1 + 0.05 * std::exp(-1.0));
  EXPECT_DOUBLE_EQ(mechanism::stribeck_coefficient(p, -2e-3), 0.1 + 0.05 * std::exp(-4.0));
  EXPECT_FALSE(p.stribeck_peak_missing());
  EXPECT_TRUE(FrictionLawParameters{}.stribeck_peak_missing());  // the seed's printed 0.1 < 0.11
  EXPECT_TRUE(FrictionLawParameters{}.has_state());
  EXPECT_TRUE(with_law(FrictionLaw::lugre_normalised).has_state());
  EXPECT_FALSE(with_law(FrictionLaw::coulomb).has_state());
  EXPECT_FALSE(with_law(FrictionLaw::ambrosio).has_state());
}

// Steady sliding (z = z_ss, dz/dt = 0): F = -(g(v) + sigma2 v) in newtons (absolute) and
// -F_N (mu(v) + sigma2 v) (normalised), i.e. the Stribeck curve plus viscous friction.
TEST(FrictionLaw, LugreSteadySlidingForceIsStribeckPlusViscous) {
  for (const FrictionLaw law : {FrictionLaw::lugre_absolute, FrictionLaw::lugre_normalised}) {
    auto p = with_law(law);
    p.static_coefficient = 0.15;
    p.sigma2 = law == FrictionLaw::lugre_absolute ? 0.4 : 0.01;
    const double fn = 30.0;
    for (const double v : {1e-4, 1e-3, 0.05, 28.0, -0.002, -5.0}) {
      SCOPED_TRACE(std::string(mechanism::to_string(law)) + " v = " + std::to_string(v));
      const double k = mechanism::bristle_relaxation_rate(p, fn, v);
      const FrictionEvaluation r = mechanism::friction(p, fn, v, 0.0, 100.0 / k);  // k t = 100
      const double mu = mechanism::stribeck_coefficient(p, v);
      const double expected = law == FrictionLaw::lugre_absolute ? -(fn * mu * std::copysign(1.0, v) + p.sigma2 * v)
                                                                 : -fn * (mu * std::copysign(1.0, v) + p.sigma2 * v);
      EXPECT_NEAR(r.force, expected, 1e-12 * std::fabs(expected));
      EXPECT_NEAR(r.deflection, std::copysign(g_of(p, fn, v), v) / p.sigma0, 1e-15);
      EXPECT_NEAR(r.deflection_rate, 0.0, 1e-30);
    }
  }
}

// The exact update against RK4 of dz/dt = v - sigma0 |v| z / g(v) (v, F_N frozen) with 2e4 steps
// over k t ~ 2 (RK4 error ~ (k h)^4 ~ 1e-16): z and dz/dt to 1e-9 relative, starting on either
// side of z_ss, in both forms.
TEST(FrictionLaw, LugreExactUpdateMatchesFineRk4) {
  for (const FrictionLaw law : {FrictionLaw::lugre_absolute, FrictionLaw::lugre_normalised}) {
    const auto p = with_law(law);
    const double fn = 10.0;
    for (const double v : {1e-3, -2e-3, 5e-4}) {
      const double g = g_of(p, fn, v);
      const double k = p.sigma0 * std::fabs(v) / g;
      for (const double z0 : {0.0, -1.5 * g / p.sigma0 * std::copysign(1.0, v), 0.3 * g / p.sigma0}) {
        SCOPED_TRACE(std::string(mechanism::to_string(law)) + " v = " + std::to_string(v) + " z0 = " + std::to_string(z0));
        const double elapsed = 2.0 / k;
        auto rhs = [&](double z) { return v - p.sigma0 * std::fabs(v) * z / g; };
        const int steps = 20000;
        const double h = elapsed / steps;
        double z = z0;
        for (int i = 0; i < steps; ++i) {
          const double k1 = rhs(z), k2 = rhs(z + 0.5 * h * k1), k3 = rhs(z + 0.5 * h * k2), k4 = rhs(z + h * k3);
          z += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
        }
        const FrictionEvaluation r = mechanism::friction(p, fn, v, z0, elapsed);
        EXPECT_NEAR(r.deflection, z, 1e-9 * std::fabs(z));
        EXPECT_NEAR(r.deflection_rate, rhs(z), 1e-9 * std::fabs(rhs(z)));
        const double s = p.sigma0 * r.deflection + p.sigma1 * r.deflection_rate + p.sigma2 * v;
        EXPECT_DOUBLE_EQ(r.force, law == FrictionLaw::lugre_absolute ? -s : -fn * s);
      }
    }
  }
}

// Stiff cases: the normalised form at 28 m/s (k = 1e5 * 28 / 0.11 = 2.5e7 1/s, the seed-notes'
// "> 1e6") and the absolute form at F_N = 1e-3 N (k = 2.5e10). For k t from 1e-3 to 1e12 the exact
// z stays between z0 and z_ss and approaches z_ss monotonically; explicit Euler multiplies
// z - z_ss by (1 - k h) per step and diverges once k h > 2.
TEST(FrictionLaw, LugreExactUpdateStableWhereEulerDiverges) {
  struct Case { FrictionLaw law; double fn; };
  for (const Case c : {Case{FrictionLaw::lugre_normalised, 50.0}, Case{FrictionLaw::lugre_absolute, 1e-3}}) {
    const auto p = with_law(c.law);
    const double v = 28.0;
    const double g = g_of(p, c.fn, v);
    const double k = mechanism::bristle_relaxation_rate(p, c.fn, v);
    EXPECT_GT(k, 1e6);
    const double z_ss = g / p.sigma0, z0 = -2.0 * z_ss;
    double previous_gap = std::fabs(z0 - z_ss);
    for (double kt = 1e-3; kt <= 1e12; kt *= 10.0) {
      SCOPED_TRACE(std::string(mechanism::to_string(c.law)) + " k t = " + std::to_string(kt));
      const FrictionEvaluation r = mechanism::friction(p, c.fn, v, z0, kt / k);
      ASSERT_TRUE(std::isfinite(r.force) && std::isfinite(r.deflection_rate));
      EXPECT_GE(r.deflection, z0);
      EXPECT_LE(r.deflection, z_ss);
      const double gap = std::fabs(r.deflection - z_ss);
      EXPECT_LE(gap, previous_gap);
      previous_gap = gap;
      // Explicit Euler over the same interval in one step.
      const double euler = z0 + (kt / k) * (v - k * z0);
      if (kt > 2.0) {
        EXPECT_GT(std::fabs(euler - z_ss), std::fabs(z0 - z_ss));
      }
    }
    EXPECT_NEAR(previous_gap, 0.0, 1e-15 * z_ss);
    // The seed's step, 1e-6 s, repeated: exact stays at z_ss, Euler grows by |1 - k h| per step.
    double z_exact = z0, z_euler = z0;
    for (int i = 0; i < 20; ++i) {
      z_exact = mechanism::friction(p, c.fn, v, z_exact, 1e-6).deflection;
      z_euler += 1e-6 * (v - k * z_euler);
    }
    EXPECT_NEAR(z_exact, z_ss, 1e-12 * z_ss);
    EXPECT_GT(std::fabs(z_euler - z_ss), 1e6 * std::fabs(z0 - z_ss));
  }
}

// Presliding: for a displacement d << g/sigma0 the bristles deflect with the body (z ~ d) and the
// force is a spring, |F| ~ sigma0 d (1 - O(sigma0 d / g)), plus sigma1 v, which at v = 1e-12 m/s
// is 4e-10 N, below 1e-3 of the smallest sigma0 d here. Reversing the motion returns z to ~0:
// presliding is elastic.
TEST(FrictionLaw, LugrePreslidingIsASpringOfStiffnessSigma0) {
  auto p = with_law(FrictionLaw::lugre_absolute);
  const double fn = 10.0, v = 1e-12;  // g ~ 1 N, so g / sigma0 ~ 1e-5 m
  for (const double d : {1e-11, 1e-10, 1e-9, 1e-8}) {
    SCOPED_TRACE("d = " + std::to_string(d));
    const FrictionEvaluation out = mechanism::friction(p, fn, v, 0.0, d / v);
    EXPECT_NEAR(out.deflection, d, 1e-3 * d);
    EXPECT_NEAR(-out.force, p.sigma0 * d, 1e-2 * p.sigma0 * d);
    const FrictionEvaluation back = mechanism::friction(p, fn, -v, out.deflection, d / v);
    EXPECT_NEAR(back.deflection, 0.0, 1e-3 * d);
  }
  // Normalised form: the same spring per newton of normal force.
  p.law = FrictionLaw::lugre_normalised;
  const double d = 1e-9;
  EXPECT_NEAR(-mechanism::friction(p, fn, v, 0.0, d / v).force, fn * p.sigma0 * d, 1e-2 * fn * p.sigma0 * d);
}

struct StickSlip {
  double breakaway = 0;       // largest spring force before the first slip (N)
  double stick_fraction = 0;  // fraction of [t_from, t_end] with |velocity| < 1e-3 m/s
  int slips = 0;              // number of stick -> slip transitions
};

// A block of mass m on a fixed floor, pulled through a spring k_s whose end moves at V:
// m x'' = k_s (V t - x) + F(x'), RK4 with step h; each stage evaluates friction with the step's
// starting z and elapsed c_i h, and after the step z is advanced with the end-of-step velocity.
StickSlip pull_block(const FrictionLawParameters& p, double t_end, double t_from) {
  const double m = 1.0, fn = 10.0, ks = 2.0, speed = 0.1, h = 1e-4;
  const double stick_speed = 1e-3;  // 1% of the pulling speed
  double x = 0.0, u = 0.0, z = 0.0, t = 0.0;
  StickSlip out;
  bool sticking = true;
  long counted = 0, stuck = 0;
  auto accel = [&](double tt, double xx, double uu, double elapsed) {
    return (ks * (speed * tt - xx) + mechanism::friction(p, fn, uu, z, elapsed).force) / m;
  };
  const long steps = std::lround(t_end / h);
  for (long i = 0; i < steps; ++i) {
    const double a1 = accel(t, x, u, 0.0);
    const double x2 = x + 0.5 * h * u, u2 = u + 0.5 * h * a1;
    const double a2 = accel(t + 0.5 * h, x2, u2, 0.5 * h);
    const double x3 = x + 0.5 * h * u2, u3 = u + 0.5 * h * a2;
    const double a3 = accel(t + 0.5 * h, x3, u3, 0.5 * h);
    const double x4 = x + h * u3, u4 = u + h * a3;
    const double a4 = accel(t + h, x4, u4, h);
    x += h / 6.0 * (u + 2 * u2 + 2 * u3 + u4);
    u += h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4);
    t += h;
    z = mechanism::friction(p, fn, u, z, h).deflection;
    const bool slow = std::fabs(u) < stick_speed;
    if (out.slips == 0) out.breakaway = std::fmax(out.breakaway, ks * (speed * t - x));
    if (sticking && std::fabs(u) > 0.5 * speed) {
      ++out.slips;
      sticking = false;
    } else if (!sticking && slow) {
      sticking = true;
    }
    if (t >= t_from) {
      ++counted;
      stuck += slow ? 1 : 0;
    }
  }
  out.stick_fraction = counted > 0 ? static_cast<double>(stuck) / static_cast<double>(counted) : 0.0;
  return out;
}

// Canudas de Wit et al. 1995's stick-slip example (m = 1 kg, F_C = 1 N, F_S = 1.5 N, sigma0 = 1e5,
// sigma1 = sqrt(1e5), sigma2 = 0.4, v_s = 1e-3, k_s = 2 N/m, V = 0.1 m/s), here as F_N = 10 N with
// mu_k = 0.1, mu_s = 0.15: repeated stick phases, and the block breaks away near mu_s F_N = 1.5 N.
// With the seed's printed mu_s = 0.1 < mu_k = 0.11 there is no Stribeck drop, no negative slope:
// the motion settles to steady sliding, no sticking once the transient has passed.
TEST(FrictionLaw, LugreStickSlipOfABlockPulledThroughASpring) {
  auto p = with_law(FrictionLaw::lugre_absolute);
  p.static_coefficient = 0.15;
  p.kinetic_coefficient = 0.1;
  p.sigma1 = std::sqrt(1e5);
  p.sigma2 = 0.4;
  const StickSlip with_peak = pull_block(p, 40.0, 10.0);
  EXPECT_NEAR(with_peak.breakaway, 0.15 * 10.0, 0.05 * 1.5);
  EXPECT_GE(with_peak.slips, 3);
  EXPECT_GT(with_peak.stick_fraction, 0.2);

  // The normalised form with sigma_i / F_N is the same law at constant F_N (see FormsAgree...).
  auto normalised = p;
  normalised.law = FrictionLaw::lugre_normalised;
  normalised.sigma0 /= 10.0;
  normalised.sigma1 /= 10.0;
  normalised.sigma2 /= 10.0;
  const StickSlip normalised_peak = pull_block(normalised, 40.0, 10.0);
  EXPECT_NEAR(normalised_peak.breakaway, with_peak.breakaway, 1e-9);
  EXPECT_EQ(normalised_peak.slips, with_peak.slips);

  p.static_coefficient = 0.1;
  p.kinetic_coefficient = 0.11;
  const StickSlip without_peak = pull_block(p, 40.0, 20.0);
  EXPECT_EQ(without_peak.slips, 1);
  EXPECT_LT(without_peak.stick_fraction, 0.01);
}

// At a constant F_N the absolute form with sigma_i is the normalised form with sigma_i / F_N:
// z_ss = F_N mu / sigma0 and k = sigma0 |v| / (F_N mu) are the same in both, so z is the same and
// F_N (sigma_i / F_N) (...) is the absolute force.
TEST(FrictionLaw, LugreFormsAgreeAtConstantNormalForce) {
  const auto absolute = with_law(FrictionLaw::lugre_absolute);
  for (const double fn : {1e-3, 2.5, 400.0})
    for (const double v : {-3.0, 2e-4, 28.0})
      for (const double elapsed : {0.0, 1e-7, 1e-3}) {
        auto normalised = absolute;
        normalised.law = FrictionLaw::lugre_normalised;
        normalised.sigma0 /= fn;
        normalised.sigma1 /= fn;
        normalised.sigma2 /= fn;
        const double z0 = 0.3 * fn * 0.1 / absolute.sigma0;
        const FrictionEvaluation a = mechanism::friction(absolute, fn, v, z0, elapsed);
        const FrictionEvaluation n = mechanism::friction(normalised, fn, v, z0, elapsed);
        SCOPED_TRACE("fn=" + std::to_string(fn) + " v=" + std::to_string(v) + " t=" + std::to_string(elapsed));
        EXPECT_NEAR(a.force, n.force, 1e-12 * std::fabs(a.force));
        EXPECT_NEAR(a.deflection, n.deflection, 1e-12 * std::fabs(a.deflection));
        EXPECT_NEAR(a.deflection_rate, n.deflection_rate, 1e-12 * std::fabs(a.deflection_rate));
      }
}

// With F_N == 0 the bristles carry no load (header): force, deflection and rate are 0 for any
// z_start, in both forms, and every other law gives 0 force.
TEST(FrictionLaw, ZeroNormalForceGivesNoFrictionAndUnloadsBristles) {
  for (const FrictionLaw law : {FrictionLaw::none, FrictionLaw::coulomb, FrictionLaw::ambrosio,
                                FrictionLaw::lugre_absolute, FrictionLaw::lugre_normalised}) {
    const FrictionEvaluation r = mechanism::friction(with_law(law), 0.0, 3.0, 1e-6, 1e-6);
    EXPECT_EQ(r.force, 0.0) << mechanism::to_string(law);
    EXPECT_EQ(r.deflection, 0.0) << mechanism::to_string(law);
    EXPECT_EQ(r.deflection_rate, 0.0) << mechanism::to_string(law);
  }
  EXPECT_EQ(mechanism::bristle_relaxation_rate(with_law(FrictionLaw::lugre_absolute), 0.0, 1.0), kInf);
}

// At v == 0 the ODE is dz/dt = 0: z holds and the force is the bristle spring sigma0 z (sticking).
TEST(FrictionLaw, LugreHoldsDeflectionAtRest) {
  const auto p = with_law(FrictionLaw::lugre_absolute);
  const FrictionEvaluation r = mechanism::friction(p, 10.0, 0.0, 3e-6, 1.0);
  EXPECT_EQ(r.deflection, 3e-6);
  EXPECT_EQ(r.deflection_rate, 0.0);
  EXPECT_DOUBLE_EQ(r.force, -p.sigma0 * 3e-6);
}

// Normal forces from 0 to 1e4 N (and subnormal), speeds 1e-12 to 100 m/s of either sign and 0,
// physical deflections, elapsed 0 to 1e3 s, both Stribeck orders, both LuGre forms: no NaN.
TEST(FrictionLaw, FiniteAtExtremes) {
  for (const FrictionLaw law : {FrictionLaw::coulomb, FrictionLaw::ambrosio, FrictionLaw::lugre_absolute,
                                FrictionLaw::lugre_normalised})
    for (const double mu_s : {0.1, 0.3})
      for (const double fn : {0.0, 4.9e-324, 1e-300, 1e-12, 1.0, 1e4})
        for (const double v : {0.0, 1e-12, -1e-12, 28.0, 100.0, -100.0})
          for (const double z0 : {0.0, 1e-3, -1e-6})
            for (const double elapsed : {0.0, 1e-6, 1e3}) {
              auto p = with_law(law);
              p.static_coefficient = mu_s;
              const FrictionEvaluation r = mechanism::friction(p, fn, v, z0, elapsed);
              EXPECT_TRUE(std::isfinite(r.force) && std::isfinite(r.deflection) && std::isfinite(r.deflection_rate))
                  << mechanism::to_string(law) << " fn=" << fn << " v=" << v << " z0=" << z0 << " t=" << elapsed;
              // From unloaded bristles z and dz/dt both follow v, so the force opposes it (with a
              // z0 left by earlier motion it may not, for a while: that is presliding memory).
              if (v != 0.0 && z0 == 0.0 && fn > 0.0 && r.force != 0.0) {
                EXPECT_LT(r.force * v, 0.0) << "does not oppose sliding";
              }
            }
}

TEST(FrictionLaw, NanStatePropagates) {
  for (const FrictionLaw law : {FrictionLaw::lugre_absolute, FrictionLaw::lugre_normalised}) {
    const auto p = with_law(law);
    EXPECT_TRUE(std::isnan(mechanism::friction(p, kNan, 1.0, 0.0, 1e-6).force));
    EXPECT_TRUE(std::isnan(mechanism::friction(p, 10.0, kNan, 0.0, 1e-6).force));
    EXPECT_TRUE(std::isnan(mechanism::friction(p, 10.0, 1.0, kNan, 1e-6).force));
  }
  EXPECT_TRUE(std::isnan(mechanism::friction(with_law(FrictionLaw::coulomb), 10.0, kNan, 0, 0).force));
}

TEST(FrictionLaw, InvalidParametersThrowNamingTheKey) {
  EXPECT_NO_THROW(FrictionLawParameters{}.validate());
  struct Bad { const char* key; double FrictionLawParameters::*field; double value; FrictionLaw law; };
  const std::array<Bad, 14> cases{{
      {"static_coefficient", &FrictionLawParameters::static_coefficient, 0.0, FrictionLaw::lugre_absolute},
      {"kinetic_coefficient", &FrictionLawParameters::kinetic_coefficient, -0.1, FrictionLaw::lugre_normalised},
      {"kinetic_coefficient", &FrictionLawParameters::kinetic_coefficient, kNan, FrictionLaw::coulomb},
      {"kinetic_coefficient", &FrictionLawParameters::kinetic_coefficient, -1.0, FrictionLaw::ambrosio},
      {"stribeck_velocity", &FrictionLawParameters::stribeck_velocity, 0.0, FrictionLaw::lugre_absolute},
      {"stribeck_exponent", &FrictionLawParameters::stribeck_exponent, kInf, FrictionLaw::lugre_absolute},
      {"sigma0", &FrictionLawParameters::sigma0, 0.0, FrictionLaw::lugre_absolute},
      {"sigma0", &FrictionLawParameters::sigma0, kNan, FrictionLaw::lugre_normalised},
      {"sigma1", &FrictionLawParameters::sigma1, -1.0, FrictionLaw::lugre_absolute},
      {"sigma2", &FrictionLawParameters::sigma2, kInf, FrictionLaw::lugre_normalised},
      {"ambrosio_v0", &FrictionLawParameters::ambrosio_v0, 0.0, FrictionLaw::ambrosio},
      {"ambrosio_v1", &FrictionLawParameters::ambrosio_v1, 1e-5, FrictionLaw::ambrosio},  // below v0
      {"ambrosio_v1", &FrictionLawParameters::ambrosio_v1, 1e-4, FrictionLaw::ambrosio},  // equal to v0
      {"ambrosio_v1", &FrictionLawParameters::ambrosio_v1, kNan, FrictionLaw::ambrosio},
  }};
  for (const Bad& c : cases) {
    auto p = with_law(c.law);
    p.*c.field = c.value;
    expect_invalid(c.key, [&] { p.validate(); });
    expect_invalid(c.key, [&] { mechanism::friction(p, 1.0, 0.1, 0.0, 1e-6); });
  }
  // Fields a law does not use are not checked.
  auto coulomb = with_law(FrictionLaw::coulomb);
  coulomb.sigma0 = -1.0;
  EXPECT_NO_THROW(coulomb.validate());
  auto stribeck = FrictionLawParameters{};
  stribeck.stribeck_velocity = 0.0;
  expect_invalid("stribeck_velocity", [&] { mechanism::stribeck_coefficient(stribeck, 1.0); });
  expect_invalid("normal_force", [] { mechanism::friction(FrictionLawParameters{}, -1.0, 0.1, 0.0, 0.0); });
  for (const double t : {-1e-9, kNan, kInf})
    expect_invalid("elapsed", [&] { mechanism::friction(FrictionLawParameters{}, 1.0, 0.1, 0.0, t); });
  expect_invalid("law", [] { mechanism::bristle_relaxation_rate(with_law(FrictionLaw::coulomb), 1.0, 0.1); });
}

TEST(FrictionLaw, NamesRoundTrip) {
  for (const FrictionLaw law : {FrictionLaw::none, FrictionLaw::coulomb, FrictionLaw::ambrosio,
                                FrictionLaw::lugre_absolute, FrictionLaw::lugre_normalised})
    EXPECT_EQ(mechanism::parse_friction_law(mechanism::to_string(law)), law);
  EXPECT_FALSE(mechanism::parse_friction_law("LuGre").has_value());
}

}  // namespace
