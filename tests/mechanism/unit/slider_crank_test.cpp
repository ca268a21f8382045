// The slider-crank's equations of motion against closed forms: the coordinates each scene implies,
// the seed's Eq. 27 for the translational-clearance scene in free flight, the slider's four
// contact configurations from hand-set poses (Flores et al. 2008), and the face and corner
// contact models agreeing for a flat, uniformly penetrating slider.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mechanism/contact_stiffness.hpp"
#include "mechanism/error.hpp"
#include "mechanism/friction_law.hpp"
#include "mechanism/line_contact.hpp"
#include "mechanism/scene.hpp"
#include "mechanism/slider_crank.hpp"

namespace mechanism {
namespace {

TEST(SliderCrank, ModelsOnlyWhatTheSceneRequires) {
  // Seed scene: translational clearance only -> conrod and slider angles (seed Eq. 27), two faces.
  const SliderCrank seed(read_scene(""));
  EXPECT_EQ(seed.coordinate_names(), (std::vector<std::string>{"conrod_angle", "slider_angle"}));
  EXPECT_EQ(seed.site_count(), 2u);
  // Every joint ideal: a one-degree-of-freedom mechanism driven at constant speed, no coordinates.
  const SliderCrank ideal(read_scene("", {"joint.slider.type=ideal"}));
  EXPECT_EQ(ideal.coordinate_count(), 0);
  EXPECT_EQ(ideal.site_count(), 0u);
  // A revolute clearance adds two coordinates and one site; an ideal guide keeps the slider level.
  const SliderCrank pin(read_scene("", {"joint.slider.type=ideal", "joint.conrod_slider.type=clearance"}));
  EXPECT_EQ(pin.coordinate_names(), (std::vector<std::string>{"conrod_angle", "slider_x"}));
  EXPECT_EQ(pin.site_count(), 1u);
  const SliderCrank all(read_scene("", {"joint.crank_ground.type=clearance", "joint.crank_conrod.type=clearance",
                                        "joint.conrod_slider.type=clearance", "joint.slider.model=corners"}));
  EXPECT_EQ(all.coordinate_count(), 8);
  EXPECT_EQ(all.site_count(), 4u + 3u);
  // q, q_dot, two work accumulators, and a LuGre bristle deflection per slider corner.
  EXPECT_EQ(all.state_size(), 2 * 8 + 2 + 4);
}

TEST(SliderCrank, FreeFlightFollowsSeedEquation27) {
  // Seed Eq. 27 with no contact force:
  //   [I3 + (b3^2 m3 + m4) L3^2] th3'' + (b3 m3 + m4) L2 L3 w^2 sin(th3 - th2) + (b3 m3 + m4) g L3 cos th3 = 0,
  //   I4 th4'' = 0.
  const Scene s = read_scene("", {"joint.slider.clearance=0.01"});  // wide enough for no contact here
  const SliderCrank sys(s);
  State x = sys.initial_state();
  x[0] = -0.2;  // conrod angle
  x[1] = 0.001;  // slider angle
  x[2] = 7.0;   // conrod rate
  x[3] = 3.0;   // slider rate
  const double t = 0.0013;
  Evaluation ev;
  sys.evaluate(t, x, ev);
  for (const auto& site : ev.sites) ASSERT_LE(site.penetration, 0.0);
  const double w = s.driver.angular_speed(), th2 = w * t, th3 = x[0];
  const double l2 = s.crank.length, l3 = s.conrod.length, b3 = s.conrod.mass_centre;
  const double m3 = s.conrod.mass, m4 = s.slider.mass, i3 = s.conrod.inertia, g = s.gravity;
  const double expected = -((b3 * m3 + m4) * l2 * l3 * w * w * std::sin(th3 - th2) + (b3 * m3 + m4) * g * l3 * std::cos(th3)) /
                          (i3 + (b3 * b3 * m3 + m4) * l3 * l3);
  EXPECT_NEAR(ev.q_ddot[0], expected, 1e-9 * std::abs(expected));
  EXPECT_NEAR(ev.q_ddot[1], 0.0, 1e-12);
}

// The slider of the seed scene placed by hand: centre height y and tilt a, at crank angle 0.
Evaluation place_slider(const Scene& s, double y, double angle) {
  const SliderCrank sys(s);
  State x = sys.initial_state();
  // At t = 0 the crank is along +x, so slider_y = L3 sin(conrod angle).
  x[0] = std::asin(y / s.conrod.length);
  x[1] = angle;
  Evaluation ev;
  sys.evaluate(0.0, x, ev);
  return ev;
}

TEST(SliderCrank, SeedClosedFormMatchesTheJets) {
  // The seed's topology is evaluated in closed form; the kinematic jets are the general reference.
  // Poses in free flight, on one face, on both (jammed), with and without friction and for both
  // slider models, at several crank angles and rates; both paths see the same memory.
  for (const char* model : {"face", "corners", "line"}) {
    for (const char* law : {"lugre_absolute", "coulomb", "none"}) {
      const SliderCrank sys(read_scene("", {std::string("joint.slider.model=") + model,
                                            std::string("joint.slider.friction.law=") + law}));
      State x = sys.initial_state();
      Evaluation a, b;
      int cases = 0;
      for (double t : {0.0, 1.3e-3, 4.1e-3, 7.7e-3}) {
        for (double slider_y : {0.0, -0.52e-3, 0.55e-3}) {
          for (double angle : {0.0, 2e-3, -4e-3}) {
            x[0] = std::asin((slider_y - 0.05 * std::sin(523.6 * t)) / 0.12);
            x[1] = angle;
            x[2] = -120.0 + 40.0 * angle * 1e3;
            x[3] = 3.0 - 1e3 * slider_y;
            for (int i = 6; i < x.size(); ++i) x[i] = 1e-4 * (i - 7);  // bristle deflections
            sys.evaluate(t, x, a);
            sys.evaluate_with_jets(t, x, b);
            auto near = [](double u, double v, double scale) { return std::abs(u - v) <= 1e-12 * scale; };
            const double acc = std::max(1.0, std::abs(b.q_ddot[0]) + std::abs(b.q_ddot[1]));
            EXPECT_TRUE(near(a.q_ddot[0], b.q_ddot[0], acc)) << a.q_ddot[0] << " " << b.q_ddot[0];
            EXPECT_TRUE(near(a.q_ddot[1], b.q_ddot[1], acc)) << a.q_ddot[1] << " " << b.q_ddot[1];
            EXPECT_TRUE(near(a.driving_torque, b.driving_torque, std::max(1.0, std::abs(b.driving_torque))));
            EXPECT_TRUE(near(a.contact_power, b.contact_power, std::max(1.0, std::abs(b.contact_power))));
            EXPECT_TRUE(near(a.kinetic_energy, b.kinetic_energy, b.kinetic_energy));
            EXPECT_TRUE(near(a.potential_energy, b.potential_energy, 1.0));
            for (int k = 0; k < 3; ++k) {
              EXPECT_TRUE(near(a.slider_pose[k], b.slider_pose[k], 1.0));
              EXPECT_TRUE(near(a.slider_velocity[k], b.slider_velocity[k], 100.0));
              EXPECT_TRUE(near(a.slider_acceleration[k], b.slider_acceleration[k], std::max(1.0, acc)));
            }
            EXPECT_EQ(a.configuration, b.configuration);
            ASSERT_EQ(a.sites.size(), b.sites.size());
            for (std::size_t i = 0; i < a.sites.size(); ++i) {
              EXPECT_TRUE(near(a.sites[i].normal_force, b.sites[i].normal_force, std::max(1.0, b.sites[i].normal_force)));
              EXPECT_TRUE(near(a.sites[i].friction_force, b.sites[i].friction_force,
                               std::max(1.0, std::abs(b.sites[i].friction_force))));
              EXPECT_TRUE(near(a.sites[i].deflection_rate, b.sites[i].deflection_rate,
                               std::max(1.0, std::abs(b.sites[i].deflection_rate))));
              cases += b.sites[i].normal_force > 0.0;
            }
          }
        }
      }
      EXPECT_GT(cases, 10) << "the poses must put the slider in contact";
    }
  }
}

TEST(SliderCrank, ExponentialBristlesAdvanceByTheLawsExactUpdate) {
  // integrator.bristles = "exponential": a stage tau after the step's start sees the deflection that
  // friction() gives for the state's z advanced over tau at that stage's sliding speed (the law's
  // exact solution, checked against its ODE in friction_law_test), the state's z stands still
  // (dz/dt = 0 in rhs), and commit() writes the step end's deflection into the state, from which the
  // next step starts with the force the last one ended with (to rounding: e^{-k tau} (z_ss - z_0) and
  // z_ss - z_1 differ in the last bits). Slider tilted by 0.05 rad: both faces touch (error_weights_test).
  const Scene s = read_scene("", {"integrator.bristles=\"exponential\""});
  SliderCrank sys(s);
  const double t0 = 2e-3, t1 = t0 + 3e-7;
  State x = sys.initial_state();
  const auto& names = sys.coordinate_names();
  auto index = [&](const char* name) { return std::find(names.begin(), names.end(), name) - names.begin(); };
  // The conrod angle that keeps the slider's centre on the guide's centre line at t0.
  x[index("conrod_angle")] = std::asin(-s.crank.length * std::sin(sys.omega() * t0) / s.conrod.length);
  x[index("slider_angle")] = 0.05;
  const FrictionLawParameters& law = s.slider_guide.friction;
  for (std::size_t i = 0; i < sys.site_count(); ++i)
    if (sys.bristle_index(i) >= 0) x[sys.bristle_index(i)] = (i % 2 ? -0.4 : 0.7) * law.kinetic_coefficient / law.sigma0;
  Evaluation start, end, next;
  sys.start_bristle_clock(t0);
  sys.evaluate(t0, x, start);
  sys.commit(t0, start, {}, x);  // latches the impact velocities; at tau = 0 z is unchanged
  sys.evaluate(t1, x, end);
  State dxdt;
  sys.rhs(t1, x, dxdt);
  State x1 = x;
  EXPECT_TRUE(sys.commit(t1, end, {}, x1));
  sys.evaluate(t1, x1, next);
  int touching = 0;
  for (std::size_t i = 0; i < sys.site_count(); ++i) {
    const int k = sys.bristle_index(i);
    const SiteEvaluation& e = end.sites[i];
    if (k < 0 || !(e.penetration > 0.0)) continue;
    ++touching;
    const FrictionEvaluation f = friction(law, e.normal_force, e.sliding_velocity, x[k], t1 - t0);
    EXPECT_EQ(e.friction_force, f.force);
    EXPECT_EQ(e.deflection, f.deflection);
    EXPECT_EQ(e.deflection_rate, f.deflection_rate);
    EXPECT_NE(e.deflection, x[k]) << "the bristles must move over the step for the test to mean anything";
    EXPECT_EQ(dxdt[k], 0.0);
    EXPECT_EQ(x1[k], e.deflection);
    EXPECT_NEAR(next.sites[i].friction_force, e.friction_force, 1e-12 * std::abs(e.friction_force));
  }
  EXPECT_EQ(touching, 2);
  for (int j = 0; j < sys.coordinate_count(); ++j)
    EXPECT_NEAR(next.q_ddot[j], end.q_ddot[j], 1e-12 * std::max(1.0, std::abs(end.q_ddot[j])));
}

TEST(SliderCrank, LockedRotationIsOneCoordinateFewerAndMatchesTheJets) {
  // joint.slider.rotation = "locked": the slider stays level, theta_4 is not a coordinate. The
  // closed form and the jets agree as for the free slider, and at a level pose the conrod's
  // acceleration equals the free slider's (the contact moment that would turn the free slider goes
  // into the constraint, not into theta_3).
  for (const char* model : {"face", "corners", "line"}) {
    const std::vector<std::string> common = {std::string("joint.slider.model=") + model, "joint.slider.friction.law=coulomb"};
    std::vector<std::string> locked_set = common;
    locked_set.push_back("joint.slider.rotation=locked");
    const SliderCrank locked(read_scene("", locked_set)), free_slider(read_scene("", common));
    ASSERT_EQ(locked.coordinate_count(), 1);
    EXPECT_EQ(locked.coordinate_names(), std::vector<std::string>{"conrod_angle"});
    State x = locked.initial_state(), xf = free_slider.initial_state();
    Evaluation a, b, f;
    int cases = 0;
    for (double t : {0.0, 1.3e-3, 4.1e-3, 7.7e-3}) {
      for (double slider_y : {0.0, -0.52e-3, 0.55e-3}) {
        x[0] = xf[0] = std::asin((slider_y - 0.05 * std::sin(523.6 * t)) / 0.12);
        x[1] = xf[2] = 3.0 - 1e3 * slider_y;  // conrod rate
        xf[1] = xf[3] = 0.0;                  // the free slider level and not turning
        locked.evaluate(t, x, a);
        locked.evaluate_with_jets(t, x, b);
        free_slider.evaluate(t, xf, f);
        const double acc = std::max(1.0, std::abs(b.q_ddot[0]));
        EXPECT_NEAR(a.q_ddot[0], b.q_ddot[0], 1e-12 * acc);
        EXPECT_NEAR(a.q_ddot[0], f.q_ddot[0], 1e-12 * acc);
        EXPECT_NEAR(a.driving_torque, b.driving_torque, 1e-12 * std::max(1.0, std::abs(b.driving_torque)));
        EXPECT_NEAR(a.contact_power, b.contact_power, 1e-12 * std::max(1.0, std::abs(b.contact_power)));
        EXPECT_EQ(a.slider_pose[2], 0.0);
        EXPECT_EQ(a.slider_velocity[2], 0.0);
        for (std::size_t i = 0; i < a.sites.size(); ++i) cases += a.sites[i].normal_force > 0.0;
      }
    }
    EXPECT_GT(cases, 4) << model << ": the poses must put the slider in contact";
  }
  // A tilted start needs a slider that can turn.
  EXPECT_THROW(read_scene("", {"joint.slider.rotation=locked", "initial.slider_angle=0.01"}), InvalidParameter);
}

TEST(SliderCrank, TheFourSliderConfigurations) {
  const Scene s = read_scene("", {"joint.slider.friction.law=none"});
  const double c = s.slider_guide.clearance, half = 0.5 * s.slider.length;
  EXPECT_EQ(place_slider(s, 0.0, 0.0).configuration, SliderConfiguration::free_flight);
  // Tilted about the centre, raised until only the top-right corner passes the upper surface.
  const double tilt = 0.5 * c / half;  // raises the right end by c / 2
  EXPECT_EQ(place_slider(s, 0.6 * c, tilt).configuration, SliderConfiguration::one_corner);
  // Level and raised past the clearance: both upper corners, flat.
  const Evaluation flat = place_slider(s, c + 1e-5, 0.0);
  EXPECT_EQ(flat.configuration, SliderConfiguration::flat);
  EXPECT_GT(flat.sites[0].normal_force, 0.0);  // the upper face pushes down
  EXPECT_EQ(flat.sites[1].normal_force, 0.0);
  // Tilted until two opposite corners touch: jammed.
  const double jam = 1.2 * c / half;
  const Evaluation jammed = place_slider(s, 0.0, jam);
  EXPECT_EQ(jammed.configuration, SliderConfiguration::jammed);
  EXPECT_GT(jammed.sites[0].normal_force, 0.0);
  EXPECT_GT(jammed.sites[1].normal_force, 0.0);
}

// Coulomb's law on RK4's grid opposes the direction held in the contact's memory, not the sign of
// the sliding velocity at each stage (slider_crank.hpp, holds_sliding_direction): the force of a
// site sliding one way with the other direction held has the held direction's sign, mu_k F_N in
// size. Only Coulomb with mu_k > 0 under RK4 holds a direction.
TEST(SliderCrank, CoulombOnRk4OpposesTheHeldDirection) {
  EXPECT_FALSE(SliderCrank(read_scene("", {"joint.slider.friction.law=lugre_absolute"})).holds_sliding_direction(0));
  EXPECT_FALSE(SliderCrank(read_scene("", {"joint.slider.friction.law=coulomb", "integrator.method=dopri5"}))
                   .holds_sliding_direction(0));
  EXPECT_FALSE(SliderCrank(read_scene("", {"joint.slider.friction.law=coulomb", "joint.slider.friction.kinetic_coefficient=0"}))
                   .holds_sliding_direction(0));
  const Scene s = read_scene("", {"joint.slider.friction.law=coulomb"});
  SliderCrank sys(s);
  ASSERT_TRUE(sys.holds_sliding_direction(1));
  // Pressed into the lower face at t = 1.3 ms, the crank 39 degrees past its dead centre (the slider
  // centre's height is L2 sin(omega t) + L3 sin(conrod angle)).
  const double t = 1.3e-3, y = -(s.slider_guide.clearance + 2e-5);
  State x = sys.initial_state();
  x[0] = std::asin((y - s.crank.length * std::sin(sys.omega() * t)) / s.conrod.length);
  x[1] = 0.0;
  Evaluation free_sign;
  sys.evaluate(t, x, free_sign);  // no direction held yet: sign(v)
  const SiteEvaluation& lower = free_sign.sites[1];
  ASSERT_GT(lower.normal_force, 0.0);
  ASSERT_NE(lower.sliding_velocity, 0.0);
  const double mu = s.slider_guide.friction.kinetic_coefficient;
  EXPECT_NEAR(lower.friction_force, -std::copysign(mu * lower.normal_force, lower.sliding_velocity),
              1e-12 * lower.normal_force);
  for (int held : {1, -1}) {
    sys.set_sliding_direction(1, held);
    Evaluation ev;
    sys.evaluate(t, x, ev);
    EXPECT_EQ(ev.sites[1].sliding_velocity, lower.sliding_velocity);
    EXPECT_NEAR(ev.sites[1].friction_force, -held * mu * ev.sites[1].normal_force, 1e-12 * ev.sites[1].normal_force)
        << "held " << held;
  }
}

TEST(SliderCrank, FaceCornerAndLineModelsAgreeForAFlatUniformPenetration) {
  // A level slider pressed uniformly into the lower surface: the face model (one force at the
  // centroid, stiffness of the full contact length), the corner model (two corners, half the
  // flat-face stiffness each) and the line model (a uniform pressure K d^n / L_s) give the same
  // total force and no moment (seed-notes' requirement).
  for (const char* stiffness : {"flat_face", "contact_length"}) {
    const Scene face = read_scene("", {"joint.slider.friction.law=none", std::string("joint.slider.stiffness_model=") + stiffness});
    const double y = -(face.slider_guide.clearance + 2e-5);
    const Evaluation a = place_slider(face, y, 0.0);
    double fa = 0;
    for (const auto& site : a.sites) fa += site.normal_force;
    EXPECT_GT(fa, 0.0);
    EXPECT_NEAR(a.slider_acceleration[2], 0.0, 1e-6);
    for (const char* model : {"corners", "line"}) {
      const Scene other = read_scene("", {"joint.slider.friction.law=none", std::string("joint.slider.model=") + model,
                                          std::string("joint.slider.stiffness_model=") + stiffness});
      const Evaluation b = place_slider(other, y, 0.0);
      double fb = 0;
      for (const auto& site : b.sites) fb += site.normal_force;
      EXPECT_NEAR(fa, fb, 1e-9 * fa) << stiffness << ", " << model;
      // Same resulting slider acceleration (force and zero moment).
      EXPECT_NEAR(b.slider_acceleration[2], 0.0, 1e-6) << model;
      EXPECT_NEAR(a.q_ddot[0], b.q_ddot[0], 1e-9 * std::abs(a.q_ddot[0])) << model;
    }
  }
}

TEST(SliderCrank, LineModelLoadsATiltedFaceWithItsPressure) {
  // A slider tilted so that only part of its lower face penetrates. The line model's normal force
  // on that face is the pressure's resultant from the corner penetrations computed here by hand
  // (line_contact.hpp), and the slider's angular acceleration is the moment of the two corner loads
  // about its centre over its inertia (the other contributions vanish: no friction, and the pin at
  // the centre carries no moment).
  const Scene s = read_scene("", {"joint.slider.friction.law=none", "joint.slider.model=line", "gravity=0",
                                  "joint.slider.contact.restitution=1"});  // no damping: the elastic loads alone
  const double c = s.slider_guide.clearance, hl = 0.5 * s.slider.length, hh = 0.5 * s.slider.height;
  for (const double tilt : {1.3 * c / hl, -1.1 * c / hl}) {
    const double y = -0.3 * c;
    const Evaluation ev = place_slider(s, y, tilt);
    // Lower-face corners (body (-hl, -hh) and (hl, -hh)): penetration below the lower surface.
    const double guide_half = hh + c;
    const auto corner_y = [&](double sx) { return y + std::sin(tilt) * sx - std::cos(tilt) * hh; };
    const double pa = -guide_half - corner_y(-hl), pb = -guide_half - corner_y(hl);
    ASSERT_TRUE((pa > 0) != (pb > 0)) << "one corner in: " << pa << ", " << pb;
    const double k = slider_face_stiffness(material_compliance(s.slider.material.young_modulus, s.slider.material.poisson_ratio),
                                           material_compliance(s.slider_guide.guide.young_modulus,
                                                               s.slider_guide.guide.poisson_ratio),
                                           s.slider.length, s.slider.width, s.slider.length);
    const LineContactLoads f = line_contact_loads(k, s.slider_guide.contact.exponent, pa, pb);
    EXPECT_NEAR(ev.sites[1].normal_force, f.left + f.right, 1e-9 * (f.left + f.right)) << tilt;
    EXPECT_EQ(ev.sites[0].normal_force, 0.0);  // the upper face is clear
    // Moment about the centre of upward forces at the corners' world x offsets.
    // (body (sx, -hh) turned by the tilt: x offset cos(a) sx + sin(a) hh)
    const double xa = std::cos(tilt) * -hl + std::sin(tilt) * hh, xb = std::cos(tilt) * hl + std::sin(tilt) * hh;
    const double moment = xa * f.left + xb * f.right;
    EXPECT_NEAR(ev.q_ddot[1], moment / s.slider.inertia, 1e-9 * std::abs(moment / s.slider.inertia)) << tilt;
  }
}

TEST(SliderCrank, IdealMechanismKinematicsMatchClosedForm) {
  // Every joint ideal: x = r cos th + sqrt(l^2 - r^2 sin^2 th); the acceleration at th = 0 is
  // -r w^2 (1 + r/l) = -19 419 m/s^2 at 5000 rpm (reference-values.md, re-derived here).
  const Scene s = read_scene("", {"joint.slider.type=ideal", "gravity=0"});
  const SliderCrank sys(s);
  const double r = s.crank.length, l = s.conrod.length, w = s.driver.angular_speed();
  State x = sys.initial_state();
  Evaluation ev;
  double vmax = 0, vmax_angle = 0, amin = 1e300, amax = -1e300;
  for (int k = 0; k < 3600; ++k) {
    const double th = 2 * std::numbers::pi * k / 3600.0, t = th / w;
    sys.evaluate(t, x, ev);
    const double xs = r * std::cos(th) + std::sqrt(l * l - r * r * std::sin(th) * std::sin(th));
    ASSERT_NEAR(ev.slider_pose[0], xs, 1e-14);
    ASSERT_NEAR(ev.slider_pose[1], 0.0, 1e-15);
    if (ev.slider_velocity[0] > vmax) {
      vmax = ev.slider_velocity[0];
      vmax_angle = th;
    }
    amin = std::min(amin, ev.slider_acceleration[0]);
    amax = std::max(amax, ev.slider_acceleration[0]);
  }
  EXPECT_NEAR(amin, -r * w * w * (1 + r / l), 1e-6 * r * w * w);
  EXPECT_NEAR(amin, -19419.0, 1.0);
  EXPECT_NEAR(amax, 9696.0, 2.0);
  EXPECT_NEAR(std::abs(vmax), 28.4, 0.05);
  // Extremes near 70.2 and 289.8 degrees (velocity negative on the first half-turn).
  EXPECT_TRUE(std::abs(vmax_angle * 180 / std::numbers::pi - 289.8) < 0.2);
}

TEST(SliderCrank, IdealDrivingTorqueIsTheRateOfKineticEnergy) {
  // With no gravity and no contact, tau w = dT/dt. T(th) from the closed-form kinematics by
  // central differences (brute force); the torque swings about +-212 N m (reference-values.md).
  const Scene s = read_scene("", {"joint.slider.type=ideal", "gravity=0"});
  const SliderCrank sys(s);
  const double w = s.driver.angular_speed();
  State x = sys.initial_state();
  Evaluation ev, ep, em;
  double tmax = -1e300, tmin = 1e300;
  for (int k = 0; k < 720; ++k) {
    const double t = (2 * std::numbers::pi * k / 720.0) / w, dt = 1e-7;
    sys.evaluate(t, x, ev);
    sys.evaluate(t + dt, x, ep);
    sys.evaluate(t - dt, x, em);
    const double dT = (ep.kinetic_energy - em.kinetic_energy) / (2 * dt);
    ASSERT_NEAR(ev.driving_torque * w, dT, 1e-5 * std::abs(s.crank.mass * w * w * w * 0.05 * 0.05) + 1e-4 * std::abs(dT));
    tmax = std::max(tmax, ev.driving_torque);
    tmin = std::min(tmin, ev.driving_torque);
  }
  EXPECT_NEAR(tmax, 212.0, 5.0);
  EXPECT_NEAR(tmin, -212.0, 5.0);
}

}  // namespace
}  // namespace mechanism
