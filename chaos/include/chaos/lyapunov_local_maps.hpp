#pragma once
// The largest Lyapunov exponent from local linear maps fitted to a delay embedding: the tangent map
// is read from the data instead of from a divergence curve (Eckmann & Ruelle, Rev. Mod. Phys. 57,
// 617 (1985); Sano & Sawada, Phys. Rev. Lett. 55, 1082 (1985); Eckmann, Oliffson Kamphorst, Ruelle &
// Ciliberto, Phys. Rev. A 34, 4971 (1986); TISEAN's lyap_spec does the same with a full fit).
//
// Along a chain of points X_0, X_s, X_2s, ... of the embedding, each point's k nearest neighbours X_j
// (outside the Theiler window) and their images X_{j+s} give a least-squares linear map
//   X_{j+s} - <X_{.+s}>  ~  M (X_j - <X_.>),
// an estimate of the Jacobian of the s-step map there. A tangent vector carried through the chain's
// maps and renormalised at every step grows on average by exp(lambda_1 s) per step (Benettin et al.
// 1980, as in lyapunov_spectrum.hpp), so lambda_1 is the mean log growth per sample.
//
// Why it reaches where the divergence curves do not (docs/notes/zoo-notes.md, section 4): a divergence
// curve needs the separation to grow over about two e-folds before it saturates, and the nearest
// neighbours of a flow at N = 10^5 start only about six e-folds below the attractor's size. The
// local map needs only one step of s samples at the neighbourhood's scale, so rotating and slowly
// diverging flows (Rossler, Genesio-Tesi) are within reach.
//
// The one known failure, and the cure: a delay embedding with m above the attractor's dimension has
// directions in which a neighbourhood has almost no extent. A plain least-squares fit is then
// ill-posed there, and the tangent vector is stretched by noise in the fit (on Chua at m = 4, a
// plain fit reads 5 to 6 times lambda_1). The fit is therefore restricted to the neighbourhood's
// significant directions (truncated SVD: singular values below `cutoff` times the largest are
// dropped), which projects the tangent vector onto the local tangent space of the attractor at every
// step (the local projection of Eckmann et al. 1986's d_L < d_E, done without choosing d_L).
//
// An estimate alone is not trusted. largest_lyapunov_local_maps re-estimates it over a neighbourhood
// of the estimator's own choices (fewer and more neighbours, one more embedding dimension, half and
// twice the cutoff, twice the residual limit, the delay -+ a quarter, each half of the chain) and
// reports a value only when all of them agree and the local maps explain the data (status `consistent`); otherwise it says why not, with no value.
// Measured on the zoo (docs/reference/lyapunov-maps.md, scripts/measure/measure_lyapunov_maps.sh).

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "chaos/lyapunov.hpp"
#include "chaos/norm.hpp"
#include "chaos/scaling_region.hpp"

