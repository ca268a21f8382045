#include "mechanism/slider_crank.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "law_kernels.hpp"
#include "mechanism/contact_law.hpp"
#include "mechanism/contact_stiffness.hpp"
#include "mechanism/error.hpp"
#include "mechanism/kinematic_jet.hpp"

namespace mechanism {

namespace {

template <int C>
struct BodyJets {
  BasicJetPoint<C> centre;
  BasicJet<C> angle;
  double mass;
  double inertia;
};

// Contact loads on one body, about its mass centre.
struct Load {
  double fx = 0.0, fy = 0.0, moment = 0.0;
  void add(double px, double py, double cx, double cy, double gx, double gy) {
    // Force (gx, gy) at point (px, py) on a body whose mass centre is (cx, cy).
    fx += gx;
    fy += gy;
    moment += (px - cx) * gy - (py - cy) * gx;
  }
};

}  // namespace

SliderCrank::SliderCrank(const Scene& scene) : scene_(scene) {
  const Scene& s = scene_;
  omega_ = s.driver.angular_speed();
  slider_clearance_ = s.slider_guide.kind == JointKind::clearance;
  const bool pin_clearance = s.conrod_slider.kind == JointKind::clearance;
  auto add = [&](const char* name) {
    names_.emplace_back(name);
    return n_++;
  };
  if (s.driver.free) idx_crank_angle_ = add("crank_angle");
  if (s.crank_ground.kind == JointKind::clearance) {
    idx_crank_pivot_ = add("crank_pivot_x");
    add("crank_pivot_y");
  }
  if (s.crank_conrod.kind == JointKind::clearance) {
    idx_conrod_pin_ = add("conrod_pin_x");
    add("conrod_pin_y");
  }
  // With the slider ideally pinned and ideally guided the conrod angle follows from the crank.
  if (pin_clearance || slider_clearance_) idx_conrod_angle_ = add("conrod_angle");
  if (pin_clearance) {
    idx_slider_x_ = add("slider_x");
    if (slider_clearance_) idx_slider_y_ = add("slider_y");
  }
  if (slider_clearance_ && s.slider_guide.rotation == SliderRotation::free) idx_slider_angle_ = add("slider_angle");

  if (slider_clearance_) {
    const TranslationalJoint& t = s.slider_guide;
    slider_compliance_ = material_compliance(s.slider.material.young_modulus, s.slider.material.poisson_ratio);
    guide_compliance_ = material_compliance(t.guide.young_modulus, t.guide.poisson_ratio);
    slider_flat_stiffness_ =
        t.stiffness_model == SliderStiffness::given
            ? t.stiffness
            : slider_face_stiffness(slider_compliance_, guide_compliance_, s.slider.length, s.slider.width, s.slider.length);
    if (t.model != SliderContactModel::corners) {  // face and line: one site per guide surface
      sites_.push_back({SiteKind::slider_face_upper, -1, -1});
      sites_.push_back({SiteKind::slider_face_lower, -1, -1});
    } else {
      for (int c = 0; c < 4; ++c) sites_.push_back({SiteKind::slider_corner, -1, c});
    }
  }
  const RevoluteJoint* joints[3] = {&s.crank_ground, &s.crank_conrod, &s.conrod_slider};
  const char* joint_names[3] = {"crank_ground", "crank_conrod", "conrod_slider"};
  for (int w = 0; w < 3; ++w) {
    const RevoluteJoint& j = *joints[w];
    if (j.kind != JointKind::clearance) continue;
    const double k =
        j.stiffness_model == JournalStiffness::given
            ? j.stiffness
            : journal_bearing_stiffness(material_compliance(j.bearing.young_modulus, j.bearing.poisson_ratio),
                                        material_compliance(j.journal.young_modulus, j.journal.poisson_ratio),
                                        j.bearing_radius, j.bearing_radius - j.clearance);
    sites_.push_back({SiteKind::journal, static_cast<int>(journals_.size()), -1});
    journals_.push_back({w, k});
    journal_names_.emplace_back(joint_names[w]);
  }
  // LuGre sites carry their bristle deflection in the state, after the work accumulators. The
  // laws are checked here once; the right-hand side then calls their unchecked kernels.
  for (Site& site : sites_) {
    const bool journal = site.kind == SiteKind::journal;
    const FrictionLawParameters& f = journal ? revolute(journals_[site.joint]).friction : s.slider_guide.friction;
    const ContactLawParameters& c = journal ? revolute(journals_[site.joint]).contact : s.slider_guide.contact;
    f.validate();
    c.validate();
    site.chi = hysteresis_factor(c.law, c.restitution);
    if (f.has_state()) site.state = 2 * n_ + 2 + bristles_++;
    // (With mu_k = 0 the law has no jump to locate.)
    site.holds_direction = f.law == FrictionLaw::coulomb && f.kinetic_coefficient > 0.0 &&
                           s.integrator.method == IntegratorMethod::rk4;
  }
  exponential_bristles_ = bristles_ > 0 && s.integrator.bristles == BristleUpdate::exponential;
  memory_.assign(sites_.size(), ContactMemory{});
  slider_sites_ = slider_clearance_ ? (scene_.slider_guide.model == SliderContactModel::corners ? 4 : 2) : 0;
  seed_topology_ = slider_clearance_ && idx_crank_angle_ < 0 && idx_crank_pivot_ < 0 && idx_conrod_pin_ < 0 &&
                  idx_slider_x_ < 0;
  // Jets need n coordinate columns and the crank's; the narrowest width that fits is cheapest.
  jet_columns_ = n_ + 1 <= 3 ? 3 : (n_ + 1 <= 5 ? 5 : max_jet_columns);
}

namespace {

// Friction at one site. LuGre (Canudas de Wit et al. 1995): z' = v - sigma0 |v| z / g(v), with g
// in newtons (absolute form) or as a coefficient (normalised form). `z` is the deflection in the
// state. Integrated (elapsed = NaN): z is the deflection now, and the relaxation rate
// k = sigma0 |v| / g is capped at 1 / floor, so z' = max-rate relaxation toward the steady
// deflection z_ss = g sign(v) / sigma0 when k floor > 1 (same fixed point, bounded stiffness).
// Exponential (elapsed: the time since the step's start, where z was written): the law's exact
// solution for this sliding speed, friction()'s own kernel, with no cap (BristleUpdate, scene.hpp).
// The other laws are stateless.
struct FrictionResult {
  double force = 0.0, z = 0.0, z_rate = 0.0;
};
// The velocity the friction law is given: the held direction where the site holds one (Coulomb's
// law on the RK4 grid, SliderCrank::holds_sliding_direction; the law reads only its sign), else v.
inline double law_velocity(bool holds_direction, const ContactMemory& memory, double v) {
  return holds_direction && memory.sliding_direction != 0 ? static_cast<double>(memory.sliding_direction) : v;
}
inline FrictionResult site_friction(const FrictionLawParameters& p, double floor, double normal, double v, double z,
                                    double elapsed) {
  if (!(normal > 0.0)) return {0.0, z, 0.0};
  if (p.law != FrictionLaw::lugre_absolute && p.law != FrictionLaw::lugre_normalised)
    return {friction(p, normal, v, 0.0, 0.0).force, 0.0, 0.0};
  if (!std::isnan(elapsed)) {
    const FrictionEvaluation e = detail::lugre_kernel(p, normal, v, z, elapsed);
    return {e.force, e.deflection, e.deflection_rate};
  }
  const bool absolute = p.law == FrictionLaw::lugre_absolute;
  const double g = detail::stribeck_kernel(p, v) * (absolute ? normal : 1.0);
  const double k = p.sigma0 * std::abs(v) / g;
  double z_rate;
  if (k * floor <= 1.0) {
    z_rate = v - k * z;
  } else {
    const double z_ss = (v > 0 ? g : -g) / p.sigma0;
    z_rate = (z_ss - z) / floor;
  }
  const double coefficient = p.sigma0 * z + p.bristle_damping(v) * z_rate + p.sigma2 * v;
  return {absolute ? -coefficient : -coefficient * normal, z, z_rate};
}

}  // namespace

State SliderCrank::initial_state() const {
  const Scene& s = scene_;
  const double l2 = s.crank.length, l3 = s.conrod.length;
  const double th2 = s.driver.initial_angle;
  const double th3 = std::asin(-l2 * std::sin(th2) / l3);
  const double th3_rate = -omega_ * l2 * std::cos(th2) / (l3 * std::cos(th3));
  State x = State::Zero(state_size());
  auto set = [&](int i, double value, double rate) {
    x[i] = value;
    x[n_ + i] = rate;
  };
  if (idx_crank_angle_ >= 0) set(idx_crank_angle_, th2, omega_);
  if (idx_crank_pivot_ >= 0) {
    set(idx_crank_pivot_, 0.0, 0.0);
    set(idx_crank_pivot_ + 1, 0.0, 0.0);
  }
  if (idx_conrod_pin_ >= 0) {
    set(idx_conrod_pin_, l2 * std::cos(th2), -l2 * omega_ * std::sin(th2));
    set(idx_conrod_pin_ + 1, l2 * std::sin(th2), l2 * omega_ * std::cos(th2));
  }
  if (idx_conrod_angle_ >= 0) set(idx_conrod_angle_, th3, th3_rate);
  if (idx_slider_x_ >= 0) {
    set(idx_slider_x_, l2 * std::cos(th2) + l3 * std::cos(th3),
        -l2 * omega_ * std::sin(th2) - l3 * th3_rate * std::sin(th3));
  }
  if (idx_slider_y_ >= 0) set(idx_slider_y_, 0.0, 0.0);
  if (idx_slider_angle_ >= 0) set(idx_slider_angle_, s.initial.slider_angle, s.initial.slider_rate);
  return x;
}

// Everything one evaluation produces, in fixed-size storage: evaluate() copies it into an
// Evaluation, rhs() into dxdt.
struct SliderCrank::Result {
  std::array<double, max_jet_columns> q_ddot;
  std::array<SiteEvaluation, max_sites> sites;
  std::array<std::array<double, 2>, 3> eccentricity;
  std::array<double, 3> slider_pose, slider_velocity, slider_acceleration;
  double crank_angle, conrod_angle, conrod_rate;
  double driving_torque, drive_power, contact_power, kinetic_energy, potential_energy;
  SliderConfiguration configuration;
  std::array<double, 4> corner_penetration;
  // Exponential bristle update: the time since the deflections in the state were written (the
  // step's start, SliderCrank::commit); NaN when the stepper integrates them (site_friction).
  double bristle_elapsed;
};

namespace {

// sin a and cos a for the angles that stay small: the slider's (a few milliradians: its corners are
// at most the clearance plus a penetration away from the guide) and the conrod's (within
// asin(l2 / l3) of level, 0.43 rad for the seed). For |a| <= 0.5 the Taylor series through a^15 and
// a^16 are accurate to an ulp (the first omitted terms, a^17/17! and a^18/18!, are under 1e-19
// relative; measured against long double over 1e7 angles: at most 0.61 ulp for sin and 0.68 for
// cos, and equal to libm's in 99 % and 97 %) and cost a fraction of libm's sincos; larger angles
// take libm.
inline void small_angle_sincos(double a, double& s, double& c) {
  if (!(std::fabs(a) <= 0.5)) {
    s = std::sin(a);
    c = std::cos(a);
    return;
  }
  const double a2 = a * a;
  s = a + a * a2 *
              (-1.0 / 6 +
               a2 * (1.0 / 120 +
                     a2 * (-1.0 / 5040 +
                           a2 * (1.0 / 362880 +
                                 a2 * (-1.0 / 39916800 + a2 * (1.0 / 6227020800.0 + a2 * (-1.0 / 1307674368000.0)))))));
  c = 1.0 +
      a2 * (-0.5 +
            a2 * (1.0 / 24 +
                  a2 * (-1.0 / 720 +
                        a2 * (1.0 / 40320 +
                              a2 * (-1.0 / 3628800 +
                                    a2 * (1.0 / 479001600.0 +
                                          a2 * (-1.0 / 87178291200.0 + a2 * (1.0 / 20922789888000.0))))))));
}

// Flores et al. 2008's configurations from the four corner penetrations (TL, TR, BL, BR).
SliderConfiguration configuration_of(const double pen[4]) {
  int count = 0;
  for (int c = 0; c < 4; ++c) count += pen[c] > 0.0;
  const bool tl = pen[0] > 0, tr = pen[1] > 0, bl = pen[2] > 0, br = pen[3] > 0;
  if (count == 0) return SliderConfiguration::free_flight;
  if (count == 1) return SliderConfiguration::one_corner;
  if (count == 2 && ((tl && tr) || (bl && br))) return SliderConfiguration::flat;
  if (count == 2 && ((tl && br) || (tr && bl))) return SliderConfiguration::jammed;
  return SliderConfiguration::other;
}

}  // namespace

void SliderCrank::slider_contacts(const double pose[3], const double rate[3], const State& x, Result& out,
                                  double load[3], double corner_pen[4]) const {
  const Scene& s = scene_;
  const TranslationalJoint& tj = s.slider_guide;
  const double px = pose[0], py = pose[1];
  // The slider angle's sine and cosine, shared by the four corners and the contact points.
  double ca, sa;
  small_angle_sincos(pose[2], sa, ca);
  // Slider corners: body-frame offsets TL, TR, BL, BR.
  const double hl = 0.5 * s.slider.length, hh = 0.5 * s.slider.height;
  const double corner_sx[4] = {-hl, hl, -hl, hl};
  const double corner_sy[4] = {hh, hh, -hh, -hh};
  double corner_rate[4];
  const double guide_half = hh + tj.clearance;
  for (int c = 0; c < 4; ++c) {
    const double ry = sa * corner_sx[c] + ca * corner_sy[c];
    const double rx = ca * corner_sx[c] - sa * corner_sy[c];
    const double vy = rate[1] + rate[2] * rx;
    const double y = py + ry;
    corner_pen[c] = c < 2 ? y - guide_half : -guide_half - y;
    corner_rate[c] = c < 2 ? vy : -vy;
  }

  for (std::size_t i = 0; i < slider_sites_; ++i) {
    const Site& site = sites_[i];
    SiteEvaluation& se = out.sites[i];
    se = SiteEvaluation{};
    const ContactMemory& mem = memory_[i];
    const bool upper = site.kind == SiteKind::slider_face_upper ||
                       (site.kind == SiteKind::slider_corner && site.corner < 2);
    double wx_body, depth, depth_rate;
    bool line_model = false;  // the line model's normal force is line_force (a NaN stays NaN)
    double line_force = 0.0;
    if (site.kind == SiteKind::slider_corner) {
      depth = corner_pen[site.corner];
      depth_rate = corner_rate[site.corner];
      wx_body = corner_sx[site.corner];
      se.stiffness = 0.5 * slider_flat_stiffness_;
      se.contact_length = 0.0;
    } else {
      const int a = upper ? 0 : 2, b = a + 1;  // left and right corner of this face
      const double da = corner_pen[a], db = corner_pen[b];
      const int deep = da >= db ? a : b;
      depth = corner_pen[deep];
      depth_rate = corner_rate[deep];
      if (depth > 0.0 && tj.model == SliderContactModel::line) {
        // The pressure along the face as two corner loads (line_contact.hpp), their resultant at
        // the load-weighted point of the face: the same force and moment about any point.
        se.contact_length = detail::contact_length_kernel(s.slider.length, da, db);
        se.stiffness = slider_flat_stiffness_;
        double fa, fb;
        detail::line_contact_kernel(se.stiffness, tj.contact.exponent, da, db, fa, fb);
        const double elastic = fa + fb;
        wx_body = elastic > 0.0 ? -hl + s.slider.length * (fb / elastic) : (da >= db ? -hl : hl);
        // Damping: the law's factor (1 + chi d_rate / v_impact), with the penetration rate of that
        // point (the loads' weighted corner rates). chi = 0 at e = 1: purely elastic.
        const double rate_w = elastic > 0.0 ? (fa * corner_rate[a] + fb * corner_rate[b]) / elastic : depth_rate;
        const double impact_w = mem.touching ? mem.impact_velocity : rate_w;
        line_model = true;
        line_force = elastic * detail::normal_force_kernel(site.chi, 1.0, tj.contact.velocity_floor, 1.0, 1.0, rate_w,
                                                           impact_w);
      } else if (depth > 0.0) {
        se.contact_length = detail::contact_length_kernel(s.slider.length, da, db);
        se.stiffness = tj.stiffness_model == SliderStiffness::contact_length
                           ? detail::slider_face_stiffness_kernel(slider_compliance_ + guide_compliance_,
                                                                  s.slider.length, s.slider.width, se.contact_length)
                           : slider_flat_stiffness_;
        // Centroid of the penetrated region along the face (a triangle, or a trapezoid when
        // both corners penetrate): the seed's point W.
        if (da > 0.0 && db > 0.0) {
          wx_body = -hl + s.slider.length * (da + 2.0 * db) / (3.0 * (da + db));
        } else if (da > 0.0) {
          wx_body = -hl + se.contact_length / 3.0;
        } else {
          wx_body = hl - se.contact_length / 3.0;
        }
      } else {
        wx_body = 0.0;
      }
    }
    se.penetration = depth;
    se.penetration_rate = depth_rate;
    if (depth <= 0.0) continue;
    const double wy_body = upper ? hh : -hh;
    const double rx = ca * wx_body - sa * wy_body, ry = sa * wx_body + ca * wy_body;
    const double wxw = px + rx, wyw = py + ry;
    // Velocity of the slider's material point at W.
    const double vx = rate[0] - rate[2] * (wyw - py);
    const double impact = mem.touching ? mem.impact_velocity : depth_rate;
    se.normal_force = line_model ? line_force
                                 : detail::normal_force_kernel(site.chi, tj.contact.exponent, tj.contact.velocity_floor,
                                                               se.stiffness, depth, depth_rate, impact);
    se.sliding_velocity = vx;
    const FrictionResult f = site_friction(tj.friction, tj.bristle_time_floor, se.normal_force,
                                           law_velocity(site.holds_direction, mem, vx),
                                           site.state >= 0 ? x[site.state] : 0.0, out.bristle_elapsed);
    se.friction_force = f.force;
    se.deflection = f.z;
    se.deflection_rate = f.z_rate;
    // Force (gx, gy) at W on the slider, and its moment about the slider's centre.
    const double gx = f.force, gy = upper ? -se.normal_force : se.normal_force;
    load[0] += gx;
    load[1] += gy;
    load[2] += (wxw - px) * gy - (wyw - py) * gx;
  }
}

// The seed's topology (only the slider-guide joint has clearance; q = (theta3, theta4), seed Eq. 27)
// in closed form: the same equations as the jets of compute<C, N>, whose Jacobians here are
//   crank centre  a2 (cos th2, sin th2)                      (no q column),
//   conrod centre l2 (cos th2, sin th2) + a3 (cos th3, sin th3)  (theta3 column a3 (-sin th3, cos th3)),
//   slider centre the same with l3,                          slider angle theta4,
// so M = diag(m3 a3^2 + I3 + m4 l3^2, I4) and each q_ddot is one division.
void SliderCrank::compute_seed(double t, const State& x, Result& out) const {
  const Scene& s = scene_;
  const double w2 = omega_, th2 = s.driver.initial_angle + w2 * t;
  // Coordinates: theta_3 and, unless the slider's rotation is locked (then level: 0), theta_4.
  const bool turns = idx_slider_angle_ >= 0;
  const double th3 = x[0], th4 = turns ? x[1] : 0.0, w3 = x[n_], w4 = turns ? x[n_ + 1] : 0.0;
  const double c2 = std::cos(th2), s2 = std::sin(th2);
  double c3, s3;
  small_angle_sincos(th3, s3, c3);
  const double l2 = s.crank.length, a2 = s.crank.mass_centre * l2;
  const double l3 = s.conrod.length, a3 = s.conrod.mass_centre * l3;
  const double m2 = s.crank.mass, m3 = s.conrod.mass, m4 = s.slider.mass;
  const double i2 = s.crank.inertia, i3 = s.conrod.inertia, i4 = s.slider.inertia;
  const double g = s.gravity;

  // Crank tip: position, velocity and acceleration (the crank turns at constant speed).
  const double tip_x = l2 * c2, tip_y = l2 * s2;
  const double tip_vx = -tip_y * w2, tip_vy = tip_x * w2;
  const double tip_ax = -tip_x * w2 * w2, tip_ay = -tip_y * w2 * w2;
  // Conrod centre and slider centre: value, velocity, and bias acceleration (q_ddot = 0).
  const double w3sq = w3 * w3;
  const double conrod_y = tip_y + a3 * s3;
  const double conrod_vx = tip_vx - a3 * s3 * w3, conrod_vy = tip_vy + a3 * c3 * w3;
  const double conrod_bx = tip_ax - a3 * c3 * w3sq, conrod_by = tip_ay - a3 * s3 * w3sq;
  const double slider_x = tip_x + l3 * c3, slider_y = tip_y + l3 * s3;
  const double slider_vx = tip_vx - l3 * s3 * w3, slider_vy = tip_vy + l3 * c3 * w3;
  const double slider_bx = tip_ax - l3 * c3 * w3sq, slider_by = tip_ay - l3 * s3 * w3sq;

  double load[3] = {0.0, 0.0, 0.0};  // contact force and moment on the slider
  double corner_pen[4];
  const double pose[3] = {slider_x, slider_y, th4};
  const double rate[3] = {slider_vx, slider_vy, w4};
  slider_contacts(pose, rate, x, out, load, corner_pen);

  // Generalised forces J^T (F - m b) and the diagonal mass matrix.
  const double fx3 = -m3 * conrod_bx, fy3 = -m3 * g - m3 * conrod_by;
  const double fx4 = load[0] - m4 * slider_bx, fy4 = load[1] - m4 * g - m4 * slider_by;
  const double q0 = a3 * (c3 * fy3 - s3 * fx3) + l3 * (c3 * fy4 - s3 * fx4);
  // A locked slider: the constraint takes the contact moment load[2] (and does no work, w4 = 0).
  const double qdd0 = q0 / (m3 * a3 * a3 + i3 + m4 * l3 * l3), qdd1 = turns ? load[2] / i4 : 0.0;
  out.q_ddot[0] = qdd0;
  if (turns) out.q_ddot[1] = qdd1;

  // Accelerations, then the driving torque J_theta2^T (m a - F) with J_theta2 = (-y, x, 1) of the
  // crank-fixed point each body hangs from.
  const double conrod_ax = conrod_bx - a3 * s3 * qdd0, conrod_ay = conrod_by + a3 * c3 * qdd0;
  const double slider_ax = slider_bx - l3 * s3 * qdd0, slider_ay = slider_by + l3 * c3 * qdd0;
  const double crank_x = a2 * c2, crank_y = a2 * s2;
  const double crank_ax = -crank_x * w2 * w2, crank_ay = -crank_y * w2 * w2;
  const double torque = -crank_y * m2 * crank_ax + crank_x * (m2 * crank_ay + m2 * g) +
                        -tip_y * (m3 * conrod_ax + m4 * slider_ax - load[0]) +
                        tip_x * (m3 * conrod_ay + m3 * g + m4 * slider_ay - load[1] + m4 * g);

  out.crank_angle = th2;
  out.conrod_angle = th3;
  out.conrod_rate = w3;
  out.driving_torque = torque;
  out.drive_power = torque * w2;
  out.contact_power = load[0] * slider_vx + load[1] * slider_vy + load[2] * w4;
  const double crank_vx = -crank_y * w2, crank_vy = crank_x * w2;
  out.kinetic_energy = 0.5 * m2 * (crank_vx * crank_vx + crank_vy * crank_vy) + 0.5 * i2 * w2 * w2 +
                       0.5 * m3 * (conrod_vx * conrod_vx + conrod_vy * conrod_vy) + 0.5 * i3 * w3 * w3 +
                       0.5 * m4 * (slider_vx * slider_vx + slider_vy * slider_vy) + 0.5 * i4 * w4 * w4;
  out.potential_energy = g * (m2 * crank_y + m3 * conrod_y + m4 * slider_y);
  out.slider_pose = {slider_x, slider_y, th4};
  out.slider_velocity = {slider_vx, slider_vy, w4};
  out.slider_acceleration = {slider_ax, slider_ay, qdd1};
  out.configuration = configuration_of(corner_pen);
  std::copy(corner_pen, corner_pen + 4, out.corner_penetration.begin());
}

template <int C, int N>
void SliderCrank::compute_jets(double t, const State& x, Result& out) const {
  using J = BasicJet<C>;
  using P = BasicJetPoint<C>;
  using R = BasicJetRotation<C>;
  const Scene& s = scene_;
  // N >= 0: the coordinate count known at compile time, so the loops over it unroll.
  const int n = N >= 0 ? N : n_;
  // Column n of every jet is the driven crank angle.
  auto coordinate = [&](int i) { return J::coordinate(i, x[i], x[n + i]); };
  const J zero = J::constant(0.0);
  // p + R (ox, 0): the same arithmetic as offset(p, r, ox, 0) without the zero term (x - 0 * s = x).
  auto along = [](const P& p, const R& r, double ox) { return P{p.x + ox * r.c, p.y + ox * r.s}; };

  // Poses as jets, from the ground up; one sincos per angle.
  // Column n of every jet is the driven crank angle; a free crank is coordinate idx_crank_angle_,
  // and column n then stays empty (nothing is prescribed: no driving torque).
  const J th2 = idx_crank_angle_ >= 0 ? coordinate(idx_crank_angle_)
                                      : J::coordinate(n, s.driver.initial_angle + omega_ * t, omega_);
  const R crank_rotation(th2);
  const P pivot = idx_crank_pivot_ >= 0 ? P{coordinate(idx_crank_pivot_), coordinate(idx_crank_pivot_ + 1)} : P{zero, zero};
  const P crank_tip = along(pivot, crank_rotation, s.crank.length);
  const P crank_centre = along(pivot, crank_rotation, s.crank.mass_centre * s.crank.length);
  const P conrod_pin = idx_conrod_pin_ >= 0 ? P{coordinate(idx_conrod_pin_), coordinate(idx_conrod_pin_ + 1)} : crank_tip;
  // Dependent conrod angle: the slider pin stays on the guide line y = 0.
  const J th3 = idx_conrod_angle_ >= 0 ? coordinate(idx_conrod_angle_) : asin((-1.0 / s.conrod.length) * conrod_pin.y);
  const R conrod_rotation(th3);
  const P conrod_end = along(conrod_pin, conrod_rotation, s.conrod.length);
  const P conrod_centre = along(conrod_pin, conrod_rotation, s.conrod.mass_centre * s.conrod.length);
  P slider = conrod_end;
  if (idx_slider_x_ >= 0) slider = {coordinate(idx_slider_x_), idx_slider_y_ >= 0 ? coordinate(idx_slider_y_) : zero};
  const J th4 = idx_slider_angle_ >= 0 ? coordinate(idx_slider_angle_) : zero;

  const BodyJets<C> bodies[3] = {{crank_centre, th2, s.crank.mass, s.crank.inertia},
                                 {conrod_centre, th3, s.conrod.mass, s.conrod.inertia},
                                 {slider, th4, s.slider.mass, s.slider.inertia}};
  Load loads[3];

  // Velocity of the material point at (px, py) of body b.
  auto point_velocity = [&](int b, double px, double py, double& vx, double& vy) {
    if (b < 0) {
      vx = vy = 0.0;  // the ground
      return;
    }
    const BodyJets<C>& body = bodies[b];
    const double w = body.angle.rate;
    vx = body.centre.x.rate - w * (py - body.centre.y.value);
    vy = body.centre.y.rate + w * (px - body.centre.x.value);
  };
  auto apply = [&](int b, double px, double py, double gx, double gy) {
    if (b < 0) return;
    loads[b].add(px, py, bodies[b].centre.x.value, bodies[b].centre.y.value, gx, gy);
  };

  double corner_pen[4] = {0, 0, 0, 0};
  if (slider_clearance_) {
    const double pose[3] = {slider.x.value, slider.y.value, th4.value};
    const double rate[3] = {slider.x.rate, slider.y.rate, th4.rate};
    double load[3] = {0.0, 0.0, 0.0};
    slider_contacts(pose, rate, x, out, load, corner_pen);
    loads[2].fx += load[0];
    loads[2].fy += load[1];
    loads[2].moment += load[2];
  }

  for (std::size_t i = slider_sites_; i < sites_.size(); ++i) {
    const Site& site = sites_[i];
    SiteEvaluation& se = out.sites[i];
    se = SiteEvaluation{};
    const ContactMemory& mem = memory_[i];
    const Journal& jr = journals_[site.joint];
    // Journal centre and bearing centre, and the bodies they belong to (-1: ground).
    const P* jc;
    const P* bc;
    const P ground{zero, zero};
    int jb, bb;
    switch (jr.which) {
      case 0: jc = &pivot; jb = 0; bc = &ground; bb = -1; break;
      case 1: jc = &crank_tip; jb = 0; bc = &conrod_pin; bb = 1; break;
      default: jc = &slider; jb = 2; bc = &conrod_end; bb = 1; break;
    }
    const double ex = jc->x.value - bc->x.value, ey = jc->y.value - bc->y.value;
    const double e = std::hypot(ex, ey);
    se.penetration = e - revolute(jr).clearance;
    if (!(se.penetration > 0.0)) {
      se.penetration_rate = e > 0.0 ? ((jc->x.rate - bc->x.rate) * ex + (jc->y.rate - bc->y.rate) * ey) / e : 0.0;
      continue;
    }
    const double nx = ex / e, ny = ey / e;
    se.penetration_rate = (jc->x.rate - bc->x.rate) * nx + (jc->y.rate - bc->y.rate) * ny;
    // The contact point on the bearing surface.
    const double qx = bc->x.value + revolute(jr).bearing_radius * nx, qy = bc->y.value + revolute(jr).bearing_radius * ny;
    double vjx, vjy, vbx, vby;
    point_velocity(jb, qx, qy, vjx, vjy);
    point_velocity(bb, qx, qy, vbx, vby);
    const double tx = -ny, ty = nx;
    const double vt = (vjx - vbx) * tx + (vjy - vby) * ty;
    se.stiffness = jr.stiffness;
    const double impact = mem.touching ? mem.impact_velocity : se.penetration_rate;
    se.normal_force = detail::normal_force_kernel(site.chi, revolute(jr).contact.exponent, revolute(jr).contact.velocity_floor,
                                                  jr.stiffness, se.penetration, se.penetration_rate, impact);
    se.sliding_velocity = vt;
    const FrictionResult f = site_friction(revolute(jr).friction, revolute(jr).bristle_time_floor, se.normal_force,
                                           law_velocity(site.holds_direction, mem, vt),
                                           site.state >= 0 ? x[site.state] : 0.0, out.bristle_elapsed);
    se.friction_force = f.force;
    se.deflection = f.z;
    se.deflection_rate = f.z_rate;
    // On the journal: pushed back toward the bearing centre, friction along the tangent.
    const double gx = -se.normal_force * nx + f.force * tx, gy = -se.normal_force * ny + f.force * ty;
    apply(jb, qx, qy, gx, gy);
    apply(bb, qx, qy, -gx, -gy);
  }

  // Equations of motion: M q_ddot = sum over bodies of J^T (F - m b), over the n free columns.
  double mass[max_jet_columns][max_jet_columns];
  double force[max_jet_columns];
  for (int i = 0; i < n; ++i) {
    force[i] = 0.0;
    for (int j = 0; j <= i; ++j) mass[i][j] = 0.0;
  }
  const double g = s.gravity;
  for (int b = 0; b < 3; ++b) {
    const BodyJets<C>& body = bodies[b];
    const auto& jx = body.centre.x.grad;
    const auto& jy = body.centre.y.grad;
    const auto& ja = body.angle.grad;
    const double fx = loads[b].fx - body.mass * body.centre.x.bias;
    const double fy = loads[b].fy - body.mass * g - body.mass * body.centre.y.bias;
    const double fa = loads[b].moment - body.inertia * body.angle.bias;
    for (int i = 0; i < n; ++i) {
      force[i] += fx * jx[i] + fy * jy[i] + fa * ja[i];
      for (int j = 0; j <= i; ++j) {
        mass[i][j] += body.mass * (jx[i] * jx[j] + jy[i] * jy[j]) + body.inertia * ja[i] * ja[j];
      }
    }
  }
  // Cholesky in place (M is symmetric positive definite: every coordinate moves some mass).
  // Written out because Eigen's general routine costs more than the whole force model at n = 2.
  double* qdd = out.q_ddot.data();
  for (int i = 0; i < n; ++i) qdd[i] = force[i];
  for (int j = 0; j < n; ++j) {
    double d = mass[j][j];
    for (int k = 0; k < j; ++k) d -= mass[j][k] * mass[j][k];
    d = std::sqrt(d);
    mass[j][j] = d;
    for (int i = j + 1; i < n; ++i) {
      double v = mass[i][j];
      for (int k = 0; k < j; ++k) v -= mass[i][k] * mass[j][k];
      mass[i][j] = v / d;
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < i; ++k) qdd[i] -= mass[i][k] * qdd[k];
    qdd[i] /= mass[i][i];
  }
  for (int i = n - 1; i >= 0; --i) {
    for (int k = i + 1; k < n; ++k) qdd[i] -= mass[k][i] * qdd[k];
    qdd[i] /= mass[i][i];
  }
  BasicJetRow<C> qdd_row = BasicJetRow<C>::Zero();
  for (int i = 0; i < n; ++i) qdd_row[i] = qdd[i];

  double torque = 0.0, contact_power = 0.0, kinetic = 0.0, potential = 0.0;
  for (int b = 0; b < 3; ++b) {
    const BodyJets<C>& body = bodies[b];
    const double ax = body.centre.x.grad.dot(qdd_row) + body.centre.x.bias;
    const double ay = body.centre.y.grad.dot(qdd_row) + body.centre.y.bias;
    const double aa = body.angle.grad.dot(qdd_row) + body.angle.bias;
    torque += body.centre.x.grad[n] * (body.mass * ax - loads[b].fx) +
              body.centre.y.grad[n] * (body.mass * ay - loads[b].fy + body.mass * g) +
              body.angle.grad[n] * (body.inertia * aa - loads[b].moment);
    contact_power += loads[b].fx * body.centre.x.rate + loads[b].fy * body.centre.y.rate +
                     loads[b].moment * body.angle.rate;
    kinetic += 0.5 * body.mass * (body.centre.x.rate * body.centre.x.rate + body.centre.y.rate * body.centre.y.rate) +
               0.5 * body.inertia * body.angle.rate * body.angle.rate;
    potential += body.mass * g * body.centre.y.value;
    if (b == 2) {
      out.slider_pose = {body.centre.x.value, body.centre.y.value, body.angle.value};
      out.slider_velocity = {body.centre.x.rate, body.centre.y.rate, body.angle.rate};
      out.slider_acceleration = {ax, ay, aa};
    }
  }
  out.crank_angle = th2.value;
  out.conrod_angle = th3.value;
  out.conrod_rate = th3.rate;
  out.driving_torque = torque;
  out.drive_power = idx_crank_angle_ >= 0 ? 0.0 : torque * omega_;
  out.contact_power = contact_power;
  out.kinetic_energy = kinetic;
  out.potential_energy = potential;

  out.configuration = slider_clearance_ ? configuration_of(corner_pen) : SliderConfiguration::free_flight;
  std::copy(corner_pen, corner_pen + 4, out.corner_penetration.begin());
  for (std::size_t j = 0; j < journals_.size(); ++j) {
    switch (journals_[j].which) {
      case 0: out.eccentricity[j] = {pivot.x.value, pivot.y.value}; break;
      case 1: out.eccentricity[j] = {crank_tip.x.value - conrod_pin.x.value, crank_tip.y.value - conrod_pin.y.value}; break;
      default: out.eccentricity[j] = {slider.x.value - conrod_end.x.value, slider.y.value - conrod_end.y.value}; break;
    }
  }
}

void SliderCrank::compute(double t, const State& x, Result& r, bool jets_only) const {
  r.bristle_elapsed = exponential_bristles_ ? t - bristle_epoch_ : std::numeric_limits<double>::quiet_NaN();
  if (seed_topology_ && !jets_only) {
    compute_seed(t, x, r);
    return;
  }
  if (n_ == 2) {
    compute_jets<3, 2>(t, x, r);
    return;
  }
  switch (jet_columns_) {
    case 3: compute_jets<3, -1>(t, x, r); break;
    case 5: compute_jets<5, -1>(t, x, r); break;
    default: compute_jets<max_jet_columns, -1>(t, x, r); break;
  }
}

namespace {
void copy_result(const auto& r, int n, std::size_t sites, std::size_t journals, Evaluation& out) {
  out.q_ddot.assign(r.q_ddot.begin(), r.q_ddot.begin() + n);
  out.crank_angle = r.crank_angle;
  out.slider_pose = r.slider_pose;
  out.slider_velocity = r.slider_velocity;
  out.slider_acceleration = r.slider_acceleration;
  out.conrod_angle = r.conrod_angle;
  out.conrod_rate = r.conrod_rate;
  out.driving_torque = r.driving_torque;
  out.drive_power = r.drive_power;
  out.contact_power = r.contact_power;
  out.kinetic_energy = r.kinetic_energy;
  out.potential_energy = r.potential_energy;
  out.sites.assign(r.sites.begin(), r.sites.begin() + static_cast<std::ptrdiff_t>(sites));
  out.configuration = r.configuration;
  out.corner_penetration = r.corner_penetration;
  out.eccentricity.assign(r.eccentricity.begin(), r.eccentricity.begin() + static_cast<std::ptrdiff_t>(journals));
}
}  // namespace

void SliderCrank::evaluate(double t, const State& x, Evaluation& out) const {
  Result r;
  compute(t, x, r);
  copy_result(r, n_, sites_.size(), journals_.size(), out);
}

void SliderCrank::evaluate_with_jets(double t, const State& x, Evaluation& out) const {
  Result r;
  compute(t, x, r, true);
  copy_result(r, n_, sites_.size(), journals_.size(), out);
}

void SliderCrank::rhs(double t, const State& x, State& dxdt) const {
  Result r;  // on the stack: no allocation, nothing shared between threads
  compute(t, x, r);
  derivatives_of(r, x, dxdt);
}

void SliderCrank::derivatives_of(const Result& r, const State& x, State& dxdt) const {
  const int n = n_;
  dxdt.resize(state_size());  // a no-op at the right size (the steppers pass it sized)
  for (int i = 0; i < n; ++i) {
    dxdt[i] = x[n + i];
    dxdt[n + i] = r.q_ddot[i];
  }
  dxdt[2 * n] = r.drive_power;
  dxdt[2 * n + 1] = r.contact_power;
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    if (sites_[i].state >= 0) dxdt[sites_[i].state] = exponential_bristles_ ? 0.0 : r.sites[i].deflection_rate;
  }
}

