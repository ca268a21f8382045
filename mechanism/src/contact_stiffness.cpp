#include "mechanism/contact_stiffness.hpp"

#include <array>
#include <cmath>
#include <string>

#include "checks.hpp"
#include "law_kernels.hpp"
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
  return detail::contact_length_kernel(slider_length, penetration_a, penetration_b);
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
  return detail::slider_face_stiffness_kernel(sigma_slider + sigma_guide, slider_length, slider_width, contact_length);
}

}  // namespace mechanism
