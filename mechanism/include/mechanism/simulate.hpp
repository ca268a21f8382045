#pragma once
// The simulation loop: integrates a SliderCrank over the scene's run with the scene's integrator,
// handles the hybrid part between steps (contact onsets located on the step's dense output, the
// impact velocity latched there, memory committed), and hands time-series and stroboscopic
// samples to an observer (Odeint's system / stepper / observer split). An integration that cannot
// continue ends with a status, the time and the reason; it is never an exception. A run that
// reaches its end with an energy balance too far off to trust ends with energy_defect.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "mechanism/slider_crank.hpp"

namespace mechanism {

enum class SimulationStatus { completed, step_underflow, non_finite, step_limit, energy_defect };
const char* to_string(SimulationStatus status) noexcept;

// A run that reaches its end is `energy_defect` instead of `completed` when its energy-balance
// defect, relative to the largest kinetic energy, grows by more than this per crank revolution
// (energy_balance_relative / max(1, revolutions simulated)); the defect accumulates over a run, so
// the rate, not the total, tells a long good run from a short bad one. Measured
// (docs/reference/mechanism/model.md, "The energy balance"): sigma1 fading, dopri5 rtol 1e-4, 2e-8 per
// revolution; rtol 1e-3 with steps up to 1e-4 s (scripts/demo.sh) at most 1.2e-4; the scene as
// printed (constant sigma1) with RK4 at 5000 rpm at most 5e-3; the same at 50 rpm and 1e-6 m
// clearance 0.18, whose stroboscopic samples are the constant sigma1's kicks, not the
// mechanism. 0.03 is the geometric middle of the last two, six times from either.
inline constexpr double max_energy_defect_per_revolution = 0.03;
// The same limit holds for one step: a run is `energy_defect` when a single step changes the
// energy balance by more than a whole revolution's allowance, relative to the largest kinetic
// energy before that step. The average alone misses a blow-up: dopri5 at rtol 1e-2 with the
// exponential bristle update accepted steps that took the slider from 2.6 to 430 m/s and 3 mm into
// the guide at revolution 247 of 1010, and the run's average stayed at 1.3e-3 per revolution, because
// the largest kinetic energy it divides by grew a thousandfold with the error. Over 3.2 s of the
// audited scene the largest change per microsecond of good runs is 4e-8 (RK4 at 1e-6 s) to 4e-4
// (dopri5 rtol 1e-2); that blow-up's is 2.5 (docs/reference/mechanism/model.md, "The energy balance").

struct SimulationSummary {
  SimulationStatus status = SimulationStatus::completed;
  std::string message;        // empty when completed
  double end_time = 0.0;      // s, where the integration stopped
  std::size_t steps = 0;      // accepted steps
  std::size_t rejected_steps = 0;
  std::size_t rhs_evaluations = 0;
  double step = 0.0;          // RK4: the step used (a whole fraction of the crank period)
  double wall_seconds = 0.0;
  double max_penetration = 0.0;  // m, deepest penetration of any contact site at a step end
  std::size_t contact_events = 0;  // contact onsets
  // Steps ended early at a contact switch located inside them (integrator.locate_switches), each
  // followed by the rest of the step: the extra steps, counted in `steps` too.
  std::size_t located_switches = 0;
  // RK4 with Coulomb's law: steps ended where a held sliding direction reverses (counted in `steps`
  // too), and pieces taken again with sign(v) at each stage because a contact stuck (its velocity
  // reversed twice within one grid step: a sliding mode, where the held direction has no meaning).
  std::size_t located_reversals = 0, unlocated_reversals = 0;
  // max over step ends of |E(t) - E(0) - W_drive(t) - W_contact(t)| (J), E = kinetic + gravity;
  // and the same divided by the largest kinetic energy seen, a scale-free measure.
  double energy_balance_error = 0.0;
  double energy_balance_relative = 0.0;
  // max over steps of the change of E(t) - E(0) - W_drive(t) - W_contact(t) within the step,
  // divided by the largest kinetic energy before it (at the start: the starting kinetic energy).
  double energy_jump_relative = 0.0;
  std::size_t samples = 0;
  std::size_t stroboscopic_samples = 0;
  State final_state;  // the state at end_time (a parameter continuation starts the next run from it)
};

// One accepted step of the simulation loop as it is about to be committed.
struct StepRecord {
  double t0 = 0.0, t1 = 0.0;
  const State* x0 = nullptr;   // at t0, after the previous commit
  const State* x1 = nullptr;   // at t1, before this step's commit
  const Evaluation* at_end = nullptr;  // at (t1, x1) with the step's memory
  const std::vector<ContactMemory>* memory = nullptr;  // the memory the step ran with
  // Per site: the onset time located inside the step and the penetration rate there (what
  // commit() latches); NaN where the site did not start touching, and for an onset whose located
  // rate was not positive (a graze: commit() latches the step end's rate).
  const std::vector<double>* onset_time = nullptr;
  const std::vector<double>* onset_rate = nullptr;
  // The site whose held sliding direction reverses at t1, after commit() (the step ended at the
  // reversal, SliderCrank::holds_sliding_direction), or -1.
  std::ptrdiff_t reversal = -1;
};

struct SimulationObserver {
  // A time-series row every run.output_interval after the transient.
  std::function<void(double t, const State& x, const Evaluation& ev)> sample;
  // Once per crank revolution after the transient, at the initial crank angle, whenever this is
  // set (`mechanism simulate` sets it for run.stroboscopic).
  std::function<void(std::size_t revolution, double t, const State& x, const Evaluation& ev)> stroboscopic;
  // Fraction of the simulated time done, called about every percent.
  std::function<void(double fraction)> progress;
  // After each accepted step, before commit(): what an integration of the variational equations
  // along the run needs (scene_lyapunov's saltation method, saltation.hpp).
  std::function<void(const StepRecord& step)> step;
};

// Runs the scene of `system` from its initial state (seed Eq. 29).
SimulationSummary simulate(SliderCrank& system, const SimulationObserver& observer = {});

// Runs it from `start` at t = 0 (a state of system.state_size() finite values, e.g. another run's
// final_state: parameter continuation). The work accumulators restart at zero, so the energy
// balance is checked from there on; a site already penetrating at the start latches its current
// penetration rate as its impact velocity.
SimulationSummary simulate(SliderCrank& system, const State& start, const SimulationObserver& observer = {});

}  // namespace mechanism
