#pragma once
// The automatic pipeline from a scalar series to its invariants, every choice made by the rules of
// choose.hpp and every estimate with a status, so a caller never has to hand-pick:
//   1. time scales (time_scales.hpp): stationarity, the correlation time, a dominant period; a
//      non-stationary series stops here, saying so;
//   2. the delay (choose_delay); none, nothing further runs;
//   3. the Theiler window (choose_theiler_window: the correlation time, at least the delay);
//   4. the embedding dimension m (choose_embedding_dimension: Cao's E1); none, nothing further runs;
//   5. D2 from correlation sums for m = 1..m + extra_dimensions (correlation_dimension.hpp); a
//      saturated D2 must be reproduced by the two halves of the record (require_reproduced_by_halves),
//      and, when asked (check_delay), at twice the delay (require_reproduced_at_delay);
//   6. lambda_1 by Rosenstein and by Kantz, each fitted over m, m+1, m+2 at once (lyapunov.hpp,
//      choose_lyapunov_options); a linear region must be reproduced by the record's two halves; the
//      two fits are then checked against each other (cross_check): a linear region that only one of
//      them finds, or two slopes more than 10% apart, leaves both unconfirmed;
//   7. lambda_1 from local linear maps (lyapunov_local_maps.hpp) at m; where its variants disagree
//      (inconsistent), once more at m + 1, which is reported when it is consistent. Cao's m is the
//      least dimension that unfolds the attractor at the chosen delay, so the variants that embed
//      differently (above all the delay + tau/4 one) can fall short of it and disagree because of
//      the embedding, not the exponent. A Rosenstein or Kantz slope stands only where the reported
//      value is consistent and within 10% of it; beside maps that are not consistent, or that could
//      not be run, it is unconfirmed as well.
// A step that refuses the series (too short for its embedding) does not lose the others: `stopped`
// says which refused and why, and what the steps before it found, and the steps after it, stand.
// `chaos analyze`, `chaos zoo` and the study run this pipeline.

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "chaos/cao.hpp"
#include "chaos/choose.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/d2_answer.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/lyapunov_answer.hpp"
#include "chaos/lyapunov_local_maps.hpp"
#include "chaos/time_scales.hpp"

