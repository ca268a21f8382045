#include "mechanism/slider_crank.hpp"

#include <cmath>
#include <limits>


#include "mechanism/contact_stiffness.hpp"
#include "mechanism/kinematic_jet.hpp"

namespace mechanism {

namespace {

struct BodyJets {
  JetPoint centre;
  Jet angle;
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
  if (slider_clearance_) idx_slider_angle_ = add("slider_angle");

  if (slider_clearance_) {
    const TranslationalJoint& t = s.slider_guide;
    slider_compliance_ = material_compliance(s.slider.material.young_modulus, s.slider.material.poisson_ratio);
    guide_compliance_ = material_compliance(t.guide.young_modulus, t.guide.poisson_ratio);
    slider_flat_stiffness_ =
        t.stiffness_model == SliderStiffness::given
            ? t.stiffness
            : slider_face_stiffness(slider_compliance_, guide_compliance_, s.slider.length, s.slider.width, s.slider.length);
    if (t.model == SliderContactModel::face) {
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
    journals_.push_back({&j, w, k});
    journal_names_.emplace_back(joint_names[w]);
  }
  // LuGre sites carry their bristle deflection in the state, after the work accumulators.
  for (Site& site : sites_) {
    const FrictionLawParameters& f =
        site.kind == SiteKind::journal ? journals_[site.joint].joint->friction : s.slider_guide.friction;
    if (f.has_state()) site.state = 2 * n_ + 2 + bristles_++;
  }
  memory_.assign(sites_.size(), ContactMemory{});
}

namespace {

// Friction at one site. LuGre (Canudas de Wit et al. 1995): z' = v - sigma0 |v| z / g(v), with g
// in newtons (absolute form) or as a coefficient (normalised form); the relaxation rate
// k = sigma0 |v| / g is capped at 1 / floor, so z' = max-rate relaxation toward the steady
// deflection z_ss = g sign(v) / sigma0 when k floor > 1 (same fixed point, bounded stiffness).
// The other laws are stateless.
struct FrictionResult {
  double force = 0.0, z_rate = 0.0;
};
FrictionResult site_friction(const FrictionLawParameters& p, double floor, double normal, double v, double z) {
  if (!(normal > 0.0)) return {};
  if (!p.has_state()) return {friction(p, normal, v, 0.0, 0.0).force, 0.0};
  const bool absolute = p.law == FrictionLaw::lugre_absolute;
  const double g = stribeck_coefficient(p, v) * (absolute ? normal : 1.0);
  const double k = p.sigma0 * std::abs(v) / g;
  double z_rate;
  if (k * floor <= 1.0) {
    z_rate = v - k * z;
  } else {
    const double z_ss = (v > 0 ? g : -g) / p.sigma0;
    z_rate = (z_ss - z) / floor;
  }
  const double coefficient = p.sigma0 * z + p.bristle_damping(v) * z_rate + p.sigma2 * v;
  return {absolute ? -coefficient : -coefficient * normal, z_rate};
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
  if (idx_slider_angle_ >= 0) set(idx_slider_angle_, 0.0, 0.0);
  return x;
}

void SliderCrank::evaluate(double t, const State& x, Evaluation& out) const {
  const Scene& s = scene_;
  const int n = n_;
  // Column n of every jet is the driven crank angle.
  auto coordinate = [&](int i) { return Jet::coordinate(i, x[i], x[n + i]); };
  const Jet zero = Jet::constant(0.0);

  // Poses as jets, from the ground up.
  Jet th2 = Jet::coordinate(n, s.driver.initial_angle + omega_ * t, omega_);
  const JetRotation crank_rotation(th2);
  const JetPoint pivot = idx_crank_pivot_ >= 0 ? JetPoint{coordinate(idx_crank_pivot_), coordinate(idx_crank_pivot_ + 1)}
                                               : JetPoint{zero, zero};
  const JetPoint crank_tip = offset(pivot, crank_rotation, s.crank.length, 0.0);
  const JetPoint crank_centre = offset(pivot, crank_rotation, s.crank.mass_centre * s.crank.length, 0.0);
  const JetPoint conrod_pin =
      idx_conrod_pin_ >= 0 ? JetPoint{coordinate(idx_conrod_pin_), coordinate(idx_conrod_pin_ + 1)} : crank_tip;
  // Dependent conrod angle: the slider pin stays on the guide line y = 0.
  const Jet th3 = idx_conrod_angle_ >= 0 ? coordinate(idx_conrod_angle_) : asin((-1.0 / s.conrod.length) * conrod_pin.y);
  const JetRotation conrod_rotation(th3);
  const JetPoint conrod_end = offset(conrod_pin, conrod_rotation, s.conrod.length, 0.0);
  const JetPoint conrod_centre = offset(conrod_pin, conrod_rotation, s.conrod.mass_centre * s.conrod.length, 0.0);
  JetPoint slider = conrod_end;
  if (idx_slider_x_ >= 0) slider = {coordinate(idx_slider_x_), idx_slider_y_ >= 0 ? coordinate(idx_slider_y_) : zero};
  const Jet th4 = idx_slider_angle_ >= 0 ? coordinate(idx_slider_angle_) : zero;

  const BodyJets bodies[3] = {{crank_centre, th2, s.crank.mass, s.crank.inertia},
                              {conrod_centre, th3, s.conrod.mass, s.conrod.inertia},
                              {slider, th4, s.slider.mass, s.slider.inertia}};
  Load loads[3];

  // Velocity of the material point at (px, py) of body b.
  auto point_velocity = [&](int b, double px, double py, double& vx, double& vy) {
    if (b < 0) {
      vx = vy = 0.0;  // the ground
      return;
    }
    const BodyJets& body = bodies[b];
    const double w = body.angle.rate;
    vx = body.centre.x.rate - w * (py - body.centre.y.value);
    vy = body.centre.y.rate + w * (px - body.centre.x.value);
  };
  auto apply = [&](int b, double px, double py, double gx, double gy) {
    if (b < 0) return;
    loads[b].add(px, py, bodies[b].centre.x.value, bodies[b].centre.y.value, gx, gy);
  };

  out.sites.resize(sites_.size());

  // Slider corners: body-frame offsets TL, TR, BL, BR.
  const double hl = 0.5 * s.slider.length, hh = 0.5 * s.slider.height;
  const double corner_sx[4] = {-hl, hl, -hl, hl};
  const double corner_sy[4] = {hh, hh, -hh, -hh};
  double corner_pen[4] = {0, 0, 0, 0}, corner_rate[4] = {0, 0, 0, 0};
  const double px = slider.x.value, py = slider.y.value, pa = th4.value;
  const double ca = std::cos(pa), sa = std::sin(pa);
  const double guide_half = hh + s.slider_guide.clearance;
  if (slider_clearance_) {
    for (int c = 0; c < 4; ++c) {
      const double ry = sa * corner_sx[c] + ca * corner_sy[c];
      const double rx = ca * corner_sx[c] - sa * corner_sy[c];
      const double vy = slider.y.rate + th4.rate * rx;
      const double y = py + ry;
      corner_pen[c] = c < 2 ? y - guide_half : -guide_half - y;
      corner_rate[c] = c < 2 ? vy : -vy;
    }
  }

  for (std::size_t i = 0; i < sites_.size(); ++i) {
    const Site& site = sites_[i];
    SiteEvaluation& se = out.sites[i];
    se = SiteEvaluation{};
    const ContactMemory& mem = memory_[i];
    if (site.kind == SiteKind::slider_face_upper || site.kind == SiteKind::slider_face_lower ||
        site.kind == SiteKind::slider_corner) {
      const TranslationalJoint& tj = s.slider_guide;
      const bool upper = site.kind == SiteKind::slider_face_upper ||
                         (site.kind == SiteKind::slider_corner && site.corner < 2);
      double wx_body, depth, depth_rate;
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
        if (depth > 0.0) {
          se.contact_length = contact_length(s.slider.length, da, db);
          se.stiffness = tj.stiffness_model == SliderStiffness::contact_length
                             ? slider_face_stiffness(slider_compliance_, guide_compliance_, s.slider.length,
                                                     s.slider.width, se.contact_length)
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
      double vx, vy;
      point_velocity(2, wxw, wyw, vx, vy);
      const double impact = mem.touching ? mem.impact_velocity : depth_rate;
      se.normal_force = normal_force(tj.contact, se.stiffness, depth, depth_rate, impact);
      se.sliding_velocity = vx;
      se.deflection = site.state >= 0 ? x[site.state] : 0.0;
      const FrictionResult f = site_friction(tj.friction, tj.bristle_time_floor, se.normal_force, vx, se.deflection);
      se.friction_force = f.force;
      se.deflection_rate = f.z_rate;
      apply(2, wxw, wyw, f.force, upper ? -se.normal_force : se.normal_force);
    } else {
      const Journal& jr = journals_[site.joint];
      // Journal centre and bearing centre, and the bodies they belong to (-1: ground).
      JetPoint jc, bc;
      int jb, bb;
      switch (jr.which) {
        case 0: jc = pivot; jb = 0; bc = {zero, zero}; bb = -1; break;
        case 1: jc = crank_tip; jb = 0; bc = conrod_pin; bb = 1; break;
        default: jc = slider; jb = 2; bc = conrod_end; bb = 1; break;
      }
      const double ex = jc.x.value - bc.x.value, ey = jc.y.value - bc.y.value;
      const double e = std::hypot(ex, ey);
      se.penetration = e - jr.joint->clearance;
      if (!(se.penetration > 0.0)) {
        se.penetration_rate = e > 0.0 ? ((jc.x.rate - bc.x.rate) * ex + (jc.y.rate - bc.y.rate) * ey) / e : 0.0;
        continue;
      }
      const double nx = ex / e, ny = ey / e;
      se.penetration_rate = (jc.x.rate - bc.x.rate) * nx + (jc.y.rate - bc.y.rate) * ny;
      // The contact point on the bearing surface.
      const double qx = bc.x.value + jr.joint->bearing_radius * nx, qy = bc.y.value + jr.joint->bearing_radius * ny;
      double vjx, vjy, vbx, vby;
      point_velocity(jb, qx, qy, vjx, vjy);
      point_velocity(bb, qx, qy, vbx, vby);
      const double tx = -ny, ty = nx;
      const double vt = (vjx - vbx) * tx + (vjy - vby) * ty;
      se.stiffness = jr.stiffness;
      const double impact = mem.touching ? mem.impact_velocity : se.penetration_rate;
      se.normal_force = normal_force(jr.joint->contact, jr.stiffness, se.penetration, se.penetration_rate, impact);
      se.sliding_velocity = vt;
      se.deflection = site.state >= 0 ? x[site.state] : 0.0;
      const FrictionResult f =
          site_friction(jr.joint->friction, jr.joint->bristle_time_floor, se.normal_force, vt, se.deflection);
      se.friction_force = f.force;
      se.deflection_rate = f.z_rate;
      // On the journal: pushed back toward the bearing centre, friction along the tangent.
      const double gx = -se.normal_force * nx + f.force * tx, gy = -se.normal_force * ny + f.force * ty;
      apply(jb, qx, qy, gx, gy);
      apply(bb, qx, qy, -gx, -gy);
    }
  }

  // Equations of motion: M q_ddot = sum over bodies of J^T (F - m b), over the n free columns.
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, max_jet_columns, max_jet_columns>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, max_jet_columns, 1>;
  Matrix mass = Matrix::Zero(n, n);
  Vector force = Vector::Zero(n);
  const double g = s.gravity;
  for (int b = 0; b < 3; ++b) {
    const BodyJets& body = bodies[b];
    const JetRow& jx = body.centre.x.grad;
    const JetRow& jy = body.centre.y.grad;
    const JetRow& ja = body.angle.grad;
    const double fx = loads[b].fx - body.mass * body.centre.x.bias;
    const double fy = loads[b].fy - body.mass * g - body.mass * body.centre.y.bias;
    const double fa = loads[b].moment - body.inertia * body.angle.bias;
    for (int i = 0; i < n; ++i) {
      force[i] += fx * jx[i] + fy * jy[i] + fa * ja[i];
      for (int j = 0; j <= i; ++j) {
        mass(i, j) += body.mass * (jx[i] * jx[j] + jy[i] * jy[j]) + body.inertia * ja[i] * ja[j];
      }
    }
  }
  // Cholesky in place (M is symmetric positive definite: every coordinate moves some mass).
  // Written out because Eigen's general routine costs more than the whole force model at n = 2.
  Vector qdd = force;
  for (int j = 0; j < n; ++j) {
    double d = mass(j, j);
    for (int k = 0; k < j; ++k) d -= mass(j, k) * mass(j, k);
    d = std::sqrt(d);
    mass(j, j) = d;
    for (int i = j + 1; i < n; ++i) {
      double v = mass(i, j);
      for (int k = 0; k < j; ++k) v -= mass(i, k) * mass(j, k);
      mass(i, j) = v / d;
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < i; ++k) qdd[i] -= mass(i, k) * qdd[k];
    qdd[i] /= mass(i, i);
  }
  for (int i = n - 1; i >= 0; --i) {
    for (int k = i + 1; k < n; ++k) qdd[i] -= mass(k, i) * qdd[k];
    qdd[i] /= mass(i, i);
  }
  out.q_ddot.assign(qdd.data(), qdd.data() + n);
  JetRow qdd_row = JetRow::Zero();
  for (int i = 0; i < n; ++i) qdd_row[i] = qdd[i];

  double torque = 0.0, contact_power = 0.0, kinetic = 0.0, potential = 0.0;
  for (int b = 0; b < 3; ++b) {
    const BodyJets& body = bodies[b];
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
  out.drive_power = torque * omega_;
  out.contact_power = contact_power;
  out.kinetic_energy = kinetic;
  out.potential_energy = potential;

  if (slider_clearance_) {
    int count = 0;
    for (double p : corner_pen) count += p > 0.0;
    const bool tl = corner_pen[0] > 0, tr = corner_pen[1] > 0, bl = corner_pen[2] > 0, br = corner_pen[3] > 0;
    if (count == 0) {
      out.configuration = SliderConfiguration::free_flight;
    } else if (count == 1) {
      out.configuration = SliderConfiguration::one_corner;
    } else if (count == 2 && ((tl && tr) || (bl && br))) {
      out.configuration = SliderConfiguration::flat;
    } else if (count == 2 && ((tl && br) || (tr && bl))) {
      out.configuration = SliderConfiguration::jammed;
    } else {
      out.configuration = SliderConfiguration::other;
    }
  }
  out.eccentricity.resize(journals_.size());
  for (std::size_t j = 0; j < journals_.size(); ++j) {
    JetPoint jc, bc;
    switch (journals_[j].which) {
      case 0: jc = pivot; bc = {zero, zero}; break;
      case 1: jc = crank_tip; bc = conrod_pin; break;
      default: jc = slider; bc = conrod_end; break;
    }
    out.eccentricity[j] = {jc.x.value - bc.x.value, jc.y.value - bc.y.value};
  }
}

void SliderCrank::rhs(double t, const State& x, State& dxdt) const {
  thread_local Evaluation ev;  // reused: the right-hand side must not allocate per call
  evaluate(t, x, ev);
  const int n = n_;
  dxdt.resize(state_size());
  for (int i = 0; i < n; ++i) {
    dxdt[i] = x[n + i];
    dxdt[n + i] = ev.q_ddot[i];
  }
  dxdt[2 * n] = ev.drive_power;
  dxdt[2 * n + 1] = ev.contact_power;
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    if (sites_[i].state >= 0) dxdt[sites_[i].state] = ev.sites[i].deflection_rate;
  }
}

bool SliderCrank::commit(const Evaluation& at_end, const std::vector<double>& onset_rate, State& x) {
  bool latched = false;
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    ContactMemory& m = memory_[i];
    const SiteEvaluation& se = at_end.sites[i];
    if (se.penetration > 0.0) {
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
  return latched;
}

}  // namespace mechanism
