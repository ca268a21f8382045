#pragma once
// The correlation dimension D2 from correlation sums (Grassberger & Procaccia 1983; seed Eq. 33),
// with the scaling region chosen automatically and an honest interval:
//  1. local slopes d ln C / d ln eps for every m (radii with fewer than min_pairs pairs are left out:
//     their relative statistical error is above 1/sqrt(min_pairs); so are radii where C = 1);
//  2. per m, the flat region across which the most pairs enter, counted in e-folds of the pair count
//     (ln pairs(eps_high) - ln pairs(eps_low), the width in ln eps times the slope), gives D2(m) (the
//     least-squares slope there) and an interval (the range of the local slopes over that region). A
//     region must see the pair count at least double across it (min_support_gain = ln 2): a stretch
//     of radii where no pair enters (below the spacing of a finite set of points: periodic or
//     quantised data) has slope 0 and carries no information, so it is never a scaling region,
//     however long and flat;
//  3. the saturated D2 needs one region shared by the `saturation_dimensions` highest dimensions
//     that have an estimate, with their D2(m) agreeing within the tolerance; its interval is the
//     range of all local slopes of those dimensions over the shared region. The shared region must
//     span at least an octave of eps (min_plateau_ratio = 2): over a shorter stretch the crest of a
//     hump in the local slopes passes the flatness test as easily as a plateau does (a slider-crank
//     series whose slopes of m = 8..10 still rise with m read 3.13 over a factor 1.76 against
//     D_KY = 2.00; docs/reference/correlation_dimension.md, step 3);
//  4. D2 is the limit of small scales. If, at radii below that region, the same dimensions share a
//     second admissible plateau (the same tolerance, support and length) whose allowance (mean +-
//     tolerance * |mean|) does not overlap the first's, the slopes still change with scale (more than
//     lacunarity's oscillation around one value, which stays within the allowances): the status is
//     `scale_dependent`, both plateaus are reported and no D2 is given. (Mackey-Glass at tau = 30,
//     N = 10^5: 2.39 over eps in [0.06, 0.3] of a range of 1.2, 3.05 over [0.0066, 0.012]; GP 1983
//     report 3.0 +- 0.2.)
//  5. A projection cannot have a larger correlation dimension than the set it projects (the delay
//     vectors of m < m' are a projection of those of m'), so over the shared plateau no lower
//     dimension that embeds the set may read a clearly higher slope: when one's mean local slope
//     there exceeds the plateau's mean by more than projection_tolerance (relative; 0.1, twice the
//     flatness tolerance), the plateau is not the saturated D2 and the status is `not_saturated`
//     (plateau and that slope reported). Only m >= 2 D2 + 1 is compared (Takens' bound with
//     d = D2): below it the delay map folds the set onto itself, and pairs across the folds raise
//     the slopes at finite scales. Found on a slider-crank series: m = 8..10 agreed on 0.85 at eps
//     0.12-0.37 um of a 45 um range while m = 3 read 0.97 there; D_KY from the equations 2.00.
//  6. Noise. Below the noise level of a measured record every embedding dimension fills its space:
//     C_m(eps) ~ eps^m, local slope m (Kantz & Schreiber, Nonlinear Time Series Analysis, 2nd ed.
//     2004, ch. 6). When, below the plateau, every saturating dimension m reads a local slope more
//     than noise_fill_fraction (0.5) of the way from the plateau's slope to m, and not above
//     m (1 + tolerance), over consecutive radii whose local slopes span min_points radii, the plateau
//     is bounded below by noise (or by structure of higher dimension) and the smaller scales, where
//     D2 is defined, cannot be read: the status is `noise_limited`, the plateau and the largest such
//     radius (noise_floor) are reported, no D2 is given. (Slopes above m are pairs entering in bursts,
//     as in the quasi-lattice of a 2-torus's samples at small scales, which reads 8.3 at m = 6: not
//     noise.) The plateau above the noise is not the attractor's D2 in general: with 3% noise (30 dB)
//     Sprott F reads 2.46 over eps 0.15-0.61, the plateau at large scales that its clean record also
//     shows beside the small-scale D2 of 2.05 (D_KY 2.19); Mackey-Glass at tau = 30 with 1% noise
//     reads 2.40 where its clean record is scale_dependent (2.39 and 3.05; docs/notes/zoo-noise.md).
//  7. The smallest well-counted scales (reported, judged by d2_answer): below a shared plateau and
//     above any finite-set structure, the lowest radii where every saturating dimension has a local
//     slope from at least small_scale_min_pairs pairs, as many as a plateau's slopes need. Where the
//     slope still moves there without settling into a second plateau (step 4 needs one), the plateau
//     is not yet the small-scale limit: Linz-Sprott x, N = 10^5, m = 2..4, w = 99, reads a plateau of
//     1.61 at eps 0.036-0.20 where its slopes rise steadily to 1.8-2.0 at eps 0.004-0.005 (35 000
//     pairs and more) and the state itself reads 1.95.
// Scales (opt-in): max_region_fraction keeps regions at radii of at most that fraction of the
// series' range (the max-norm diameter of the embedded set). Eckmann & Ruelle (Physica D 56, 185
// (1992)) ask for radii small against the attractor's diameter and take a tenth of it for their
// bound D2 < 2 log10 N. At large radii the attractor's shape, not its dimension, sets the slope:
// on a circle of radius R the chord-length fraction (2/pi) asin(eps / 2R) has a log-log slope of
// 1.02 at eps = R/2 and 1.10 at eps = R, so a three-frequency torus (N = 10^5, range 6) reads 3.31
// over eps in [0.64, 1.5]. A tenth of the range gives it 3.10 [2.98, 3.23], but it is off by
// default: it also takes the plateau from a sine with 317 distinct points (0.96-1.05 on [0.06, 0.5]
// of a range of 2) and from a 2-torus at N = 2*10^4, whose samples form a quasi-lattice below
// eps = 0.3 (docs/notes/zoo-notes.md). Local slopes above the limit are still reported.
// Radii where the pair counts stop changing (three or more consecutive radii with the same non-zero
// count in the highest dimension) are reported: at those scales the data are a finite set of points.
// Otherwise the result says "not saturated" (D2(m) keeps growing, as for noise) or "no scaling
// region".
// Reference-point subsets and pair caps (CorrelationSumResult::group_pairs): the pairs around one
// reference point are not independent (they share its local density), so the pair count overstates
// the evidence at small radii, where a few reference points bring all the pairs. There every local
// slope gets a delete-a-group jackknife standard error (Efron & Tibshirani, An Introduction to the
// Bootstrap, 1993, ch. 11; groups of reference points left out in turn), and a slope whose error
// exceeds slope_error_fraction of the plateau's tolerance band (tolerance * |slope|) is left out
// before any region is searched: noise that happens to look flat is not a plateau. (Henon x,
// N = 10^5, m = 1..4, 1024 random reference points: without this rule two seeds of five read
// D2 = 1.14 and 1.15 "saturated" at eps 0.007-0.024, against 1.234 from the exact counts.) D2 then
// carries a jackknife standard error too. A second, independent estimate is the Takens-Theiler maximum-likelihood D2 at the upper
// edge of the region (Takens 1985; Theiler 1988), with its standard error.

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "chaos/correlation_sum.hpp"
#include "chaos/scaling_region.hpp"

