#pragma once
// The Lyapunov exponents of a scene from its equations of motion, not from a measured series.
//
// The crank turns at constant speed, so the equations are periodic in t with the crank period T:
// one period of simulate() is one iteration of an autonomous map of the phase point (the
// stroboscopic map), the composition of m maps over the intervals T/m between renormalisations. finite_difference_lyapunov.hpp runs Benettin's renormalisation on that map with
// k + 1 copies of the system, each carrying its own contact memory, so contact onsets, releases,
// latched impact velocities and bristle resets are all inside the map; no saltation matrix is
// needed. LyapunovMethod::saltation carries variational equations with saltation matrices instead
// (saltation.hpp). The phase point is (q, q_dot, z): the generalised coordinates, their rates and the LuGre
// bristle deflections; the work accumulators are bookkeeping, not dynamics, and are left out.
//
// The period map's exponents mu_j are the flow's exponents times T; the flow in the extended
// phase space (with the crank phase) has one more exponent, 0, along the time direction. So
// lambda_j = mu_j / T (1/s), the section's Kaplan-Yorke dimension is that of the mu_j, and the
// attractor's is one more.
//
// Coordinates of different units are compared through a scale: the standard deviation of each
// coordinate over one period after the transient, sampled 200 times per interval (its mean
// magnitude where it does not move, 1 where it is 0). A mechanical coordinate whose spread is at most
// 1e3 epsilon times the largest spread or mean of its kind (positions, rates) did not move: a level
// slider's angle of rounding size. The perturbation is relative to that scale.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "mechanism/scene.hpp"

