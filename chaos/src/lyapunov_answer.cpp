#include "chaos/lyapunov_answer.hpp"

#include <algorithm>
#include <vector>

#include "chaos/format.hpp"

namespace chaos {

Estimate LyapunovAnswer::per_time() const { return dt ? scaled(estimate, 1.0 / *dt) : estimate; }

LyapunovAnswer combine_lyapunov(const LyapunovResult* rosenstein, const LyapunovResult* kantz,
                                const LocalMapResult* local_maps, std::optional<double> dt) {
  LyapunovAnswer answer;
  answer.dt = dt;
  const Estimate* r = rosenstein && rosenstein->fit.estimate.value ? &rosenstein->fit.estimate : nullptr;
  const Estimate* k = kantz && kantz->fit.estimate.value ? &kantz->fit.estimate : nullptr;
  Estimate& e = answer.estimate;
  if (r && k) {
    // The local maps, where their variants agree, are a third estimate: their range joins the span.
    const bool maps = local_maps && local_maps->status == LocalMapStatus::consistent && local_maps->lambda;
    answer.source = maps ? "Rosenstein, Kantz and local maps" : "Rosenstein and Kantz";
    std::vector<double> values{*r->value, *k->value};
    if (maps) values.push_back(*local_maps->lambda);
    std::sort(values.begin(), values.end());
    e.value = values.size() == 3 ? values[1] : 0.5 * (values[0] + values[1]);  // the median
    for (const double v : values) e.include(v);
    for (const Estimate* one : {r, k})
      if (one->interval) {
        e.include(one->interval->low);
        e.include(one->interval->high);
      }
    if (maps && local_maps->lambda_interval) {
      e.include(local_maps->lambda_interval->low);
      e.include(local_maps->lambda_interval->high);
    }
    const bool one_confident = r->status == EstimateStatus::confident || k->status == EstimateStatus::confident;
    const double spread = e.relative_half_width();
    const std::string span = "the interval spans " + answer.source + ", " +
                             format_number(spread * 100, Precision::title) + "% either side";
    if (one_confident && spread <= 0.1) {
      e.status = EstimateStatus::confident;
      e.reason = "Rosenstein (" + std::string(to_string(r->status)) + ") and Kantz (" + to_string(k->status) +
                 ") agree; " + span;
    } else {
      e.status = EstimateStatus::rough;
      e.reason = one_confident ? span + ", more than 10%"
                               : "neither estimator is confident (Rosenstein: " + r->reason + "; Kantz: " + k->reason +
                                     "); " + span;
    }
    return answer;
  }
  if (r || k) {
    answer.source = r ? "Rosenstein" : "Kantz";
    e = r ? *r : *k;
    e.downgrade(std::string("only ") + answer.source + " gives a value");
    return answer;
  }
  if (local_maps && local_maps->status != LocalMapStatus::not_deterministic &&
      local_maps->status != LocalMapStatus::not_positive && local_maps->base.maps > 0) {
    answer.source = "local maps";
    e.status = EstimateStatus::rough;
    if (local_maps->lambda) {
      e.value = local_maps->lambda;
      e.interval = local_maps->lambda_interval;
    } else {
      e.value = local_maps->base.lambda;
      for (const auto& v : local_maps->variants) e.include(v.lambda);
    }
    e.reason = "only the local maps give a value (" + std::string(to_string(local_maps->status)) +
               "); the divergence curves have no rising straight stretch";
    return answer;
  }
  std::string why;
  if (rosenstein) why += "Rosenstein: " + rosenstein->fit.estimate.reason;
  if (kantz) why += std::string(why.empty() ? "" : "; ") + "Kantz: " + kantz->fit.estimate.reason;
  if (local_maps)
    why += std::string(why.empty() ? "" : "; ") + "local maps: " + to_string(local_maps->status);
  e.reason = why.empty() ? "no estimator was run" : why;
  return answer;
}

}  // namespace chaos
