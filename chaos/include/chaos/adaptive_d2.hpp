#pragma once
// D2 at a budget chosen by the data (`chaos d2 --fast`): correlation sums from a random subset of
// reference points that doubles until two disjoint subsets agree on one unambiguous plateau.
//
// A subset of R reference points estimates C(eps) without bias (each point's partner fraction is
// an unbiased sample of it), at about 2R/P of the exact cost (its pairs are counted from both
// ends), but a small subset can choose another plateau than the exact counts would: Henon's local
// slopes oscillate in scale by about +-6% around 1.2 (lacunarity), with plateaus near 1.13, 1.23
// and 1.19 at successive scales, and with 1024 reference points two seeds of five read 1.14-1.15
// "saturated", against 1.234 from the exact counts (N = 10^5, m = 1..4). So the budget is not
// fixed in advance. Round k compares the D2 of the T reference points counted so far with that of
// the next T points of the same seeded order (disjoint, equally many, hence equally precise), then
// merges them. A round is accepted when
//   - both subsets and the merged counts saturate, the two D2 agree within `target`, and the
//     merged plateau overlaps both subsets' plateaus (the same scales, not another phase);
//   - both subsets' scaling regions end within `region_slack` radii of the merged one's, at both
//     ends: the region has stopped moving as the budget doubles. A subset's local slopes at small
//     radii are too uncertain to join a plateau that the exact counts extend further down, and
//     where the slope drifts across the plateau (within the 5% tolerance) the region's ends move
//     D2. On Rikitake x (N = 10^5, seed 1) two subsets of 250 points agreed on 2.026 and 2.031 on
//     regions starting at radius 13 of 40; the merged region started at 10, and the exact one at 3
//     reads 2.073, 0.037 away;
//   - the merged D2's jackknife standard error times `confidence` is at most `target`. One
//     agreement of two draws is weak evidence where each draw spreads by about the target: on
//     Lorenz-84 x two subsets of 500 points agreed within 0.015, and the merged 2.279 (standard
//     error 0.016) lay 0.025 from the exact 2.304;
//   - the merged counts keep that plateau, within target / 2, with any one of their jackknife
//     groups of reference points left out;
//   - no other admissible plateau of the saturating dimensions, above or below, reads a slope more
//     than `target` away. Two readings of one set of counts mean that a near-tie in support picks
//     the answer: two disjoint subsets of 8000 Henon points (seed 2) both read 1.13 at eps
//     0.005-0.015, where the exact counts choose 1.234 at 0.019-0.053, and only this test sees it.
// The second and third conditions came from `scripts/measure/measure_fast_d2.sh`: without them, on the
// zoo's chaotic series at N = 10^5 (three seeds, first rounds of 250 points), 7 of 62 accepted
// budgets lay 0.020-0.041 from the exact D2; with them, none of 32 at the default first round
// (docs/validation/fast-d2-zoo.md). When the next round would count more than an eighth of the points, or
// more than the budget, the rounds stop and the merged counts answer, rough (subsets_answer):
// counting exactly then would cost the whole exact job on top of the rounds (Henon, N = 10^5: 1.3
// times the exact job), and the user asked for speed; the exact D2 is one flag away (no --fast).
// Where the first round alone would count more than an eighth of the points (N below about 8000),
// the exact counts are used: they are cheap there.
// With `halves`, subset a comes from the record's first half and b from its second, each counted
// against its own half's points: a round is then also the halves check of the final D2, which
// otherwise costs two more counts of the final budget (Lorenz x, N = 10^5: 2 x 200 points take
// 0.13-0.16 s in all, 400 points of the whole record with the halves counted after 0.28-0.33 s).

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "chaos/correlation_dimension.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/d2_answer.hpp"
#include "chaos/estimate.hpp"

namespace chaos {

struct AdaptiveD2Options {
  double target = 0.02;                     // two disjoint subsets' D2 must agree within this
  std::size_t initial_reference_points = 500;  // T of the first round (each subset)
  // Reference points the rounds may count in all (both subsets of every round): no round after the
  // first goes beyond it. 0: up to an eighth of the points.
  std::size_t budget = 0;
  // Draw subset a from the record's first half and b from its second, each counted against its own
  // half's points (the exact halves check's sums, on a subset): the rounds' agreement is then also
  // the halves check, and the final D2 goes through require_reproduced_by_halves with a and b, at
  // no extra count. false, or a half too short to embed (AdaptiveD2Result::halves then says
  // false): both subsets from the whole record.
  bool halves = false;
  std::size_t region_slack = 1;             // radii a subset's scaling region may end from the merged one's
  double confidence = 2.5;                  // the merged D2's standard error times this is at most the target
  void validate() const;
};

// One comparison: the points counted so far (a) against the next equally many (b), and the merge.
struct AdaptiveD2Round {
  std::size_t reference_points = 0;  // in each of a and b
  D2Status status_a = D2Status::no_scaling_region, status_b = D2Status::no_scaling_region,
           status_merged = D2Status::no_scaling_region;
  std::optional<double> d2_a, d2_b, d2_merged;
  std::optional<Interval> region_a, region_b, region_merged;  // the scaling regions (radii)
  std::optional<double> standard_error;  // the merged D2's, jackknife over groups of reference points
  bool agreed = false;  // a and b saturate and agree within the target on overlapping plateaus
  std::optional<std::size_t> region_shift;  // agreed: in radii, how far a subset's region ends from the merged one's
  bool same_region = false;  // agreed, with region_shift at most region_slack
  bool precise = false;      // confidence * standard_error <= target
  bool stable = false;  // same_region and precise, the merged plateau survives leaving out any
                        // jackknife group, and no competing plateau (accepted)
  std::optional<double> competing;  // the slope of another plateau more than the target from D2
};

struct AdaptiveD2Result {
  CorrelationSumResult sums;         // the counts the final D2 comes from
  CorrelationDimensionResult d2;
  std::size_t reference_points = 0;  // reference points behind `sums`; 0 when the counts are exact
  bool exact = false;    // the first round would already count more than an eighth of the points: exact counts
  bool settled = false;  // a round was accepted; otherwise (and not exact) the last round's merged counts
  bool halves = false;   // the subsets were the record's halves, and d2 has their verdict (not exact)
  std::vector<AdaptiveD2Round> rounds;
  std::string explanation;           // how the budget was chosen, one sentence
};

// D2 of a fast run as one answer (d2_answer.hpp) from `d2` (its result, after any halves check):
// the interval also spans the last round's two subsets; where no round was accepted the answer is
// rough, its interval widened by two standard errors of the merged counts, and the reason says so.
// The floor of the final status (d2_answer.hpp) comes last, so an unsettled answer reaches at least
// d2_rough_floor either side.
Estimate subsets_answer(const AdaptiveD2Result& fast, const CorrelationDimensionResult& d2,
                        const CorrelationDimensionOptions& dimension = {});

// `sums` gives the delay, dimensions, window, radii, norm, search, seed and threads; its
// reference_points, reference_offset and pairs_per_radius must be 0 (the budget is chosen here).
AdaptiveD2Result adaptive_correlation_dimension(std::span<const double> x, CorrelationSumOptions sums,
                                                const CorrelationDimensionOptions& dimension = {},
                                                const AdaptiveD2Options& options = {});

}  // namespace chaos
