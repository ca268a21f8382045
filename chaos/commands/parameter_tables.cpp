// The parameter table of each command (parameter_table.hpp): the options of `chaos X` and the
// keyword arguments of chaos.X, in the order the command's help lists them. Defaults are the
// parameters structs' own (commands.hpp).

#include "commands.hpp"

namespace chaos::cli {

namespace {

// The help of the embedding parameters that cao, fnn, d2, lyapunov and lyapunov-maps choose when
// they are left out.
const char* const delay_help =
    "delay tau in samples (default: automatic, the first mutual-information minimum or the rule that stands in for "
    "it; the output names the rule)";
const char* const theiler_help =
    "Theiler window in samples (default: automatic, the longer of the autocorrelation 1/e time and half the dominant "
    "oscillation period, at least the delay)";
const char* const dimension_help = "embedding dimension (default: automatic, where Cao's E1 saturates)";
const char* const threads_help = "threads (results identical for any number)";
const char* const end_match_help = "first trim the series to the segment whose ends match best (TISEAN endtoend)";

}  // namespace

const ParameterTable<MutualParams>& mutual_parameters() {
  static const ParameterTable<MutualParams> table{
      {"max_delay", "-D,--max-delay",
       "largest delay (default: automatic, 100 (at most N/10), and where the information has no minimum there, on to "
       "two Theiler windows, as chaos analyze searches)",
       field(&MutualParams::max_delay)},
      {"boxes", "-b,--boxes", "boxes per axis", field(&MutualParams::options, &MutualInformationOptions::boxes)},
      {"estimator", "--estimator", "equal_width (TISEAN) or equiprobable", field(&MutualParams::estimator)},
  };
  return table;
}

const ParameterTable<AutocorrelationParams>& autocorrelation_parameters() {
  static const ParameterTable<AutocorrelationParams> table{
      {"max_lag", "-D,--max-lag", "largest lag (default N/10, at most 1000)", field(&AutocorrelationParams::max_lag)},
  };
  return table;
}

const ParameterTable<CaoParams>& cao_parameters() {
  static const ParameterTable<CaoParams> table{
      {"delay", "-d,--delay", delay_help, field(&CaoParams::delay)},
      {"min_dimension", "-m,--min-dimension", "smallest embedding dimension",
       field(&CaoParams::options, &CaoOptions::min_dimension)},
      {"max_dimension", "-M,--max-dimension", "largest embedding dimension",
       field(&CaoParams::options, &CaoOptions::max_dimension)},
      {"theiler", "-t,--theiler", theiler_help, field(&CaoParams::theiler)},
      {"norm", "--norm", "max or euclidean", field(&CaoParams::norm)},
      {"level", "--level", "E1 must reach this level to count as saturated",
       field(&CaoParams::options, &CaoOptions::saturation_level)},
      {"change", "--change", "and change by at most this per dimension from there on",
       field(&CaoParams::options, &CaoOptions::saturation_change)},
      {"sigmas", "--sigmas", "stochastic when every |E2 - 1| is within this many standard errors",
       field(&CaoParams::options, &CaoOptions::stochastic_sigmas)},
      {"threads", "--threads", threads_help, field(&CaoParams::options, &CaoOptions::threads)},
  };
  return table;
}

const ParameterTable<FnnParams>& fnn_parameters() {
  static const ParameterTable<FnnParams> table{
      {"delay", "-d,--delay", delay_help, field(&FnnParams::delay)},
      {"min_dimension", "-m,--min-dimension", "smallest embedding dimension",
       field(&FnnParams::options, &FnnOptions::min_dimension)},
      {"max_dimension", "-M,--max-dimension", "largest embedding dimension",
       field(&FnnParams::options, &FnnOptions::max_dimension)},
      {"theiler", "-t,--theiler", theiler_help, field(&FnnParams::theiler)},
      {"rtol", "--rtol", "distance-ratio threshold (criterion 1)", field(&FnnParams::options, &FnnOptions::rtol)},
      {"atol", "--atol", "size threshold in units of the standard deviation (criterion 2)",
       field(&FnnParams::options, &FnnOptions::atol)},
      {"norm", "--norm", "euclidean (Kennel et al.) or max", field(&FnnParams::norm)},
      {"threshold", "--threshold", "dimension chosen where the false fraction <= this",
       field(&FnnParams::options, &FnnOptions::threshold)},
      {"threads", "--threads", threads_help, field(&FnnParams::options, &FnnOptions::threads)},
  };
  return table;
}

const ParameterTable<D2Params>& d2_parameters() {
  using Sums = CorrelationSumOptions;
  using Dimension = CorrelationDimensionOptions;
  using Region = ScalingRegionOptions;
  static const ParameterTable<D2Params> table{
      {"delay", "-d,--delay", delay_help, field(&D2Params::delay)},
      {"min_dimension", "-m,--min-dimension", "smallest embedding dimension", field(&D2Params::sums, &Sums::min_dimension)},
      {"max_dimension", "-M,--max-dimension", "largest embedding dimension", field(&D2Params::sums, &Sums::max_dimension)},
      {"theiler", "-t,--theiler", theiler_help, field(&D2Params::theiler)},
      {"min_radius", "-r,--min-radius", "smallest radius (default: data range / 1000)", field(&D2Params::r_min)},
      {"max_radius", "-R,--max-radius", "largest radius (default: data range / 4)", field(&D2Params::r_max)},
      {"radii", "-#,--radii", "number of log-spaced radii", field(&D2Params::radii)},
      {.name = "radius_list",
       .flags = "--radius-list",
       .help = "explicit increasing radii (comma-separated), instead of -r -R -#",
       .field = field(&D2Params::radius_list),
       .delimiter = ','},
      {"norm", "--norm", "max or euclidean", field(&D2Params::norm)},
      {"inclusive", "--inclusive", "count pairs at distance <= eps, as TISEAN's d2 does (default: < eps)",
       field(&D2Params::sums, &Sums::inclusive)},
      {"search", "--search",
       "box (box-assisted, the fastest), kd (kd-tree, one traversal per point for all radii and m: 0.8-1.3 times the "
       "box time) or brute (the definition, slowest)",
       field(&D2Params::search)},
      {"pairs_per_radius", "-N,--pairs-per-radius", "stop counting a radius after this many close pairs (0: exact)",
       field(&D2Params::sums, &Sums::pairs_per_radius)},
      {"reference_points", "--reference-points", "random subset of reference points (0: all)",
       field(&D2Params::sums, &Sums::reference_points)},
      {"seed", "--seed", "seed of the reference order and subset", field(&D2Params::sums, &Sums::seed)},
      {"fast", "--fast",
       "count subsets of reference points: two disjoint ones of --fast-start points, doubling within --fast-budget "
       "until they agree on D2 within --fast-target, else the counts answer rough; the default budget is one round, "
       "a quick look whose two subsets are the record's halves (the halves check)",
       field(&D2Params::fast)},
      {"fast_target", "--fast-target", "--fast: agreement of two disjoint subsets' D2",
       field(&D2Params::adaptive, &AdaptiveD2Options::target)},
      {"fast_start", "--fast-start", "--fast: reference points in each subset of the first round",
       field(&D2Params::adaptive, &AdaptiveD2Options::initial_reference_points)},
      {"fast_budget", "--fast-budget",
       "--fast: reference points the rounds may count together (the first round always runs; 0: up to an eighth of "
       "the points)",
       field(&D2Params::adaptive, &AdaptiveD2Options::budget)},
      {"threads", "--threads", threads_help, field(&D2Params::sums, &Sums::threads)},
      {"tolerance", "--tolerance", "relative flatness of the local slopes in the region",
       field(&D2Params::dimension, &Dimension::region, &Region::tolerance)},
      {"min_points", "--min-points", "radii in a scaling region, at least",
       field(&D2Params::dimension, &Dimension::region, &Region::min_points)},
      {"saturation_dimensions", "--saturation-dimensions", "highest dimensions that must share the plateau",
       field(&D2Params::dimension, &Dimension::saturation_dimensions)},
      {"min_pairs", "--min-pairs", "radii with fewer close pairs are left out",
       field(&D2Params::dimension, &Dimension::min_pairs)},
      {"min_plateau_ratio", "--min-plateau-ratio",
       "the highest dimensions' shared plateau spans at least this factor in eps (eps_high / eps_low)",
       field(&D2Params::dimension, &Dimension::min_plateau_ratio)},
      // FLOAT|inf: not the command line's FLOAT check, which refuses infinity; the library validates it.
      {"projection_tolerance", "--projection-tolerance",
       "no lower dimension m >= 2 D2 + 1 may read a mean local slope over the plateau more than this fraction above "
       "it (a projection cannot have a larger dimension; inf: no check)",
       field(&D2Params::dimension, &Dimension::projection_tolerance), "FLOAT|inf"},
      {"noise_fill_fraction", "--noise-fill-fraction",
       "a plateau is noise-limited when, over consecutive radii below it, every saturating dimension m reads a local "
       "slope more than this fraction of the way from the plateau's slope to m (inf: no check)",
       field(&D2Params::dimension, &Dimension::noise_fill_fraction), "FLOAT|inf"},
      {.name = "max_region_fraction",
       .flags = "--max-region-fraction",
       .help = "a region ends at or below this fraction of the data range (Eckmann-Ruelle take 0.1; default: no limit)",
       .field = field(&D2Params::dimension, &Dimension::max_region_fraction),
       .default_described = true},
      {"halves", "--halves,!--no-halves",
       "a saturated D2 must be reproduced by the first and the second half of the record, else it is "
       "'not_reproduced' (on by default, as in chaos analyze; --no-halves gives the plain estimate)",
       field(&D2Params::halves)},
      {"delay_check", "--delay-check",
       "a saturated D2 must be reproduced at twice the delay, within --delay-tolerance (as in chaos analyze)",
       field(&D2Params::delay_check)},
      {"delay_tolerance", "--delay-tolerance",
       "the largest difference between D2 at the delay and at twice it, with --delay-check",
       field(&D2Params::dimension, &Dimension::delay_tolerance)},
  };
  return table;
}

const ParameterTable<LyapunovParams>& lyapunov_parameters() {
  using Fit = LyapunovFitOptions;
  static const ParameterTable<LyapunovParams> table{
      {"method", "--method",
       "rosenstein (mean log distance of nearest neighbours) or kantz (log of the mean distance in an "
       "eps-neighbourhood)",
       field(&LyapunovParams::method)},
      {"dimension", "-m,--dimension", dimension_help, field(&LyapunovParams::dimension)},
      {"delay", "-d,--delay", delay_help, field(&LyapunovParams::delay)},
      {"theiler", "-t,--theiler", theiler_help, field(&LyapunovParams::theiler)},
      {"steps", "-s,--steps", "steps the divergence is followed (default: 20 correlation times or periods, 20..N/10)",
       field(&LyapunovParams::steps)},
      {"period", "--period",
       "oscillation period in samples: local slopes span a whole period (default: twice the first autocorrelation "
       "minimum; 0: none)",
       field(&LyapunovParams::period)},
      {"dimensions", "--dimensions",
       "embedding dimensions m, m+1, ... whose curves must share the linear region and agree on its slope",
       field(&LyapunovParams::fit, &Fit::dimensions)},
      {"radius", "-r,--radius",
       "Kantz: neighbourhood radius eps (default: data range / 1000, scaled by powers of 2 so that half the reference "
       "points have a neighbour and at most 20 on average)",
       field(&LyapunovParams::options, &LyapunovOptions::radius)},
      {"min_neighbours", "-k,--min-neighbours", "Kantz: reference points with fewer neighbours are skipped",
       field(&LyapunovParams::options, &LyapunovOptions::min_neighbours)},
      {"max_neighbours", "--max-neighbours",
       "Kantz: at most this many neighbours per reference point; a larger neighbourhood is represented by that many "
       "of its members evenly spaced in time, and the output counts them (capped_neighbourhoods; 0: no bound)",
       field(&LyapunovParams::options, &LyapunovOptions::max_neighbours)},
      {"reference_points", "--reference-points",
       "use this many evenly spaced reference points (default: at most 10^4, as chaos analyze; 0: all)",
       field(&LyapunovParams::reference_points)},
      {"norm", "--norm", "max or euclidean", field(&LyapunovParams::norm)},
      {"threads", "--threads", threads_help, field(&LyapunovParams::options, &LyapunovOptions::threads)},
      {"tolerance", "--tolerance", "relative flatness of the local slopes in the linear region",
       field(&LyapunovParams::fit, &Fit::tolerance)},
      {"half_width", "--half-width", "local-slope half width in steps (0: max(2, steps/25, period/2))",
       field(&LyapunovParams::fit, &Fit::half_width)},
      {"min_steps", "--min-steps", "steps in a linear region, at least (0: 3 half widths + 1, and a period + 1)",
       field(&LyapunovParams::fit, &Fit::min_steps)},
      {"min_rise", "--min-rise", "e-folds the curve must rise across the linear region",
       field(&LyapunovParams::fit, &Fit::min_rise)},
      {"cross_check", "!--no-cross-check",
       "skip the other estimators' checks: the status is then this estimator's alone (by default a linear region the "
       "other method does not confirm within the tolerance, or that lambda_1 from local maps does not confirm (maps "
       "not consistent, or more than the tolerance away), as in chaos analyze, is 'unconfirmed')",
       field(&LyapunovParams::cross_check)},
      {"halves", "--halves,!--no-halves",
       "run the estimator over each half of the record too: a linear region that neither half shows, or that a half "
       "puts more than the tolerance away, is 'not_reproduced' (on by default, as in chaos analyze; --no-halves gives "
       "the plain estimate)",
       field(&LyapunovParams::halves)},
  };
  return table;
}

const ParameterTable<LyapunovMapsParams>& lyapunov_maps_parameters() {
  static const ParameterTable<LyapunovMapsParams> table{
      {"dimension", "-m,--dimension", dimension_help, field(&LyapunovMapsParams::dimension)},
      {"delay", "-d,--delay", delay_help, field(&LyapunovMapsParams::delay)},
      {"theiler", "-t,--theiler", theiler_help, field(&LyapunovMapsParams::theiler)},
      {"step", "--step", "samples the local maps advance (0: max(1, round(tau/2)))",
       field(&LyapunovMapsParams::options, &LocalMapOptions::step)},
      {"neighbours", "-k,--neighbours", "neighbours per local map (0: 5 m)",
       field(&LyapunovMapsParams::options, &LocalMapOptions::neighbours)},
      {"cutoff", "--cutoff", "singular values of a neighbourhood below this fraction of the largest are not fitted",
       field(&LyapunovMapsParams::options, &LocalMapOptions::cutoff)},
      {"tolerance", "--tolerance", "agreement required of every variant, relative to the base",
       field(&LyapunovMapsParams::tolerance)},
      {"max_residual", "--max-residual",
       "a map leaving more of its neighbourhood's image spread unexplained is not averaged; more than half such maps: "
       "not_deterministic",
       field(&LyapunovMapsParams::options, &LocalMapOptions::max_residual)},
      {"norm", "--norm", "max or euclidean (neighbour search)", field(&LyapunovMapsParams::norm)},
      {"threads", "--threads", threads_help, field(&LyapunovMapsParams::options, &LocalMapOptions::threads)},
  };
  return table;
}

const ParameterTable<AnalyzeParams>& analyze_parameters() {
  static const ParameterTable<AnalyzeParams> table{
      {"delay", "-d,--delay", "use this delay instead of the mutual-information minimum", field(&AnalyzeParams::delay)},
      {"theiler", "-t,--theiler",
       "use this Theiler window instead of the automatic one (the longer of the autocorrelation 1/e time and half the "
       "dominant period, at least the delay)",
       field(&AnalyzeParams::theiler)},
      {"max_delay", "-D,--max-delay",
       "largest delay searched first for the MI minimum; where nothing is found up to it, the search goes on to twice "
       "the record's Theiler window (at most N/10)",
       field(&AnalyzeParams::max_delay)},
      {"boxes", "-b,--boxes", "boxes for mutual information", field(&AnalyzeParams::boxes)},
      {"max_dimension", "-M,--max-dimension", "largest embedding dimension", field(&AnalyzeParams::max_dimension)},
      {"delay_check", "--delay-check",
       "a saturated D2 must also be reproduced at twice the delay, within 0.05 (chaos d2 --delay-check)",
       field(&AnalyzeParams::delay_check)},
      {"builtin_length", "--builtin-length", "length of the built-in Lorenz series", field(&AnalyzeParams::builtin_length)},
      {"test_length", "--test-length", "samples given to the nonlinearity test (the first ones)",
       field(&AnalyzeParams::test_length)},
      {"surrogates", "--surrogates", "surrogates of the one-sided nonlinearity test (19: 5%)",
       field(&AnalyzeParams::surrogates)},
      {"seed", "--seed", "seed of the surrogates", field(&AnalyzeParams::seed)},
      {"threads", "--threads", threads_help, field(&AnalyzeParams::threads)},
  };
  return table;
}

const ParameterTable<SurrogatesParams>& surrogates_parameters() {
  static const ParameterTable<SurrogatesParams> table{
      {"method", "--method", "ft (phase randomised), aaft or iaaft", field(&SurrogatesParams::method)},
      {"count", "-n,--count", "number of surrogates", field(&SurrogatesParams::count)},
      {"seed", "--seed", "seed; surrogate k uses the k-th draw of its stream", field(&SurrogatesParams::seed)},
      {"max_iterations", "--max-iterations", "IAAFT: iteration limit",
       field(&SurrogatesParams::options, &SurrogateOptions::max_iterations)},
      {"tolerance", "--tolerance", "IAAFT: stop when the spectral deviation is this small (0: only at a fixed point)",
       field(&SurrogatesParams::options, &SurrogateOptions::tolerance)},
      {"end_match", "--end-match", end_match_help, field(&SurrogatesParams::end_match)},
      {"max_trim", "--max-trim", "end matching: largest fraction cut off",
       field(&SurrogatesParams::end, &EndMatchOptions::max_trim)},
  };
  return table;
}

const ParameterTable<NonlinearityParams>& nonlinearity_parameters() {
  using Test = NonlinearityTestOptions;
  using Prediction = PredictionErrorOptions;
  static const ParameterTable<NonlinearityParams> table{
      {"count", "-n,--count", "surrogates K (39: two-sided 5%; 19: one-sided 5%)",
       field(&NonlinearityParams::options, &Test::surrogates)},
      {"seed", "--seed", "seed of the surrogates", field(&NonlinearityParams::options, &Test::seed)},
      {"statistic", "--statistic", "prediction_error or time_reversal_asymmetry", field(&NonlinearityParams::statistic)},
      {"alternative", "--alternative", "two_sided, smaller or larger", field(&NonlinearityParams::alternative)},
      {"method", "--method", "surrogates: ft, aaft or iaaft", field(&NonlinearityParams::method)},
      {"max_iterations", "--max-iterations", "IAAFT: iteration limit",
       field(&NonlinearityParams::options, &Test::surrogate, &SurrogateOptions::max_iterations)},
      {"delay", "-d,--delay",
       "delay: of the predictor's embedding, or the lag of the asymmetry (default: automatic, the first "
       "mutual-information minimum; the output names the rule)",
       field(&NonlinearityParams::delay)},
      {"dimension", "-m,--dimension", "prediction: embedding dimension (default: automatic, where Cao's E1 saturates)",
       field(&NonlinearityParams::dimension)},
      {"theiler", "-t,--theiler",
       "prediction: Theiler window in samples (default: automatic, the longer of the autocorrelation 1/e time and "
       "half the dominant period, at least the delay)",
       field(&NonlinearityParams::theiler)},
      {"horizon", "--horizon", "prediction: steps ahead",
       field(&NonlinearityParams::options, &Test::prediction, &Prediction::horizon)},
      {"neighbours", "-k,--neighbours", "prediction: neighbours averaged",
       field(&NonlinearityParams::options, &Test::prediction, &Prediction::neighbours)},
      {"norm", "--norm", "prediction: max or euclidean", field(&NonlinearityParams::norm)},
      {"end_match", "--end-match", end_match_help, field(&NonlinearityParams::end_match)},
  };
  return table;
}

const ParameterTable<GenerateParams>& generate_parameters() {
  static const ParameterTable<GenerateParams> table{
      {"length", "-l,--length", "number of samples", field(&GenerateParams::length)},
      {"parameter", "-p,--parameter", "system parameter name=value (repeatable)", field(&GenerateParams::parameters)},
      {"seed", "--seed", "seed of the stochastic systems and the logistic start", field(&GenerateParams::seed)},
      {"components", "--components", "comma-separated components to write, or all", field(&GenerateParams::components)},
  };
  return table;
}

const ParameterTable<SpectrumParams>& spectrum_parameters() {
  static const ParameterTable<SpectrumParams> table{
      {"parameter", "-p,--parameter", "model parameter name=value (repeatable), as in chaos generate",
       field(&SpectrumParams::parameters)},
      {"time", "--time", "flows: averaging time (default 10000; zoo systems: their own)", field(&SpectrumParams::time)},
      {"step", "--step", "flows: RK4 step (default 0.01; zoo systems: their own; delay: tau / step steps per delay)",
       field(&SpectrumParams::step)},
      {"interval", "--interval", "flows: time between QR factorisations (default 0.1)",
       field(&SpectrumParams::flow_interval)},
      {"transient", "--transient", "flows: time not averaged (default 100)", field(&SpectrumParams::flow_transient)},
      {"iterations", "--iterations", "maps: iterations averaged (default 1000000)", field(&SpectrumParams::iterations)},
      {"map_interval", "--map-interval", "maps: iterations between QR factorisations (default 1)",
       field(&SpectrumParams::map_interval)},
      {"map_transient", "--map-transient", "maps: iterations not averaged (default 1000)",
       field(&SpectrumParams::map_transient)},
      {"identity", "--identity", "zoo systems: also give what the sum must equal (trace or ln|det J|)",
       field(&SpectrumParams::identity)},
      {"exponents", "--exponents", "delay systems: how many leading exponents (1..8, default 6)",
       field(&SpectrumParams::delay_exponents)},
      {"seed", "--seed", "logistic map: seed of the initial condition", field(&SpectrumParams::seed)},
  };
  return table;
}

const ParameterTable<DensityParams>& density_parameters() {
  static const ParameterTable<DensityParams> table{
      {"bins", "-b,--bins", "a fixed number of bins (default: the Freedman-Diaconis rule, at most --max-bins)",
       field(&DensityParams::bins)},
      {"max_bins", "--max-bins", "the cap on the Freedman-Diaconis count", field(&DensityParams::max_bins)},
      {"kde", "--kde",
       "Gaussian kernel estimate (Silverman's bandwidth) averaged over each bin, instead of the histogram",
       field(&DensityParams::kde)},
      {"bandwidth", "--bandwidth", "kde: one bandwidth for every parameter value", field(&DensityParams::bandwidth)},
      {"low", "--low", "lower end of the common range (with --high)", field(&DensityParams::low)},
      {"high", "--high", "upper end of the common range (with --low)", field(&DensityParams::high)},
      {"padding", "--padding", "without a range: fraction of the pooled span added on each side",
       field(&DensityParams::padding)},
  };
  return table;
}

const ParameterTable<SectionParams>& section_parameters() {
  static const ParameterTable<SectionParams> table{
      {.name = "columns",
       .flags = "-c,--columns",
       .help = "columns to read, 1-based, comma separated (default: every column but the time column)",
       .field = field(&SectionParams::columns),
       .delimiter = ','},
      {"dt", "--dt", "time between rows, when there is no time column", field(&SectionParams::dt)},
      {"time_column", "--time-column", "column holding the time (increasing; steps may be uneven)",
       field(&SectionParams::time_column)},
      {"stroboscopic", "--stroboscopic", "stroboscopic section: every PERIOD-th row", field(&SectionParams::period)},
      {"phase", "--phase", "stroboscopic: the first row taken, 0 <= K < PERIOD", field(&SectionParams::phase)},
      {"hyperplane", "--hyperplane", "hyperplane section: crossings of this column (1-based)",
       field(&SectionParams::hyperplane)},
      {"level", "--level", "hyperplane: the plane is column = C", field(&SectionParams::level)},
      {"direction", "--direction", "hyperplane: up, down or both", field(&SectionParams::direction)},
  };
  return table;
}

const ParameterTable<ValidateParams>& validate_parameters() {
  static const ParameterTable<ValidateParams> table{
      {.name = "filter",
       .flags = "--filter",
       .help = "only cases whose id contains this text",
       .field = field(&ValidateParams::filter),
       .default_described = true},
  };
  return table;
}

namespace {

// The options `chaos zoo` shares with its --series form (chaos.zoo and chaos.zoo_series).
const char* const zoo_fast_help = "the CI subset: 4 systems and 5 controls at N = 10^4, automatic choices only";
const char* const zoo_threads_help = "cases run in parallel (the report does not depend on it)";

}  // namespace

const ParameterTable<ZooParams>& zoo_parameters() {
  static const ParameterTable<ZooParams> table{
      {"fast", "--fast", zoo_fast_help, field(&ZooParams::fast)},
      {"grid", "!--no-grid", "automatic choices only, no neighbourhood grid", field(&ZooParams::grid)},
      {"grid_points", "--grid-points",
       "grid points per chaotic system at N = 10^5, 1 to 12 (12: the whole grid of three Theiler windows by four "
       "dimensions; fewer are chosen by the system's name, so that the zoo covers them all)",
       field(&ZooParams::grid_points)},
      {.name = "only",
       .flags = "--only",
       .help = "run only these cases (by name; repeatable or comma-separated)",
       .field = field(&ZooParams::only),
       .delimiter = ','},
      {"threads", "--threads", zoo_threads_help, field(&ZooParams::threads)},
      {.name = "checkpoint",
       .flags = "--checkpoint",
       .help = "append each finished case to this file (JSON lines) and skip the cases it already holds, so that a "
               "stopped run resumes; the file belongs to one build and one choice of --fast, --no-grid and --grid-points",
       .field = field(&ZooParams::checkpoint),
       .default_described = true},
  };
  return table;
}

const ParameterTable<ZooSeriesParams>& zoo_series_parameters() {
  static const ParameterTable<ZooSeriesParams> table{
      {"fast", "--fast", zoo_fast_help, field(&ZooSeriesParams::fast)},
      {"threads", "--threads", zoo_threads_help, field(&ZooSeriesParams::threads)},
  };
  return table;
}

}  // namespace chaos::cli
