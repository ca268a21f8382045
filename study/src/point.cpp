#include "study/point.hpp"

#include <algorithm>

#include "mechanism/error.hpp"
#include "mechanism/signals.hpp"
#include "mechanism/slider_crank.hpp"

namespace study {

PointResult run_point(const SweepSpec& spec, std::size_t point, const mechanism::State* start) {
  PointResult r;
  r.point = point;
  r.coordinates = spec.grid.coordinates(point);
  const mechanism::Scene scene = point_run_scene(spec, point);
  const double period = scene.driver.period();
  const std::size_t transient = spec.periods - spec.keep;
  mechanism::SliderCrank system(scene);

  const auto table = mechanism::signal_table(system);
  std::vector<std::size_t> columns;
  for (const std::string& s : spec.signals)
    columns.push_back(static_cast<std::size_t>(std::find(table.names.begin(), table.names.end(), s) - table.names.begin()));
  const std::size_t y_column =
      static_cast<std::size_t>(std::find(table.names.begin(), table.names.end(), "slider_y") - table.names.begin());

  std::vector<double> values;
  std::vector<double> series;
  const double analysis_start = static_cast<double>(spec.periods - spec.analysis.periods) * period;
  mechanism::SimulationObserver observer;
  // The run ends at a whole revolution, so its last stroboscopic sample falls at the end time; a
  // revolution is kept when it lies in the last `keep` of the spec.periods revolutions after t = 0.
  observer.stroboscopic = [&](std::size_t revolution, double t, const mechanism::State& x, const mechanism::Evaluation& ev) {
    if (revolution <= transient || revolution > spec.periods) return;
    mechanism::signal_values(system, t, x, ev, values);
    std::vector<double> row{static_cast<double>(revolution), t};
    for (std::size_t c : columns) row.push_back(values[c]);
    r.samples.push_back(std::move(row));
  };
  if (spec.analyse) {
    observer.sample = [&](double t, const mechanism::State& x, const mechanism::Evaluation& ev) {
      if (t < analysis_start - 1e-9 * period) return;
      mechanism::signal_values(system, t, x, ev, values);
      series.push_back(values[y_column]);
    };
  }
  const bool continued = start && start->size() == system.state_size();
  r.summary = continued ? mechanism::simulate(system, *start, observer) : mechanism::simulate(system, observer);
  if (start && !continued && r.summary.message.empty())
    r.summary.message = "started fresh: the previous point's state has another size";
  if (spec.analyse) {
    if (r.summary.status == mechanism::SimulationStatus::completed) {
      r.analysis = analyse_series_with_curves(series, scene.run.output_interval, spec.analysis);
    } else {
      SeriesAnalysis a;
      a.status = std::string("not analysed: the simulation ended with ") + mechanism::to_string(r.summary.status);
      r.analysis = a;
    }
  }
  if (spec.lyapunov) {
    mechanism::SceneLyapunov l;
    if (r.summary.status == mechanism::SimulationStatus::completed) {
      const LyapunovSpec& ls = spec.lyapunov_options;
      mechanism::Scene from_end = point_scene(spec, point);
      from_end.run.transient = 0.0;  // the point's own run was the transient
      mechanism::SceneLyapunovOptions o;
      o.periods = ls.periods;
      o.transient_periods = ls.transient_periods;
      o.perturbation = ls.perturbation;
      o.intervals_per_period = static_cast<int>(ls.intervals_per_period);  // at most 10000 (validate)
      const auto dimension = static_cast<std::size_t>(system.phase_dimension());
      o.exponents = static_cast<int>(std::min(ls.exponents, dimension));
      o.start.assign(r.summary.final_state.data(), r.summary.final_state.data() + r.summary.final_state.size());
      try {
        l = mechanism::scene_lyapunov(from_end, o);
      } catch (const mechanism::InvalidParameter& e) {
        // The perturbation's floor depends on the point's state: below it, this point has no answer.
        l = {};
        l.status = "refused";
        l.message = e.what();
      }
    } else {
      l.status = "not_computed";
      l.message = std::string("the simulation ended with ") + mechanism::to_string(r.summary.status);
    }
    r.lyapunov = std::move(l);
  }
  return r;
}

}  // namespace study
