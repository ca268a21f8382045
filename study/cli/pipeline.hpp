#pragma once
// `study pipeline`: the seed's Fig. 7 for one scene. The slider's vertical displacement over the
// last --analysis-periods of --periods revolutions goes through the correlation-dimension pipeline
// (series_analysis.hpp) and the six panels are drawn: (a) the phase portrait slider_vy against
// slider_y, (b) the mutual information against the delay, (c) the reconstructed portrait
// y(t + tau) against y(t), (d) log C(eps) for m = 1..max, (e) D2(m), (f) Cao's E1 and E2.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "study/series_analysis.hpp"

namespace study::cli {

struct PipelineRequest {
  std::string scene_file;
  std::vector<std::string> overrides;
  std::size_t periods = 1000;
  AnalysisOptions analysis;
  std::string plot;
  std::string series_output;
};

void add_pipeline_options(CLI::App& cmd, PipelineRequest& request);
// Prints the JSON summary to stdout; returns false when the simulation did not complete.
bool run_pipeline(const PipelineRequest& request);

}  // namespace study::cli
