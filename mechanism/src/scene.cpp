// Scene reading and writing. Every key is listed once, in visit_fields(), with its rule and a
// one-line description; reading, validation, the resolved-scene output and the commented default
// scene all walk that one list, so a key cannot be documented in one place and missing in another.

#include "mechanism/scene.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <tuple>
#include <sstream>

#include <toml++/toml.h>

#include "checks.hpp"
#include "mechanism/error.hpp"

namespace mechanism {

double Driver::angular_speed() const { return speed_rpm * 2.0 * std::numbers::pi / 60.0; }
double Driver::period() const { return 60.0 / speed_rpm; }

namespace {

enum class Rule { finite, positive, non_negative, restitution, poisson, fraction };

const char* rule_text(Rule r) {
  switch (r) {
    case Rule::finite: return "must be a finite number";
    case Rule::positive: return "must be a finite number > 0";
    case Rule::non_negative: return "must be a finite number >= 0";
    case Rule::restitution: return "must be in (0, 1]";
    case Rule::poisson: return "must be in [0, 0.5)";
    case Rule::fraction: return "must be in [0, 1]";
  }
  return "";
}

bool satisfies(Rule r, double v) {
  if (!std::isfinite(v)) return false;
  switch (r) {
    case Rule::finite: return true;
    case Rule::positive: return v > 0.0;
    case Rule::non_negative: return v >= 0.0;
    case Rule::restitution: return v > 0.0 && v <= 1.0;
    case Rule::poisson: return v >= 0.0 && v < 0.5;
    case Rule::fraction: return v >= 0.0 && v <= 1.0;
  }
  return false;
}

std::string format_number(double v) {
  std::string s = detail::text(v);
  // TOML needs a '.' or an exponent to read a float back as a float.
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// Names of enumerators, in enumerator order.
template <class E>
struct EnumNames;
template <>
struct EnumNames<JointKind> {
  static constexpr std::string_view names[] = {"ideal", "clearance"};
};
template <>
struct EnumNames<SliderContactModel> {
  static constexpr std::string_view names[] = {"face", "corners", "line"};
};
template <>
struct EnumNames<SliderRotation> {
  static constexpr std::string_view names[] = {"free", "locked"};
};
template <>
struct EnumNames<SliderStiffness> {
  static constexpr std::string_view names[] = {"contact_length", "flat_face", "given"};
};
template <>
struct EnumNames<JournalStiffness> {
  static constexpr std::string_view names[] = {"hertz", "given"};
};
template <>
struct EnumNames<IntegratorMethod> {
  static constexpr std::string_view names[] = {"rk4", "dopri5"};
};
template <>
struct EnumNames<BristleUpdate> {
  static constexpr std::string_view names[] = {"integrated", "exponential"};
};
// The laws' names are theirs (contact_law.hpp, friction_law.hpp): read them, do not repeat them.
template <class E, std::size_t N>
std::array<std::string_view, N> names_from_to_string() {
  std::array<std::string_view, N> names;
  for (std::size_t i = 0; i < N; ++i) names[i] = to_string(static_cast<E>(i));
  return names;
}
template <>
struct EnumNames<NormalContactLaw> {
  static inline const auto names = names_from_to_string<NormalContactLaw, 7>();
};
template <>
struct EnumNames<FrictionLaw> {
  static inline const auto names = names_from_to_string<FrictionLaw, 5>();
};

template <class E>
std::string choices_text() {
  std::string s = "must be one of";
  for (auto n : EnumNames<E>::names) s += std::string(" \"") + std::string(n) + "\"";
  return s;
}

// Calls v.number(key, double&, Rule, doc), v.flag(key, bool&, doc) and v.choice(key, Enum&, doc)
// for every key of the scene, in the order the resolved scene is printed.
template <class Visitor>
void visit_contact(Visitor& v, const std::string& p, ContactLawParameters& c) {
  v.choice(p + "law", c.law, "normal contact law (force K d^n (1 + chi d_rate / d_rate_impact))");
  v.number(p + "restitution", c.restitution, Rule::restitution,
           "coefficient of restitution c_e (seed Eq. 10 leaves it open; Flores' benchmarks use 0.9)");
  v.number(p + "exponent", c.exponent, Rule::positive,
           "n of seed Eq. 10 (Hertz's 1.5 for the journals; 1 for the slider, whose Eq. 11 stiffness is in N/m)");
  v.number(p + "velocity_floor", c.velocity_floor, Rule::positive,
           "m/s; smallest latched impact velocity (keeps the damping finite at grazing contact)");
}

template <class Visitor>
void visit_friction(Visitor& v, const std::string& p, FrictionLawParameters& f, double& bristle_time_floor) {
  v.choice(p + "law", f.law, "friction law");
  v.number(p + "static_coefficient", f.static_coefficient, Rule::non_negative,
           "mu_s (the seed's Table 2 prints 0.1, below mu_k, so its Stribeck curve has no stiction peak; kept to "
           "reproduce the paper, and only another pair with mu_s < mu_k is warned about)");
  v.number(p + "kinetic_coefficient", f.kinetic_coefficient, Rule::non_negative, "mu_k (the seed's Table 2: 0.11)");
  v.number(p + "stribeck_velocity", f.stribeck_velocity, Rule::positive,
           "v_s, m/s (blank in the seed's Table 2; 1e-3 is common)");
  v.number(p + "stribeck_exponent", f.stribeck_exponent, Rule::positive,
           "gamma (blank in the seed's Table 2; 2 is common)");
  v.number(p + "sigma0", f.sigma0, Rule::positive,
           "LuGre bristle stiffness (N/m absolute form, 1/m normalised form)");
  v.number(p + "sigma1", f.sigma1, Rule::non_negative,
           "LuGre bristle damping (N s/m absolute form, s/m normalised form)");
  v.number(p + "sigma1_velocity", f.sigma1_velocity, Rule::non_negative,
           "m/s; sigma1 fades as exp(-(v/this)^2) (Canudas de Wit 2003); 0: constant, as the seed prints");
  v.number(p + "sigma2", f.sigma2, Rule::non_negative, "LuGre viscous coefficient (same units as sigma1)");
  v.number(p + "ambrosio_v0", f.ambrosio_v0, Rule::positive, "m/s; Ambrosio's law: no friction below");
  v.number(p + "ambrosio_v1", f.ambrosio_v1, Rule::positive, "m/s; Ambrosio's law: full friction above");
  v.number(p + "bristle_time_floor", bristle_time_floor, Rule::positive,
           "s; LuGre bristles relax no faster than this (RK4 needs step < 2.78 x floor)");
}

template <class Visitor>
void visit_material(Visitor& v, const std::string& p, Material& m) {
  v.number(p + "young_modulus", m.young_modulus, Rule::positive, "Pa");
  v.number(p + "poisson_ratio", m.poisson_ratio, Rule::poisson, "");
}

template <class Visitor>
void visit_revolute(Visitor& v, const std::string& p, RevoluteJoint& j) {
  v.choice(p + "type", j.kind, "ideal (a pin: no coordinates, no contact code) or clearance");
  v.number(p + "bearing_radius", j.bearing_radius, Rule::positive,
           "m (not given by the seed; Flores uses 10 mm); the journal radius is bearing_radius - clearance");
  v.number(p + "clearance", j.clearance, Rule::positive, "m, radial clearance c_r");
  v.choice(p + "stiffness_model", j.stiffness_model, "hertz (from materials and radii) or given");
  v.number(p + "stiffness", j.stiffness, Rule::positive, "N/m^n, used when stiffness_model = \"given\"");
  visit_material(v, p + "journal.", j.journal);
  visit_material(v, p + "bearing.", j.bearing);
  visit_contact(v, p + "contact.", j.contact);
  visit_friction(v, p + "friction.", j.friction, j.bristle_time_floor);
}

template <class Visitor>
void visit_link(Visitor& v, const std::string& p, Link& l) {
  v.number(p + "length", l.length, Rule::positive, "m, pin to pin");
  v.number(p + "mass", l.mass, Rule::positive, "kg");
  v.number(p + "inertia", l.inertia, Rule::positive, "kg m^2, about the mass centre");
  v.number(p + "mass_centre", l.mass_centre, Rule::fraction,
           "mass centre as a fraction of the length from the first pin (not given by the seed: mid-length)");
}

template <class Visitor>
void visit_fields(Visitor& v, Scene& s) {
  // Top-level keys first: in TOML a key after a [table] header belongs to that table.
  v.number("gravity", s.gravity, Rule::non_negative, "m/s^2, along -y");
  visit_link(v, "crank.", s.crank);
  visit_link(v, "conrod.", s.conrod);
  v.number("slider.mass", s.slider.mass, Rule::positive, "kg");
  v.number("slider.inertia", s.slider.inertia, Rule::positive, "kg m^2");
  v.number("slider.length", s.slider.length, Rule::positive, "m, along the guide (L_s)");
  v.number("slider.height", s.slider.height, Rule::positive, "m, across the guide (H)");
  v.number("slider.width", s.slider.width, Rule::positive, "m, out of plane (W, for the contact area of Eq. 11)");
  visit_material(v, "slider.", s.slider.material);
  v.number("driver.speed_rpm", s.driver.speed_rpm, Rule::positive, "constant crank speed, rpm (a free crank's initial speed)");
  v.number("driver.initial_angle", s.driver.initial_angle, Rule::finite, "crank angle at t = 0, rad");
  v.flag("driver.free", s.driver.free,
         "true: no driver, the crank angle is a coordinate starting at speed_rpm (no stroboscopic samples)");
  v.number("initial.slider_angle", s.initial.slider_angle, Rule::finite,
           "rad, the slider's angle at t = 0 (the seed's Eq. 29 starts it level: 0)");
  v.number("initial.slider_rate", s.initial.slider_rate, Rule::finite, "rad/s, the slider's angular rate at t = 0");
  const std::string t = "joint.slider.";
  v.choice(t + "type", s.slider_guide.kind, "ideal (slider on the guide line) or clearance");
  v.number(t + "clearance", s.slider_guide.clearance, Rule::positive,
           "m, gap per side: guide height = slider height + 2 clearance");
  v.choice(t + "model", s.slider_guide.model,
           "line (a pressure along each face: conserves energy at any tilt), face (seed Eq. 18-19: one force per "
           "surface at the contact centroid; not conservative once tilted) or corners (Flores 2008)");
  v.choice(t + "rotation", s.slider_guide.rotation,
           "free (the seed: the slider's angle is a coordinate) or locked (an ideal anti-rotation constraint keeps it "
           "level: one coordinate fewer)");
  v.choice(t + "stiffness_model", s.slider_guide.stiffness_model,
           "contact_length (seed Eq. 11-12), flat_face (Eq. 11 at L_c = L_s) or given");
  v.number(t + "stiffness", s.slider_guide.stiffness, Rule::positive,
           "N/m^n, used when stiffness_model = \"given\"");
  visit_material(v, t + "guide.", s.slider_guide.guide);
  visit_contact(v, t + "contact.", s.slider_guide.contact);
  visit_friction(v, t + "friction.", s.slider_guide.friction, s.slider_guide.bristle_time_floor);
  visit_revolute(v, "joint.crank_ground.", s.crank_ground);
  visit_revolute(v, "joint.crank_conrod.", s.crank_conrod);
  visit_revolute(v, "joint.conrod_slider.", s.conrod_slider);
  v.choice("integrator.method", s.integrator.method,
           "rk4 (fixed step, the seed's method) or dopri5 (adaptive Dormand-Prince 5(4))");
  v.number("integrator.step", s.integrator.step, Rule::positive,
           "s; RK4's largest step (the step divides the crank period exactly)");
  v.number("integrator.relative_tolerance", s.integrator.relative_tolerance, Rule::positive, "dopri5");
  v.number("integrator.absolute_tolerance", s.integrator.absolute_tolerance, Rule::positive, "dopri5");
  v.number("integrator.max_step", s.integrator.max_step, Rule::positive, "s; dopri5's largest step");
  v.number("integrator.min_step", s.integrator.min_step, Rule::positive,
           "s; dopri5 reports step_underflow when it needs a smaller step");
  v.number("integrator.max_steps", s.integrator.max_steps, Rule::positive,
           "steps (accepted and rejected) before a run stops with step_limit");
  v.flag("integrator.locate_switches", s.integrator.locate_switches,
         "end steps where a contact opens or closes (located on the step's dense output), so no step "
         "integrates across the force's switch");
  v.choice("integrator.bristles", s.integrator.bristles,
           "LuGre bristle deflections: integrated (in the ODE state, rate capped by bristle_time_floor; RK4 "
           "needs step <= 2.5 x the floor) or exponential (the law's exact update at each stage's sliding "
           "speed; no cap, no step limit)");
  v.number("run.duration", s.run.duration, Rule::positive, "s, simulated after the transient");
  v.number("run.transient", s.run.transient, Rule::non_negative, "s, simulated and not written");
  v.number("run.output_interval", s.run.output_interval, Rule::non_negative,
           "s between time-series rows (0: none)");
  v.flag("run.stroboscopic", s.run.stroboscopic, "also sample once per crank revolution");
}

std::string node_text(const toml::node& n) {
  std::ostringstream os;
  if (auto s = n.as_string()) {
    os << '"' << s->get() << '"';
  } else if (auto i = n.as_integer()) {
    os << i->get();
  } else if (auto d = n.as_floating_point()) {
    os << format_number(d->get());
  } else if (auto b = n.as_boolean()) {
    os << (b->get() ? "true" : "false");
  } else {
    os << "(a " << n.type() << ")";
  }
  return os.str();
}

// Reads the keys present in a table into the scene, checking types and rules; records each key
// it knows so that the rest can be reported as unknown.
struct Reader {
  const toml::table& table;
  std::set<std::string> known;

  const toml::node* find(const std::string& key) {
    known.insert(key);
    return table.at_path(key).node();
  }
  void number(const std::string& key, double& out, Rule rule, std::string_view) {
    const toml::node* n = find(key);
    if (!n) return;
    double v;
    if (auto i = n->as_integer()) {
      v = static_cast<double>(i->get());
    } else if (auto d = n->as_floating_point()) {
      v = d->get();
    } else {
      throw InvalidParameter(key, node_text(*n), "must be a number");
    }
    if (!satisfies(rule, v)) throw InvalidParameter(key, node_text(*n), rule_text(rule));
    // A subnormal size or modulus passed "> 0" and overflowed what is computed from it: a Young's
    // modulus of 1e-320 gave "sigma_slider = inf", an inertia of 1e-320 a non-finite state (issue
    // 16, corrupt-file tier).
    if (rule == Rule::positive && v < std::numeric_limits<double>::min())
      throw InvalidParameter(key, node_text(*n), "must be at least 2.2e-308 (the smallest normal double)");
    out = v;
  }
  void flag(const std::string& key, bool& out, std::string_view) {
    const toml::node* n = find(key);
    if (!n) return;
    auto b = n->as_boolean();
    if (!b) throw InvalidParameter(key, node_text(*n), "must be true or false");
    out = b->get();
  }
  template <class E>
  void choice(const std::string& key, E& out, std::string_view) {
    const toml::node* n = find(key);
    if (!n) return;
    auto s = n->as_string();
    if (!s) throw InvalidParameter(key, node_text(*n), choices_text<E>());
    const auto& names = EnumNames<E>::names;
    for (std::size_t i = 0; i < std::size(names); ++i) {
      if (names[i] == s->get()) {
        out = static_cast<E>(i);
        return;
      }
    }
    throw InvalidParameter(key, node_text(*n), choices_text<E>());
  }
};

void collect_leaves(const toml::table& t, const std::string& prefix, std::vector<std::string>& out) {
  for (const auto& [k, node] : t) {
    const std::string key = prefix + std::string(k.str());
    if (auto sub = node.as_table()) {
      collect_leaves(*sub, key + ".", out);
    } else {
      out.push_back(key);
    }
  }
}

// Writes "key = value  # doc" lines grouped under [section] headers, in visiting order.
struct Writer {
  bool with_docs = false;
  std::ostringstream out;
  std::string section = "\x01";

  void line(const std::string& key, const std::string& value, std::string_view doc) {
    const auto dot = key.rfind('.');
    const std::string sec = dot == std::string::npos ? "" : key.substr(0, dot);
    const std::string name = dot == std::string::npos ? key : key.substr(dot + 1);
    if (sec != section) {
      if (section != "\x01") out << '\n';
      if (!sec.empty()) out << '[' << sec << "]\n";
      section = sec;
    }
    out << name << " = " << value;
    if (with_docs && !doc.empty()) out << "  # " << doc;
    out << '\n';
  }
  void number(const std::string& key, double& v, Rule, std::string_view doc) { line(key, format_number(v), doc); }
  void flag(const std::string& key, bool& v, std::string_view doc) { line(key, v ? "true" : "false", doc); }
  template <class E>
  void choice(const std::string& key, E& v, std::string_view doc) {
    std::string d(doc);
    if (with_docs) {
      d += " (";
      bool first = true;
      for (auto n : EnumNames<E>::names) {
        if (!first) d += " | ";
        d += n;
        first = false;
      }
      d += ")";
    }
    std::string value = "\"";
    value += EnumNames<E>::names[static_cast<std::size_t>(v)];
    value += '"';
    line(key, value, d);
  }
};

std::string write_scene(const Scene& scene, bool with_docs) {
  Scene copy = scene;
  Writer w;
  w.with_docs = with_docs;
  visit_fields(w, copy);
  return w.out.str();
}

// Inserts value (TOML syntax) at a dotted key, creating tables on the way.
void apply_override(toml::table& table, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InvalidParameter("--set", assignment, "must be KEY=VALUE, e.g. joint.slider.clearance=0.2e-3");
  }
  const std::string key = assignment.substr(0, eq);
  const std::string value = assignment.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    // A bare word is taken as a string, so --set joint.slider.model=corners works unquoted.
    try {
      parsed = toml::parse("v = \"" + value + "\"");
    } catch (const toml::parse_error&) {
      throw InvalidParameter(key, value, "must be a TOML value (a number, true/false or a string)");
    }
  }
  toml::table* t = &table;
  std::size_t start = 0;
  for (;;) {
    const auto dot = key.find('.', start);
    const std::string part = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (part.empty()) throw InvalidParameter(key, value, "the key has an empty part");
    if (dot == std::string::npos) {
      t->insert_or_assign(part, *parsed.get("v"));
      return;
    }
    auto* next = t->get(part);
    if (!next) {
      t->insert(part, toml::table{});
      next = t->get(part);
    }
    if (!next->is_table()) throw InvalidParameter(key, value, "'" + part + "' is a value, not a table");
    t = next->as_table();
    start = dot + 1;
  }
}

// The laws' own rules (a friction law's mu_s > 0 for LuGre, ...), refused under the scene key that
// holds the value ("joint.slider.friction.static_coefficient", not "static_coefficient").
void validate_laws(const std::string& joint, const ContactLawParameters& contact, const FrictionLawParameters& friction) {
  try {
    contact.validate();
  } catch (const InvalidParameter& e) {
    throw InvalidParameter(joint + ".contact." + e.key(), e.value(), e.rule());
  }
  try {
    friction.validate();
  } catch (const InvalidParameter& e) {
    throw InvalidParameter(joint + ".friction." + e.key(), e.value(), e.rule());
  }
}

void check_consistency(const Scene& s) {
  // The conrod must reach the guide line from every crank position (and the clearances only add
  // to the offset), so that the ideal-joint initial conditions and the ideal slider exist.
  // The message names every key in the sum: the one a user set wrong may be any of them.
  double reach = s.crank.length;
  std::string keys = "crank.length";
  for (auto [name, j] : {std::pair{"joint.crank_ground", &s.crank_ground}, std::pair{"joint.crank_conrod", &s.crank_conrod},
                         std::pair{"joint.conrod_slider", &s.conrod_slider}}) {
    if (j->kind != JointKind::clearance) continue;
    reach += j->clearance;
    keys += std::string(" + ") + name + ".clearance";
  }
  if (s.slider_guide.kind == JointKind::clearance) {
    reach += s.slider_guide.clearance;
    keys += " + joint.slider.clearance";
  }
  if (!(s.conrod.length > reach)) {
    throw InvalidParameter("conrod.length", format_number(s.conrod.length),
                           "must exceed " + keys + " (" + format_number(reach) +
                               " m), or the slider cannot stay on the guide");
  }
  // A tilted start: the slider needs its angle coordinate (a clearance guide) and must fit in the
  // guide at t = 0, its corners inside the clearance (a start in deep penetration is a collision,
  // not an initial state).
  if (s.initial.slider_angle != 0.0 || s.initial.slider_rate != 0.0) {
    if (s.slider_guide.kind != JointKind::clearance)
      throw InvalidParameter(s.initial.slider_angle != 0.0 ? "initial.slider_angle" : "initial.slider_rate",
                             format_number(s.initial.slider_angle != 0.0 ? s.initial.slider_angle
                                                                         : s.initial.slider_rate),
                             "needs joint.slider.type = \"clearance\": on an ideal guide the slider cannot turn");
    if (s.slider_guide.rotation == SliderRotation::locked)
      throw InvalidParameter(s.initial.slider_angle != 0.0 ? "initial.slider_angle" : "initial.slider_rate",
                             format_number(s.initial.slider_angle != 0.0 ? s.initial.slider_angle
                                                                         : s.initial.slider_rate),
                             "needs joint.slider.rotation = \"free\": a locked slider stays level");
    const double a = s.initial.slider_angle;
    const double half_extent = 0.5 * s.slider.length * std::abs(std::sin(a)) + 0.5 * s.slider.height * std::abs(std::cos(a));
    const double guide_half = 0.5 * s.slider.height + s.slider_guide.clearance;
    if (!(std::abs(a) < 1.0) || half_extent > guide_half)
      throw InvalidParameter("initial.slider_angle", format_number(a),
                             "must leave the tilted slider inside the guide at t = 0 (its corners reach " +
                                 format_number(half_extent) + " m from the guide's centre line, the guide surfaces are at " +
                                 format_number(guide_half) + " m)");
  }
  for (auto [name, j] : {std::pair{"joint.crank_ground", &s.crank_ground},
                         std::pair{"joint.crank_conrod", &s.crank_conrod},
                         std::pair{"joint.conrod_slider", &s.conrod_slider}}) {
    if (j->kind == JointKind::clearance && !(j->clearance < j->bearing_radius)) {
      throw InvalidParameter(std::string(name) + ".clearance", format_number(j->clearance),
                             "must be smaller than bearing_radius (" + format_number(j->bearing_radius) +
                                 " m): the journal radius would be <= 0");
    }
    if (j->kind == JointKind::clearance) validate_laws(std::string(name), j->contact, j->friction);
  }
  if (s.slider_guide.kind == JointKind::clearance)
    validate_laws("joint.slider", s.slider_guide.contact, s.slider_guide.friction);
  if (s.run.output_interval > 0.0 && s.run.output_interval > s.run.duration) {
    throw InvalidParameter("run.output_interval", format_number(s.run.output_interval),
                           "must not exceed run.duration (" + format_number(s.run.duration) + " s)");
  }
  if (!(s.integrator.min_step <= s.integrator.max_step)) {
    throw InvalidParameter("integrator.min_step", format_number(s.integrator.min_step),
                           "must not exceed integrator.max_step (" + format_number(s.integrator.max_step) + " s)");
  }
  auto lugre = [](const FrictionLawParameters& f) {
    return f.law == FrictionLaw::lugre_absolute || f.law == FrictionLaw::lugre_normalised;
  };
  for (auto [name, kind, f, floor] :
       {std::tuple{"joint.slider", s.slider_guide.kind, &s.slider_guide.friction, s.slider_guide.bristle_time_floor},
        std::tuple{"joint.crank_ground", s.crank_ground.kind, &s.crank_ground.friction, s.crank_ground.bristle_time_floor},
        std::tuple{"joint.crank_conrod", s.crank_conrod.kind, &s.crank_conrod.friction, s.crank_conrod.bristle_time_floor},
        std::tuple{"joint.conrod_slider", s.conrod_slider.kind, &s.conrod_slider.friction, s.conrod_slider.bristle_time_floor}}) {
    if (kind == JointKind::clearance && lugre(*f) && s.integrator.method == IntegratorMethod::rk4 &&
        s.integrator.bristles == BristleUpdate::integrated && s.integrator.step > 2.5 * floor * (1 + 1e-12)) {
      throw InvalidParameter("integrator.step", format_number(s.integrator.step),
                             "must be <= 2.5 x " + std::string(name) + ".friction.bristle_time_floor (" +
                                 format_number(floor) +
                                 " s): explicit RK4 is unstable on the LuGre bristle state beyond that "
                                 "(integrator.bristles = \"exponential\" has no such limit)");
    }
  }
  if (s.driver.free && s.run.stroboscopic)
    throw InvalidParameter("run.stroboscopic", "true",
                           "needs a driven crank: with driver.free = true the crank has no fixed period to sample at");
  if (s.integrator.method == IntegratorMethod::rk4 && s.integrator.step > s.driver.period()) {
    throw InvalidParameter("integrator.step", format_number(s.integrator.step),
                           "must not exceed the crank period, 60 / driver.speed_rpm = " +
                               format_number(s.driver.period()) + " s");
  }
  check_run_size(s);
}

}  // namespace

