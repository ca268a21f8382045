#pragma once
// One D2 answer (estimate.hpp) from a correlation-dimension result (correlation_dimension.hpp): a
// value, an interval and confident / rough / none, the detailed status kept as the explanation.
//   saturated        the plateau's D2. The interval spans the local slopes and per-dimension fits
//                    over the plateau (d2_interval), the halves' D2 and the other delay's D2 where
//                    those checks ran, and two jackknife standard errors where the counts are a
//                    subset. Confident when its half-width is at most 0.1; rough when it is wider,
//                    when another plateau of the same dimensions at smaller scales reads more than
//                    0.1 away, or when every slope at the smallest well-counted scales below the
//                    plateau (step 7 of correlation_dimension.hpp) reads more than 0.1 away on one
//                    side (the interval then spans them: the slope still changes towards the
//                    small-scale limit), or when the value exceeds the Eckmann-Ruelle limit
//                    2 log10 N. A reading below the plateau counts only where its mean also lies
//                    beyond its counting error (pair_counting_error / sqrt(pairs)): the few pairs at
//                    small scales scatter the slopes of a flow by about 0.17 at 10^4 pairs. A
//                    plateau wholly above the one read only enters the reason: it reads the
//                    attractor's larger-scale shape, not its D2.
//   not_reproduced   the plateau's slope, rough; the interval spans it and the halves' (or the other
//                    delay's) D2: the records disagree, and the interval says by how much.
//   scale_dependent  the plateau at the smaller scales (D2 is the small-scale limit), rough; the
//                    interval spans both plateaus.
//   noise_limited    the plateau above the noise floor, rough: below it the scales where D2 is defined
//                    cannot be read, and the plateau above may be a large-scale exponent.
//   not_saturated    with a plateau that a lower dimension contradicts (step 5 of
//                    correlation_dimension.hpp): its slope, rough, the interval reaching that lower
//                    dimension's slope. Without a shared plateau: where the highest dimensions'
//                    own D2(m) agree within twice the flatness tolerance, their mean, rough (they
//                    saturate, but on no common octave of scales); otherwise none (D2(m) still grows
//                    with m, as for noise).
//   no_scaling_region  none.
// The status is decided on the interval above; the interval is then widened to at least
// d2_confident_floor either side of the value (confident) or d2_rough_floor (rough). The spread over
// the estimator's own choices misses what separates a finite record's embedded D2 from the
// attractor's own at the same N and scales (the coordinates, the lacunarity of the plateau): on the
// zoo that spread held the state's D2 in 73% of the answers, with these floors in 92% (chosen on the
// rows at N = 10^4, checked on those at 10^5; docs/reference/correlation_dimension.md, "Answers and
// their intervals").

#include "chaos/correlation_dimension.hpp"
#include "chaos/estimate.hpp"

namespace chaos {

// The largest half-width of a confident D2.
inline constexpr double d2_confident_half_width = 0.1;
// The least half-width of an answer's interval: confident, rough.
inline constexpr double d2_confident_floor = d2_confident_half_width;
inline constexpr double d2_rough_floor = 0.4;

Estimate d2_answer(const CorrelationDimensionResult& d2, const CorrelationDimensionOptions& options = {});
// The interval widened to the floor of the answer's status as it stands (d2_answer's last step). A
// caller that changes the status after reading (the fast D2's unsettled rounds) applies it last.
Estimate with_d2_floor(Estimate e);
// The same answer before the floors: the interval spans only what the estimator's own choices and
// checks read. The zoo holds an answer to the state's reading with this interval (its band was
// fixed on it before the floors).
Estimate d2_reading(const CorrelationDimensionResult& d2, const CorrelationDimensionOptions& options = {});

}  // namespace chaos
