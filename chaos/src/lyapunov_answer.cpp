#include "chaos/lyapunov_answer.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "chaos/format.hpp"

namespace chaos {

namespace {

// The least half-width an answer's interval has, relative to its value: the systematic error the
// spread over the estimators' choices does not show (on the zoo at N = 10^5 that spread alone held
// lambda_1 from the equations in 72% of the answers). A rough answer's floor is the smallest multiple
// of 10% under which the interval holds lambda_1 in at least 90% of the zoo's rough answers at
// N = 10^4 (411 of its 457 rough answers; 376 hold at 40%, 354 at 20%, 363 at 30%); the rows at 10^5
// and the automatic runs at 2*10^4 only check it (docs/reference/lyapunov.md, "The rough floor").
constexpr double confident_floor = 0.1;
constexpr double rough_floor = 0.4;
// Three estimators with different systematic errors (the mean log distance of one neighbour, the log
// mean distance of a neighbourhood, the local maps' Jacobians) that land within this fraction of the
// centre of their span confirm one another even where neither curve has a strict linear region. On
// the zoo's 141 automatic runs (N = 10^4, 2*10^4, 10^5), 0.05 to 0.08 made confident only answers
// whose interval holds lambda_1 from the equations; 0.09 also made Windmi confident 11% low
// (docs/reference/lyapunov.md, "Answers and their intervals").
constexpr double three_way_agreement = 0.07;

void widen(Estimate& e, double floor) {
  e.include(*e.value * (1.0 - floor));
  e.include(*e.value * (1.0 + floor));
}

// The local maps ran to the end and their variants have values, agreeing or not.
bool maps_ran(const LocalMapResult* maps) {
  return maps && (maps->status == LocalMapStatus::consistent || maps->status == LocalMapStatus::inconsistent);
}

// A rough answer's interval spans the local maps' variants, where the maps ran, and the rough floor.
void widen_rough(Estimate& e, const LocalMapResult* maps) {
  if (maps_ran(maps))
    for (const auto& v : maps->variants) e.include(v.lambda);
  widen(e, rough_floor);
}

void include_interval(Estimate& e, const std::optional<Interval>& i) {
  if (!i) return;
  e.include(i->low);
  e.include(i->high);
}

// A divergence curve's answer in a few words: "0.0017 per sample, rough".
std::string curve_value(const Estimate& e) {
  return format_number(*e.value, Precision::title) + " per sample, " + to_string(e.status);
}

// Local maps whose variants agree (consistent) are an answer on their own: they have passed the
// check of their own choices (neighbourhood size, m + 1, cutoff, residual limit, delay, halves of
// the chain), and the divergence curves are checked against them, not they against the curves. On
// the zoo's grid every consistent local-map value lay within 10% of lambda_1 from the equations
// (192 of 192 rows), where the curves beside them had no strict linear region or read low
// (docs/reference/lyapunov.md, "Consistent local maps answer on their own").
void answer_from_consistent_maps(LyapunovAnswer& answer, const LocalMapResult& maps, const std::string& curves) {
  answer.source = "local maps";
  Estimate& e = answer.estimate;
  e = Estimate{};
  e.value = *maps.lambda;
  include_interval(e, maps.lambda_interval);
  e.status = EstimateStatus::confident;
  e.reason = "the local maps are consistent (every variant of their choices agrees with their base); the divergence "
             "curves are evidence beside them (" + curves + ")";
  widen(e, confident_floor);
}

}  // namespace

Estimate LyapunovAnswer::per_time() const { return dt ? scaled(estimate, 1.0 / *dt) : estimate; }

LyapunovAnswer combine_lyapunov(const LyapunovResult* rosenstein, const LyapunovResult* kantz,
                                const LocalMapResult* local_maps, std::optional<double> dt) {
  return combine_lyapunov(rosenstein ? &rosenstein->fit.estimate : nullptr, kantz ? &kantz->fit.estimate : nullptr,
                          local_maps, dt);
}

LyapunovAnswer combine_lyapunov(const Estimate* rosenstein, const Estimate* kantz, const LocalMapResult* local_maps,
                                std::optional<double> dt) {
  LyapunovAnswer answer;
  answer.dt = dt;
  const Estimate* r = rosenstein && rosenstein->value ? rosenstein : nullptr;
  const Estimate* k = kantz && kantz->value ? kantz : nullptr;
  const bool maps_consistent =
      local_maps && local_maps->status == LocalMapStatus::consistent && local_maps->lambda.has_value();
  Estimate& e = answer.estimate;
  if (r && k) {
    // The local maps, where their variants agree, are a third estimate: the median of the three.
    answer.source = maps_consistent ? "Rosenstein, Kantz and local maps" : "Rosenstein and Kantz";
    std::vector<double> values{*r->value, *k->value};
    if (maps_consistent) values.push_back(*local_maps->lambda);
    std::sort(values.begin(), values.end());
    e.value = values.size() == 3 ? values[1] : 0.5 * (values[0] + values[1]);
    for (const double v : values) e.include(v);
    include_interval(e, r->interval);
    include_interval(e, k->interval);
    if (maps_consistent) include_interval(e, local_maps->lambda_interval);
    const bool one_confident = r->status == EstimateStatus::confident || k->status == EstimateStatus::confident;
    const double spread = e.relative_half_width();
    const std::string span = "their spread is " + format_number(spread * 100, Precision::title) + "% either side";
    const auto statuses = [&](const char* between) {
      return "Rosenstein (" + std::string(to_string(r->status)) + ")" + between + "Kantz (" + to_string(k->status) + ")";
    };
    if (one_confident && spread <= confident_floor) {
      e.status = EstimateStatus::confident;
      e.reason = statuses(" and ") + " agree; " + span;
      widen(e, confident_floor);
      return answer;
    }
    if (maps_consistent) {
      // The three values alone, about the centre of their span: agreement of three estimators
      // is the cross-check, whatever the curves' own fit ranges say.
      const double centre = 0.5 * (values.front() + values.back());
      const double half = 0.5 * (values.back() - values.front());
      if (centre > 0.0 && half <= three_way_agreement * centre) {
        e = Estimate{};
        e.value = centre;
        e.include(values.front());
        e.include(values.back());
        e.status = EstimateStatus::confident;
        e.reason = statuses(", ") + " and the local maps (consistent) lie within " +
                   format_number(100 * half / centre, Precision::title) + "% of the centre of their span";
        widen(e, confident_floor);
        return answer;
      }
    }
    if (maps_consistent) {
      answer_from_consistent_maps(answer, *local_maps,
                                  "Rosenstein " + curve_value(*r) + "; Kantz " + curve_value(*k));
      return answer;
    }
    e.status = EstimateStatus::rough;
    e.reason = one_confident ? span + ", more than 10%"
                             : "neither estimator is confident (Rosenstein: " + r->reason + "; Kantz: " + k->reason +
                                   "); " + span;
    widen_rough(e, local_maps);
    return answer;
  }
  if (maps_consistent) {
    answer_from_consistent_maps(answer, *local_maps,
                                r   ? "only Rosenstein gives a value, " + curve_value(*r)
                                : k ? "only Kantz gives a value, " + curve_value(*k)
                                    : "they have no rising straight stretch");
    return answer;
  }
  if (r || k) {
    answer.source = r ? "Rosenstein" : "Kantz";
    e = r ? *r : *k;
    e.downgrade(std::string("only ") + answer.source + " gives a value");
    widen_rough(e, local_maps);
    return answer;
  }
  if (maps_ran(local_maps) && local_maps->base.maps > 0 && local_maps->base.lambda > 0.0) {
    // Inconsistent maps: their base estimate, rough, the interval spanning their variants.
    answer.source = "local maps";
    e.status = EstimateStatus::rough;
    e.value = local_maps->base.lambda;
    widen_rough(e, local_maps);
    e.reason = "only the local maps give a value (inconsistent: their variants disagree); the divergence curves have "
               "no rising straight stretch";
    return answer;
  }
  std::string why;
  if (rosenstein) why += "Rosenstein: " + rosenstein->reason;
  if (kantz) why += std::string(why.empty() ? "" : "; ") + "Kantz: " + kantz->reason;
  if (local_maps) why += std::string(why.empty() ? "" : "; ") + "local maps: " + to_string(local_maps->status);
  e.reason = why.empty() ? "no estimator was run" : why;
  return answer;
}

}  // namespace chaos