void check_run_size(const Scene& s) {
  if (s.integrator.max_steps > max_run_steps)
    throw InvalidParameter("integrator.max_steps", format_number(s.integrator.max_steps),
                           "must be at most " + format_number(max_run_steps));
  const double simulated = s.run.transient + s.run.duration;
  // RK4 steps the period in equal steps no longer than integrator.step; dopri5 needs at least
  // one step per integrator.max_step.
  const bool rk4 = s.integrator.method == IntegratorMethod::rk4;
  const double longest = rk4 ? s.driver.period() / std::ceil(s.driver.period() / s.integrator.step - 1e-9)
                             : s.integrator.max_step;
  const double steps = simulated / longest;
  // A step of 1e-320 s made this "needs inf RK4 steps of 0.0 s" without naming the step: the step's key and value are named, and an overflowing count is said so.
  if (!(steps <= max_run_steps))
    throw InvalidParameter("run.duration", format_number(s.run.duration),
                           "with run.transient " + format_number(s.run.transient) + " s and " +
                               (rk4 ? "integrator.step = " + format_number(s.integrator.step) + " s needs "
                                    : "integrator.max_step = " + format_number(s.integrator.max_step) + " s needs ") +
                               (std::isfinite(steps) ? format_number(steps) : std::string("more than 1e308")) +
                               (rk4 ? " RK4 steps" : " dopri5 steps") + ", more than the limit of " +
                               format_number(max_run_steps) + " steps");
  if (s.run.output_interval > 0.0) {
    const double rows = s.run.duration / s.run.output_interval;
    if (!(rows <= max_output_rows))
      throw InvalidParameter("run.output_interval", format_number(s.run.output_interval),
                             "gives " + format_number(rows) + " rows over run.duration " + format_number(s.run.duration) +
                                 " s, more than the limit of " + format_number(max_output_rows) +
                                 " rows (use a longer interval, or 0 with run.stroboscopic)");
  }
}

