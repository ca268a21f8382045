#pragma once
// The largest Lyapunov exponent from a scalar time series, by the divergence of neighbouring
// trajectories in a delay embedding. Two published estimators, named for what they average:
//
//   Rosenstein, Collins & De Luca 1993 (Physica D 65:117): every reference point X_i is paired with
//     its nearest neighbour X_j (|i - j| > w, the Theiler window); the curve is the mean of the LOG
//     distances of the pairs followed for k steps,
//       y(k) = < ln |X_{i+k} - X_{j+k}| >_i ;
//   Kantz 1994 (Phys. Lett. A 185:77): every reference point X_i collects all points X_j with
//     |X_i - X_j| < eps (the eps-neighbourhood U_i, |i - j| > w); the curve is the mean over
//     reference points of the log of the MEAN distance within the neighbourhood,
//       S(k) = < ln( (1/|U_i|) sum_{j in U_i} |X_{i+k} - X_{j+k}| ) >_i .
//
// Both grow as lambda_1 k while the separation is small and the direction of largest growth has
// taken over, then saturate at the size of the attractor. The estimator returns the raw curve;
// fitting is a separate step (fit_divergence) that finds the straight part without a hand-picked
// range by the scaling-region machinery (scaling_region.hpp): the widest stretch of steps on which
// the local slopes are positive and stay within a tolerance of their mean. lambda_1 is the
// least-squares slope there, per sample, and per time unit when the sampling interval is known;
// its interval is the range of the local slopes over the stretch. A curve that never rises, or has
// no straight rising stretch, gets a status and no number: white noise has no linear region (its
// curve jumps to saturation within m steps). Only positive exponents are estimated.
//
// Conventions (docs/reference/lyapunov.md):
//   - neighbours come from the kd-tree of neighbors.hpp; the Theiler window w excludes |i - j| <= w;
//   - the pairs are followed for the same steps 0..K: reference points and neighbours are the first
//     P = N - (m-1) tau - K embedded points, so every curve value averages the same pairs and no
//     pair runs off the end of the series;
//   - ties: a neighbour identical to the reference point (distance 0 at step 0, quantised data) is
//     not a neighbour (neighbors.hpp's skip_zero_distance: nothing can diverge exponentially from 0);
//     a zero distance at a later step has no logarithm and is left out of that step's average
//     (Rosenstein: the pair; Kantz: the reference point when its neighbourhood's mean distance is 0),
//     and counted. A step where nothing is left is undefined (nullopt), never -inf or NaN;
//   - distances in the chosen norm (max by default, as everywhere in the library); the distance
//     between X_{i+k} and X_{j+k} is that of the whole delay vectors, as TISEAN's lyap_k computes
//     it (Hegger, Kantz & Schreiber 1999);
//   - deterministic: the same result for any thread count (partial sums are formed over fixed
//     blocks of reference points and added in block order).

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "chaos/estimate.hpp"
#include "chaos/norm.hpp"
#include "chaos/scaling_region.hpp"

