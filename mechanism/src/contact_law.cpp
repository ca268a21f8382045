#include "mechanism/contact_law.hpp"

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "checks.hpp"
#include "law_kernels.hpp"
#include "mechanism/error.hpp"

namespace mechanism {

using detail::text;

namespace {

constexpr std::array<std::pair<NormalContactLaw, std::string_view>, 7> kNames{{
    {NormalContactLaw::hertz, "hertz"},
    {NormalContactLaw::hunt_crossley, "hunt_crossley"},
    {NormalContactLaw::lankarani_nikravesh, "lankarani_nikravesh"},
    {NormalContactLaw::flores, "flores"},
    {NormalContactLaw::hu_guo, "hu_guo"},
    {NormalContactLaw::gonthier, "gonthier"},
    {NormalContactLaw::exact_restitution, "exact_restitution"},
}};

void check_restitution(double e) {
  // Written so that NaN fails too.
  if (!(e > 0.0 && e <= 1.0)) throw InvalidParameter("restitution", text(e), "must be in (0, 1]");
}

}  // namespace

void ContactLawParameters::validate() const {
  check_restitution(restitution);
  if (!(std::isfinite(exponent) && exponent > 0.0))
    throw InvalidParameter("exponent", text(exponent), "must be finite and > 0");
  if (!(std::isfinite(velocity_floor) && velocity_floor > 0.0))
    throw InvalidParameter("velocity_floor", text(velocity_floor), "must be finite and > 0 (m/s)");
}

double hysteresis_factor(NormalContactLaw law, double restitution) {
  check_restitution(restitution);
  const double e = restitution;
  switch (law) {
    case NormalContactLaw::hertz: return 0.0;
    case NormalContactLaw::hunt_crossley: return 1.5 * (1.0 - e);
    case NormalContactLaw::lankarani_nikravesh: return 0.75 * (1.0 - e * e);
    case NormalContactLaw::flores: return 8.0 * (1.0 - e) / (5.0 * e);
    case NormalContactLaw::hu_guo: return 3.0 * (1.0 - e) / (2.0 * e);
    case NormalContactLaw::gonthier: return (1.0 - e * e) / e;
    case NormalContactLaw::exact_restitution: return exact_hysteresis_factor(e);
  }
  throw InvalidParameter("law", std::to_string(static_cast<int>(law)), "unknown NormalContactLaw");
}

double exact_hysteresis_factor(double restitution) {
  check_restitution(restitution);
  const double e = restitution;
  if (e == 1.0) return 0.0;
  // f(chi) = chi - ln(1 + chi) + chi e + ln(1 - chi e): f' = chi (1 / (1 + chi) - e^2 / (1 - chi e))
  // vanishes at (1 - e) / e, where f is at its maximum (> 0); f -> -inf at 1 / e.
  auto f = [e](double chi) { return chi - std::log1p(chi) + chi * e + std::log1p(-chi * e); };
  double lo = (1.0 - e) / e, hi = 1.0 / e;
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  return lo;
}

double normal_force(const ContactLawParameters& p, double stiffness, double penetration,
                    double penetration_rate, double impact_velocity) {
  p.validate();
  if (!(std::isfinite(stiffness) && stiffness >= 0.0))
    throw InvalidParameter("stiffness", text(stiffness), "must be finite and >= 0");
  if (penetration <= 0.0) return 0.0;  // NaN goes on and comes out as NaN
  return detail::normal_force_kernel(hysteresis_factor(p.law, p.restitution), p.exponent, p.velocity_floor, stiffness,
                                     penetration, penetration_rate, impact_velocity);
}

std::string_view to_string(NormalContactLaw law) noexcept {
  for (const auto& [value, name] : kNames)
    if (value == law) return name;
  return "unknown";
}

std::optional<NormalContactLaw> parse_normal_contact_law(std::string_view name) noexcept {
  for (const auto& [value, known] : kNames)
    if (known == name) return value;
  return std::nullopt;
}

}  // namespace mechanism
