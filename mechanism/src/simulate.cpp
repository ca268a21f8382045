#include "mechanism/simulate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "mechanism/dormand_prince.hpp"
#include "mechanism/error.hpp"
#include "mechanism/event_location.hpp"
#include "mechanism/rk4.hpp"

namespace mechanism {

const char* to_string(SimulationStatus status) noexcept {
  switch (status) {
    case SimulationStatus::completed: return "completed";
    case SimulationStatus::step_underflow: return "step_underflow";
    case SimulationStatus::non_finite: return "non_finite";
    case SimulationStatus::step_limit: return "step_limit";
    case SimulationStatus::energy_defect: return "energy_defect";
  }
  return "unknown";
}

namespace {

// The slider-crank as the adaptive stepper sees it, keeping the evaluation of each attempt's last
// stage: at (t_new, x_new), the step end, which the stepper evaluates for its error weights and
// the next step's first stage. After an accepted step the loop reads the contacts and energies
// there from it instead of evaluating the equations once more (one evaluation in seven).
class RecordingSystem {
 public:
  explicit RecordingSystem(const SliderCrank& system) : sys_(system) {}
  void rhs(double t, const State& x, State& dxdt) const { sys_.rhs(t, x, dxdt); }
  void error_weights(double t, const State& x, State& w) const { sys_.error_weights(t, x, w); }
  void rhs_and_error_weights(double t, const State& x, State& dxdt, State& w) const {
    sys_.rhs_and_error_weights(t, x, dxdt, w, last_);
    last_t_ = t;
    last_x_ = x;
    recorded_ = true;
  }
  // The recorded evaluation if it was made at exactly (t, x) with the memory the system has now.
  const Evaluation* recorded(double t, const State& x) const {
    return recorded_ && t == last_t_ && detail::same_state(x, last_x_) ? &last_ : nullptr;
  }
  // The system's memory is about to change (commit): the record no longer describes it.
  void forget() { recorded_ = false; }

 private:
  const SliderCrank& sys_;
  // The stepper holds the system by const reference; the record is this adapter's own state,
  // used by one loop on one thread.
  mutable Evaluation last_;
  mutable State last_x_;
  mutable double last_t_ = 0.0;
  mutable bool recorded_ = false;
};

// Everything that happens between two accepted steps, for either stepper.
template <class Stepper>
class HybridLoop {
 public:
  // recorder: the adaptive stepper's view of the system, whose step-end evaluations after_step
  // reuses (null for RK4, whose last stage is not at the step end).
  HybridLoop(SliderCrank& system, Stepper& stepper, const SimulationObserver& observer, SimulationSummary& summary,
             RecordingSystem* recorder = nullptr)
      : sys_(system), stepper_(stepper), obs_(observer), sum_(summary), rec_(recorder) {
    const Scene& s = sys_.scene();
    t_end_ = s.run.transient + s.run.duration;
    transient_ = s.run.transient;
    out_dt_ = s.run.output_interval;
    period_ = s.driver.period();
    // Time-series rows at transient + k dt; revolutions at whole periods from the transient on.
    next_out_ = 0;
    next_rev_ = static_cast<std::size_t>(std::ceil(transient_ / period_ - 1e-9));
    locate_ = s.integrator.locate_switches;
    onset_rate_.assign(sys_.site_count(), std::numeric_limits<double>::quiet_NaN());
    onset_time_ = onset_rate_;
  }

  double end_time() const { return t_end_; }

  // At t = 0: the first evaluation, the energy reference and a sample if the transient is 0.
  void start(const State& x) {
    sys_.start_bristle_clock(0.0);
    sys_.evaluate(0.0, x, ev_);
    energy0_ = ev_.kinetic_energy + ev_.potential_energy;
    kinetic_max_ = ev_.kinetic_energy;
    penetration_prev_.resize(sys_.site_count());
    sliding_prev_.resize(sys_.site_count());
    for (std::size_t i = 0; i < sys_.site_count(); ++i) {
      penetration_prev_[i] = ev_.sites[i].penetration;
      sliding_prev_[i] = ev_.sites[i].sliding_velocity;
    }
    if (locate_) sys_.switching_functions(ev_, switch_prev_);
    emit_due(0.0, x, true);
    State x0 = x;
    sys_.commit(0.0, ev_, onset_rate_, x0);
    if (obs_.step) x_start_ = x;
  }

