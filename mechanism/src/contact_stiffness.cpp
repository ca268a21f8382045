#include "mechanism/contact_stiffness.hpp"

#include <array>
#include <cmath>
#include <string>

#include "checks.hpp"
#include "mechanism/error.hpp"

namespace mechanism {

using detail::require_positive;
using detail::text;

double material_compliance(double young_modulus, double poisson_ratio) {
  require_positive("young_modulus", young_modulus);
  if (!(poisson_ratio >= 0.0 && poisson_ratio < 0.5))
    throw InvalidParameter("poisson_ratio", text(poisson_ratio), "must be in [0, 0.5)");
  return (1.0 - poisson_ratio * poisson_ratio) / young_modulus;
}

double journal_bearing_stiffness(double sigma_bearing, double sigma_journal, double bearing_radius,
                                 double journal_radius) {
  require_positive("sigma_bearing", sigma_bearing);
  require_positive("sigma_journal", sigma_journal);
  require_positive("journal_radius", journal_radius);
  require_positive("bearing_radius", bearing_radius);
  if (!(bearing_radius > journal_radius))
    throw InvalidParameter("bearing_radius", text(bearing_radius),
                           "must be > journal_radius = " + text(journal_radius));
  const double clearance = bearing_radius - journal_radius;
  return (4.0 / 3.0) / (sigma_bearing + sigma_journal) *
         std::sqrt(bearing_radius * journal_radius / clearance);
}

double contact_length(double slider_length, double penetration_a, double penetration_b) {
  require_positive("slider_length", slider_length);
  const double a = penetration_a, b = penetration_b;
  if (std::isnan(a) || std::isnan(b)) return std::nan("");
  if (a > 0.0 && b > 0.0) return slider_length;
  if (a <= 0.0 && b <= 0.0) return 0.0;
  // Exactly one is > 0, so |a - b| >= max(a, b) > 0 (also after rounding): the ratio is in (0, 1].
  return slider_length * (std::fmax(a, b) / std::fabs(a - b));
}

double slider_face_stiffness(double sigma_slider, double sigma_guide, double slider_length,
                             double slider_width, double contact_length) {
  require_positive("sigma_slider", sigma_slider);
  require_positive("sigma_guide", sigma_guide);
  require_positive("slider_length", slider_length);
  require_positive("slider_width", slider_width);
  if (!(contact_length >= 0.0 && contact_length <= slider_length))
    throw InvalidParameter("contact_length", text(contact_length),
                           "must be in [0, slider_length = " + text(slider_length) + "]");
  if (contact_length == 0.0) return 0.0;
  const double area = contact_length * slider_width;  // S = L_c W (our reading of the seed)
  // 11.15 (L_s/L_c + 15.72)^-1 written as 11.15 L_c / (L_s + 15.72 L_c): no overflow of L_s/L_c
  // for a tiny L_c.
  const double shape = 11.15 * contact_length / (slider_length + 15.72 * contact_length) + 0.2854;
  return std::sqrt(area) / (sigma_slider + sigma_guide) / shape;
}

}  // namespace mechanism
