#include "study/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mechanism/error.hpp"
#include "mechanism/scene_lyapunov.hpp"
#include "mechanism/signals.hpp"
#include "mechanism/slider_crank.hpp"
#include "study/error.hpp"

namespace study {

const char* to_string(InitialConditions ic) noexcept {
  return ic == InitialConditions::fresh ? "fresh" : "continuation";
}

mechanism::Scene point_scene(const SweepSpec& spec, std::size_t point) {
  std::vector<std::string> overrides = spec.overrides;
  for (const std::string& o : spec.grid.overrides(point)) overrides.push_back(o);
  return mechanism::read_scene(spec.scene_text, overrides, spec.scene_source);
}

mechanism::Scene point_run_scene(const SweepSpec& spec, std::size_t point) {
  mechanism::Scene scene = point_scene(spec, point);
  const double period = scene.driver.period();
  const std::size_t transient = spec.periods - spec.keep;
  // Outputs start at the end of the transient; the analysed series is the last analysis.periods
  // revolutions, so it may begin inside the transient when it is longer than `keep`.
  const std::size_t first_output =
      spec.analyse ? std::min(transient, spec.periods - spec.analysis.periods) : transient;
  scene.run.transient = static_cast<double>(first_output) * period;
  scene.run.duration = static_cast<double>(spec.periods - first_output) * period;
  scene.run.stroboscopic = true;
  const double interval =
      spec.analysis.samples_per_period ? period / static_cast<double>(spec.analysis.samples_per_period) : spec.analysis.interval;
  scene.run.output_interval = spec.analyse ? interval : 0.0;
  try {
    mechanism::check_run_size(scene);
  } catch (const mechanism::InvalidParameter& e) {
    // The run's times come from the sweep's options, so the message names those.
    throw StudyError("--periods", std::to_string(spec.periods),
                     "point " + std::to_string(point) + "'s run is too large (" + std::string(e.what()) + ")");
  }
  return scene;
}

std::size_t largest_analysis_dimension() {
  const double d = std::floor(2.0 * std::log10(mechanism::max_output_rows));
  return static_cast<std::size_t>(2.0 * d + 1.0);
}

void validate_analysis(const AnalysisOptions& analysis) {
  if (!(analysis.interval > 0.0))
    throw StudyError("--analysis-interval", exact(analysis.interval), "must be > 0 s");
  if (analysis.samples_per_period == 1)
    throw StudyError("--analysis-samples-per-period", "1", "must be 0 (use --analysis-interval) or at least 2");
  if (analysis.max_delay < 1 && analysis.given_delay == 0)
    throw StudyError("--max-delay", "0", "must be at least 1 sample (the mutual-information minimum is searched from 1)");
  if (analysis.max_dimension < 2 || analysis.max_dimension > largest_analysis_dimension())
    throw StudyError("--max-dimension", std::to_string(analysis.max_dimension),
                     "must be 2 .. " + std::to_string(largest_analysis_dimension()) +
                         ": no series a sweep analyses (at most " + exact(mechanism::max_output_rows) +
                         " samples) resolves a dimension D above Eckmann-Ruelle's 2 log10 N, and Takens' 2 D + 1 "
                         "embeds any it does");
}

void SweepSpec::validate() const {
  if (periods == 0) throw StudyError("--periods", "0", "a point runs at least one revolution");
  if (keep == 0 || keep > periods)
    throw StudyError("--keep", std::to_string(keep), "must be 1 .. --periods (" + std::to_string(periods) + ")");
  if (analyse) {
    if (analysis.periods == 0 || analysis.periods > periods)
      throw StudyError("--analysis-periods", std::to_string(analysis.periods),
                       "must be 1 .. --periods (" + std::to_string(periods) + ")");
    validate_analysis(analysis);
  } else if (analysis.surrogates > 0) {
    throw StudyError("--surrogates", std::to_string(analysis.surrogates),
                     "tests the analysed series: it needs --analysis");
  }
  if (lyapunov) {
    const LyapunovSpec& l = lyapunov_options;
    if (l.periods < 10)
      throw StudyError("--lyapunov-periods", std::to_string(l.periods), "must be >= 10 (10 block means give the error)");
    if (l.exponents < 1) throw StudyError("--lyapunov-exponents", std::to_string(l.exponents), "must be >= 1");
    if (!(l.perturbation >= mechanism::min_perturbation && l.perturbation < 1.0))
      throw StudyError("--lyapunov-perturbation", exact(l.perturbation),
                       "must be in [" + exact(mechanism::min_perturbation) +
                           ", 1) (the lower end: 1e3 x machine epsilon; each point's own floor is higher)");
    if (l.intervals_per_period < 1 || l.intervals_per_period > 10000)
      throw StudyError("--lyapunov-intervals", std::to_string(l.intervals_per_period), "must be 1 .. 10000");
  }
  if (signals.empty()) throw StudyError("--signals", "(none)", "name at least one signal");
  // Every point's scene must be valid (an axis may run into a refused value, e.g. clearance 0) and
  // have the signals asked for (the table is the same for every point of a sweep over numbers).
  for (std::size_t p = 0; p < grid.size(); ++p) {
    const mechanism::Scene scene = point_run_scene(*this, p);
    // A sweep samples every point once per crank revolution; a free crank has no revolution period.
    if (scene.driver.free)
      throw StudyError("driver.free", "true",
                       "point " + std::to_string(p) + ": a sweep needs a driven crank (its samples are stroboscopic)");
    if (p > 0) continue;
    const mechanism::SliderCrank system(scene);
    // More exponents than the phase space has would only widen lyapunov.tsv with empty columns
    // (--lyapunov-exponents 2000000000 ran for minutes writing them).
    const auto phase_dimension = static_cast<std::size_t>(system.phase_dimension());
    if (lyapunov && phase_dimension == 0)
      throw StudyError("--lyapunov", "true",
                       "the scene has no phase space (every joint ideal and the crank driven): no exponent to compute");
    if (lyapunov && lyapunov_options.exponents > phase_dimension)
      throw StudyError("--lyapunov-exponents", std::to_string(lyapunov_options.exponents),
                       "must be at most the scene's phase-space dimension, " + std::to_string(phase_dimension));
    const auto table = mechanism::signal_table(system);
    for (const std::string& s : signals)
      if (std::find(table.names.begin(), table.names.end(), s) == table.names.end()) {
        std::string all;
        for (const auto& n : table.names) all += " " + n;
        throw StudyError("--signals", s, "is not a signal of this scene; it has:" + all);
      }
  }
}

std::string SweepSpec::describe() const {
  std::ostringstream d;
  d << "scene_source = " << scene_source << "\n";
  for (const std::string& o : overrides) d << "set = " << o << "\n";
  for (const Axis& a : grid.axes()) {
    d << "axis = " << a.key << ":";
    for (double v : a.values) d << " " << exact(v);
    d << "\n";
  }
  d << "initial_conditions = " << to_string(initial) << "\n"
    << "periods = " << periods << "\n"
    << "keep = " << keep << "\n"
    << "signals =";
  for (const std::string& s : signals) d << " " << s;
  d << "\n";
  if (analyse) {
    d << "analysis.rules = " << analysis_rules_revision << "\n"
      << "analysis.periods = " << analysis.periods << "\n"
      << "analysis.interval = " << (analysis.samples_per_period ? std::string("period / ") + std::to_string(analysis.samples_per_period) : exact(analysis.interval)) << "\n"
      << "analysis.max_delay = " << analysis.max_delay << "\n"
      << "analysis.boxes = " << analysis.boxes << "\n"
      << "analysis.max_dimension = " << analysis.max_dimension << "\n"
      << "analysis.radii = " << analysis.radii << "\n"
      << "analysis.given_delay = " << analysis.given_delay << "\n";
    if (analysis.surrogates > 0)
      d << "analysis.surrogates = " << analysis.surrogates << "\n"
        << "analysis.test_length = " << analysis.test_length << "\n"
        << "analysis.seed = " << analysis.seed << "\n";
  } else {
    d << "analysis = off\n";
  }
  if (lyapunov) {
    const LyapunovSpec& l = lyapunov_options;
    d << "lyapunov.periods = " << l.periods << "\n"
      << "lyapunov.transient_periods = " << l.transient_periods << "\n"
      << "lyapunov.exponents = " << l.exponents << "\n"
      << "lyapunov.perturbation = " << exact(l.perturbation) << "\n"
      << "lyapunov.intervals_per_period = " << l.intervals_per_period << "\n";
  }
  d << "base scene (resolved, before the axis values):\n"
    << mechanism::to_toml(mechanism::read_scene(scene_text, overrides, scene_source));
  return d.str();
}

}  // namespace study