std::string_view default_scene_toml() {
  static const std::string text =
      "# The seed paper's slider-crank (Tables 1 and 2) with a translational clearance joint.\n"
      "# Keys the paper leaves open carry our choice; docs/reference/mechanism/scene.md says why. The slider joint\n"
      "# uses the reading that passes the physics audit (line contact, exponent 1, normalised LuGre with\n"
      "# sigma1 fading); the printed reading is model = \"face\", exponent = 1.5, law = \"lugre_absolute\",\n"
      "# sigma1_velocity = 0.\n\n" +
      write_scene(Scene{}, true);
  return text;
}

namespace {

// The longest key of TOML text, in dotted parts, and the line it starts on.
struct DeepestKey {
  std::size_t parts = 0;
  std::size_t line = 0;
};

// A lexical scan, not a parser: it finds the keys (at a line's start, after a table header's '['
// or '[[', after an inline table's '{' or ',') and counts their parts, skipping strings and
// comments so that dots in them do not count. Text that is not valid TOML is left to toml++ to
// refuse; the scan only has to find every key toml++ would read before its first error. A byte
// above 0x7F counts as a bare-key character, so a parser that accepts Unicode bare keys is covered.
DeepestKey deepest_key(std::string_view text) {
  const std::size_t n = text.size();
  std::size_t i = 0, line = 1;
  DeepestKey deepest;
  enum class At { line_start, key, value } at = At::line_start;
  std::vector<char> open;  // the arrays ('[') and inline tables ('{') the scan is inside
  auto bare = [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return std::isalnum(u) || c == '_' || c == '-' || u > 0x7F;
  };
  // Past the string that starts at i: '...' and "..." end at their quote or at the line's end (an
  // error toml++ reports), '''...''' and """...""" at their closing triple quote.
  auto skip_string = [&] {
    const char q = text[i];
    const bool basic = q == '"';
    const std::string triple(3, q);
    if (text.substr(i, 3) == triple) {
      i += 3;
      while (i < n && text.substr(i, 3) != triple) {
        if (basic && text[i] == '\\' && i + 1 < n && text[i + 1] != '\n') {
          i += 2;  // an escaped character, a quote among them
          continue;
        }
        if (text[i] == '\n') ++line;
        ++i;
      }
      i = std::min(n, i + 3);
      while (i < n && text[i] == q) ++i;  // up to two quotes may close the content
      return;
    }
    ++i;
    while (i < n && text[i] != q && text[i] != '\n')
      i += basic && text[i] == '\\' && i + 1 < n && text[i + 1] != '\n' ? 2 : 1;
    if (i < n && text[i] == q) ++i;
  };
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
      if (open.empty()) at = At::line_start;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
      continue;
    }
    if (c == '#') {
      while (i < n && text[i] != '\n') ++i;
      continue;
    }
    if (at == At::line_start && c == '[') {  // a table header: [a.b] or [[a.b]]
      i += text.substr(i, 2) == "[[" ? 2 : 1;
      at = At::key;
      continue;
    }
    if (at != At::value) {  // a key: parts separated by dots, whitespace allowed around them
      std::size_t parts = 0;
      const std::size_t key_line = line;
      for (;;) {
        while (i < n && (text[i] == ' ' || text[i] == '\t')) ++i;
        if (i < n && (text[i] == '"' || text[i] == '\'')) {
          skip_string();
        } else if (i < n && bare(text[i])) {
          while (i < n && bare(text[i])) ++i;
        } else {
          break;
        }
        ++parts;
        while (i < n && (text[i] == ' ' || text[i] == '\t')) ++i;
        if (i == n || text[i] != '.') break;
        ++i;
      }
      if (parts > deepest.parts) deepest = {parts, key_line};
      at = At::value;
      continue;
    }
    if (c == '"' || c == '\'') {
      skip_string();
      continue;
    }
    ++i;
    if (c == '[' || c == '{') open.push_back(c);
    if ((c == ']' || c == '}') && !open.empty()) open.pop_back();
    if (c == '{' || (c == ',' && !open.empty() && open.back() == '{')) at = At::key;
  }
  return deepest;
}