  // The evaluation at the end (t1, x) of the step just taken, which find_switch and after_step
  // read: the adaptive stepper's record when it made one there, else one evaluation. With
  // integrator.locate_switches, also the switching functions there.
  void evaluate_end(double t1, const State& x) {
    const Evaluation* recorded = rec_ ? rec_->recorded(t1, x) : nullptr;
    if (recorded)
      ev_ = *recorded;
    else
      sys_.evaluate(t1, x, ev_);
    if (locate_) sys_.switching_functions(ev_, switch_now_);
  }

  // After evaluate_end: whether the step [t0, t1] just taken should end earlier, at tc, the earliest
  // zero of a switching function (SliderCrank::switching_functions) that changed sign inside it,
  // located on the step's dense output to a millionth of the step (locate_crossing's `after` end:
  // the first time at which the function has its new sign). False without
  // integrator.locate_switches, and when that zero lies within `margin` of either end of the step.
  bool find_switch(double t0, double t1, double margin, double& tc) {
    if (!locate_) return false;
    bool found = false;
    tc = t1;
    for (std::size_t i = 0; i < switch_now_.size(); ++i) {
      if ((switch_prev_[i] > 0.0) == (switch_now_[i] > 0.0)) continue;
      auto g = [&](double t) {
        stepper_.interpolate(t, scratch_);
        sys_.evaluate(t, scratch_, probe_);
        sys_.switching_functions(probe_, switch_probe_);
        return switch_probe_[i];
      };
      const double tol = std::max(1e-15, 1e-6 * (t1 - t0));
      const double ti = locate_crossing(g, t0, t1, switch_prev_[i], switch_now_[i], tol);
      if (ti < tc) tc = ti;
      found = true;
    }
    return found && tc - t0 > margin && t1 - tc > margin;
  }

  // After evaluate_end, on the RK4 grid: the earliest time in (t0, t1] at which a site that holds a
  // sliding direction (SliderCrank::holds_sliding_direction) sees its sliding velocity reverse,
  // located on the step's dense output, which the held direction keeps smooth. `done[i]`: site i
  // reversed earlier in this grid step; a second reversal there is a sliding mode (the contact
  // sticks: with either direction held the velocity is driven back through zero), returned as
  // `sticks` with no time. Unlike find_switch there is no margin: a reversal is located however
  // close to an end of the step it lies, so the state at t1 stays a continuous function of the
  // state at t0 (the Lyapunov map's requirement, scene_lyapunov.hpp).
  enum class Reversal { none, located, sticks };
  Reversal find_reversal(double t0, double t1, const std::vector<char>& done, double& tr, std::size_t& site) {
    Reversal out = Reversal::none;
    tr = t1;
    const auto& memory = sys_.memory();
    for (std::size_t i = 0; i < sys_.site_count(); ++i) {
      const int d = memory[i].sliding_direction;
      if (!sys_.holds_sliding_direction(i) || d == 0 || !memory[i].touching) continue;
      const double g1 = d * ev_.sites[i].sliding_velocity;
      if (!(g1 < 0.0)) continue;
      const double g0 = d * sliding_prev_[i];
      if (done[i] || !(g0 > 0.0)) {  // reversed already in this step, or back across zero at once
        site = i;
        return Reversal::sticks;
      }
      auto g = [&](double t) {
        stepper_.interpolate(t, scratch_);
        sys_.evaluate(t, scratch_, probe_);
        return d * probe_.sites[i].sliding_velocity;
      };
      // To the last bits of t: the crossing time's error moves the state by (f+ - f-) times it,
      // and the map's derivative across the reversal (Mueller's saltation) assumes none.
      const double tol = 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t0), std::abs(t1));
      const double ti = locate_crossing(g, t0, t1, g0, g1, std::max(tol, 1e-300));
      if (ti < tr || out == Reversal::none) {
        tr = ti;
        site = i;
      }
      out = Reversal::located;
    }
    return out;
  }