namespace chaos {

enum class LyapunovMethod { rosenstein, kantz };
const char* to_string(LyapunovMethod method) noexcept;

struct LyapunovOptions {
  LyapunovMethod method = LyapunovMethod::rosenstein;
  std::size_t dimension = 2;   // m
  std::size_t delay = 1;       // tau, samples
  std::size_t theiler = 0;     // w, samples: neighbours need |i - j| > w
  std::size_t steps = 20;      // K: the curve covers k = 0..K samples
  Norm norm = Norm::max;
  // Kantz only: the neighbourhood radius eps (strict: distance < eps, the correlation-sum
  // convention). nullopt: start from the data's range / 1000 (TISEAN lyap_k's smallest default
  // length scale: small neighbourhoods leave the most room for growth before saturation), then,
  // judged on at most 1000 evenly spaced reference points: double it while fewer than half of them
  // have min_neighbours neighbours, else halve it while they have more than 20 on average and at
  // least half keep min_neighbours (the cost grows with the neighbourhood, the precision hardly
  // does). Reference points with fewer than min_neighbours neighbours are skipped.
  std::optional<double> radius;
  std::size_t min_neighbours = 1;
  // Kantz only: at most this many neighbours per reference point (0: no bound). A neighbourhood
  // with more (after the thinning of ties below) is represented by max_neighbours of its members,
  // with their weights, evenly spaced in index order
  // (U[floor(r |U| / max_neighbours)], r = 0, 1, ...), so a curve costs at most reference points x
  // max_neighbours x (K + 1) distances whatever eps and the data (a given eps on drifting data can
  // put most of the record in every neighbourhood). The curve counts the reference points affected
  // (capped_neighbourhoods).
  std::size_t max_neighbours = 0;
  // Kantz only: members of a neighbourhood that share one exact distance from the reference point
  // (ties: in quantised data most pairs lie at one of a few distances, and a radius just above the
  // smallest of them takes thousands of points at once) are represented, when more than this many,
  // by this many of them, each standing for its share of the group, so the mean over the
  // neighbourhood keeps each distance's weight: the group ordered by delay vector
  // (lexicographically) and then by index, the members at ranks floor(r |G| / max_tied_neighbours).
  // Untied data never have such a group, so their curves are unchanged; the curve counts the
  // reference points affected (tied_neighbourhoods). 0: no thinning.
  std::size_t max_tied_neighbours = 8;
  // Reference points: 0 uses all P; otherwise this many, evenly spaced over 0..P-1 (deterministic).
  std::size_t reference_points = 0;
  std::size_t threads = 1;     // results are identical for any thread count
  // Called with the fraction done (0 to 1), for a progress display; the result does not depend on it.
  std::function<void(double)> progress = nullptr;
  void validate() const;
};

// The raw divergence curve.
struct DivergenceCurve {
  LyapunovMethod method = LyapunovMethod::rosenstein;
  std::vector<std::size_t> step;                  // k = 0..K
  std::vector<std::optional<double>> divergence;  // y(k) (Rosenstein) or S(k) (Kantz), ln of data units
  std::vector<std::size_t> terms;                 // log terms averaged at each step
  std::vector<std::size_t> zero_distances;        // terms left out at each step (zero distance)
  std::size_t points = 0;              // P: embedded points that can be followed for K steps
  std::size_t reference_points = 0;    // reference points examined
  std::size_t references_used = 0;     // with a neighbour (Rosenstein) or >= min_neighbours (Kantz)
  double radius = 0.0;                 // Kantz: eps used; 0 for Rosenstein
  double mean_neighbours = 0.0;        // mean neighbourhood size of the references used (1 for Rosenstein)
  std::size_t capped_neighbourhoods = 0;  // Kantz: references whose neighbourhood was cut to max_neighbours
  std::size_t tied_neighbourhoods = 0;    // Kantz: references with a tie group thinned to max_tied_neighbours
  std::size_t pairs_followed = 0;         // pairs whose distances were followed for K steps: the curve's work
  double mean_initial_distance = 0.0;  // exp of the step-0 value: typical starting separation
};

// The curve by the chosen method. Refuses (InvalidInput) non-finite or constant series, invalid
// options, and series too short: N must be at least (m-1) tau + K + 2w + 3 so that P >= 2w + 3
// and every reference point has admissible candidates. When no reference point finds a neighbour
// the curve is returned empty of terms (every value nullopt) and the fit says so.
DivergenceCurve divergence_curve(std::span<const double> x, const LyapunovOptions& options = {});

enum class LyapunovStatus {
  linear_region,     // lambda from the fitted straight stretch
  no_linear_region,  // no stretch of min_steps steps whose positive local slopes agree within the tolerance
  not_diverging,     // no local slope is positive: the curve does not rise, no exponential divergence
  no_neighbours,     // no reference point had a neighbour: nothing to fit
  unconfirmed,       // a linear region, but another estimator finds none or another slope (cross_check)
  not_reproduced,    // a linear region that neither half of the record shows, or that a half contradicts
};
const char* to_string(LyapunovStatus status) noexcept;

struct LyapunovFitOptions {
  // The straight stretch is the widest run of steps whose local slopes (least-squares slopes
  // through 2 half_width + 1 steps) are all positive and lie within tolerance * mean of their
  // mean, over at least min_steps steps. 0 selects the automatic value, which scales with the curve's length K:
  // half_width = max(2, K / 25), min_steps = 3 half_width + 1 (one and a half local-slope windows).
  double tolerance = 0.1;
  std::size_t half_width = 0;
  std::size_t min_steps = 0;
  // The period of a dominant oscillation, in steps (0: none). A rotating flow (Rossler) modulates
  // the divergence with its orbit period, so local slopes over a few steps swing by more than any
  // tolerance. With a period (and the automatic half width), the local slope at k is the secant
  // over one whole period centred on k, the mean of the short slopes over the period, in which the
  // periodic part cancels; a linear region spans at least one period plus one step.
  std::size_t period = 0;
  // Embedding dimensions that must agree (largest_lyapunov): curves for m, m+1, ..., m+dimensions-1
  // must share the linear region and their slopes there agree within the tolerance. The exponent
  // does not depend on m, while the initial transient (neighbours selected close in the delay
  // window, then relaxing onto the unstable direction) does: a stretch of the transient that looks
  // straight in one dimension has another slope in the next, and is refused. 1: the given m alone.
  std::size_t dimensions = 1;
  // The curve must rise by at least this much (natural log units) across the linear region: an
  // exponential divergence is only identified when the separation grows over a range of scales.
  // 2 (a factor e^2 = 7.4, close to a decade) refuses the short straight-looking pieces of the
  // initial transient, which rise by less than one e-fold before the true slope takes over.
  double min_rise = 2.0;
  void validate() const;
};

struct LyapunovFit {
  LyapunovStatus status = LyapunovStatus::no_neighbours;
  std::size_t half_width = 0, min_steps = 0;         // the values used
  std::vector<std::optional<double>> local_slope;    // per step, per sample
  std::optional<std::size_t> first_step, last_step;  // the straight stretch, inclusive
  std::optional<double> lambda;                      // per sample (per iteration for maps)
  std::optional<Interval> lambda_interval;           // range of the local slopes over the stretch
  std::vector<double> lambda_by_curve;               // least-squares slope of each curve over the stretch
  std::string explanation;                           // one sentence a user can read
  // The answer (estimate.hpp), per sample: the strict linear region's slope where there is one;
  // else the straightest stretch rising by 1 e-fold at the tolerance, then at 2 and 3 times it
  // (these two `rough`). Its interval spans the least-squares slopes of every curve over the
  // stretch and over each half of it. It is `confident` only when its stretch meets the tolerance
  // and that span is at most 10% of the value either side; the checks below (cross_check,
  // require_reproduced_by_halves) only ever make it rough, saying why. `none` where nothing rises.
  Estimate estimate;
};

LyapunovFit fit_divergence(const DivergenceCurve& curve, const LyapunovFitOptions& options = {});
// Several curves of one series (embedding dimensions m, m+1, ...) fitted together: one stretch
// shared by all, lambda the mean of their least-squares slopes, which must agree within the
// tolerance. The reported local slopes are the first curve's.
LyapunovFit fit_divergence(const std::vector<DivergenceCurve>& curves, const LyapunovFitOptions& options = {});

struct LyapunovResult {
  DivergenceCurve curve;
  LyapunovFit fit;
  LyapunovOptions options;                  // the settings used (radius filled in for Kantz)
  std::optional<double> dt;                 // sampling interval, when known
  std::optional<double> lambda_per_time;    // fit.lambda / dt
  std::optional<Interval> lambda_per_time_interval;
  std::optional<Interval> fit_range_time;   // the fitted stretch in time units, when dt is known
  std::vector<std::size_t> dimensions;      // the embedding dimensions fitted together (fit.dimensions)

