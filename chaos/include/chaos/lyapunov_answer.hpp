#pragma once
// One lambda_1 from the three estimators of lyapunov.hpp and lyapunov_local_maps.hpp, with one
// interval and one status (estimate.hpp), the three kept beside it as the evidence.
//   - Rosenstein's and Kantz's answers, each already checked against the other, the record's halves
//     and the local maps (cross_check, require_reproduced_by_halves): where both give a value, lambda_1
//     is their mean and the interval spans both intervals; confident when at least one of them is
//     confident and that span's half-width is at most 10% of the value.
//   - Where only one gives a value, that value, rough (the other estimator does not confirm it).
//   - Where neither does, the local maps: their value where their variants agree, else their base
//     estimate with the variants' range as the interval; rough either way (a divergence curve
//     that shows no exponential stretch is evidence against a sharp value).
//   - none where no estimator gives a value.

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

}  // namespace chaos
