#pragma once
// The computation and the JSON of the `chaos` commands, shared by the command line (chaos/cli/) and
// the Python package (python/). Each run_X takes the series and the command's parameters (with the
// command's defaults), applies the command's own defaults that depend on the data, computes, and
// fills a Report: its parameters (the '#' header / "parameters") and its JSON body, exactly what
// `chaos X --json` writes. The command line adds the text table and the plot; the Python package
// hands the JSON over as the result. X_parameters() is the command's parameter table
// (support/parameters/parameter_table.hpp, parameter_tables.cpp): its options and Python keyword arguments.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "chaos/adaptive_d2.hpp"
#include "chaos/automatic_analysis.hpp"
#include "chaos/autocorrelation.hpp"
#include "chaos/bifurcation.hpp"
#include "chaos/cao.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/fnn.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/lyapunov_local_maps.hpp"
#include "chaos/models/lyapunov_spectrum.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/nonlinearity_test.hpp"
#include "chaos/series.hpp"
#include "chaos/surrogates.hpp"
#include "chaos/models/validation.hpp"
#include "chaos/models/zoo_suite.hpp"
#include "parameter_table.hpp"
#include "report.hpp"

namespace chaos::cli {

using cli_support::field;
using cli_support::Parameter;
using cli_support::ParameterField;
using cli_support::ParameterTable;

// chaos mutual
// Without max_delay, the delay search of choose_delay (100 samples, then on to two Theiler windows,
// at most N / 10), so the minimum `chaos analyze` finds is the one reported here.
struct MutualParams {
  std::optional<std::size_t> max_delay;
  MutualInformationOptions options;
  std::string estimator = "equal_width";
};
const ParameterTable<MutualParams>& mutual_parameters();
struct MutualRun {
  MutualInformationResult result;
  std::optional<std::size_t> minimum;
  std::string no_minimum;  // why there is no minimum, else empty
  Report report;
};
MutualRun run_mutual(const SeriesInput& in, MutualParams params, const OutputOptions& output = {});

// chaos autocorrelation
struct AutocorrelationParams {
  std::optional<std::size_t> max_lag;  // default: N/10, at most 1000, at least 1
};
const ParameterTable<AutocorrelationParams>& autocorrelation_parameters();
struct AutocorrelationRun {
  AutocorrelationResult result;
  std::optional<std::size_t> zero;
  std::optional<double> decay;
  Report report;
};
AutocorrelationRun run_autocorrelation(const SeriesInput& in, const AutocorrelationParams& params,
                                       const OutputOptions& output = {});

// chaos cao
// cao, fnn, d2, lyapunov, lyapunov-maps: a delay, Theiler window or dimension left out is chosen by
// choose_embedding (chaos/choose.hpp), and the report names the rule ("delay_source", ...).
struct CaoParams {
  std::optional<std::size_t> delay, theiler;
  CaoOptions options;
  std::string norm = "max";
};
const ParameterTable<CaoParams>& cao_parameters();
struct CaoRun {
  CaoResult result;
  Report report;
};
CaoRun run_cao(const SeriesInput& in, CaoParams params, const OutputOptions& output = {});

// chaos fnn
struct FnnParams {
  std::optional<std::size_t> delay, theiler;
  FnnOptions options;
  std::string norm = "euclidean";
};
const ParameterTable<FnnParams>& fnn_parameters();
struct FnnRun {
  FnnResult result;
  Report report;
};
FnnRun run_fnn(const SeriesInput& in, FnnParams params, const OutputOptions& output = {});

// chaos d2
struct D2Params {
  D2Params() { sums.max_dimension = 10; }
  CorrelationSumOptions sums;  // sums.progress: called with the fraction done (may throw to stop)
  std::function<void(double)> halves_progress;  // the same for each half's sums in the halves check
  CorrelationDimensionOptions dimension;
  std::optional<std::size_t> delay, theiler;
  std::optional<double> r_min, r_max;
  std::size_t radii = 40;
  std::vector<double> radius_list;
  std::string norm = "max";
  std::string search = "box";
  // A saturated D2 must be reproduced by each half of the record (check_record_halves), as in
  // chaos analyze; `--no-halves` for the plain estimate.
  bool halves = true;
  bool delay_check = false;  // --delay-check: a saturated D2 must be reproduced at twice the delay
  // --fast: two disjoint subsets of reference points, one from each half of the record with the
  // halves check and a budget (adaptive_d2.hpp). The command's budget is one round of 2 x 200
  // points, a quick look (0.11-0.16 s on Lorenz and Henon x at N = 10^5) that answers rough unless
  // it settles; --fast-budget 0 lets subsets of the whole record double until they agree, as the
  // library does by default (run_d2 then counts the halves after them).
  bool fast = false;
  AdaptiveD2Options adaptive{.initial_reference_points = 200, .budget = 400};
};
const ParameterTable<D2Params>& d2_parameters();
struct D2Run {
  CorrelationSumResult sums;
  CorrelationDimensionResult d2;
  Estimate estimate;  // D2 as one answer (d2_answer.hpp)
  Report report;
  std::optional<AdaptiveD2Result> fast;  // with --fast: the budget chosen and the rounds (its sums and d2 moved out)
};
D2Run run_d2(const SeriesInput& in, D2Params params, const OutputOptions& output = {});
CorrelationSearch parse_search(const std::string& name);

// chaos lyapunov
struct LyapunovParams {
  // m, m+1, m+2 must agree; Kantz neighbourhoods of at most 1000 points, as chaos analyze
  // (choose_lyapunov_options; lyapunov.hpp, max_neighbours)
  LyapunovParams() {
    fit.dimensions = 3;
    options.max_neighbours = default_max_neighbours;
  }
  LyapunovOptions options;
  LyapunovFitOptions fit;
  std::optional<std::size_t> delay, dimension, theiler, steps, period;
  // Left out: as chaos analyze, min(N, 10^4) evenly spaced reference points (choose_lyapunov_options);
  // 0: all of them.
  std::optional<std::size_t> reference_points;
  std::function<void(double)> choice_progress;  // Cao's method, where the dimension is chosen
  std::string method = "rosenstein";
  std::string norm = "max";
  // Run the other method too, with the same settings, and check the two against each other
  // (lyapunov.hpp, cross_check); its progress goes to check_progress. Also, as the
  // pipeline does (automatic_analysis.hpp, step 6), lambda_1 from local maps at m (and m + 1 where m
  // is inconsistent): a slope stands only where the local-map exponent is consistent and within the
  // tolerance of it (lyapunov_local_maps.hpp, cross_check); otherwise it is unconfirmed.
  bool cross_check = true;
  std::function<void(double)> check_progress;
  std::function<void(double)> maps_progress;  // the local-map check: 0 before, 0.5 before m + 1, 1 after
  // Run the same estimator over each half of the record: a linear region that neither half shows,
  // or that a half contradicts, is not_reproduced (check_record_halves), before the cross-check.
  // On by default, as in chaos analyze; `--no-halves` for the plain estimate.
  bool halves = true;
};
const ParameterTable<LyapunovParams>& lyapunov_parameters();
struct LyapunovRun {
  LyapunovResult result;
  std::optional<LyapunovResult> check;  // the other method's result, when cross-checked
  std::optional<LocalMapResult> local_maps;  // the local-map check, when cross-checked and it could run
  std::string local_maps_refusal;            // why it could not run (series too short), else empty
  // The answers, per time unit when dt is known: this method's, and lambda_1 from every estimator
  // run (none with the checks off).
  Estimate estimate;
  std::optional<LyapunovAnswer> lambda_1;
  Report report;
};
LyapunovRun run_lyapunov(const SeriesInput& in, LyapunovParams params, const OutputOptions& output = {});

// chaos lyapunov-maps: lambda_1 from local linear maps, checked over the estimator's own choices
// (lyapunov_local_maps.hpp). The Theiler window defaults to the data's correlation time, as in lyapunov.
struct LyapunovMapsParams {
  LocalMapOptions options;
  std::optional<std::size_t> delay, dimension, theiler;
  std::function<void(double)> choice_progress;  // Cao's method, where the dimension is chosen
  std::string norm = "max";
  double tolerance = 0.05;
};
const ParameterTable<LyapunovMapsParams>& lyapunov_maps_parameters();
struct LyapunovMapsRun {
  LocalMapResult result;
  Report report;
};
LyapunovMapsRun run_lyapunov_maps(const SeriesInput& in, LyapunovMapsParams params, const OutputOptions& output = {});

// chaos neighbors: a benchmark of the neighbour searches on the user's series and embedding
struct NeighborsParams {
  std::size_t dimension = 3;               // -m
  std::size_t delay = 1;                   // -d
  std::size_t theiler = 0;                 // -t
  std::optional<double> radius;            // -r: fixed-radius counts
  std::optional<std::size_t> k;            // -k: k nearest (k = 1 when neither -r nor -k is given)
  std::string norm = "max";
  std::vector<std::size_t> sizes;          // --sizes: the first n samples for each n (empty: all of them)
  bool brute = true;                       // false (--no-brute): nothing is checked
  std::optional<std::size_t> check_points; // --check-points K: brute force at K evenly spaced points only
  std::function<void(double)> progress;    // fraction of the queries done; may throw to stop
};
struct NeighborsRow {
  std::size_t n = 0;           // samples used
  std::size_t points = 0;      // embedded points, each a query point
  std::string structure;       // brute_force, kd_tree, box_grid, nanoflann
  std::string query;           // count (-r) or knn (-k)
  bool ran = true;             // false: skipped (nanoflann under the maximum norm), see note
  double build_seconds = 0.0, query_seconds = 0.0;
  std::size_t queries = 0;     // query points timed (brute force with --check-points: K)
  std::size_t memory_bytes = 0;  // held by the structure besides the series (brute force: 0)
  std::size_t checked = 0;     // query points compared with brute force
  std::size_t mismatches = 0;  // of those, answers that differ from brute force
  std::size_t tie_swaps = 0;   // nanoflann: answers with other indices at the same distances (not mismatches)
  std::string equal;           // yes, no, reference (brute force itself), unchecked (--no-brute), skipped
  std::string note;
};
struct NeighborsRun {
  std::vector<NeighborsRow> rows;
  bool all_equal = true;       // no row says "no"
  Report report;
};
// The option checks that need no data (k, radius, m, tau, K).
void check_neighbors_params(const NeighborsParams& params);
NeighborsRun run_neighbors(const SeriesInput& in, NeighborsParams params, const OutputOptions& output = {});

// chaos analyze
struct AnalyzeParams {
  std::optional<std::size_t> delay;
  std::optional<std::size_t> theiler;
  std::size_t max_delay = 100;
  std::size_t boxes = 16;
  std::size_t max_dimension = 10;
  std::size_t test_length = 4096;  // samples given to the nonlinearity test
  std::size_t surrogates = 19;
  std::uint64_t seed = 1;
  std::size_t builtin_length = 100000;  // of the built-in series, analysed without a file (enough for a confident lambda_1)
  bool delay_check = false;   // a saturated D2 must be reproduced at twice the delay too
  bool mutual_curve = false;  // also compute the information curve the delay was read from (for a plot)
  std::size_t threads = 1;    // Cao, FNN, the correlation sums, the curves and the maps; results identical for any number
  // Called with each step's name and the fraction of it done (AutomaticAnalysisOptions::progress),
  // also for the false neighbours and the surrogate test; may throw to stop.
  std::function<void(const std::string&, double)> progress;
};
const ParameterTable<AnalyzeParams>& analyze_parameters();
struct AnalyzeRun {
  AutomaticAnalysis analysis;
  std::optional<FnnResult> fnn;
  FnnOptions fnn_options;
  std::optional<NonlinearityTestResult> nonlinear;
  std::optional<EndMatch> segment;
  std::optional<MutualInformationResult> mutual;  // with params.mutual_curve, for a stationary series
  std::string theiler_source;
  // Whether the series shows determinism: Cao's E2 and the surrogate test together. E2 departs
  // from 1 for a linear stochastic oscillation seen through a static nonlinearity too (an AR(2)
  // process of period 40 through atan: max|E2 - 1| = 0.22-0.25 at N = 5000 and 2*10^4), which the
  // IAAFT surrogates share, so the surrogate test must reject as well. "deterministic",
  // "not_shown" (E2 departs, the surrogates do not differ), "stochastic" (E2 within its sampling
  // error of 1), or "not_run"; the explanation says which evidence gave it.
  std::string determinism, determinism_explanation;
  Report report;
};
// The file name of the built-in series, as `chaos analyze` reports it.
extern const char* const builtin_series_name;
// The built-in demonstration: Lorenz (10, 28, 8/3), x, RK4 h = 0.001 sampled every 0.01.
Series builtin_series(std::size_t length);
AnalyzeRun run_analyze(const SeriesInput& in, const AnalyzeParams& params, const OutputOptions& output = {});

// chaos surrogates
struct SurrogatesParams {
  SurrogateOptions options;
  std::string method = "iaaft";
  std::size_t count = 1;
  std::uint64_t seed = 1;
  bool end_match = false;
  EndMatchOptions end;
};
const ParameterTable<SurrogatesParams>& surrogates_parameters();
struct SurrogatesRun {
  std::vector<Surrogate> surrogates;
  std::optional<EndMatch> match;
  std::size_t length = 0;  // of the (trimmed) series the surrogates imitate
  Report report;
};
SurrogatesRun run_surrogates(const SeriesInput& in, SurrogatesParams params, const OutputOptions& output = {});
SurrogateMethod parse_surrogate_method(const std::string& name);

// chaos nonlinearity
struct NonlinearityParams {
  NonlinearityTestOptions options;
  std::string statistic = "prediction_error";
  std::string alternative = "two_sided";
  std::string method = "iaaft";
  std::string norm = "max";
  // Left out: chosen on the (trimmed) series by choose.hpp's rules (the dimension and window for the
  // prediction statistic only), the same embedding for the data and every surrogate.
  std::optional<std::size_t> delay, dimension, theiler;
  std::function<void(double)> choice_progress;  // Cao's method, where the dimension is chosen
  bool end_match = false;
};
const ParameterTable<NonlinearityParams>& nonlinearity_parameters();
struct NonlinearityRun {
  NonlinearityTestResult result;
  Report report;
};
NonlinearityRun run_nonlinearity(const SeriesInput& in, NonlinearityParams params, const OutputOptions& output = {});

// chaos generate SYSTEM (a reference system of generate.hpp or a zoo system)
struct GenerateParams {
  std::string system;
  std::size_t length = 10000;
  std::map<std::string, double> parameters;  // -p name=value
  std::uint64_t seed = 1;
  std::string components = "all";
};
const ParameterTable<GenerateParams>& generate_parameters();
struct GenerateRun {
  Trajectory trajectory;
  std::vector<std::size_t> chosen;  // the components written, in order
  Report report;
};
// with_components: put the chosen components into the JSON ("components"), as --json writes them.
GenerateRun run_generate(const GenerateParams& params, const OutputOptions& output = {}, bool with_components = true);

// chaos spectrum SYSTEM (a reference system or a zoo system, from its equations)
struct SpectrumParams {
  std::string system;
  std::map<std::string, double> parameters;  // -p name=value
  std::optional<double> time, step, flow_interval, flow_transient;
  std::optional<std::size_t> iterations, map_interval, map_transient;
  std::uint64_t seed = 1;
  std::optional<std::size_t> delay_exponents;
  bool identity = false;
};
const ParameterTable<SpectrumParams>& spectrum_parameters();
struct SpectrumRun {
  LyapunovSpectrum spectrum;
  Report report;
};
SpectrumRun run_spectrum(const SpectrumParams& params, const OutputOptions& output = {});

// chaos density: rows of (parameter, value) -> the density of the values per parameter value
struct DensityParams {
  std::optional<std::size_t> bins;
  std::size_t max_bins = 200;
  bool kde = false;
  std::optional<double> bandwidth, low, high;
  double padding = 0.05;
};
const ParameterTable<DensityParams>& density_parameters();
struct DensityRun {
  std::vector<double> parameters;             // the distinct parameter values, ascending
  std::vector<std::vector<double>> samples;   // the values of each
  DensityMap map;
  std::string method;
  Report report;
};
// The option checks (before any input is read).
void check_density_params(const DensityParams& params);
DensityRun run_density(std::span<const double> parameter, std::span<const double> value, const std::string& file,
                       std::size_t parameter_column, std::size_t value_column, const DensityParams& params,
                       const OutputOptions& output = {});

// chaos section: a Poincare section of a multi-column series
struct SectionParams {
  std::vector<std::size_t> columns;          // the columns read, 1-based (empty: every column but the time column)
  std::optional<std::size_t> time_column;    // the column holding the time; none: rows dt apart
  double dt = 1.0;
  std::optional<std::size_t> period;         // stroboscopic: every PERIOD-th row ...
  std::size_t phase = 0;                     // ... from this row
  std::optional<std::size_t> hyperplane;     // hyperplane: the crossings of this column ...
  std::optional<double> level;               // ... through this level
  std::string direction = "up";              // up, down or both
};
const ParameterTable<SectionParams>& section_parameters();
// The option checks made before any input is read (one section, a level for a hyperplane, dt > 0,
// the direction's name).
void check_section_params(const SectionParams& params);
// The columns of a section's input text, read as `chaos section` reads them (-x -l): params.columns
// (filled with every column but the time column when empty) and, with a time column, the times.
struct SectionColumns {
  std::vector<std::vector<double>> columns;
  std::vector<double> times;  // empty without params.time_column
};
SectionColumns read_section_columns(const std::string& text, const std::string& name, SectionParams& params,
                                    std::size_t skip, std::optional<std::size_t> length);
struct SectionRun {
  std::vector<double> time;                  // of each section point
  std::vector<std::vector<double>> points;   // one row per section point, one value per column read
  std::vector<std::optional<double>> return_time;  // hyperplane: since the previous crossing (none for the first)
  std::size_t rows = 0;                      // N, the rows read
  Report report;
};
// data: one column per params.columns, all of the same length; times: the time column's values
// (empty: rows dt apart).
SectionRun run_section(const std::vector<std::span<const double>>& data, std::span<const double> times,
                       const std::string& file, const SectionParams& params, const OutputOptions& output = {});

// chaos validate: the reference cases of references/references.tsv, run on this machine
struct ValidateParams {
  std::string filter;  // only cases whose id contains this text; empty: every case
};
const ParameterTable<ValidateParams>& validate_parameters();
// The cases selected, in table order; refuses a filter that matches no case id.
std::vector<Reference> validate_cases(const ValidateParams& params);
// The report with its parameters, before any case runs (the command line writes its header then).
Report validate_report(const ValidateParams& params, const OutputOptions& output = {});
struct ValidateTally {
  std::size_t passed = 0, failed = 0;
};
// Runs the selected cases in table order, each appended to the report's "cases" as `chaos validate
// --json` writes it, then "passed" and "failed". `each` is called after every case (the command
// line prints its row; it may throw to stop).
ValidateTally run_validate(const ValidateParams& params, Report& report,
                           const std::function<void(const ValidationResult&)>& each = nullptr);

// chaos zoo --series NAME: the exact series a zoo case is analysed with
struct ZooSeriesParams {
  std::string name;          // the case (the first column of docs/validation/zoo.md)
  bool fast = false;         // the CI subset's cases (N = 10^4)
  std::size_t threads = 1;   // the spectra behind the cases' bands
};
// Its Python function's table: `chaos zoo --series` takes --fast and --threads from zoo_parameters.
const ParameterTable<ZooSeriesParams>& zoo_series_parameters();
struct ZooSeriesRun {
  std::vector<double> x;
  Report report;             // parameters case, kind, description, N, dt; "x" the series
};
ZooSeriesRun run_zoo_series(const ZooSeriesParams& params, const OutputOptions& output = {});

// chaos zoo: the out-of-sample regression suite (zoo_suite.hpp) and its Markdown report
struct ZooParams {
  bool fast = false;                // the CI subset
  bool grid = true;                 // chaotic systems over the neighbourhood grid
  std::size_t grid_points = 2;      // grid points per system at N = 10^5, 1..12 (ZooSuiteOptions)
  std::vector<std::string> only;    // these cases (empty: every case)
  std::size_t threads = 1;          // cases run in parallel (the report does not depend on it)
  std::string checkpoint;           // append each finished case here and skip those it holds (zoo_checkpoint.hpp)
};
const ParameterTable<ZooParams>& zoo_parameters();
struct ZooRun {
  std::vector<ZooCase> cases;
  std::vector<ZooCaseResult> results;  // one per case, in case order
  double wall_seconds = 0.0;           // this run's; cases read from a checkpoint keep their own times
  std::size_t resumed = 0;             // cases read from the checkpoint, not run
  std::size_t wrong = 0;               // confident estimates outside their band, over every row
  // Coverage at the automatic choices: chaotic systems whose D2 answer and whose lambda_1 answer
  // are confident and in band.
  std::size_t chaotic = 0, d2_covered = 0, lambda_covered = 0;
  std::string markdown;                // the report `chaos zoo` writes (docs/validation/zoo.md)
  nlohmann::ordered_json json;         // the same as data: parameters, counts, one entry per row
};
// `each` is called after every case run (serialised, from the worker threads) with the number of
// cases done (those read from the checkpoint included), their total, the case and its result; it may
// throw to stop (the other threads finish their case first, and the checkpoint keeps it).
ZooRun run_zoo(const ZooParams& params,
               const std::function<void(std::size_t, std::size_t, const ZooCase&, const ZooCaseResult&)>& each = nullptr);

}  // namespace chaos::cli