namespace chaos {

struct LocalMapOptions {
  std::size_t dimension = 2;  // m
  std::size_t delay = 1;      // tau, samples
  std::size_t theiler = 0;    // w: neighbours need |i - j| > w
  // s, samples the local maps advance. 0: max(1, round(tau / 2)). A step of one sample makes the
  // maps of a finely sampled flow nearly the identity, and the small stretching is lost in the noise
  // of the fit; half a delay keeps the neighbourhoods small (a fraction of the correlation time)
  // while the stretching over the step dominates the fit's error (docs/reference/lyapunov-maps.md).
  std::size_t step = 0;
  std::size_t neighbours = 0;  // k: 0 = 5 m. At least m + 1, so an affine map can be determined.
  // Singular values of a neighbourhood below cutoff times its largest are not fitted.
  double cutoff = 0.1;
  // A map whose residual (|B - A M^T| / |B| over the neighbourhood) exceeds this is a poor fit: the
  // tangent vector goes through it, but its growth is not averaged. 0.25: the map explains less than
  // about 94% of the spread of the neighbourhood's image.
  double max_residual = 0.25;
  Norm norm = Norm::max;
  // At most this many maps along the chain, the first ones (0: the whole chain, (N - (m-1) tau - s) / s
  // maps). The neighbours are still searched in the whole embedding; the bound caps the searches and
  // fits, so the cost beyond the kd-tree's N log N does not grow with N.
  std::size_t max_maps = 0;
  std::size_t threads = 1;  // the result is identical for any thread count
  void validate() const;
};

// One run of the estimator at fixed options.
struct LocalMapEstimate {
  double lambda = 0.0;               // mean log growth per sample over the chain
  double first_half = 0.0, second_half = 0.0;  // the same over each half of the chain
  double median_residual = 0.0;      // median over the maps of |residual| / |image spread| (Frobenius)
  double residual_q90 = 0.0;         // its 90th percentile
  double residual_q99 = 0.0;         // its 99th percentile
  double mean_rank = 0.0;            // mean number of directions fitted (singular values kept)
  std::size_t maps = 0;              // steps averaged (0: none fitted well, lambda is 0 and meaningless)
  std::size_t restarts = 0;          // steps where the tangent vector left the fitted directions
  std::size_t poor_fits = 0;         // steps not averaged: residual above options.max_residual
  std::size_t step = 0, neighbours = 0;  // s and k used
};

// One run. Refuses (InvalidInput) non-finite or constant series, invalid options, and series too
// short: N must be at least (m-1) tau + s + 2 w + k + 2, so that every chain point has k candidates
// outside its Theiler window.
LocalMapEstimate local_map_exponent(std::span<const double> x, const LocalMapOptions& options);

enum class LocalMapStatus {
  consistent,         // every variant agrees with the base estimate: lambda reported
  inconsistent,       // the variants disagree: no value
  not_deterministic,  // the local linear maps do not explain the data (noise at the neighbourhoods' scale)
  not_positive,       // the base estimate is not positive: no exponential divergence to report
};
const char* to_string(LocalMapStatus status) noexcept;

struct LocalMapVariant {
  std::string name;         // "base", "k = 3m", "k = 8m", "m + 1", "cutoff / 2", "cutoff x 2", "residual limit x 2",
                            // "delay - tau/4", "delay + tau/4" (tau >= 2 only), "first half", "second half"
  std::size_t dimension = 0, delay = 0, neighbours = 0;
  double lambda = 0.0;      // per sample
};

struct LocalMapResult {
  LocalMapStatus status = LocalMapStatus::inconsistent;
  std::optional<double> lambda;               // per sample, when consistent
  std::optional<Interval> lambda_interval;    // range over the variants, when consistent
  std::optional<double> dt;
  std::optional<double> lambda_per_time;      // lambda / dt
  std::optional<Interval> lambda_per_time_interval;
  LocalMapEstimate base;
  std::vector<LocalMapVariant> variants;      // the base first
  double tolerance = 0.0;                     // the agreement required, relative to the base
  std::string explanation;
};

// The checked estimate. Variants: k = 3m and 8m (the neighbourhood's size), m + 1 (the exponent does
// not depend on m, a fit to empty directions does), half and twice the cutoff (the directions
// fitted), twice the residual limit (which maps are averaged), and the two halves of the base chain
// (the average has converged). `consistent` needs
// every variant within tolerance * |base| of the base, a positive base, and a median fit residual of
// at most options.max_residual (white noise leaves about 90% of the image spread unexplained). A
// variant the series is too short for makes the result `inconsistent`. Where the base already fails
// (median residual above the limit, no map averaged, or a base that is not positive) the variants are
// not computed and `variants` holds the base and the halves. The variants that keep the base's chain
// (k, cutoff, residual limit) share one neighbour search; the values equal separate runs bit for bit.
LocalMapResult largest_lyapunov_local_maps(std::span<const double> x, const LocalMapOptions& options,
                                           std::optional<double> dt = std::nullopt, double tolerance = 0.05);

// A divergence-curve slope (Rosenstein's or Kantz's, lyapunov.hpp) checked against the local-map
// exponent of the same series and sampling (docs/reference/lyapunov.md, "Two estimators must agree"). A linear
// region stands only where the local-map result is `consistent` and its value differs from the slope
// by at most `tolerance` times their mean; otherwise the fit becomes `unconfirmed`: its value and
// region are withdrawn, and its explanation says why (both values where both exist). Where the maps
// are `inconsistent` or `not_positive` they confirm nothing (with only a contradiction withdrawing
// a slope, Sprott F x with 1% noise kept a slope 15% low that Rosenstein
// and Kantz agreed on, beside inconsistent maps; docs/notes/zoo-notes.md, section 4). The local-map value
// keeps its status: it has passed its own ten variants, and the disagreements found so far were the
// divergence curves' known low bias on flows (Genesio-Tesi: Rosenstein 10% low, inside a straight
// stretch that Kantz confirmed; docs/notes/zoo-notes.md, section 3). Where the local-map result is
// `not_deterministic` (the maps explain less than 75% of their neighbourhoods' image spread: noise at
// the scale of the nearest neighbours), the fit becomes `unconfirmed` too: the divergence curves
// start from those neighbours, and above a noise floor they rise more slowly than lambda_1 before
// saturating, by the same amount in both methods (Henon, Lozi, Ricker and Gauss maps with 1% noise:
// Rosenstein and Kantz 11-19% low and within 7% of each other; docs/notes/zoo-noise.md).
void cross_check(LyapunovFit& fit, LyapunovMethod method, const LocalMapResult& local_maps, double tolerance = 0.1);
// The same on a full result (its method from result.options), with the per-time values withdrawn too.
void cross_check(LyapunovResult& result, const LocalMapResult& local_maps, double tolerance = 0.1);
// Where the local maps could not be run (`refusal` says why, e.g. a series too short for them), a
// linear region has nothing to confirm it and becomes `unconfirmed` as well.
void cross_check_without_local_maps(LyapunovFit& fit, LyapunovMethod method, const std::string& refusal);
void cross_check_without_local_maps(LyapunovResult& result, const std::string& refusal);

}  // namespace chaos
