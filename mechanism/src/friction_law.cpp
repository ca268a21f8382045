#include "mechanism/friction_law.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "checks.hpp"
#include "law_kernels.hpp"
#include "mechanism/error.hpp"

namespace mechanism {

using detail::require_non_negative;
using detail::require_positive;
using detail::text;

namespace {


void check_stribeck(const FrictionLawParameters& p) {
  require_non_negative("static_coefficient", p.static_coefficient);
  require_non_negative("kinetic_coefficient", p.kinetic_coefficient);
  require_positive("stribeck_velocity", p.stribeck_velocity);
  require_positive("stribeck_exponent", p.stribeck_exponent);
}

void check_ambrosio(const FrictionLawParameters& p) {
  require_positive("ambrosio_v0", p.ambrosio_v0);
  require_positive("ambrosio_v1", p.ambrosio_v1);
  if (!(p.ambrosio_v1 > p.ambrosio_v0))
    throw InvalidParameter("ambrosio_v1", text(p.ambrosio_v1),
                           "must be > ambrosio_v0 = " + text(p.ambrosio_v0));
}

bool is_lugre(FrictionLaw law) {
  return law == FrictionLaw::lugre_absolute || law == FrictionLaw::lugre_normalised;
}

double sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : v); }  // NaN stays NaN

// g(v) of the bristle ODE: newtons in the absolute form, a coefficient in the normalised one.
double bristle_limit(const FrictionLawParameters& p, double normal_force, double v) {
  const double mu = stribeck_coefficient(p, v);
  return p.law == FrictionLaw::lugre_absolute ? normal_force * mu : mu;
}

constexpr std::array<std::pair<FrictionLaw, std::string_view>, 5> kNames{{
    {FrictionLaw::none, "none"},
    {FrictionLaw::coulomb, "coulomb"},
    {FrictionLaw::ambrosio, "ambrosio"},
    {FrictionLaw::lugre_absolute, "lugre_absolute"},
    {FrictionLaw::lugre_normalised, "lugre_normalised"},
}};

}  // namespace

void FrictionLawParameters::validate() const {
  switch (law) {
    case FrictionLaw::none: return;
    case FrictionLaw::coulomb:
      require_non_negative("kinetic_coefficient", kinetic_coefficient);
      return;
    case FrictionLaw::ambrosio:
      require_non_negative("kinetic_coefficient", kinetic_coefficient);
      check_ambrosio(*this);
      return;
    case FrictionLaw::lugre_absolute:
    case FrictionLaw::lugre_normalised:
      // mu_s, mu_k > 0 so that g(v) > 0 for every v (g appears in a denominator).
      require_positive("static_coefficient", static_coefficient);
      require_positive("kinetic_coefficient", kinetic_coefficient);
      require_positive("stribeck_velocity", stribeck_velocity);
      require_positive("stribeck_exponent", stribeck_exponent);
      require_positive("sigma0", sigma0);
      require_non_negative("sigma1", sigma1);
      require_non_negative("sigma1_velocity", sigma1_velocity);
      require_non_negative("sigma2", sigma2);
      return;
  }
  throw InvalidParameter("law", std::to_string(static_cast<int>(law)), "unknown FrictionLaw");
}

bool FrictionLawParameters::stribeck_peak_missing() const {
  return static_coefficient < kinetic_coefficient;
}

bool FrictionLawParameters::has_state() const { return is_lugre(law); }

double stribeck_coefficient(const FrictionLawParameters& p, double sliding_velocity) {
  check_stribeck(p);
  return detail::stribeck_kernel(p, sliding_velocity);
}

double ambrosio_correction(const FrictionLawParameters& p, double sliding_velocity) {
  check_ambrosio(p);
  const double s = std::fabs(sliding_velocity);
  if (std::isnan(s)) return s;
  if (s <= p.ambrosio_v0) return 0.0;
  if (s >= p.ambrosio_v1) return 1.0;
  return (s - p.ambrosio_v0) / (p.ambrosio_v1 - p.ambrosio_v0);
}

double bristle_relaxation_rate(const FrictionLawParameters& p, double normal_force,
                               double sliding_velocity) {
  p.validate();
  if (!is_lugre(p.law))
    throw InvalidParameter("law", std::string(to_string(p.law)), "must be a LuGre law");
  if (normal_force < 0.0) throw InvalidParameter("normal_force", text(normal_force), "must be >= 0");
  if (sliding_velocity == 0.0) return 0.0;
  const double g = bristle_limit(p, normal_force, sliding_velocity);
  if (g == 0.0) return std::numeric_limits<double>::infinity();
  return p.sigma0 * std::fabs(sliding_velocity) / g;
}

FrictionEvaluation friction(const FrictionLawParameters& p, double normal_force,
                            double sliding_velocity, double z_start, double elapsed) {
  p.validate();
  if (normal_force < 0.0) throw InvalidParameter("normal_force", text(normal_force), "must be >= 0");
  if (!(std::isfinite(elapsed) && elapsed >= 0.0))
    throw InvalidParameter("elapsed", text(elapsed), "must be finite and >= 0 (s)");
  const double v = sliding_velocity;
  FrictionEvaluation out;
  switch (p.law) {
    case FrictionLaw::none: return out;
    case FrictionLaw::coulomb:
      // sign(0) = 0: the set-valued law has no single value at rest; we return none.
      out.force = normal_force == 0.0 ? 0.0 : -p.kinetic_coefficient * normal_force * sign(v);
      return out;
    case FrictionLaw::ambrosio:
      out.force = normal_force == 0.0
                      ? 0.0
                      : -p.kinetic_coefficient * ambrosio_correction(p, v) * normal_force * sign(v);
      return out;
    case FrictionLaw::lugre_absolute:
    case FrictionLaw::lugre_normalised: return detail::lugre_kernel(p, normal_force, v, z_start, elapsed);
  }
  return out;  // unreachable: validate() rejects unknown laws
}

std::string_view to_string(FrictionLaw law) noexcept {
  for (const auto& [value, name] : kNames)
    if (value == law) return name;
  return "unknown";
}

std::optional<FrictionLaw> parse_friction_law(std::string_view name) noexcept {
  for (const auto& [value, known] : kNames)
    if (known == name) return value;
  return std::nullopt;
}

}  // namespace mechanism
