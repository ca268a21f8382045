#pragma once
// The out-of-sample regression suite run by `chaos zoo`: every chaotic system of the zoo (zoo.hpp)
// and a set of negative and tricky controls (control_signals.hpp, IAAFT surrogates, noisy,
// quantised and short chaos) through the automatic pipeline (automatic_analysis.hpp), with each
// confident estimate judged against a band fixed in advance:
//   - D2 within 0.1 of the attractor's own D2 at the same N, Theiler window and scales: the
//     plateau of the full state's correlation sums from the equations (zoo_state_d2.hpp), per N and
//     window, with its own interval (the band is that interval widened by 0.1 at each end). Where the
//     state has none (a delay equation, no plateau, or a reading that moves by more than 0.1 in
//     another coding of the same samples: zoo_state_d2.hpp), within +-0.1 of a cited
//     literature D2, or, where none is cited, not above D_KY + 0.1 (D_KY from the equations). The
//     zero-scale values (literature, D_KY) stay in the report for information;
//   - lambda_1 within 10% of the spectrum's lambda_1 from the equations (each estimator's strict fit,
//     and the one answer of lyapunov_answer.hpp where it is confident);
//   - noise, surrogates and random walks: no confident D2 and no confident lambda_1 at all;
//   - periodic and quasi-periodic signals: a confident D2 must equal the torus dimension (1, 2 or 3)
//     within +-0.1, and no confident lambda_1.
// A confident estimate outside its band is "wrong": the one outcome the suite exists to exclude.
// Chaotic systems are also run over a neighbourhood of the automatic choices: N in {1e4, 1e5}, the
// Theiler window at 1, 2 and 3 times the automatic one, and the embedding dimension from Cao's to
// Cao's + 3 (for D2 the highest dimension of the saturation test, for lambda_1 the lowest of the
// three fitted together).

#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "chaos/correlation_dimension.hpp"
#include "chaos/lyapunov.hpp"

namespace chaos {

enum class ZooCaseKind { chaotic, noise, surrogate, random_walk, periodic, quasi_periodic, noisy_chaos, quantised, short_series };
const char* to_string(ZooCaseKind kind) noexcept;

// One estimate judged: a confident value inside its band, a confident value outside it, or unsure
// (a status without a value: not saturated, no linear region, not run).
enum class ZooVerdict { in_band, wrong, unsure };
const char* to_string(ZooVerdict verdict) noexcept;

struct ZooBand {
  std::vector<Interval> accepted;  // a confident value must lie in one of these; empty: none is right
  std::string source;              // where the band comes from, in words
};

struct ZooCase {
  std::string name;
  ZooCaseKind kind = ZooCaseKind::chaotic;
  std::string system;       // the zoo system behind it, empty for pure signals
  std::string description;
  std::size_t length = 100000;
  std::optional<double> dt;  // sampling interval (flows)
  std::function<std::vector<double>(std::size_t n)> series;
  // Chaotic systems with a state vector: the state of the same n samples (zoo_state), from which
  // each row's D2 reference is computed; empty otherwise.
  std::function<std::vector<std::vector<double>>(std::size_t n)> state;
  ZooBand d2_band, lambda_band;  // lambda band per time unit (flows) or per iteration (maps)
  // From the equations and the references (chaotic cases): NaN where not known.
  double lambda_equations = std::numeric_limits<double>::quiet_NaN();
  double kaplan_yorke = std::numeric_limits<double>::quiet_NaN();
  double literature_lambda = std::numeric_limits<double>::quiet_NaN();
  double literature_d2 = std::numeric_limits<double>::quiet_NaN();
  double dysts_lambda = std::numeric_limits<double>::quiet_NaN();
  double dysts_d2 = std::numeric_limits<double>::quiet_NaN();
  bool grid = false;  // run the neighbourhood grid, not only the automatic choices
};

struct ZooSuiteOptions {
  bool fast = false;        // the CI subset: a few systems and controls at N = 10^4, automatic choices only
  bool grid = true;         // chaotic systems over the neighbourhood grid
  // Grid points per system at N = 10^5, 1 to 12 (three Theiler windows by four dimensions; 12: all),
  // chosen by the case's name so that over the zoo each point is run about equally often. N = 10^4
  // runs all 12.
  std::size_t grid_points = 2;
  std::vector<std::string> only;  // case names to run (empty: all)
  std::size_t threads = 1;        // zoo_cases: the spectra behind the bands in parallel
};

// The cases, in a stable order; builds the chaotic bands from each system's spectrum (zoo_spectrum),
// on options.threads threads. An exception from a spectrum (a system that escapes) propagates.
std::vector<ZooCase> zoo_cases(const ZooSuiteOptions& options);

// One evaluated estimate.
struct ZooEstimate {
  std::optional<double> value;
  std::optional<Interval> interval;
  std::string status;
  ZooVerdict verdict = ZooVerdict::unsure;
  // The embedding dimension the estimate used, where it is not the row's: the pipeline's local maps
  // at m + 1 (automatic_analysis.hpp, step 6).
  std::optional<std::size_t> dimension;
};

// One row: a case at one point of the grid (N, Theiler window, dimension).
struct ZooRow {
  std::size_t n = 0;
  double theiler_factor = 1.0;
  std::size_t theiler = 0, delay = 0, dimension = 0;  // dimension: m of the grid point (0: none)
  bool automatic = true;                              // the automatic choices, not a neighbour
  ZooEstimate d2, rosenstein, kantz;
  ZooEstimate local_maps;  // lambda_1 from local linear maps (lyapunov_local_maps.hpp), confident when consistent
  // lambda_1, the one answer of lyapunov_answer.hpp (status confident, rough or none), judged like
  // the others where confident; its interval's calibration is summarised in the report.
  ZooEstimate lyapunov;
  // D2, the one answer of d2_answer.hpp (confident, rough or none), judged like `d2` where confident;
  // its interval's calibration against the reference is summarised in the report.
  ZooEstimate d2_answer;
  // The attractor's own D2 at this row's N and Theiler window (state_d2_reference; status none where
  // the state gives no plateau or the case has no state), and the band both D2 columns were judged by.
  ZooEstimate d2_reference;
  ZooBand d2_band;
  std::string note;  // why the pipeline stopped, when it did
};

struct ZooCaseResult {
  std::size_t case_index = 0;
  std::vector<ZooRow> rows;
  double seconds = 0.0;
  std::string error;  // a refusal from the pipeline (e.g. a series too short), when there was one
};

// A point of the neighbourhood grid: Theiler window 1, 2 or 3 times the automatic one (window 0, 1,
// 2) and embedding dimension m0 + extra (extra 0..3), with m0 Cao's.
struct ZooGridPoint {
  std::size_t window = 0, extra = 0;
};

// The grid points a case runs at record length n: all 12 at N <= 10^4; at longer records `sample` of
// them, evenly spaced in the order (window, extra) from a start drawn from the case's name (FNV-1a),
// so that a case runs the same points in any selection of cases and over the zoo every point is run
// about equally often.
std::vector<ZooGridPoint> zoo_grid_points(std::size_t n, const std::string& name, std::size_t sample);

// Runs one case (deterministic; single-threaded inside).
ZooCaseResult run_zoo_case(const ZooCase& c, std::size_t case_index, const ZooSuiteOptions& options);

// Judges a value against a band.
ZooVerdict judge(const std::optional<double>& value, bool confident, const ZooBand& band);

}  // namespace chaos