  // The fit's answer (LyapunovFit::estimate) per time unit when dt is known, else per sample.
  Estimate estimate_per_time() const { return dt ? scaled(fit.estimate, 1.0 / *dt) : fit.estimate; }
};

// The shortest series the curves of `dimensions` embedding dimensions m, m+1, ... can be computed
// from: (m_highest - 1) tau + steps + 2 w + 3 (saturating, for any option values).
std::size_t minimum_length(const LyapunovOptions& options, std::size_t dimensions = 1);

// Curve and fit in one call; `dt` (when known) converts to time units.
LyapunovResult largest_lyapunov(std::span<const double> x, const LyapunovOptions& options = {},
                                const LyapunovFitOptions& fit = {}, std::optional<double> dt = std::nullopt);
// Several runs on one series at once, typically Rosenstein's and Kantz's estimators with their
// cross-check: each result equals largest_lyapunov(x, runs[r], fit, dt) bit for bit, while each
// embedding dimension is embedded once for all runs (one rescaled series, one kd-tree, one
// reference order). The runs may differ in method, radius, min_neighbours, max_neighbours and
// progress; they must share m, delay, Theiler window, steps, norm and reference points
// (InvalidInput otherwise).
std::vector<LyapunovResult> largest_lyapunov_runs(std::span<const double> x, const std::vector<LyapunovOptions>& runs,
                                                  const LyapunovFitOptions& fit = {},
                                                  std::optional<double> dt = std::nullopt);
// The same with the method fixed.
LyapunovResult largest_lyapunov_rosenstein(std::span<const double> x, LyapunovOptions options = {},
                                           const LyapunovFitOptions& fit = {}, std::optional<double> dt = std::nullopt);
LyapunovResult largest_lyapunov_kantz(std::span<const double> x, LyapunovOptions options = {},
                                      const LyapunovFitOptions& fit = {}, std::optional<double> dt = std::nullopt);

// The two estimators checked against each other on one series (docs/reference/lyapunov.md, "Two estimators
// must agree"). Rosenstein's mean log distance of single nearest neighbours and Kantz's log of a
// neighbourhood's mean distance are biased differently by the alignment transient, by noise and by
// the approach to saturation, so a slope both show is evidence and a slope only one shows is not:
// on rotating flows Rosenstein's curve can hold a straight stretch 10% below lambda_1 while Kantz's
// has none (docs/notes/zoo-notes.md). Where one fit has a linear region and the other has none, or the
// two exponents differ by more than `tolerance` times their mean, each fit that had a linear region
// becomes `unconfirmed`: its value and region are withdrawn, and its explanation gives both
// verdicts. Fits that agree are left as they are. The fits must come from the same series and
// sampling (their slopes are compared per sample).
void cross_check(LyapunovFit& rosenstein, LyapunovFit& kantz, double tolerance = 0.1);
// The same on full results, with the per-time values withdrawn as well.
void cross_check(LyapunovResult& rosenstein, LyapunovResult& kantz, double tolerance = 0.1);

// Reproducibility, as for D2 (require_reproduced_by_halves in correlation_dimension.hpp): `first`
// and `second` are the same estimator, with the same options and fit settings, on the first and the
// second half of the record. A linear region of `full` stays only when at least one half finds one,
// and every half that finds one agrees with `full` within `tolerance` times their mean (cross_check's
// sense of agreement); otherwise `full` becomes not_reproduced, its value and region withdrawn, and
// its explanation gives both halves' verdicts. Two disjoint records of one attractor diverge at one
// rate; a straight stretch that no part of the record shows on its own came from that record's few
// close pairs. (Genesio-Tesi x, N = 10^4, m = 6..8, tau = 31, w = 63: Rosenstein reads 0.0858 per
// time unit, 16% below lambda_1 = 0.1019, and Kantz 0.0935 confirms it within 10%, while neither
// half has a linear region.) One silent half is allowed: a half's nearest neighbours lie about
// 2^(1/D2) times farther apart, so its curve has less room to rise before saturation, and requiring
// both halves withdrew 63 right values on the zoo for these 3 wrong ones (docs/reference/lyapunov.md).
void require_reproduced_by_halves(LyapunovFit& full, const LyapunovFit& first, const LyapunovFit& second,
                                  double tolerance = 0.1);
// The same on full results, with the per-time values withdrawn as well.
void require_reproduced_by_halves(LyapunovResult& full, const LyapunovResult& first, const LyapunovResult& second,
                                  double tolerance = 0.1);

}  // namespace chaos
