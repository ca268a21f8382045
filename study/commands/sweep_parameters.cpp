#include "sweep_parameters.hpp"

#include <algorithm>
#include <utility>

#include "study/error.hpp"

namespace study {

const cli_support::ParameterTable<SweepParams>& sweep_parameters() {
  using cli_support::field;
  static const cli_support::ParameterTable<SweepParams> table{
      {"initial", "--initial",
       "fresh (the seed's Eq. 29 at every point) or continuation (from the previous point's final state along the "
       "first axis)",
       field(&SweepParams::initial)},
      {"periods", "--periods", "crank revolutions per point, transient included (the seed: 1000)",
       field(&SweepParams::spec, &SweepSpec::periods)},
      {"keep", "--keep", "stroboscopic revolutions kept at the end of each point (the seed: 500 for the PDF, 50 plotted)",
       field(&SweepParams::spec, &SweepSpec::keep)},
      {"signals", "--signals",
       "comma-separated signals sampled once per kept revolution (mechanism simulate's names; default: slider_y, "
       "slider_vy)",
       field(&SweepParams::spec, &SweepSpec::signals), "", ',', true},
      {"analysis", "--analysis",
       "also analyse slider_y over the last --analysis-periods revolutions: MI delay, Cao E1/E2, D2",
       field(&SweepParams::spec, &SweepSpec::analyse)},
      {"analysis_periods", "--analysis-periods", "revolutions analysed (the seed: 5)",
       field(&SweepParams::spec, &SweepSpec::analysis, &AnalysisOptions::periods)},
      {"analysis_interval", "--analysis-interval", "s between samples of the analysed series",
       field(&SweepParams::spec, &SweepSpec::analysis, &AnalysisOptions::interval)},
      {"analysis_samples_per_period", "--analysis-samples-per-period",
       "sample the analysed series this many times per crank revolution instead of every --analysis-interval (0: "
       "use the interval)",
       field(&SweepParams::spec, &SweepSpec::analysis, &AnalysisOptions::samples_per_period)},
      {"max_delay", "--max-delay",
       "largest mutual-information delay of the first search, samples (with no minimum there, the search goes on to "
       "two Theiler windows)",
       field(&SweepParams::spec, &SweepSpec::analysis, &AnalysisOptions::max_delay)},
      {"max_dimension", "--max-dimension", "Cao and D2 up to this embedding dimension",
       field(&SweepParams::spec, &SweepSpec::analysis, &AnalysisOptions::max_dimension)},
      {"surrogates", "--surrogates",
       "with --analysis: the IAAFT surrogate test for nonlinearity with this many surrogates (19: one-sided 5%; 0: "
       "none)",
       field(&SweepParams::spec, &SweepSpec::analysis, &AnalysisOptions::surrogates)},
      {"test_length", "--test-length", "samples given to the surrogate test (the first ones of the analysed series)",
       field(&SweepParams::spec, &SweepSpec::analysis, &AnalysisOptions::test_length)},
      {"seed", "--seed", "seed of the surrogates", field(&SweepParams::spec, &SweepSpec::analysis, &AnalysisOptions::seed)},
      {"lyapunov", "--lyapunov",
       "also compute each point's Lyapunov exponents from the equations, from its final state (mechanism lyapunov)",
       field(&SweepParams::spec, &SweepSpec::lyapunov)},
      {"lyapunov_periods", "--lyapunov-periods", "crank periods averaged (>= 10)",
       field(&SweepParams::spec, &SweepSpec::lyapunov_options, &LyapunovSpec::periods)},
      {"lyapunov_exponents", "--lyapunov-exponents",
       "leading exponents per point (at most the phase space's dimension; fewer where a point's is smaller)",
       field(&SweepParams::spec, &SweepSpec::lyapunov_options, &LyapunovSpec::exponents)},
      {"lyapunov_perturbation", "--lyapunov-perturbation", "separation relative to each coordinate's scale",
       field(&SweepParams::spec, &SweepSpec::lyapunov_options, &LyapunovSpec::perturbation)},
      {"lyapunov_intervals", "--lyapunov-intervals", "renormalisations per crank period",
       field(&SweepParams::spec, &SweepSpec::lyapunov_options, &LyapunovSpec::intervals_per_period)},
  };
  return table;
}

SweepSpec sweep_spec(SweepParams params) {
  SweepSpec spec = std::move(params.spec);
  if (params.initial == "fresh")
    spec.initial = InitialConditions::fresh;
  else if (params.initial == "continuation")
    spec.initial = InitialConditions::continuation;
  else
    throw StudyError("--initial", params.initial, "must be fresh or continuation");
  std::erase(spec.signals, std::string());
  return spec;
}

}  // namespace study