  // After an accepted step from t0 to t1 (x is the state at t1, evaluate_end called there);
  // `reversal`: the site whose sliding direction the caller reverses at t1 (find_reversal), or -1.
  void after_step(double t0, double t1, State& x, std::ptrdiff_t reversal = -1) {
    emit_due(t1, x, false);
    if (locate_) switch_prev_.swap(switch_now_);  // evaluate_end's, at this step end
    const int n = sys_.coordinate_count();
    const double balance = ev_.kinetic_energy + ev_.potential_energy - energy0_ - x[2 * n] - x[2 * n + 1];
    sum_.energy_balance_error = std::max(sum_.energy_balance_error, std::abs(balance));
    if (kinetic_max_ > 0.0)
      sum_.energy_jump_relative = std::max(sum_.energy_jump_relative, std::abs(balance - balance_prev_) / kinetic_max_);
    balance_prev_ = balance;
    kinetic_max_ = std::max(kinetic_max_, ev_.kinetic_energy);
    bool onset = false;
    for (std::size_t i = 0; i < sys_.site_count(); ++i) {
      const double now = ev_.sites[i].penetration;
      sum_.max_penetration = std::max(sum_.max_penetration, now);
      onset_rate_[i] = onset_time_[i] = std::numeric_limits<double>::quiet_NaN();
      if (penetration_prev_[i] <= 0.0 && now > 0.0) {
        onset_rate_[i] = rate_at_onset(i, t0, t1, penetration_prev_[i], now, onset_time_[i]);
        ++sum_.contact_events;
        onset = true;
      }
      penetration_prev_[i] = now;
      sliding_prev_[i] = ev_.sites[i].sliding_velocity;
    }
    if (obs_.step) {
      StepRecord r;
      r.t0 = t0;
      r.t1 = t1;
      r.x0 = &x_start_;
      r.x1 = &x;
      r.at_end = &ev_;
      r.memory = &sys_.memory();
      r.onset_time = &onset_time_;
      r.onset_rate = &onset_rate_;
      r.reversal = reversal;
      obs_.step(r);
    }
    if (rec_) rec_->forget();
    const bool changed = sys_.commit(t1, ev_, onset_rate_, x);
    if (onset || changed) stepper_.invalidate();
    if (obs_.step) x_start_ = x;
  }

  void finish() {
    sum_.energy_balance_relative = kinetic_max_ > 0.0 ? sum_.energy_balance_error / kinetic_max_ : 0.0;
  }