std::string key_parts_rule(std::size_t parts) {
  return "has " + std::to_string(parts) + " dotted parts; at most " + std::to_string(max_key_parts) +
         " are allowed (a scene key has at most four)";
}

// Refuses input beyond the bounds of scene.hpp (max_scene_bytes, max_key_parts,
// max_override_value_bytes) before toml++ sees it: the parser's stack and memory grow with them.
void check_input_bounds(std::string_view toml_text, const std::vector<std::string>& overrides, std::string_view source) {
  if (toml_text.size() > max_scene_bytes)
    throw InvalidParameter(std::string(source), "(the file)",
                           "is " + std::to_string(toml_text.size()) + " bytes; a scene file may have at most " +
                               std::to_string(max_scene_bytes) + " bytes");
  if (const DeepestKey k = deepest_key(toml_text); k.parts > max_key_parts)
    throw InvalidParameter(std::string(source), "(the file)",
                           "the scene key on line " + std::to_string(k.line) + " " + key_parts_rule(k.parts));
  for (const std::string& o : overrides) {
    const std::size_t eq = std::min(o.find('='), o.size());
    const std::size_t parts = 1 + static_cast<std::size_t>(std::count(o.begin(), o.begin() + eq, '.'));
    if (parts > max_key_parts)
      throw InvalidParameter("--set", o.substr(0, 40) + "...", "the scene key " + key_parts_rule(parts));
    const std::size_t value_bytes = o.size() - std::min(o.size(), eq + 1);
    if (value_bytes > max_override_value_bytes)
      throw InvalidParameter("--set", o.substr(0, std::min(eq, std::size_t{200})) + "=...",
                             "the value is " + std::to_string(value_bytes) + " bytes; at most " +
                                 std::to_string(max_override_value_bytes) + " are allowed");
  }
}

}  // namespace

