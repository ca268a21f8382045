#include "mechanism/signals.hpp"

#include <algorithm>

namespace mechanism {

namespace {
bool has_slider_clearance(const SliderCrank& s) { return s.scene().slider_guide.kind == JointKind::clearance; }
}  // namespace

SignalTable signal_table(const SliderCrank& system) {
  SignalTable t;
  auto add = [&](std::string name, std::string unit) {
    t.names.push_back(std::move(name));
    t.units.push_back(std::move(unit));
  };
  add("t", "s");
  add("crank_angle", "rad");
  add("slider_x", "m");
  add("slider_y", "m");
  add("slider_angle", "rad");
  add("slider_vx", "m/s");
  add("slider_vy", "m/s");
  add("slider_omega", "rad/s");
  add("conrod_angle", "rad");
  add("driving_torque", "N m");
  add("energy", "J");
  add("work_drive", "J");
  add("work_contact", "J");
  if (has_slider_clearance(system)) {
    add("slider_mode", "-");
    add("slider_penetration", "m");
    add("slider_normal_upper", "N");
    add("slider_normal_lower", "N");
    add("slider_friction", "N");
  }
  for (const auto& j : system.journal_names()) {
    add(j + "_ecc_x", "m");
    add(j + "_ecc_y", "m");
    add(j + "_penetration", "m");
    add(j + "_normal", "N");
    add(j + "_friction", "N");
  }
  return t;
}

void signal_values(const SliderCrank& system, double t, const State& x, const Evaluation& ev,
                   std::vector<double>& out) {
  out.clear();
  const int n = system.coordinate_count();
  out.push_back(t);
  out.push_back(ev.crank_angle);
  out.insert(out.end(), ev.slider_pose.begin(), ev.slider_pose.end());
  out.insert(out.end(), ev.slider_velocity.begin(), ev.slider_velocity.end());
  out.push_back(ev.conrod_angle);
  out.push_back(ev.driving_torque);
  out.push_back(ev.kinetic_energy + ev.potential_energy);
  out.push_back(x[2 * n]);
  out.push_back(x[2 * n + 1]);
  std::size_t journal = 0;
  double deepest = -1e300, upper = 0, lower = 0, friction = 0;
  bool slider_sites = false;
  for (std::size_t i = 0; i < system.site_count(); ++i) {
    const SiteEvaluation& s = ev.sites[i];
    switch (system.site_kind(i)) {
      case SiteKind::slider_face_upper:
        upper += s.normal_force;
        break;
      case SiteKind::slider_face_lower:
        lower += s.normal_force;
        break;
      case SiteKind::slider_corner:
        (static_cast<int>(i) < 2 ? upper : lower) += s.normal_force;
        break;
      case SiteKind::journal:
        continue;
    }
    slider_sites = true;
    deepest = std::max(deepest, s.penetration);
    friction += s.friction_force;
  }
  if (slider_sites) {
    out.push_back(static_cast<double>(ev.configuration));
    out.push_back(deepest);
    out.push_back(upper);
    out.push_back(lower);
    out.push_back(friction);
  }
  for (std::size_t i = 0; i < system.site_count(); ++i) {
    if (system.site_kind(i) != SiteKind::journal) continue;
    const SiteEvaluation& s = ev.sites[i];
    out.push_back(ev.eccentricity[journal][0]);
    out.push_back(ev.eccentricity[journal][1]);
    out.push_back(s.penetration);
    out.push_back(s.normal_force);
    out.push_back(s.friction_force);
    ++journal;
  }
}

}  // namespace mechanism
