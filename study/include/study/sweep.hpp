#pragma once
// What a sweep computes, stated once (the protocol of docs/reference/study.md):
//   - every point's scene is the base scene (a file, or the built-in seed scene), the --set
//     overrides, then the point's axis values;
//   - initial conditions: `fresh` starts every point from the seed's Eq. 29 (the points are
//     independent); `continuation` starts each point from the final state of the previous point
//     on the first axis (a chain per value of the second axis; the first point of a chain is fresh);
//   - each point runs `periods` crank revolutions; the first periods - keep are the transient;
//     the stroboscopic samples (once per revolution, at the initial crank angle) of the last `keep`
//     revolutions are kept: the seed keeps 1000 periods, plots the last 50 and builds the PDF from
//     the last 500;
//   - optionally the chaos analysis of the slider's vertical displacement over the last
//     analysis.periods revolutions, sampled every analysis.interval (series_analysis.hpp);
//   - optionally the Lyapunov exponents from the equations, from the point's final state.
// The spec's canonical text (`describe`) heads every output file and identifies a result directory
// on resume.

#include <cstddef>
#include <string>
#include <vector>

#include "mechanism/scene.hpp"
#include "study/grid.hpp"
#include "study/series_analysis.hpp"

namespace study {

enum class InitialConditions { fresh, continuation };

// The Lyapunov exponents of each point from its equations (mechanism/scene_lyapunov.hpp), started
// from the point's final state (its attractor): the `exponents` leading ones (fewer where the phase
// space is smaller), the standard errors and the Kaplan-Yorke dimensions.
struct LyapunovSpec {
  std::size_t periods = 100;            // crank periods averaged
  std::size_t transient_periods = 20;   // periods that align the directions
  std::size_t exponents = 4;           // at most the scene's phase-space dimension
  double perturbation = 1e-8;
  std::size_t intervals_per_period = 50;
};
const char* to_string(InitialConditions ic) noexcept;

struct SweepSpec {
  std::string scene_text;                 // TOML of the base scene (empty: the built-in seed scene)
  std::string scene_source = "built-in seed scene";
  std::vector<std::string> overrides;     // --set key=value, before the axis values
  Grid grid;
  InitialConditions initial = InitialConditions::fresh;
  std::size_t periods = 1000;             // revolutions per point, transient included
  std::size_t keep = 500;                 // stroboscopic revolutions kept, at the end
  std::vector<std::string> signals{"slider_y", "slider_vy"};  // sampled at each kept revolution
  bool analyse = false;
  AnalysisOptions analysis;
  bool lyapunov = false;
  LyapunovSpec lyapunov_options;

  // Refuses keep = 0, keep > periods, analysis periods > periods, analysis options outside their
  // ranges (validate_analysis), an empty signal
  // list, and an axis key or value the scene refuses or a run too large to finish (checked by
  // building every point's run scene).
  void validate() const;
  // Canonical text: one "key = value" line per setting, the resolved base scene last.
  std::string describe() const;
};

// The largest --max-dimension worth computing, 33: an analysed series has at most
// mechanism::max_output_rows = 1e8 samples, so no dimension above 2 log10 N = 16 can be measured
// in it (Eckmann & Ruelle 1992), and 2 D + 1 = 33 embeds any that can (Takens 1981). Beyond it
// the analysis of every point fails (--max-dimension 1000 needed 22232 samples of 2401).
std::size_t largest_analysis_dimension();

// Refuses analysis options outside their ranges before any point runs (--max-delay 0
// and --max-dimension 1000 failed every point's analysis): interval <= 0, samples_per_period 1,
// max_delay 0 without a given delay, max_dimension outside 2 .. largest_analysis_dimension().
// The message names the command-line option.
void validate_analysis(const AnalysisOptions& analysis);

// The scene of point p, validated by the mechanism library.
mechanism::Scene point_scene(const SweepSpec& spec, std::size_t point);
// The same with the run the sweep makes of it: spec.periods revolutions, outputs from the end of
// the transient (or from the analysed series' start), stroboscopic samples, the analysed series'
// interval. Refused (mechanism::check_run_size) when that run is too large to finish.
mechanism::Scene point_run_scene(const SweepSpec& spec, std::size_t point);

}  // namespace study