namespace chaos {

enum class D2Status { saturated, not_saturated, no_scaling_region, scale_dependent, not_reproduced, noise_limited };
const char* to_string(D2Status status) noexcept;

struct CorrelationDimensionOptions {
  ScalingRegionOptions region{0.05, true, 5, 1, 0.6931471805599453};
  std::size_t saturation_dimensions = 3;
  // The shared plateau of the saturation step spans at least this factor in eps (eps_high / eps_low).
  // Per-dimension regions and the search for a second plateau below it (step 4) are not limited.
  double min_plateau_ratio = 2.0;
  // Step 5: a lower dimension's mean local slope over the shared plateau may exceed the plateau's
  // mean slope by at most this fraction of it (infinity: no check).
  double projection_tolerance = 0.1;
  // Step 6: the fraction of the way from the plateau's slope to m that every saturating dimension's
  // local slope must exceed over consecutive radii below the plateau for it to count as bounded by
  // noise (infinity: no check).
  double noise_fill_fraction = 0.5;
  std::uint64_t min_pairs = 100;
  // Step 7: the pairs every saturating dimension needs at a radius for it to count among the smallest
  // well-counted scales below the plateau (0: not reported).
  std::uint64_t small_scale_min_pairs = 10000;
  // The counting error of a local slope read from p close pairs is about pair_counting_error /
  // sqrt(p). A reading below the plateau (another plateau, the smallest scales) disputes the D2 in
  // d2_answer only where it lies more than that error away, and more than the confident half-width.
  // The close pairs of a finely sampled flow are not independent (two strands of the orbit that pass
  // near each other give a run of consecutive pairs): over twelve independent Lorenz x records
  // (dt 0.01, N = 10^5, m = 4..6) the local slopes at one radius scatter by 13-18.5 / sqrt(pairs),
  // 16.5 in root mean square, from 10^4 to 4 10^5 pairs, where independent pairs would give about 4.
  // A map's pairs are nearly independent (Henon x: 4.6), so there the constant errs large; the zoo's
  // maps answer the same with either (scripts/measure/small_scale_slope_error.py;
  // docs/reference/correlation_dimension.md, "Readings below the plateau").
  double pair_counting_error = 16.5;
  // Regions are searched at radii <= max_region_fraction * range (CorrelationSumResult::range);
  // infinity (the default) searches every radius.
  double max_region_fraction = std::numeric_limits<double>::infinity();
  // Reference subsets and caps only: the largest jackknife error of a usable local slope, as a
  // fraction of tolerance * |slope| (0.5: two standard errors fit inside the flatness band).
  double slope_error_fraction = 0.5;
  // The delay check (require_reproduced_at_delay): the largest difference allowed between the D2 at
  // the chosen delay and at twice it, absolute; half the zoo's +-0.1 band, so that a value the
  // embedding moves by more cannot be claimed to within that band.
  double delay_tolerance = 0.05;
  void validate() const;
};

// A flat stretch of the local slopes shared by the highest dimensions.
struct D2Plateau {
  Interval radii;            // [low, high]
  double slope = 0.0;        // mean local slope over the stretch and the dimensions
  Interval slopes;           // their range
  std::uint64_t pairs = 0;   // the fewest close pairs of those dimensions at any of its radii (0: not counted)
};

struct CorrelationDimensionResult {
  std::vector<std::size_t> dimension;
  std::vector<double> radius;
  std::vector<std::vector<std::optional<double>>> local_slope;  // [m index][radius index]
  // Reference subsets and caps only (else empty): the jackknife standard error of each local slope,
  // and how many slopes were left out for an error above the limit.
  std::vector<std::vector<std::optional<double>>> local_slope_error;
  std::size_t slopes_too_uncertain = 0;
  std::vector<std::optional<double>> d2_by_dimension;
  std::vector<std::optional<Interval>> d2_by_dimension_interval;
  std::vector<std::optional<Interval>> region_by_dimension;     // radii bounding each per-m region
  std::optional<double> max_region_radius;  // the largest radius a region may reach (nullopt: no limit)
  D2Status status = D2Status::no_scaling_region;
  std::optional<double> d2;                 // saturated value
  std::optional<Interval> d2_interval;
  std::optional<double> d2_standard_error;  // jackknife over groups of reference points (subsets and caps)
  std::optional<Interval> scaling_region;   // radii [low, high] of the shared region
  std::vector<std::size_t> saturation_dimensions_used;
  // The best-supported shared plateau and, when the status is scale_dependent, the disagreeing one
  // at smaller radii (in that order). Also kept when the plateau is withdrawn (noise_limited,
  // not_saturated by step 5, not_reproduced).
  std::vector<D2Plateau> plateaus;
  // Step 5, whenever a shared plateau was found: the dimension m >= 2 D2 + 1 below the saturating
  // ones whose mean local slope over that plateau is the largest, and that mean (nullopt: no such
  // dimension has slopes over at least half of the plateau's radii).
  std::optional<std::size_t> steepest_lower_dimension;
  std::optional<double> steepest_lower_slope;
  // A saturated D2 only: the other admissible plateaus of the same dimensions, reported and not
  // judged: the one below that step 4 took for the same scaling (its allowance overlaps), and the
  // best one above the region. Where one reads another slope, the D2 depends on which scales are
  // taken (Henon's lacunarity); `chaos d2 --fast` does not accept a budget while one reads more than
  // its target away from D2 (adaptive_d2.hpp).
  std::vector<D2Plateau> other_plateaus;
  std::string explanation;                  // one sentence a user can read
  double eckmann_ruelle_limit = 0.0;        // 2 log10(points)
  bool exceeds_eckmann_ruelle = false;
  std::optional<double> takens_theiler;     // at the upper edge of the shared region, highest m used
  std::optional<double> takens_theiler_error;
  // The largest radius below which the highest dimension's pair count stays the same over at least
  // three consecutive radii: the data look like a finite set of points at smaller scales (periodic
  // with a rational period, or quantised). nullopt when the counts keep changing.
  std::optional<double> finite_set_below;
  // Step 6, whenever a shared plateau was found: the largest radius below it that ends a run of radii
  // where every saturating dimension fills its space as noise does (status noise_limited), and
  // their local slopes there.
  std::optional<double> noise_floor;
  std::vector<double> noise_floor_slopes;
  // Step 7, whenever a shared plateau was found: the lowest radii below it, above finite_set_below,
  // where every saturating dimension has a usable local slope from at least small_scale_min_pairs
  // pairs (as many consecutive radii as a plateau's local slopes need), with the mean and range of
  // those slopes (nullopt: no such run below the plateau).
  std::optional<D2Plateau> smallest_scales;
  // The halves check (require_reproduced_by_halves), when it ran: each half's status and D2.
  std::optional<D2Status> first_half_status, second_half_status;
  std::optional<double> first_half_d2, second_half_d2;
  // The delay check (require_reproduced_at_delay), when it ran: the other delay, its status and D2.
  std::optional<std::size_t> variant_delay;
  std::optional<D2Status> variant_delay_status;
  std::optional<double> variant_delay_d2;
};

CorrelationDimensionResult correlation_dimension(const CorrelationSumResult& sums,
                                                 const CorrelationDimensionOptions& options = {});

// Reproducibility (the automatic pipeline's last D2 step). `first` and `second` are D2 from the
// first and the second half of the same record, with the same delay, Theiler window, dimensions and
// radii. A saturated `full` stays saturated only when both halves are saturated and their D2 agree
// in the sense of step 4 (allowances mean +- tolerance * |mean| overlap); otherwise its status
// becomes not_reproduced and its D2 is withdrawn (the plateau stays in `plateaus`). Two disjoint
// records of the same attractor measure the same dimension; a plateau that one half does not show,
// or shows at another height, came from that record's sampling, not from the attractor. (Sprott F,
// N = 10^4: the full record reads 2.35, its halves 1.97 and 2.50; D_KY = 2.19.)
void require_reproduced_by_halves(CorrelationDimensionResult& full, const CorrelationDimensionResult& first,
                                  const CorrelationDimensionResult& second,
                                  const CorrelationDimensionOptions& options = {});

// Invariance under the embedding (opt-in: `chaos d2 --delay-check`, AutomaticAnalysisOptions::
// check_delay, after the halves check). `variant` is D2 from the same record with the same Theiler
// window, dimensions and radii at another delay (`variant_delay`; check_delay_variant takes twice
// the chosen one). D2 belongs to the attractor, not to
// the embedding (Takens 1981), so a saturated `d2` stays saturated only when the variant saturates
// too and reads within options.delay_tolerance of it; otherwise its status becomes not_reproduced
// and its D2 is withdrawn, as for the halves. A plateau whose height moves with the delay is shaped
// by the embedding at the resolved scales, not by the attractor. (Thomas x, N = 10^5, m = 6..8: 1.719
// at tau = 39, 1.846 at 78.) Not a default: on the zoo many plateaus, right ones as often as
// wrong ones, move by more than 0.05 when the delay doubles (docs/notes/zoo-notes.md, section 8).
void require_reproduced_at_delay(CorrelationDimensionResult& d2, const CorrelationDimensionResult& variant,
                                 std::size_t variant_delay, const CorrelationDimensionOptions& options = {});

// Takens-Theiler estimate at radius index k: C(r_k) / integral_0^{r_k} C(r)/r dr, with C a power
// law between grid radii (and below the first, with the first interval's exponent). Standard error
// D / sqrt(pairs closer than r_k) (Theiler 1988). nullopt where C vanishes.
std::optional<std::pair<double, double>> takens_theiler(const std::vector<double>& radius,
                                                        const std::vector<double>& correlation_sum,
                                                        std::uint64_t pairs_at_k, std::size_t k);

}  // namespace chaos