namespace mechanism {

// How the tangents of the period map are computed.
//   benettin:  finite differences of k + 1 trajectories (finite_difference_lyapunov.hpp);
//   saltation: the variational equations along the reference trajectory, with Müller's jump
//              matrices at its contact onsets and releases (saltation.hpp); RK4 scenes without
//              Coulomb friction (saltation_unsupported says why not).
enum class LyapunovMethod { benettin, saltation };
const char* to_string(LyapunovMethod method) noexcept;

struct SceneLyapunovOptions {
  LyapunovMethod method = LyapunovMethod::benettin;
  // Saltation only: the variations of the latched impact velocities go on across the
  // renormalisations (the map's derivative). false zeroes them there, which is what Benettin's
  // companions do, each restarting with the reference's memory: for measuring that difference.
  bool carry_latched_variations = true;
  int exponents = 0;                 // k leading exponents; 0: all of them (the phase-space dimension)
  // delta, relative to each coordinate's scale; at least the floor (perturbation_digits below)
  double perturbation = 1e-8;
  std::size_t transient_periods = 20;  // periods that align the directions (after run.transient)
  std::size_t periods = 200;         // periods averaged
  // Renormalisations per crank period: the separations must stay small within one interval, and
  // contacts stretch them fast (the seed scene: about e^20 per period).
  int intervals_per_period = 50;
  std::uint64_t seed = 1;            // the initial directions
  // The state to start from (SliderCrank::state_size() values, e.g. a run's final_state: a sweep
  // point's attractor); empty: the seed's Eq. 29. run.transient is run from it either way. Contact
  // memory starts empty: a site already penetrating latches its current rate (as simulate() does).
  std::vector<double> start;
  std::function<void(double fraction)> progress;
  void validate() const;             // throws InvalidParameter naming the option
};

// The perturbation's floor. A difference quotient keeps about three digits only where the
// separation is a thousand times the rounding it is computed through: each coordinate is stored to
// machine epsilon times its magnitude, and each integrator step rounds it again, so after the n steps
// of one interval the rounding is at most n epsilon |x_i|. In scaled coordinates the floor is
//   perturbation_digits x epsilon x n x max_i max_t |x_i(t)| / scale_i,
// the maximum over the sampled period, taken as at least 1 (for a coordinate that moves,
// max |x_i| >= its root mean square >= its standard deviation anyway), so the floor is never below
// min_perturbation, which validate() refuses before any integration. scene_lyapunov refuses a
// perturbation below the scene's floor (InvalidParameter naming it). Measured on the built-in scene
// (docs/reference/mechanism/lyapunov.md): the floor is 2.4e-10, and the exponents drift upward
// below about 1e-9 as the rounding takes over.
inline constexpr double perturbation_digits = 1e3;
inline constexpr double min_perturbation = perturbation_digits * std::numeric_limits<double>::epsilon();

// A separation that grows beyond this (in scaled coordinates) within one interval has left the
// linear range of most contacts: the result's status is then `nonlinear`.
inline constexpr double max_linear_separation = 1e-3;

struct SceneLyapunov {
  // completed (every exponent finite); not_finite (some exponent is -inf or NaN: a direction
  // collapsed to zero within an interval, which the bristles' reset at release does, as the map is
  // not invertible there; message names them and why); nonlinear (see max_linear_separation: repeat with
  // a smaller perturbation); invariant_subspace (a coordinate did not move: the orbit is confined to a subspace, such as a
  // level slider without friction, and the exponents are those of that set and of the growth
  // transverse to it); trajectory_failed (a period could not be integrated: message says why; no
  // exponents are reported, only the running means up to the failure).
  std::string status = "completed";
  std::string message;
  std::string method = "benettin";       // to_string(LyapunovMethod)
  bool latched_variations_carried = false;  // saltation: options.carry_latched_variations
  std::vector<std::string> coordinates;  // the phase-space coordinates, in the state's order
  std::vector<double> scale;             // their scales
  double period = 0.0;                   // s, one crank period (one iteration)
  std::size_t periods = 0;               // periods averaged
  // benettin: delta; saltation: the central differences' step of J v (SaltationTangents::jacobian_step),
  // relative to each coordinate's scale. The floor and the largest separation are Benettin's (0
  // for saltation, whose tangents are linear by construction).
  double perturbation = 0.0;
  // The floor the perturbation was checked against (perturbation_digits above), its parts: the
  // most integrator steps in one interval and the largest |coordinate| / scale, with its name.
  double perturbation_floor = 0.0;
  std::size_t steps_per_interval = 0;
  double largest_scaled_coordinate = 0.0;
  std::string largest_scaled_name;
  double largest_separation = 0.0;       // delta times the largest growth within one interval
  std::vector<double> exponents;         // 1/s, lambda_j = mu_j / T, in QR order
  // 1/s: a direction that contracts faster than this loses all its digits within one interval
  // (ln of double's epsilon per interval), so exponents near or below it are bounds, not values
  // (the LuGre bristles' relaxation, for instance).
  double resolution_limit = 0.0;
  std::vector<double> standard_error;    // 1/s, from 10 block means
  std::vector<double> exponents_per_period;  // mu_j
  std::vector<std::size_t> collapsed;    // per exponent: periods in which its direction collapsed
  // Kaplan-Yorke of the section (from the mu_j) and of the attractor (one more); NaN when the
  // k exponents computed do not reach a negative partial sum (the dimension is then at least k).
  double kaplan_yorke_section = std::numeric_limits<double>::quiet_NaN();
  double kaplan_yorke = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> running;           // 1/s: periods x k running means, row-major
  double wall_seconds = 0.0;
};

// Kaplan & Yorke (1979): j + (x_1 + ... + x_j) / |x_(j+1)| with j the largest index whose partial
// sum of the descending exponents is >= 0; 0 when x_1 < 0; NaN when every partial sum is >= 0 (the
// exponents given do not bound the dimension) or an exponent is NaN.
double kaplan_yorke_dimension(std::vector<double> exponents);

SceneLyapunov scene_lyapunov(const Scene& scene, const SceneLyapunovOptions& options = {});

// The status and message of a run that was not cut short, from its exponents, collapse counts and
// largest separation (scene_lyapunov's last step, apart so that each rule can be tested): not_finite
// when any exponent is -inf or NaN (before every other rule: such a run is never completed; the
// message names the exponents, and blames the bristle reset only where the scene has bristles,
// `bristles`), then nonlinear, then invariant_subspace (`still` names the coordinates that did not
// move; empty: none), else completed.
void assign_status(SceneLyapunov& result, const std::string& still, bool bristles);

}  // namespace mechanism