 private:
  // Locates the onset on the step's dense output and returns the penetration rate there: the
  // impact velocity of the Lankarani-Nikravesh family, free of the step's position in the impact.
  double rate_at_onset(std::size_t i, double t0, double t1, double p0, double p1, double& at) {
    auto g = [&](double t) {
      stepper_.interpolate(t, scratch_);
      sys_.evaluate(t, scratch_, probe_);
      return probe_.sites[i].penetration;
    };
    const double tol = std::max(1e-15, 1e-6 * (t1 - t0));
    const double tc = locate_crossing(g, t0, t1, p0, p1, tol);
    stepper_.interpolate(tc, scratch_);
    sys_.evaluate(tc, scratch_, probe_);
    const double rate = probe_.sites[i].penetration_rate;
    // A crossing on the dense output with a non-positive rate is a graze at the step's
    // resolution: fall back to the end-of-step rate.
    if (!(rate > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    at = tc;
    return rate;
  }

  // Emits the time-series rows and revolutions due up to t1 (inside the step just taken, or at
  // t = 0 on start).
  void emit_due(double t1, const State& x1, bool at_start) {
    const double eps = 1e-9 * std::max(out_dt_ > 0 ? out_dt_ : period_, 1e-12);
    if (obs_.sample && out_dt_ > 0.0) {
      for (;;) {
        const double t = transient_ + static_cast<double>(next_out_) * out_dt_;
        if (t > t_end_ + eps) break;
        if (!due(t, t1, eps, at_start)) break;
        emit(t, t1, x1, [&](const State& xs) { obs_.sample(t, xs, probe_); });
        ++next_out_;
        ++sum_.samples;
      }
    }
    if (obs_.stroboscopic) {
      for (;;) {
        const double t = static_cast<double>(next_rev_) * period_;
        if (t > t_end_ + eps) break;
        if (!due(t, t1, eps, at_start)) break;
        const std::size_t rev = next_rev_;
        emit(t, t1, x1, [&](const State& xs) { obs_.stroboscopic(rev, t, xs, probe_); });
        ++next_rev_;
        ++sum_.stroboscopic_samples;
      }
    }
  }

  // Whether an output time t belongs to the step ending at t1: inside it, or (only for the run's
  // last step) within eps after it, where t and t_end differ by rounding. An output just after an
  // inner step's end belongs to the next step, whose dense output covers it.
  bool due(double t, double t1, double eps, bool at_start) const {
    if (at_start) return t <= eps;
    if (t <= t1) return true;
    return t1 >= t_end_ && t <= t_end_ + eps;
  }

  template <class F>
  void emit(double t, double t1, const State& x1, F&& f) {
    // At (or, at the run's end, rounding past) the step's end the state is exact; inside the step
    // it comes from the dense output.
    if (t >= t1 || std::abs(t - t1) <= 1e-12 * std::max(1.0, std::abs(t1))) {
      sys_.evaluate(t1, x1, probe_);
      f(x1);
    } else {
      stepper_.interpolate(t, scratch_);
      sys_.evaluate(t, scratch_, probe_);
      f(scratch_);
    }
  }

  SliderCrank& sys_;
  Stepper& stepper_;
  const SimulationObserver& obs_;
  SimulationSummary& sum_;
  RecordingSystem* rec_;
  bool locate_ = false;  // integrator.locate_switches
  double t_end_ = 0, transient_ = 0, out_dt_ = 0, period_ = 0;
  std::size_t next_out_ = 0, next_rev_ = 0;
  double energy0_ = 0, kinetic_max_ = 0;
  double balance_prev_ = 0;  // the energy balance at the last step end (0 at the start)
  std::vector<double> penetration_prev_, onset_rate_, onset_time_;
  std::vector<double> sliding_prev_;  // each site's sliding velocity at the last step end
  State x_start_;  // the step's start, kept only for observer.step
  // Switching functions at the last accepted step end, at the step end being checked, at a probe.
  std::vector<double> switch_prev_, switch_now_, switch_probe_;
  Evaluation ev_, probe_;
  State scratch_;
};

std::string at_time(const char* what, double t) {
  std::ostringstream os;
  os.precision(10);
  os << what << " at t = " << t << " s";
  return os.str();
}

// A run that reached its end with an energy balance too far off to trust (simulate.hpp).
void check_energy_balance(SimulationSummary& sum, double period) {
  if (sum.status != SimulationStatus::completed) return;
  if (sum.energy_jump_relative > max_energy_defect_per_revolution) {
    std::ostringstream os;
    os.precision(3);
    os << "one step changed the energy balance by " << sum.energy_jump_relative
       << " of the largest kinetic energy before it (above the limit " << max_energy_defect_per_revolution
       << ", a whole revolution's allowance): the integration does not resolve this run "
          "(docs/reference/mechanism/model.md, \"The energy balance\")";
    sum.status = SimulationStatus::energy_defect;
    sum.message = os.str();
    return;
  }
  const double revolutions = sum.end_time / period;
  const double rate = sum.energy_balance_relative / std::max(1.0, revolutions);
  if (!(rate > max_energy_defect_per_revolution)) return;
  std::ostringstream os;
  os.precision(3);
  os << "the energy balance is off by " << sum.energy_balance_relative << " of the largest kinetic energy over "
     << revolutions << " crank revolutions (" << rate << " per revolution, above the limit "
     << max_energy_defect_per_revolution
     << "): the integration does not resolve this run (docs/reference/mechanism/model.md, \"The energy balance\")";
  sum.status = SimulationStatus::energy_defect;
  sum.message = os.str();
}

}  // namespace

SimulationSummary simulate(SliderCrank& system, const SimulationObserver& observer) {
  return simulate(system, system.initial_state(), observer);
}

SimulationSummary simulate(SliderCrank& system, const State& start, const SimulationObserver& observer) {
  const auto wall0 = std::chrono::steady_clock::now();
  const Scene& scene = system.scene();
  if (start.size() != system.state_size())
    throw InvalidParameter("start state", std::to_string(start.size()) + " values",
                           "must have the system's state size " + std::to_string(system.state_size()));
  if (!start.allFinite()) throw InvalidParameter("start state", "non-finite values", "every value must be finite");
  if (scene.driver.free && (observer.stroboscopic || scene.run.stroboscopic))
    throw InvalidParameter("run.stroboscopic", "true",
                           "needs a driven crank: with driver.free = true the crank has no fixed period to sample at");
  SimulationSummary sum;
  State x = start;
  const int n = system.coordinate_count();
  x[2 * n] = x[2 * n + 1] = 0.0;  // the energy balance starts here
  double t = 0.0;
  double last_progress = -1.0;
  auto report_progress = [&](double t_now, double t_end) {
    if (!observer.progress) return;
    const double f = t_now / t_end;
    if (f - last_progress >= 0.01 || f >= 1.0) {
      observer.progress(f);
      last_progress = f;
    }
  };

  if (scene.integrator.method == IntegratorMethod::rk4) {
    Rk4 stepper;
    HybridLoop<Rk4> loop(system, stepper, observer, sum);
    const double period = scene.driver.period();
    const double per_period = std::ceil(period / scene.integrator.step - 1e-9);
    const double h = period / per_period;
    sum.step = h;
    loop.start(x);
    const double t_end = loop.end_time();
    // Step k ends at k h exactly (no accumulated round-off); the last step may be shorter, and
    // ends on t_end itself: total h can round below it (2 T + T at 5000 rpm is 0.036000000000000004
    // s, 36000 h is 0.036 s), and the run then stopped short of its last revolution.
    const auto total = static_cast<std::size_t>(std::ceil(t_end / h - 1e-9));
    std::vector<char> reversed(system.site_count(), 0);  // sites whose direction reversed in this grid step
    // The piece [t0, te] taken again from its start (the dense output is exact at its ends), te
    // inside the step just taken; false when the state became non-finite.
    const auto retake_to = [&](double t0, double te) {
      stepper.interpolate(t0, x);
      t = t0;
      stepper.step(system, t, x, te - t0);
      t = te;
      if (!x.allFinite()) return false;
      loop.evaluate_end(te, x);
      return true;
    };
    for (std::size_t k = 1; k <= total; ++k) {
      if (static_cast<double>(k) > scene.integrator.max_steps) {
        sum.status = SimulationStatus::step_limit;
        sum.message = at_time("the step limit was reached", t);
        break;
      }
      const double t1 = k == total ? t_end : std::min(static_cast<double>(k) * h, t_end);
      // The grid step [t, t1], in pieces when contacts switch inside it: each piece ends at the
      // first switch located in what is left (a piece shorter than a thousandth of the step is
      // not split again: the switch's error there is negligible and it could not end otherwise),
      // or at the first reversal of a held sliding direction (find_reversal), which reverses it.
      bool finite = true;
      std::fill(reversed.begin(), reversed.end(), 0);
      for (;;) {
        const double t0 = t;
        stepper.step(system, t, x, t1 - t0);
        t = t1;
        if (!(finite = x.allFinite())) break;
        loop.evaluate_end(t1, x);
        double tc = t1, tr = t1;
        std::size_t site = 0;
        const bool switched = loop.find_switch(t0, t1, 1e-3 * h, tc);
        const auto reversal = loop.find_reversal(t0, t1, reversed, tr, site);
        if (reversal == decltype(reversal)::sticks) {
          // The contact sticks: take the piece again with Coulomb's sign(v) at each stage, as
          // dopri5 does; the step's end sets a direction again.
          stepper.interpolate(t0, x);
          t = t0;
          system.set_sliding_direction(site, 0);
          stepper.invalidate();
          ++sum.unlocated_reversals;
          continue;
        }
        if (reversal == decltype(reversal)::located && (!switched || tr <= tc)) {
          const int direction = system.memory()[site].sliding_direction;
          // (Located at t1 itself, the piece is the step just taken.)
          if (tr < t1 && !(finite = retake_to(t0, tr))) break;
          ++sum.steps;
          ++sum.located_reversals;
          loop.after_step(t0, tr, x, static_cast<std::ptrdiff_t>(site));
          system.set_sliding_direction(site, -direction);
          reversed[site] = 1;
          stepper.invalidate();
          if (tr < t1) continue;
          break;
        }
        if (switched) {
          if (!(finite = retake_to(t0, tc))) break;
          ++sum.steps;
          ++sum.located_switches;
          loop.after_step(t0, tc, x);
          continue;
        }
        ++sum.steps;
        loop.after_step(t0, t1, x);
        break;
      }
      if (!finite) {
        sum.status = SimulationStatus::non_finite;
        sum.message = at_time("the state became non-finite", t);
        break;
      }
      report_progress(t, t_end);
    }
    sum.rhs_evaluations = stepper.rhs_evaluations();
    loop.finish();
  } else {
    AdaptiveOptions opt;
    opt.relative_tolerance = scene.integrator.relative_tolerance;
    opt.absolute_tolerance = scene.integrator.absolute_tolerance;
    opt.max_step = scene.integrator.max_step;
    opt.min_step = scene.integrator.min_step;
    opt.max_steps = static_cast<std::size_t>(scene.integrator.max_steps);
    opt.validate();
    DormandPrince54 stepper(opt);
    RecordingSystem recorder(system);
    HybridLoop<DormandPrince54> loop(system, stepper, observer, sum, &recorder);
    loop.start(x);
    const double t_end = loop.end_time();
    double h = std::min(opt.max_step, t_end);
    // Contacts make the first steps hard to guess; start small and let the controller grow it.
    h = std::min(h, 1e-6);
    while (t < t_end) {
      if (stepper.accepted_steps() + stepper.rejected_steps() >= opt.max_steps) {
        sum.status = SimulationStatus::step_limit;
        sum.message = at_time("the step limit was reached", t);
        break;
      }
      // Stretch the last step by up to 1 % rather than leave a sliver below min_step (DOPRI5's rule).
      const bool last = 1.01 * h >= t_end - t;
      double trial = last ? t_end - t : h;
      const double t0 = t;
      const StepOutcome outcome = stepper.try_step(recorder, t, x, trial);
      if (outcome == StepOutcome::rejected) {
        h = trial;
        continue;
      }
      if (outcome == StepOutcome::step_underflow) {
        sum.status = SimulationStatus::step_underflow;
        sum.message = at_time("the step fell below integrator.min_step", t);
        break;
      }
      if (outcome == StepOutcome::non_finite) {
        sum.status = SimulationStatus::non_finite;
        sum.message = at_time("the stages became non-finite", t);
        break;
      }
      if (last) t = t_end;  // land exactly on the end
      h = std::min(trial, opt.max_step);
      loop.evaluate_end(t, x);
      double tc = t;
      if (loop.find_switch(t0, t, 1e-3 * (t - t0), tc)) {
        // A contact switched inside the accepted step: take it again up to the switch, with one
        // step and no error control (it is shorter than the step the controller accepted and
        // smoother), and go on from there with the controller's proposal. Nothing was committed
        // since the step's start, so the stepper reuses its first stage there.
        stepper.interpolate(t0, x);  // the step's start: the dense output is exact at its ends
        t = t0;
        stepper.step_fixed_to(recorder, t, x, tc);
        if (!x.allFinite()) {
          sum.status = SimulationStatus::non_finite;
          sum.message = at_time("the stages became non-finite", t);
          break;
        }
        loop.evaluate_end(t, x);
        ++sum.located_switches;
      }
      ++sum.steps;
      loop.after_step(t0, t, x);
      report_progress(t, t_end);
    }
    sum.rejected_steps = stepper.rejected_steps();
    sum.rhs_evaluations = stepper.rhs_evaluations();
    loop.finish();
  }
  sum.end_time = t;
  sum.final_state = x;
  check_energy_balance(sum, scene.driver.period());
  sum.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return sum;
}

}  // namespace mechanism