Scene read_scene(std::string_view toml_text, const std::vector<std::string>& overrides, std::string_view source) {
  check_input_bounds(toml_text, overrides, source);
  toml::table table;
  try {
    table = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << e.description() << " (line " << e.source().begin.line << ", column " << e.source().begin.column << ")";
    throw InvalidParameter(std::string(source), "(the file)", "is not valid TOML: " + os.str());
  }
  for (const auto& o : overrides) apply_override(table, o);

  Scene scene;
  Reader reader{table, {}};
  visit_fields(reader, scene);
  std::vector<std::string> leaves;
  collect_leaves(table, "", leaves);
  for (const auto& key : leaves) {
    if (!reader.known.count(key)) {
      throw InvalidParameter(key, node_text(*table.at_path(key).node()),
                             "is not a scene key (`mechanism scene --default` lists them all)");
    }
  }
  check_consistency(scene);
  return scene;
}

std::string to_toml(const Scene& scene) { return write_scene(scene, false); }

namespace {

// The keys of to_toml's text as dotted names with their printed values, in the text's order.
std::vector<std::pair<std::string, std::string>> dotted_keys(const std::string& toml) {
  std::vector<std::pair<std::string, std::string>> keys;
  std::istringstream lines(toml);
  std::string table;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (line[0] == '[') {
      table = line.substr(1, line.find(']') - 1) + ".";
      continue;
    }
    const auto eq = line.find(" = ");
    if (eq == std::string::npos) continue;
    keys.emplace_back(table + line.substr(0, eq), line.substr(eq + 3));
  }
  return keys;
}

}  // namespace