void SliderCrank::error_weights(double t, const State& x, State& weights) const {
  weights.setOnes(x.size());
  if (bristles_ == 0) return;
  Result r;
  compute(t, x, r);
  weights_of(r, weights);
}

void SliderCrank::weights_of(const Result& r, State& weights) const {
  for (std::size_t i = 0; i < sites_.size(); ++i)
    if (sites_[i].state >= 0 && !(r.sites[i].penetration > 0.0)) weights[sites_[i].state] = 0.0;
}

void SliderCrank::rhs_and_error_weights(double t, const State& x, State& dxdt, State& weights) const {
  Result r;
  compute(t, x, r);
  derivatives_of(r, x, dxdt);
  weights.setOnes(x.size());
  if (bristles_ > 0) weights_of(r, weights);
}

void SliderCrank::rhs_and_error_weights(double t, const State& x, State& dxdt, State& weights,
                                        Evaluation& out) const {
  Result r;
  compute(t, x, r);
  derivatives_of(r, x, dxdt);
  weights.setOnes(x.size());
  if (bristles_ > 0) weights_of(r, weights);
  copy_result(r, n_, sites_.size(), journals_.size(), out);
}

void SliderCrank::set_memory(const std::vector<ContactMemory>& memory) {
  if (memory.size() != memory_.size())
    throw InvalidParameter("memory", std::to_string(memory.size()) + " sites",
                           "must have one entry per contact site (" + std::to_string(memory_.size()) + ")");
  memory_ = memory;
}

