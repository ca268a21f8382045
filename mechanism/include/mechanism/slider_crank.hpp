#pragma once
// The slider-crank as an ODE system built from a scene. It models only what the scene requires:
// the generalised coordinates are chosen from the joints (an ideal joint adds none and no contact
// code), and each clearance joint adds its coordinates and its contact sites, each with the
// memory its laws need (the impact velocity latched at onset; the LuGre bristle deflection).
//
// Coordinates (when present, in this order):
//   crank_angle                    theta_2, only when the crank is free (driver.free)
//   crank_pivot_x, crank_pivot_y   crank-ground clearance: the crank's journal centre
//   conrod_pin_x, conrod_pin_y     crank-conrod clearance: the conrod's bearing centre at its first pin
//   conrod_angle                   theta_3; dependent (not a coordinate) when the slider is ideally
//                                  pinned to the conrod and ideally guided
//   slider_x, slider_y             conrod-slider clearance: the slider's centre (slider_y only when
//                                  the translational joint has clearance)
//   slider_angle                   translational clearance: theta_4
// The crank turns at constant speed (its angle is prescribed), unless it is free. The seed's scene (translational
// clearance only) integrates conrod_angle and slider_angle: seed Eq. 27.
//
// Continuous state x = (q, q_dot, W_drive, W_contact, z): W_drive and W_contact integrate the work
// of the driving torque and of all contact and friction forces, so the energy balance
// E(t) - E(0) = W_drive + W_contact checks the integration; z holds the LuGre bristle deflection
// of each site whose law is LuGre (integrated with the same order as the mechanics, or updated
// exactly for each stage's sliding speed: integrator.bristles; its relaxation rate is capped by the
// joint's bristle_time_floor, and it is reset to zero when the contact opens). The equations of motion are the
// principle of virtual power over the three moving bodies, with Jacobians and bias accelerations
// from kinematic jets (kinematic_jet.hpp); for the seed's topology the same equations are written
// out in closed form (a diagonal mass matrix), which is what the right-hand side's speed needs.
// Evaluations use no shared mutable state: SliderCrank objects may run in parallel, one per thread.
//
// Discrete memory (per contact site) changes only between integrator steps, in commit(): during
// a step's stages every site sees the memory of the step's start, so rejected or repeated stages
// are reproducible.

#include <array>
#include <string>
#include <vector>

#include "mechanism/ode.hpp"
#include "mechanism/scene.hpp"

namespace mechanism {

// Where the slider touches the guide, after Flores et al. 2008.
enum class SliderConfiguration {
  free_flight = 0,   // no corner penetrates
  one_corner = 1,    // a single corner
  flat = 2,          // two adjacent corners on the same surface
  jammed = 3,        // two diagonally opposite corners, one on each surface
  other = 4,         // any other combination (deep penetration)
};

enum class SiteKind { slider_face_upper, slider_face_lower, slider_corner, journal };

// Memory of one contact site between steps.
struct ContactMemory {
  bool touching = false;         // penetrating at the end of the last accepted step
  double impact_velocity = 0.0;  // penetration rate latched at onset (m/s)
  // Coulomb's law on the RK4 grid (SliderCrank::holds_sliding_direction): the sign of the sliding
  // velocity the friction force opposes throughout the step, +1 or -1; 0 (before the first step in
  // contact ends, or after a reversal that could not be located) falls back to sign(v) at each stage.
  int sliding_direction = 0;
};

// One contact site's state at an evaluation.
struct SiteEvaluation {
  double penetration = 0.0;       // > 0 in contact (the deepest corner for a slider face)
  double penetration_rate = 0.0;  // > 0 approaching
  double normal_force = 0.0;      // N, >= 0
  double friction_force = 0.0;    // N, along the tangent, opposing the sliding velocity
  double sliding_velocity = 0.0;  // m/s
  double deflection = 0.0;        // LuGre bristle deflection (0 for the other laws)
  double deflection_rate = 0.0;   // its time derivative
  double contact_length = 0.0;    // slider faces: L_c of seed Eq. 12
  double stiffness = 0.0;         // the stiffness used
};

// Everything the equations produce at (t, x): used by the right-hand side, by commit() and by
// the outputs, so all three see the same numbers.
struct Evaluation {
  std::vector<double> q_ddot;
  double crank_angle = 0.0;
  std::array<double, 3> slider_pose{};       // x, y, angle of the slider centre
  std::array<double, 3> slider_velocity{};   // their rates
  std::array<double, 3> slider_acceleration{};
  double conrod_angle = 0.0, conrod_rate = 0.0;
  double driving_torque = 0.0;      // N m on the crank, keeping its speed constant
  double drive_power = 0.0;         // driving_torque * omega
  double contact_power = 0.0;       // power of all contact and friction forces on the bodies
  double kinetic_energy = 0.0;
  double potential_energy = 0.0;    // gravity
  std::vector<SiteEvaluation> sites;
  SliderConfiguration configuration = SliderConfiguration::free_flight;
  // Penetration of the slider's corners TL, TR, BL, BR (> 0 beyond the guide surface; 0 when the
  // slider-guide joint is ideal).
  std::array<double, 4> corner_penetration{};
  // Journal eccentricity (journal centre minus bearing centre) for each revolute clearance joint,
  // in the order of joint_names().
  std::vector<std::array<double, 2>> eccentricity;
};

class SliderCrank {
 public:
  explicit SliderCrank(const Scene& scene);

