#pragma once
// A scene: everything the simulator needs to know about one run, read from TOML (toml++) and
// validated once. It says what to model: the bodies, the crank driver, gravity, and for each joint
// whether it is ideal or has clearance (then with its contact and friction laws); then the
// integrator and the run. The built-in default is the seed paper's scene (Tables 1 and 2) with our
// documented choices for what the paper leaves open (docs/reference/mechanism/scene.md).
//
// Units are SI throughout (m, kg, kg m^2, s, N, Pa) except the crank speed, given in rpm as the
// seed does. Angles are in radians.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "mechanism/contact_law.hpp"
#include "mechanism/friction_law.hpp"

namespace mechanism {

// A link: length between its two pins, mass, moment of inertia about its mass centre, and the
// mass centre's position as a fraction of the length from its first pin (b2, b3 of seed Eq. 25).
struct Link {
  double length = 0.0;
  double mass = 0.0;
  double inertia = 0.0;
  double mass_centre = 0.5;
};

struct Material {
  double young_modulus = 207e9;
  double poisson_ratio = 0.3;
};

// The slider: a rectangle of `length` (along the guide) by `height`, `width` deep (out of plane,
// used only by the contact-area stiffness of seed Eq. 11). Its pin and mass centre are at its
// geometric centre.
struct Slider {
  double mass = 0.28;
  double inertia = 2.5e-4;
  double length = 0.05;
  double height = 0.05;
  double width = 0.05;
  Material material;
};

// The crank: driven at a constant speed (the seed), or free: its angle is then a coordinate that
// starts at initial_angle with the rate speed_rpm, and no torque acts on it (Flores, Leine &
// Glocker 2010's free mechanism, which starts from initial speeds and runs down under its contacts
// and gravity). period() stays 60 / speed_rpm, the nominal revolution that fixes RK4's step; a free
// crank has no stroboscopic section and no crank-period map (run.stroboscopic and
// `mechanism lyapunov` refuse it).
struct Driver {
  double speed_rpm = 5000.0;  // constant crank speed; a free crank's initial speed
  double initial_angle = 0.0;  // crank angle at t = 0
  bool free = false;           // no driver: the crank angle is a coordinate
  double angular_speed() const;  // rad/s
  double period() const;         // s, one crank revolution
};

enum class JointKind { ideal, clearance };

// How the slider meets a guide surface.
//   face:    the seed's model (Eq. 11-12, 18-19): per surface one resultant force at the centroid
//            W of the penetrated region, the penetration of the deepest corner, and the stiffness of
//            the contact length L_c.
//   corners: Flores et al. 2008: each penetrating corner is its own point contact with the
//            stiffness of `stiffness_model`, halved so that a flat, uniformly penetrating slider
//            feels the same total force as in the face model.
//   line:    each face is a line contact: a pressure k' d(s)^n on every point s of the face that
//            penetrates (d linear along the straight face), k' = K / L_s with K the flat-face
//            stiffness, so that a flat, uniformly penetrating slider feels K d^n as in the other
//            two. The elastic part derives from the potential k' integral d(s)^(n+1) / (n+1) ds,
//            so with restitution 1 and no friction it conserves energy from any tilt; the face
//            model's one force at the centroid with the deepest corner's penetration does not
//            (docs/reference/mechanism/model.md, "Energy from a tilted start").
enum class SliderContactModel { face, corners, line };

// Whether the slider may turn in the guide.
//   free:   the seed's model (Eq. 19 and 27): the slider's angle is a coordinate;
//   locked: an ideal anti-rotation constraint keeps it level. It is modelled as what it is, one
//           coordinate fewer, not as a huge inertia; the constraint's moment does no work. The
//           contacts are those of a level slider (docs/notes/mechanism/scene-lyapunov.md uses this to ask how
//           much of the dynamics the slider's rotation makes).
enum class SliderRotation { free, locked };

// The stiffness of the slider-guide contact.
//   contact_length: seed Eq. 11 with S = L_c W and L_c from Eq. 12 (changes during contact);
//   flat_face:      Eq. 11 evaluated once at L_c = L_s (a constant);
//   given:          the number in `stiffness` (N/m^n).
enum class SliderStiffness { contact_length, flat_face, given };

struct TranslationalJoint {
  JointKind kind = JointKind::clearance;
  double clearance = 0.5e-3;  // gap per side: guide height = slider height + 2 clearance
  // The built-in reading of the seed's slider joint is the one that passes the physics audit
  // (docs/reference/mechanism/scene.md): a line contact (conserves energy from any tilt), Eq. 11
  // with exponent 1 (its stiffness is in N/m), and the normalised LuGre of Eqs. 14-15 with sigma1
  // fading (bounded by mu F_N). The seed's printed reading is `model = "face"`, `exponent = 1.5`,
  // `law = "lugre_absolute"`, `sigma1_velocity = 0`.
  SliderContactModel model = SliderContactModel::line;
  SliderRotation rotation = SliderRotation::free;
  SliderStiffness stiffness_model = SliderStiffness::contact_length;
  double stiffness = 1e10;  // used only when stiffness_model = given
  Material guide;
  ContactLawParameters contact = [] {
    ContactLawParameters c;
    c.exponent = 1.0;
    return c;
  }();
  FrictionLawParameters friction = [] {
    FrictionLawParameters f;
    f.law = FrictionLaw::lugre_normalised;
    f.sigma1_velocity = 1e-3;
    return f;
  }();
  // LuGre only: the bristle deflection relaxes toward its steady value no faster than this (s).
  // The true rate sigma0 |v| / g(v) grows without bound as the normal force vanishes at contact
  // onset and release; an explicit integrator is stable on the bristle state only with
  // step < 2.78 x this floor (RK4). docs/reference/mechanism/contact-and-friction.md.
  double bristle_time_floor = 1e-6;
};

// Journal-in-bearing stiffness: Hertz's cylinder-in-hole value from the materials and radii
// (Flores' formula), or a given number.
enum class JournalStiffness { hertz, given };

// A revolute joint; with clearance the journal (the pin, radius bearing_radius - clearance) moves
// inside the bearing (the hole, radius bearing_radius).
struct RevoluteJoint {
  JointKind kind = JointKind::ideal;
  double bearing_radius = 0.01;
  double clearance = 0.5e-3;
  JournalStiffness stiffness_model = JournalStiffness::hertz;
  double stiffness = 1e10;  // used only when stiffness_model = given
  Material journal;
  Material bearing;
  ContactLawParameters contact;
  // No friction by default: the seed's Fig. 12 weakens revolute friction (mu = 0 or 0.05).
  FrictionLawParameters friction = [] {
    FrictionLawParameters f;
    f.law = FrictionLaw::none;
    return f;
  }();
  double bristle_time_floor = 1e-6;  // as for the translational joint
};

enum class IntegratorMethod { rk4, dopri5 };

// How the LuGre bristle deflections z advance (docs/reference/mechanism/contact-and-friction.md, "The exact
// bristle update").
//   integrated:  z is part of the ODE state and the stepper integrates z' = k (z_ss - z) with the
//                mechanics; the rate k is capped at 1 / bristle_time_floor, which explicit steps
//                must resolve (RK4: step <= 2.5 floors).
//   exponential: the state holds z at the step's start; each stage uses the law's exact solution
//                z_ss + (z_start - z_ss) exp(-k tau) at its own sliding speed, tau after the start
//                (friction()'s kernel), and the step's end writes that value into the state. Exact
//                at constant sliding speed and stable at any k, so there is no cap and no step limit
//                (bristle_time_floor is not used).
enum class BristleUpdate { integrated, exponential };

struct IntegratorSettings {
  IntegratorMethod method = IntegratorMethod::rk4;
  // RK4: the largest step; the step used is the crank period divided by the smallest whole number
  // of steps that keeps it at or below this, so stroboscopic samples fall on step ends.
  double step = 1e-6;
  // Dormand-Prince 5(4).
  double relative_tolerance = 1e-8;
  double absolute_tolerance = 1e-10;
  // An impact at these speeds lasts about 1e-4 s; a contact that opens and closes inside one
  // step is invisible to the error estimate, so the step is capped well below that.
  double max_step = 1e-5;
  double min_step = 1e-14;     // below this dopri5 reports step_underflow
  double max_steps = 1e9;      // accepted + rejected steps before a run reports step_limit
  // End a step where a contact opens or closes (a zero of SliderCrank::switching_functions, located
  // on the step's dense output) and take the rest of the step from there. The contact forces are
  // smooth between those zeros but not across them (with Eq. 11's exponent 1 the force's slope
  // jumps at onset), and a step across one loses the method's order.
  bool locate_switches = true;
  BristleUpdate bristles = BristleUpdate::integrated;
};

// Refused before a run starts (read_scene, check_run_size): more simulated steps, or more
// time-series rows, than these. No run of the seed's comes near them (about 1e7 steps and 1e5
// rows); beyond them a run would not finish or would fill the disk (a duration of
// 1.9e13 s wrapped the step count to 0 and "completed"; an output interval of 1e-300 s wrote rows
// until the disk was full). integrator.max_steps stays the run-time limit below them.
inline constexpr double max_run_steps = 1e12;
inline constexpr double max_output_rows = 1e8;

struct RunSettings {
  double duration = 0.06;         // simulated time after the transient, s (5 crank periods)
  double transient = 0.0;         // simulated time run but not written, s
  double output_interval = 1e-5;  // time-series sampling interval, s (0: no time series)
  bool stroboscopic = false;      // also sample once per crank revolution (at the initial angle)
};

// The state at t = 0 beyond the seed's Eq. 29 (which starts every coordinate on the ideal
// mechanism, at rest relative to it): the slider's angle and angular rate. A tilted, spinning start
// exercises the slider's rotation against the guide, e.g. to check that a contact model conserves
// energy from a generic state and not only from the symmetric one.
struct InitialState {
  double slider_angle = 0.0;  // rad
  double slider_rate = 0.0;   // rad/s
};

struct Scene {
  Link crank{0.05, 0.3, 1e-4, 0.5};
  Link conrod{0.12, 0.21, 2.5e-4, 0.5};
  Slider slider;
  Driver driver;
  InitialState initial;
  double gravity = 9.81;  // m/s^2 along -y
  TranslationalJoint slider_guide;
  RevoluteJoint crank_ground;
  RevoluteJoint crank_conrod;
  RevoluteJoint conrod_slider;
  IntegratorSettings integrator;
  RunSettings run;
};

// The seed's scene as commented TOML: the text `mechanism scene --default` prints.
std::string_view default_scene_toml();

// Bounds on the text read_scene accepts, checked before the TOML parser sees it. A scene is a few
// KB with keys of at most four parts (joint.slider.friction.law). toml++ limits the nesting of
// arrays and inline tables but not the parts of a dotted key, and recurses over the tables such a
// key makes: a key of 50,000 parts overflowed the stack inside it. A scene file or a --set value
// far beyond any real one is refused too. Every key counts: a `key = value` line's, a table
// header's ([a.b.c]), an inline table's and an override's.
inline constexpr std::size_t max_scene_bytes = std::size_t{1} << 20;  // 1 MiB
inline constexpr std::size_t max_key_parts = 64;
inline constexpr std::size_t max_override_value_bytes = 4096;

// Reads a scene: the default scene, then the keys of `toml_text` (may be empty), then each
// override "dotted.key=value" (the value in TOML syntax: 0.2e-3, "corners", true). Unknown keys,
// wrong types and impossible values (negative mass, conrod not longer than the crank offset,
// clearance <= 0, zero step, ...) throw InvalidParameter naming the key, the value and the rule,
// as does text beyond the bounds above. `source` names the text in messages (a file name).
Scene read_scene(std::string_view toml_text, const std::vector<std::string>& overrides = {},
                 std::string_view source = "scene");

// Throws InvalidParameter when the run needs more than max_run_steps steps (from its duration,
// transient and step) or writes more than max_output_rows rows, or integrator.max_steps exceeds
// max_run_steps. read_scene calls it; so does a caller that sets the run's times itself.
void check_run_size(const Scene& scene);

// The resolved scene as TOML, every key with its value (defaults included).
std::string to_toml(const Scene& scene);

// The keys whose values differ from the built-in scene's, as "dotted.key = value" in to_toml's order
// and spelling (`--set dotted.key=value` sets each): with the built-in scene they determine the scene
// in full, in a few lines where to_toml takes some 180. Empty for the built-in scene.
std::vector<std::string> scene_differences(const Scene& scene);

// The SI unit of a numeric scene key as its documentation (`mechanism scene --default`) states it
// ("m" for joint.slider.clearance, "rpm" for driver.speed_rpm); empty for a key without one (a
// coefficient, a tolerance, a choice) or a name that is no key.
std::string scene_key_unit(const std::string& key);

// Warnings a valid scene still deserves (mu_s < mu_k: LuGre without a stiction peak, ...).
std::vector<std::string> scene_warnings(const Scene& scene);

}  // namespace mechanism