void SliderCrank::switching_functions(const Evaluation& ev, std::vector<double>& g) const {
  g.clear();
  if (slider_clearance_) g.insert(g.end(), ev.corner_penetration.begin(), ev.corner_penetration.end());
  for (std::size_t i = slider_sites_; i < sites_.size(); ++i) g.push_back(ev.sites[i].penetration);
}

bool SliderCrank::commit(double t, const Evaluation& at_end, const std::vector<double>& onset_rate, State& x) {
  bool latched = false;
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    ContactMemory& m = memory_[i];
    const SiteEvaluation& se = at_end.sites[i];
    if (se.penetration > 0.0) {
      // The exponential update's deflection at the step's end becomes the next step's start.
      if (exponential_bristles_ && sites_[i].state >= 0 && x[sites_[i].state] != se.deflection) {
        x[sites_[i].state] = se.deflection;
        latched = true;
      }
      // Coulomb on the RK4 grid: the direction the next steps hold, where none is held yet.
      if (sites_[i].holds_direction && m.sliding_direction == 0 && se.sliding_velocity != 0.0)
        m.sliding_direction = se.sliding_velocity > 0.0 ? 1 : -1;
      if (!m.touching) {
        m.touching = true;
        const double at_onset = i < onset_rate.size() ? onset_rate[i] : std::numeric_limits<double>::quiet_NaN();
        m.impact_velocity = std::isfinite(at_onset) ? at_onset : se.penetration_rate;
        latched = true;
      }
    } else {
      m = ContactMemory{};  // released: the next impact latches anew
      if (sites_[i].state >= 0 && x[sites_[i].state] != 0.0) {
        x[sites_[i].state] = 0.0;  // and the bristles unload
        latched = true;
      }
    }
  }
  bristle_epoch_ = t;
  return latched;
}

}  // namespace mechanism
