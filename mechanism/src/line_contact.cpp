#include "mechanism/line_contact.hpp"

#include <cmath>

#include "checks.hpp"
#include "law_kernels.hpp"
#include "mechanism/error.hpp"

namespace mechanism {

namespace {
void check(double stiffness, double exponent) {
  if (!(stiffness >= 0.0 && std::isfinite(stiffness)))
    throw InvalidParameter("stiffness", detail::text(stiffness), "must be a finite number >= 0");
  if (!(exponent > 0.0 && std::isfinite(exponent)))
    throw InvalidParameter("exponent", detail::text(exponent), "must be a finite number > 0");
}
}  // namespace

LineContactLoads line_contact_loads(double stiffness, double exponent, double penetration_a, double penetration_b) {
  check(stiffness, exponent);
  LineContactLoads loads;
  detail::line_contact_kernel(stiffness, exponent, penetration_a, penetration_b, loads.left, loads.right);
  return loads;
}

double line_contact_energy(double stiffness, double exponent, double penetration_a, double penetration_b) {
  check(stiffness, exponent);
  double i0, i1;
  detail::linear_power_moments(exponent + 1.0, penetration_a, penetration_b, i0, i1);
  return stiffness * i0 / (exponent + 1.0);
}

}  // namespace mechanism