namespace chaos {

struct AutomaticAnalysisOptions {
  std::optional<std::size_t> delay, theiler, dimension;  // given values replace the automatic choices
  DelaySearch delay_search;
  std::size_t max_dimension = 10;    // of Cao's method
  std::size_t extra_dimensions = 3;  // D2 up to m + 3: saturation is judged above m
  std::size_t radii = 40;            // choose_radii
  // Off only where stationarity is known from how the record was made (a driven mechanism sampled
  // over whole periods of its drive): the rule of time_scales.hpp cannot tell a few periods of a
  // regular oscillation from a drift.
  bool check_stationarity = true;
  bool check_halves = true;          // a saturated D2 and a divergence slope must be reproduced by the record's two halves
  // ... and at twice the delay. Off by default: on the zoo it withdrew more right values than wrong
  // ones (docs/notes/zoo-notes.md, "The delay neighbourhood").
  bool check_delay = false;
  bool rosenstein = true, kantz = true;
  bool cross_check = true;           // a lambda_1 the other estimators do not confirm is unconfirmed
  bool local_maps = true;            // lambda_1 from local linear maps too (lyapunov_local_maps.hpp)
  bool local_maps_next_dimension = true;  // ... and at m + 1 where the run at m is inconsistent
  std::size_t threads = 1;           // results identical for any number
  // Called with the step running ("Cao's method", "correlation sums", ...) and its fraction done,
  // for a progress display; the analysis does not depend on it.
  std::function<void(const std::string& step, double fraction)> progress = nullptr;
};

struct AutomaticAnalysis {
  TimeScales scales;
  std::optional<std::size_t> delay;
  std::string delay_source;
  std::size_t delay_searched = 0;  // the largest delay the search examined (0: the delay was given or 1)
  MutualInformationResult delay_information;  // the search's curve, I(0..delay_searched) (choose_delay)
  std::size_t theiler = 0;
  std::string theiler_source;
  std::optional<std::size_t> dimension;  // Cao's, or the given one
  std::optional<CaoResult> cao;
  std::size_t cao_samples = 0;  // the samples Cao's method read (choose_embedding_dimension)
  std::optional<CorrelationDimensionResult> d2;
  // D2 as one answer with an interval and a status (d2_answer.hpp); empty where D2 did not run.
  std::optional<Estimate> d2_estimate;
  std::optional<LyapunovResult> rosenstein, kantz;
  // lambda_1 from local linear maps at (m, tau, w) with the estimator's defaults, or at (m + 1, tau,
  // w) where the run at m was inconsistent and that one is consistent (its variants' first entry
  // gives the dimension; its explanation names the run at m, which local_maps_at_m keeps). Where
  // both are unsure, the run at m, its explanation extended by the retry's. Empty when not run or
  // refused (local_maps_refusal says why).
  std::optional<LocalMapResult> local_maps;
  std::optional<LocalMapResult> local_maps_at_m;
  std::string local_maps_refusal;
  // lambda_1 from the three together, with one interval and status (lyapunov_answer.hpp); empty
  // where the Lyapunov step did not run.
  std::optional<LyapunovAnswer> lyapunov;
  std::string stopped;  // empty when every step ran; otherwise why it stopped, or which steps refused
};

// D2 as the pipeline computes it: correlation sums of x with `sums`, and, when D2 saturates, the
// halves check on the same radii (the first and the second half of x), then, when asked, the delay
// check.
CorrelationDimensionResult automatic_correlation_dimension(std::span<const double> x, const CorrelationSumOptions& sums,
                                                           bool check_halves = true, bool check_delay = false);
// The halves check for a D2 already computed from x with `sums` and `options`: when it saturated,
// the same sums and rules over each half (require_reproduced_by_halves). A half too short to embed
// counts as not reproducing the plateau, and the explanation says why.
void check_record_halves(CorrelationDimensionResult& d2, std::span<const double> x, const CorrelationSumOptions& sums,
                         const CorrelationDimensionOptions& options = {});
// The halves check for a divergence fit already computed from x with `options` and `fit`: when it
// found a linear region, the same estimator with the same options over each half (the Kantz radius
// found by the same rule on each half, the same steps). A half too short for the curve counts as not
// reproducing the slope, and the explanation says why.
void check_record_halves(LyapunovResult& result, std::span<const double> x, LyapunovOptions options,
                         const LyapunovFitOptions& fit);
// The same for several results of one series that share their embeddings (largest_lyapunov_runs,
// e.g. Rosenstein's and Kantz's): each half is embedded once for all of them, and each
// result ends as check_record_halves on it alone leaves it. options[r] are the options of results[r].
void check_record_halves(std::span<LyapunovResult* const> results, std::span<const double> x,
                         const std::vector<LyapunovOptions>& options, const LyapunovFitOptions& fit);
// The delay check for a D2 already computed from x with `sums` and `options`: when it saturated, the
// same sums and rules at twice sums.delay (require_reproduced_at_delay). A record too short to embed
// at that delay counts as not reproducing the plateau, and the explanation says why.
void check_delay_variant(CorrelationDimensionResult& d2, std::span<const double> x, const CorrelationSumOptions& sums,
                         const CorrelationDimensionOptions& options = {});
// The two halves of a record, as the halves check splits it: [0, n/2) and [n/2, n).
std::pair<std::span<const double>, std::span<const double>> record_halves(std::span<const double> x);

// Step 7 on its own: lambda_1 from local maps with `options` (its dimension m), and, where that run is
// inconsistent and `next_dimension` holds, once more at m + 1 (progress through `retrying`, when set,
// before it). `result` is the run at m + 1 when that one is consistent (its explanation then names
// both runs, and `at_m` keeps the first), else the run at m with the retry's verdict appended. Throws
// InvalidInput when the run at m cannot be made; a retry that cannot be made is named in the result.
struct LocalMapsRuns {
  LocalMapResult result;
  std::optional<LocalMapResult> at_m;
};
LocalMapsRuns local_maps_with_next_dimension(std::span<const double> x, const LocalMapOptions& options,
                                             std::optional<double> dt, bool next_dimension = true,
                                             const std::function<void()>& retrying = {});

AutomaticAnalysis analyse_series(std::span<const double> x, std::optional<double> dt = std::nullopt,
                                 const AutomaticAnalysisOptions& options = {});

}  // namespace chaos
