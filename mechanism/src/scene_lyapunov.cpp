#include "mechanism/scene_lyapunov.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <utility>

#include "mechanism/error.hpp"
#include "mechanism/finite_difference_lyapunov.hpp"
#include "mechanism/saltation.hpp"
#include "mechanism/simulate.hpp"
#include "mechanism/slider_crank.hpp"

namespace mechanism {

namespace {

// One interval (a whole fraction 1/m of the crank period) of simulate() as a map of the phase
// point (q, q_dot, z). Interval j of a period runs on a SliderCrank whose crank starts at phase j/m;
// the m systems are shared by every trajectory, and each trajectory carries its own contact memory
// into the system it runs on. A copy is therefore a companion with the reference's memory, and
// copying costs a state and a memory, not m systems.
class SceneTrajectory {
 public:
  SceneTrajectory(const Scene& scene, int intervals) : systems_(std::make_shared<std::vector<SliderCrank>>()) {
    const double period = scene.driver.period();
    for (int j = 0; j < intervals; ++j) {
      Scene part = scene;
      part.run.transient = 0.0;
      part.run.duration = period / intervals;
      part.run.output_interval = period / intervals / 200.0;  // rows only when an observer asks
      part.run.stroboscopic = false;
      part.driver.initial_angle = scene.driver.initial_angle + 2.0 * M_PI * j / intervals;
      // Difference quotients need a period map that is continuous in the state. Ending steps at
      // located contact switches makes the step partition depend on the state, and it changes by
      // a jump where a switch crosses the split threshold, which the stiff bristle mode (rate up to
      // 1/bristle_time_floor, about one per RK4 step) turns into jumps of the state. Measured on the
      // built-in scene at 0.5 mm: with the switches located the largest separation within an
      // interval stays at 1.4e-3 of its coordinate's scale whether delta is 1e-8 or 1e-10, and
      // lambda_1 reads 889 or 1087 1/s; without, delta = 1e-10 stays linear (largest separation
      // 1.3e-6) and lambda_1 = 830 (815 at 1e-8). Without the stiff mode (integrator.bristles =
      // "exponential") located switches still jump (0.0146 of scale at delta = 1e-8). So the map is
      // integrated on the scene's fixed grid (docs/notes/mechanism/scene-lyapunov.md, "Steps and contact switches").
      part.integrator.locate_switches = false;
      systems_->emplace_back(part);
    }
    x_ = systems_->front().initial_state();
    memory_ = systems_->front().memory();
  }

  Eigen::VectorXd phase_point() const { return system().phase_point(x_); }
  void set_phase_point(const Eigen::VectorXd& p) { system().set_phase_point(x_, p); }
  bool advance() { return advance({}); }
  bool advance(const SimulationObserver& observer) {
    SliderCrank& sys = (*systems_)[phase_];
    sys.set_memory(memory_);
    const SimulationSummary s = simulate(sys, x_, observer);
    if (s.status != SimulationStatus::completed) {
      failure_ = std::string(to_string(s.status)) + ": " + s.message;
      return false;
    }
    x_ = s.final_state;
    memory_ = sys.memory();
    last_steps_ = s.steps;
    phase_ = (phase_ + 1) % systems_->size();
    return true;
  }
  const SliderCrank& system() const { return systems_->front(); }
  const SliderCrank& system_at(std::size_t j) const { return (*systems_)[j]; }
  std::size_t intervals() const { return systems_->size(); }
  std::size_t phase() const { return phase_; }  // the interval the next advance() runs
  const State& state() const { return x_; }
  const std::vector<ContactMemory>& contact_memory() const { return memory_; }
  void set_state(const std::vector<double>& x) {
    if (static_cast<Eigen::Index>(x.size()) != x_.size())
      throw InvalidParameter("start", std::to_string(x.size()) + " values",
                             "must have the system's state size " + std::to_string(x_.size()));
    for (double v : x)
      if (!std::isfinite(v)) throw InvalidParameter("start", "non-finite values", "every value must be finite");
    x_ = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
  }
  const std::string& failure() const { return failure_; }
  std::size_t last_steps() const { return last_steps_; }  // accepted steps of the last advance()

