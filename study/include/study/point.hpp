#pragma once
// One point of a sweep: its scene simulated for spec.periods revolutions, the kept stroboscopic
// samples, the simulation's summary and, when asked, the analysis of the slider's vertical
// displacement over the last analysis.periods revolutions and the Lyapunov exponents from the
// equations, started from the point's final state.

#include <cstddef>
#include <optional>
#include <vector>

#include "mechanism/scene_lyapunov.hpp"
#include "mechanism/simulate.hpp"
#include "study/series_analysis.hpp"
#include "study/sweep.hpp"

namespace study {

struct PointResult {
  std::size_t point = 0;
  std::vector<double> coordinates;
  mechanism::SimulationSummary summary;     // includes final_state
  // One row per kept revolution: revolution (counted from the run's start), t, then spec.signals.
  std::vector<std::vector<double>> samples;
  std::optional<SeriesAnalysis> analysis;
  std::optional<mechanism::SceneLyapunov> lyapunov;  // when spec.lyapunov
};

// From the seed's initial conditions, or from `start` (a continuation: the previous point's
// final state; it must have this scene's state size, else the point starts fresh and says so in
// summary.message).
PointResult run_point(const SweepSpec& spec, std::size_t point, const mechanism::State* start = nullptr);

}  // namespace study