namespace {

// Finds one key's unit in its documentation: the text before the first ',' or ';' ("m, gap per
// side"), else after the last ", " ("constant crank speed, rpm"), when that is one of the units the
// scene uses; anything else (a description, "dopri5", "mu_s") is no unit.
struct UnitFinder {
  std::string key, unit;
  static bool is_unit(const std::string& u) {
    static const std::set<std::string> units = {"m", "kg", "kg m^2", "Pa", "m/s", "m/s^2", "rad", "rad/s",
                                                "s", "rpm", "N/m", "N/m^n", "N s/m", "N", "1/m", "s/m"};
    return units.count(u) > 0;
  }
  void found(const std::string& k, std::string_view doc) {
    if (k != key) return;
    const std::string d(doc);
    const std::string first = d.substr(0, d.find_first_of(",;"));
    const auto comma = d.rfind(", ");
    if (is_unit(first)) unit = first;
    else if (comma != std::string::npos && is_unit(d.substr(comma + 2))) unit = d.substr(comma + 2);
  }
  void number(const std::string& k, double&, Rule, std::string_view doc) { found(k, doc); }
  void flag(const std::string&, bool&, std::string_view) {}
  template <class E>
  void choice(const std::string&, E&, std::string_view) {}
};

}  // namespace

std::string scene_key_unit(const std::string& key) {
  UnitFinder finder{key, {}};
  Scene scene;
  visit_fields(finder, scene);
  return finder.unit;
}