 private:
  std::shared_ptr<std::vector<SliderCrank>> systems_;
  std::size_t phase_ = 0;  // the interval of the period the next advance() runs
  State x_;
  std::vector<ContactMemory> memory_;
  std::string failure_;
  std::size_t last_steps_ = 0;
};
static_assert(PerturbableTrajectory<SceneTrajectory>);

std::vector<std::string> phase_names(const SliderCrank& system) {
  std::vector<std::string> names = system.coordinate_names();
  for (const std::string& c : system.coordinate_names()) names.push_back(c + "_rate");
  for (std::size_t i = 0; i < system.site_count(); ++i)
    if (system.bristle_index(i) >= 0) names.push_back("bristle_" + std::to_string(i));
  return names;
}

// Benettin's renormalisation on the tangents of the saltation method (saltation.hpp): one
// reference trajectory, the k tangents carried along each interval's steps, a QR of their scaled
// phase rows after each interval, the other rows (work accumulators, latched velocities) carried
// with the same column operations.
FiniteDifferenceLyapunov saltation_benettin(SceneTrajectory& reference, const FiniteDifferenceOptions& options,
                                            bool carry_latched) {
  const SliderCrank& sys = reference.system();
  const Eigen::Index d = sys.phase_dimension();
  options.validate(d);
  const int k = options.exponents;
  const Eigen::VectorXd& scale = options.scale;
  const Eigen::Index n_state = sys.state_size();
  const int n = sys.coordinate_count();
  // Each row's scale for the central differences: the phase scales, and the work accumulators
  // (which no force reads) out of the measure.
  Eigen::VectorXd state_scale = Eigen::VectorXd::Constant(n_state, std::numeric_limits<double>::infinity());
  sys.set_phase_point(state_scale, scale);
  std::vector<SaltationTangents> tangents;
  tangents.reserve(reference.intervals());
  for (std::size_t j = 0; j < reference.intervals(); ++j) tangents.emplace_back(reference.system_at(j), state_scale);

  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd q = detail::initial_directions(d, k, rng, normal);
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(tangents.front().rows(), k);
  auto load = [&](int j) {
    State column = State::Zero(n_state);
    sys.set_phase_point(column, scale.cwiseProduct(q.col(j)));
    y.col(j).setZero();
    y.col(j).head(n_state) = column;
  };
  for (int j = 0; j < k; ++j) load(j);
  Eigen::VectorXd r_diag(k);
  std::vector<bool> dead(static_cast<std::size_t>(k));
  FiniteDifferenceLyapunov out;
  detail::BenettinAverages averages(k, options, out);
  SimulationObserver observer;
  SaltationTangents* current = nullptr;
  // A touching Coulomb site stepped without a held direction: simulate() fell back to sign(v) at
  // each stage because the contact stuck, a sliding mode with no saltation matrix.
  double stuck_at = std::numeric_limits<double>::quiet_NaN();
  observer.step = [&](const StepRecord& step) {
    for (std::size_t i = 0; i < sys.site_count(); ++i)
      if (sys.holds_sliding_direction(i) && (*step.memory)[i].touching && (*step.memory)[i].sliding_direction == 0 &&
          std::isnan(stuck_at))
        stuck_at = step.t0;
    current->step(step, y);
  };
  for (std::size_t it = 0; it < averages.total(); ++it) {
    current = &tangents[reference.phase()];
    current->start(0.0, reference.state(), reference.contact_memory(), y);
    if (!reference.advance(observer)) {
      out.status = FiniteDifferenceLyapunov::Status::trajectory_failed;
      out.message = "the reference trajectory could not be advanced at iteration " + std::to_string(it) + ": " +
                    reference.failure();
      break;
    }
    if (!std::isnan(stuck_at)) {
      out.status = FiniteDifferenceLyapunov::Status::trajectory_failed;
      out.message = "a Coulomb contact stuck at t = " + std::to_string(stuck_at) + " s into iteration " +
                    std::to_string(it) + " (its sliding velocity reversed twice within one step, a sliding mode): "
                    "Coulomb's law has no saltation matrix there; use --method benettin";
      break;
    }
    for (int j = 0; j < k; ++j) q.col(j) = sys.phase_point(y.col(j).head(n_state)).cwiseQuotient(scale);
    detail::orthonormalise_columns(q, &y, r_diag, dead, rng, normal);
    for (int j = 0; j < k; ++j)
      if (dead[static_cast<std::size_t>(j)]) load(j);
    y.row(2 * n).setZero();  // the work accumulators' rows: nothing reads them
    y.row(2 * n + 1).setZero();
    if (!carry_latched) y.bottomRows(y.rows() - n_state).setZero();
    averages.add(it, r_diag, dead);
  }
  averages.finish();
  return out;
}

}  // namespace

const char* to_string(LyapunovMethod method) noexcept {
  return method == LyapunovMethod::saltation ? "saltation" : "benettin";
}

void SceneLyapunovOptions::validate() const {
  if (exponents < 0) detail::throw_invalid_option("exponents", exponents, "must be >= 0 (0: all)");
  if (!(perturbation > 0.0 && perturbation < 1.0))
    detail::throw_invalid_option("perturbation", perturbation, "must be in (0, 1) (relative to each coordinate's scale)");
  if (perturbation < min_perturbation) {
    char floor[32];
    std::snprintf(floor, sizeof floor, "%.3g", min_perturbation);
    detail::throw_invalid_option("perturbation", perturbation,
                                 std::string("is below the floor ") + floor +
                                     " that no state resolves (1e3 x machine epsilon: a separation must be a thousand "
                                     "times the rounding of the coordinates; a scene's own floor is higher, see "
                                     "docs/reference/mechanism/lyapunov.md)");
  }
  if (intervals_per_period < 1 || intervals_per_period > 10000)
    detail::throw_invalid_option("intervals_per_period", intervals_per_period, "must be between 1 and 10000");
  if (periods < 10)
    detail::throw_invalid_option("periods", static_cast<double>(periods),
                                 "must be >= 10 (the standard error comes from 10 block means)");
}

double kaplan_yorke_dimension(std::vector<double> exponents) {
  for (double v : exponents)
    if (std::isnan(v)) return std::numeric_limits<double>::quiet_NaN();
  std::sort(exponents.begin(), exponents.end(), std::greater<>());
  if (exponents.empty() || exponents.front() < 0.0) return 0.0;
  double sum = 0.0;
  for (std::size_t j = 0; j < exponents.size(); ++j) {
    const double next = sum + exponents[j];
    if (next < 0.0) return static_cast<double>(j) + sum / std::abs(exponents[j]);
    sum = next;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void assign_status(SceneLyapunov& r, const std::string& still, bool bristles) {
  r.status = "completed";
  r.message.clear();
  if (std::any_of(r.exponents.begin(), r.exponents.end(), [](double v) { return !std::isfinite(v); })) {
    // Never `completed`: a non-finite exponent is not an estimate.
    std::string which;
    bool collapsed = false;
    for (std::size_t j = 0; j < r.exponents.size(); ++j)
      if (!std::isfinite(r.exponents[j])) {
        which += (which.empty() ? "" : ", ") + std::string("lambda_") + std::to_string(j + 1);
        collapsed = collapsed || (j < r.collapsed.size() && r.collapsed[j] > 0);
      }
    r.status = "not_finite";
    r.message = which + " not finite";
    if (collapsed)
      r.message += std::string(": their directions collapsed to a zero separation within an interval; ") +
                   (bristles ? "the LuGre bristle deflections reset to 0 when their contact opens, so the map is not "
                               "invertible there and those exponents are -inf (a bound, not an estimate)"
                             : "this scene has no bristles to reset, so the separation was lost in rounding: give a "
                               "larger perturbation");
  } else if (r.largest_separation > max_linear_separation) {
    r.status = "nonlinear";
    r.message = "a separation grew to " + std::to_string(r.largest_separation) +
                " of its coordinate's scale within one interval: repeat with a smaller perturbation or more "
                "intervals per period";
  } else if (!still.empty()) {
    r.status = "invariant_subspace";
    r.message = still + " did not move over the sampled period: the orbit lies in an invariant subspace (a level "
                        "slider without friction stays level), and the exponents describe that subspace, with the "
                        "growth transverse to it, not an attractor off it; start it off the subspace (e.g. "
                        "initial.slider_angle) to study that";
  }
}

SceneLyapunov scene_lyapunov(const Scene& scene, const SceneLyapunovOptions& options) {
  options.validate();
  if (scene.driver.free)
    throw InvalidParameter("driver.free", "true",
                           "has no crank-period map: the exponents are computed for a driven crank (driver.free = false)");
  if (options.method == LyapunovMethod::saltation)
    if (const std::string why = saltation_unsupported(scene); !why.empty())
      throw InvalidParameter("method", "saltation", "does not apply to this scene: " + why);
  const auto wall0 = std::chrono::steady_clock::now();
  const double period = scene.driver.period();
  const int m = options.intervals_per_period;
  const double interval = period / m;
  SceneTrajectory reference(scene, m);
  if (!options.start.empty()) reference.set_state(options.start);

  SceneLyapunov out;
  out.method = to_string(options.method);
  out.latched_variations_carried = options.method == LyapunovMethod::saltation && options.carry_latched_variations;
  out.period = period;
  out.perturbation = options.perturbation;
  out.coordinates = phase_names(reference.system());
  const auto d = static_cast<Eigen::Index>(out.coordinates.size());
  if (d == 0)
    throw InvalidParameter("scene", "every joint ideal",
                           "has no phase space: the mechanism is rigid (give a joint clearance)");

  // The scene's transient, in whole periods so that the first iteration starts at the initial
  // crank angle.
  const auto transient = static_cast<std::size_t>(std::ceil(scene.run.transient / period - 1e-9)) * m;
  for (std::size_t i = 0; i < transient; ++i) {
    if (!reference.advance()) {
      out.status = "trajectory_failed";
      out.message = "the transient could not be integrated: " + reference.failure();
      return out;
    }
  }
  // Scales: one period, 200 samples per interval (mechanism::simulate's time-series rows).
  std::vector<Eigen::VectorXd> samples;
  SimulationObserver sampler;
  SceneTrajectory probe = reference;
  sampler.sample = [&](double, const State& x, const Evaluation&) { samples.push_back(reference.system().phase_point(x)); };
  samples.push_back(reference.phase_point());
  std::size_t steps_per_interval = 1;
  for (int j = 0; j < m; ++j) {
    if (!probe.advance(sampler)) {
      out.status = "trajectory_failed";
      out.message = "the scale period could not be integrated: " + probe.failure();
      return out;
    }
    steps_per_interval = std::max(steps_per_interval, probe.last_steps());
  }
  Eigen::VectorXd scale(d), mean = Eigen::VectorXd::Zero(d), spread = Eigen::VectorXd::Zero(d);
  for (const auto& p : samples) mean += p;
  mean /= static_cast<double>(samples.size());
  for (const auto& p : samples) spread += (p - mean).cwiseAbs2();
  spread = (spread / static_cast<double>(samples.size())).cwiseSqrt();
  // A mechanical coordinate whose spread is rounding next to the largest spread or mean of its kind
  // (positions, rates) did not move: a level slider's angle is 1e-18 rad where the conrod's swings
  // by 0.3. Scaled by that rounding, a perturbation of 1e-8 would be 1e-26 rad, lost at once.
  std::string still;  // mechanical coordinates that did not move over the sampled period
  const int n = reference.system().coordinate_count();
  const auto rounding = [&](Eigen::Index begin, Eigen::Index count) {
    return perturbation_digits * std::numeric_limits<double>::epsilon() *
           std::max(spread.segment(begin, count).maxCoeff(), mean.segment(begin, count).cwiseAbs().maxCoeff());
  };
  const double rounding_of[2] = {n > 0 ? rounding(0, n) : 0.0, n > 0 ? rounding(n, n) : 0.0};
  for (Eigen::Index i = 0; i < d; ++i) {
    const bool mechanical = i < 2 * n;
    const double floor = mechanical ? rounding_of[i / n] : 0.0;
    const bool moved = spread[i] > floor;
    scale[i] = moved ? spread[i] : (std::abs(mean[i]) > floor ? std::abs(mean[i]) : 1.0);
    if (!moved && mechanical) still += (still.empty() ? "" : ", ") + out.coordinates[static_cast<std::size_t>(i)];
  }
  out.scale.assign(scale.data(), scale.data() + d);

  // The perturbation's floor (scene_lyapunov.hpp, perturbation_digits): what the state resolves
  // after one interval's steps, in scaled coordinates.
  double largest = 1.0;
  Eigen::Index largest_at = 0;
  for (const auto& p : samples)
    for (Eigen::Index i = 0; i < d; ++i)
      if (std::abs(p[i]) / scale[i] > largest) largest = std::abs(p[i]) / scale[i], largest_at = i;
  out.steps_per_interval = steps_per_interval;
  out.largest_scaled_coordinate = largest;
  out.largest_scaled_name = out.coordinates[static_cast<std::size_t>(largest_at)];
  out.perturbation_floor =
      perturbation_digits * std::numeric_limits<double>::epsilon() * static_cast<double>(steps_per_interval) * largest;
  const bool saltation = options.method == LyapunovMethod::saltation;
  if (saltation) {
    out.perturbation = SaltationTangents::jacobian_step;
    out.perturbation_floor = 0.0;
  }
  if (!saltation && options.perturbation < out.perturbation_floor) {
    char why[400];
    std::snprintf(why, sizeof why,
                  "is below this scene's floor %.3g: 1e3 x machine epsilon %.3g x %zu integrator steps per interval x "
                  "the largest |coordinate| / scale %.3g (%s); a separation below it is mostly rounding (give at "
                  "least %.1g)",
                  out.perturbation_floor, std::numeric_limits<double>::epsilon(), steps_per_interval, largest,
                  out.largest_scaled_name.c_str(), std::pow(10.0, std::ceil(std::log10(out.perturbation_floor))));
    detail::throw_invalid_option("perturbation", options.perturbation, why);
  }

  FiniteDifferenceOptions fd;
  fd.exponents = options.exponents == 0 ? static_cast<int>(d) : options.exponents;
  fd.perturbation = options.perturbation;
  fd.transient = options.transient_periods * static_cast<std::size_t>(m);
  fd.iterations = options.periods * static_cast<std::size_t>(m);
  fd.blocks = 10;
  fd.seed = options.seed;
  fd.scale = scale;
  fd.progress = options.progress;
  const FiniteDifferenceLyapunov r = saltation ? saltation_benettin(reference, fd, options.carry_latched_variations)
                                               : finite_difference_lyapunov(reference, fd);

  const std::size_t k = r.exponents.size();
  out.periods = r.iterations / static_cast<std::size_t>(m);
  out.resolution_limit = std::log(std::numeric_limits<double>::epsilon()) / interval;
  out.largest_separation = saltation ? 0.0 : options.perturbation * r.largest_growth;
  out.collapsed = r.collapsed;
  for (double mu : r.exponents) out.exponents.push_back(mu / interval);
  for (double mu : r.exponents) out.exponents_per_period.push_back(mu * m);
  for (double se : r.standard_error) out.standard_error.push_back(se / interval);
  out.running.reserve(out.periods * k);
  for (std::size_t p = 1; p <= out.periods; ++p)
    for (std::size_t j = 0; j < k; ++j) out.running.push_back(r.running[(p * m - 1) * k + j] / interval);
  out.kaplan_yorke_section = kaplan_yorke_dimension(out.exponents_per_period);
  out.kaplan_yorke = out.kaplan_yorke_section + 1.0;
  if (r.status != FiniteDifferenceLyapunov::Status::completed) {
    // A run cut short gives no exponents: its partial means are not an answer (the running means
    // up to the failure stay, for diagnosis).
    out.status = "trajectory_failed";
    out.message = r.message + " (after " + std::to_string(out.periods) + " of " + std::to_string(options.periods) +
                  " periods averaged)";
    out.exponents.clear();
    out.exponents_per_period.clear();
    out.standard_error.clear();
    out.kaplan_yorke = out.kaplan_yorke_section = std::numeric_limits<double>::quiet_NaN();
  } else {
    bool bristles = false;
    for (std::size_t i = 0; i < reference.system().site_count(); ++i)
      bristles = bristles || reference.system().bristle_index(i) >= 0;
    assign_status(out, still, bristles);
  }
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

}  // namespace mechanism
