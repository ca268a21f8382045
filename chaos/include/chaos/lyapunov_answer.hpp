#pragma once
// One lambda_1 from the three estimators of lyapunov.hpp and lyapunov_local_maps.hpp, with one
// interval and one status (estimate.hpp), the three kept beside it as the evidence.
//   - Rosenstein's and Kantz's answers, each already checked against the other, the record's halves
//     and the local maps (cross_check, require_reproduced_by_halves): where both give a value,
//     lambda_1 is their mean, or the median of the three where the local maps are consistent; the
//     interval spans their intervals. Confident when at least one of the two is confident and that
//     span is at most 10% of the value either side. Otherwise, where the local maps are consistent
//     and the three values lie within 7% of the centre of their span, that centre, confident: three
//     estimators with different systematic errors agree.
//   - Otherwise, wherever the local maps are consistent (their variants agree), their value,
//     confident, the interval spanning their variants: the curves are checked against the maps,
//     and on the zoo's grid every consistent local-map value lay within 10% of lambda_1.
//   - Where only one curve gives a value, that value, rough (the other estimator does not confirm it).
//   - Where neither does, the base estimate of inconsistent local maps, rough.
//   - none where no estimator gives a value.
// The interval is then widened to at least 10% of the value either side (confident) or 40% (rough),
// and a rough one spans the local maps' variants too: the spread over the estimators' choices misses
// their systematic error, which these floors cover on the zoo, where at least 90% of the rough
// intervals hold lambda_1 (docs/reference/lyapunov.md, "Answers and their intervals").

#include <optional>
#include <string>

#include "chaos/estimate.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/lyapunov_local_maps.hpp"

namespace chaos {

struct LyapunovAnswer {
  Estimate estimate;         // per sample (per iteration for maps)
  std::optional<double> dt;  // the sampling interval, when known
  std::string source;        // the estimators the value comes from, in words

  // The estimate per time unit when dt is known, else per sample.
  Estimate per_time() const;
};

LyapunovAnswer combine_lyapunov(const LyapunovResult* rosenstein, const LyapunovResult* kantz,
                                const LocalMapResult* local_maps, std::optional<double> dt = std::nullopt);
// The same from the two estimators' answers (LyapunovFit::estimate), for callers that hold fits.
LyapunovAnswer combine_lyapunov(const Estimate* rosenstein, const Estimate* kantz, const LocalMapResult* local_maps,
                                std::optional<double> dt = std::nullopt);

}  // namespace chaos