std::vector<std::string> scene_differences(const Scene& scene) {
  const auto builtin = dotted_keys(to_toml(Scene{}));
  std::map<std::string, std::string> base(builtin.begin(), builtin.end());
  std::vector<std::string> changed;
  for (const auto& [key, value] : dotted_keys(to_toml(scene))) {
    const auto it = base.find(key);
    if (it == base.end() || it->second != value) changed.push_back(key + " = " + value);
  }
  return changed;
}

std::vector<std::string> scene_warnings(const Scene& s) {
  std::vector<std::string> w;
  // The seed's Table 2 prints mu_s = 0.1 < mu_k = 0.11, and the built-in scene keeps that pair so that
  // it reproduces the paper (docs/reference/mechanism/scene.md says so, and why). A warning about it
  // on every run of the built-in scene told the user nothing they could act on; any other pair with
  // mu_s < mu_k is a scene's own choice and is still warned about.
  const FrictionLawParameters seed;
  auto check = [&](const std::string& name, JointKind kind, const FrictionLawParameters& f) {
    const bool seed_pair = f.static_coefficient == seed.static_coefficient && f.kinetic_coefficient == seed.kinetic_coefficient;
    if (kind == JointKind::clearance && f.law != FrictionLaw::none && f.stribeck_peak_missing() && !seed_pair) {
      w.push_back(name + ".friction: static_coefficient " + format_number(f.static_coefficient) +
                  " < kinetic_coefficient " + format_number(f.kinetic_coefficient) +
                  ": the Stribeck curve has no stiction peak (friction rises from rest instead of falling); "
                  "a static coefficient at least the kinetic one gives the usual peak");
    }
    if (kind == JointKind::clearance && f.has_state() && s.integrator.bristles == BristleUpdate::exponential &&
        f.sigma1 > 0 && f.sigma1_velocity == 0.0) {
      w.push_back(name + ".friction: integrator.bristles = \"exponential\" with a constant sigma1: its sigma1 dz/dt "
                  "term makes the update first order in the step (the energy-balance error only halves as the "
                  "step halves; docs/reference/mechanism/contact-and-friction.md, \"The exact bristle update\")");
    }
  };
  if (s.slider_guide.kind == JointKind::clearance && s.slider_guide.friction.has_state() &&
      s.slider_guide.friction.sigma1 > 0 && s.slider_guide.friction.sigma1_velocity == 0.0) {
    w.push_back("joint.slider.friction: LuGre with a constant sigma1 = " + format_number(s.slider_guide.friction.sigma1) +
                ": its damping term kicks the slider where the normal force changes fast (docs/reference/mechanism/model.md);"
                " joint.slider.friction.sigma1_velocity = 1e-3 fades it with speed (Canudas de Wit 2003)");
  }
  check("joint.slider", s.slider_guide.kind, s.slider_guide.friction);
  check("joint.crank_ground", s.crank_ground.kind, s.crank_ground.friction);
  check("joint.crank_conrod", s.crank_conrod.kind, s.crank_conrod.friction);
  check("joint.conrod_slider", s.conrod_slider.kind, s.conrod_slider.friction);
  return w;
}

}  // namespace mechanism