  const Scene& scene() const { return scene_; }
  int coordinate_count() const { return n_; }
  int state_size() const { return 2 * n_ + 2 + bristles_; }
  // The phase point (q, q_dot, z): the state less the two work accumulators, which no force
  // depends on. Its dimension is the number of Lyapunov exponents (scene_lyapunov.hpp).
  int phase_dimension() const { return 2 * n_ + bristles_; }
  Eigen::VectorXd phase_point(const State& x) const {
    Eigen::VectorXd p(phase_dimension());
    p.head(2 * n_) = x.head(2 * n_);
    p.tail(bristles_) = x.tail(bristles_);
    return p;
  }
  // Writes p into x's (q, q_dot, z), leaving the work accumulators as they are.
  void set_phase_point(State& x, const Eigen::VectorXd& p) const {
    x.head(2 * n_) = p.head(2 * n_);
    x.tail(bristles_) = p.tail(bristles_);
  }
  // Index in the state of site i's bristle deflection, or -1 when its friction law has no state.
  int bristle_index(std::size_t i) const { return sites_[i].state; }
  const std::vector<std::string>& coordinate_names() const { return names_; }
  // Revolute clearance joints modelled, e.g. {"crank_conrod"}.
  const std::vector<std::string>& journal_names() const { return journal_names_; }
  std::size_t site_count() const { return sites_.size(); }
  SiteKind site_kind(std::size_t i) const { return sites_[i].kind; }

  // The seed's Eq. 29: the ideal mechanism's pose and velocities at t = 0 (clearance coordinates
  // at the centre of their clearance, slider level), work accumulators at zero.
  State initial_state() const;

  // The ODE right-hand side (OdeSystem).
  void rhs(double t, const State& x, State& dxdt) const;

  // ErrorWeightedSystem: weight 0 for the bristle deflection of every LuGre site that is open at
  // (t, x) (commit() resets it to zero there, so its value at a step end is never used), else 1.
  void error_weights(double t, const State& x, State& weights) const;
  // WeightedRhsSystem: rhs() and error_weights() at (t, x) from one evaluation of the equations.
  void rhs_and_error_weights(double t, const State& x, State& dxdt, State& weights) const;
  // The same and evaluate()'s output, from that one evaluation: what the simulation loop reads at
  // a step's end, where the adaptive stepper evaluates anyway (simulate.cpp).
  void rhs_and_error_weights(double t, const State& x, State& dxdt, State& weights, Evaluation& out) const;

  // Full evaluation at (t, x) with the current memory.
  void evaluate(double t, const State& x, Evaluation& out) const;
  // The same through the kinematic jets whatever the topology: evaluate() and rhs() use a closed
  // form for the seed's topology (clearance only in the slider-guide joint), tested against this.
  void evaluate_with_jets(double t, const State& x, Evaluation& out) const;

  // After an accepted step ending at (t, x), given the evaluation there made with the step's
  // memory: latch impact velocities at onsets (onset_rate[i] is the penetration rate at the
  // located onset time for sites that started touching during the step, NaN or absent otherwise),
  // forget them at release and unload the bristles there (z = 0 in x). With the exponential
  // bristle update, also write each touching site's deflection at t into x and start the next
  // step's bristle clock at t. Returns true when this changed x or the right-hand side at x (the
  // stepper's cached first stage is then stale).
  bool commit(double t, const Evaluation& at_end, const std::vector<double>& onset_rate, State& x);
  // A run that starts at t from a state whose bristle deflections hold at t (simulate() calls it
  // first; with the exponential update every evaluation reads the time elapsed since then or since
  // the last commit).
  void start_bristle_clock(double t) { bristle_epoch_ = t; }

  // The functions whose zeros switch a contact force on or off or change its formula: the slider's
  // four corner penetrations (when its joint has clearance: every slider model's force is smooth
  // between their zeros) and each journal's penetration, from an evaluation. The simulation ends
  // its steps on these zeros (integrator.locate_switches, simulate.cpp).
  void switching_functions(const Evaluation& ev, std::vector<double>& g) const;

  // Whether site i's friction is Coulomb's law (mu_k > 0) on the RK4 grid. Its force jumps by
  // 2 mu F_N where the sliding velocity reverses, and a fixed step that straddles the jump is
  // neither accurate nor a differentiable map of its start; so such a site opposes the direction
  // held in its memory (commit() sets it from the step end's velocity when the site has none), and
  // simulate() ends the step where the velocity reverses and reverses the direction there
  // (set_sliding_direction). Under dopri5 the step-size control resolves the jump, and every stage
  // uses sign(v).
  bool holds_sliding_direction(std::size_t i) const { return sites_[i].holds_direction; }
  void set_sliding_direction(std::size_t i, int direction) { memory_[i].sliding_direction = direction; }

  const std::vector<ContactMemory>& memory() const { return memory_; }
  // Replaces the memory (one entry per site, as memory() returns): how a trajectory that is
  // continued by another SliderCrank of the same joints (a later crank phase) keeps its contacts.
  void set_memory(const std::vector<ContactMemory>& memory);
  double omega() const { return omega_; }

 private:
  struct Site {
    SiteKind kind;
    int joint = -1;     // for journals: index into the revolute joints modelled
    int corner = -1;    // for slider corners: 0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right
    int state = -1;     // index of the bristle deflection in the state (LuGre), else -1
    double chi = 0.0;   // hysteresis factor of its normal law (checked once, in the constructor)
    bool holds_direction = false;  // Coulomb's law on the RK4 grid (holds_sliding_direction)
  };
  // At most four slider sites (corners) and three journals.
  static constexpr std::size_t max_sites = 7;
  // An evaluation in fixed-size storage (slider_crank.cpp): rhs() fills one on the stack, so the
  // right-hand side neither allocates nor touches shared scratch (one SliderCrank per thread).
  struct Result;
  // The equations at (t, x) with jets of `Columns` columns (>= n + 1) and, when Coordinates >= 0,
  // n fixed at compile time.
  template <int Columns, int Coordinates>
  void compute_jets(double t, const State& x, Result& r) const;
  // The closed form where it applies (unless jets_only), else the narrowest jet width.
  void compute(double t, const State& x, Result& r, bool jets_only = false) const;
  // The seed's topology (clearance only in the slider-guide joint) in closed form.
  void compute_seed(double t, const State& x, Result& r) const;
  // dx/dt from an evaluation at (t, x), and the error weights' zeros (bristles of open sites).
  void derivatives_of(const Result& r, const State& x, State& dxdt) const;
  void weights_of(const Result& r, State& weights) const;
  // The slider's contact sites (the first slider_sites_ sites) at the slider's pose (x, y, angle)
  // and its rates: fills their SiteEvaluations, adds their force and moment about the slider's
  // centre to load, and returns the corner penetrations (TL, TR, BL, BR).
  void slider_contacts(const double pose[3], const double rate[3], const State& x, Result& r, double load[3],
                       double corner_pen[4]) const;
  // A revolute clearance joint, named by position rather than by pointer so that a copy of the
  // system (a companion trajectory, finite_difference_lyapunov.hpp) reads its own scene.
  struct Journal {
    int which;  // 0 crank_ground, 1 crank_conrod, 2 conrod_slider
    double stiffness;
  };
  const RevoluteJoint& revolute(const Journal& j) const {
    return j.which == 0 ? scene_.crank_ground : (j.which == 1 ? scene_.crank_conrod : scene_.conrod_slider);
  }

  Scene scene_;
  int n_ = 0;
  int idx_crank_angle_ = -1, idx_crank_pivot_ = -1, idx_conrod_pin_ = -1, idx_conrod_angle_ = -1;
  int idx_slider_x_ = -1, idx_slider_y_ = -1, idx_slider_angle_ = -1;
  bool slider_clearance_ = false;
  double omega_ = 0.0;
  double slider_flat_stiffness_ = 0.0;  // Eq. 11 at L_c = L_s, or the given value
  double slider_compliance_ = 0.0, guide_compliance_ = 0.0;  // seed Eq. 13
  std::vector<std::string> names_;
  std::vector<std::string> journal_names_;
  std::vector<Journal> journals_;
  std::vector<Site> sites_;
  std::vector<ContactMemory> memory_;
  int bristles_ = 0;
  bool exponential_bristles_ = false;  // integrator.bristles = "exponential" and some site has LuGre
  double bristle_epoch_ = 0.0;         // when the state's deflections were written (commit)
  int jet_columns_ = 9;           // the jet width compute() uses: n + 1 rounded up to 3, 5 or 9
  std::size_t slider_sites_ = 0;  // sites_ starts with the slider's (2 faces or 4 corners)
  bool seed_topology_ = false;    // compute_seed applies
};

}  // namespace mechanism
