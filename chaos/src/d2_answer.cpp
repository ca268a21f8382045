#include "chaos/d2_answer.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "chaos/format.hpp"

namespace chaos {

namespace {

std::string text(double v) { return format_number(v, Precision::title); }

std::string radii_text(const Interval& r) { return "eps in [" + text(r.low) + ", " + text(r.high) + "]"; }

// Widens the interval by the checks that ran beside the estimate: the record's halves and the
// other delay. Returns what they read, in words (empty when none ran or gave a value).
std::string include_checks(Estimate& e, const CorrelationDimensionResult& d2) {
  std::string read;
  const auto add = [&](const std::optional<double>& v, const std::string& label) {
    if (!v) return;
    e.include(*v);
    read += (read.empty() ? "" : ", ") + label + " " + text(*v);
  };
  add(d2.first_half_d2, "first half");
  add(d2.second_half_d2, "second half");
  if (d2.variant_delay) add(d2.variant_delay_d2, "delay " + std::to_string(*d2.variant_delay));
  return read;
}

Estimate from_plateau(const D2Plateau& p) {
  Estimate e;
  e.status = EstimateStatus::rough;
  e.value = p.slope;
  e.interval = p.slopes;
  e.include(p.slope);
  return e;
}

}  // namespace

Estimate d2_reading(const CorrelationDimensionResult& d2, const CorrelationDimensionOptions& options) {
  Estimate e;
  switch (d2.status) {
    case D2Status::saturated: {
      if (!d2.d2) break;
      e.status = EstimateStatus::confident;
      e.value = *d2.d2;
      if (d2.d2_interval) e.interval = *d2.d2_interval;
      e.include(*d2.d2);
      if (d2.d2_standard_error) {
        e.include(*d2.d2 - 2.0 * *d2.d2_standard_error);
        e.include(*d2.d2 + 2.0 * *d2.d2_standard_error);
      }
      const std::string checks = include_checks(e, d2);
      const auto& used = d2.saturation_dimensions_used;
      e.reason = (used.empty() ? std::string("a shared plateau")
                               : "a plateau shared by m = " + std::to_string(used.front()) + ".." +
                                     std::to_string(used.back())) +
                 (d2.scaling_region ? " over " + radii_text(*d2.scaling_region) : std::string()) +
                 (checks.empty() ? std::string() : " (reproduced: " + checks + ")");
      // D2 is the small-scale limit: another plateau below the one read says the slope still changes
      // towards that limit; one above it reads the attractor's larger-scale shape and is only reported.
      // A reading disputes the value only beyond the confident half-width and beyond its own counting
      // error: at small scales the pairs are few, and on a flow they come in correlated runs. (One
      // error, not two: twice it also let pass a real rise on a short record, Lorenz-Stenflo at
      // N = 10^4, and a confident value wrong by three half-widths is the worse mistake.)
      const auto counting_error = [&](const D2Plateau& p) {
        return p.pairs > 0 ? options.pair_counting_error / std::sqrt(static_cast<double>(p.pairs)) : 0.0;
      };
      const auto margin = [&](const D2Plateau& p) { return std::max(d2_confident_half_width, counting_error(p)); };
      const auto error_text = [&](const D2Plateau& p) {
        return p.pairs > 0 ? " (counting error about " + text(counting_error(p)) + " from " + std::to_string(p.pairs) +
                                 " pairs)"
                           : std::string();
      };
      const auto rival = [&](const D2Plateau& other) { return std::abs(other.slope - *d2.d2) > margin(other); };
      const auto above = [&](const D2Plateau& other) {
        return d2.scaling_region && other.radii.low >= d2.scaling_region->high;
      };
      for (const auto& other : d2.other_plateaus)
        if (rival(other) && above(other))
          e.reason += "; at larger scales, " + radii_text(other.radii) + ", the slopes read " + text(other.slope);
      for (const auto& other : d2.other_plateaus)
        if (rival(other) && !above(other)) {
          e.include(other.slope);
          e.downgrade("another plateau of the same dimensions reads " + text(other.slope) + " at " +
                      radii_text(other.radii) + error_text(other) +
                      ", below the one read: the value depends on which scales are read");
        }
      // The same at the smallest well-counted scales, where the slopes may still move without
      // settling into a plateau: every slope there more than the confident half-width away, on one
      // side, and their mean beyond the margin, says the plateau is not yet the small-scale limit.
      if (const auto& s = d2.smallest_scales;
          s && (s->slopes.low > *d2.d2 + d2_confident_half_width || s->slopes.high < *d2.d2 - d2_confident_half_width) &&
          std::abs(s->slope - *d2.d2) > margin(*s)) {
        e.include(s->slopes.low);
        e.include(s->slopes.high);
        e.downgrade("at the smallest well-counted scales, " + radii_text(s->radii) + ", the slopes read " +
                    text(s->slopes.low) + " to " + text(s->slopes.high) + error_text(*s) +
                    ": the slope still changes below the plateau, towards the small-scale limit that D2 is");
      }
      if (e.interval && 0.5 * (e.interval->high - e.interval->low) > d2_confident_half_width)
        e.downgrade("the interval is wider than +-" + text(d2_confident_half_width));
      if (d2.exceeds_eckmann_ruelle)
        e.downgrade("the value exceeds the Eckmann-Ruelle limit 2 log10(N) = " + text(d2.eckmann_ruelle_limit));
      return e;
    }
    case D2Status::not_reproduced: {
      if (d2.plateaus.empty()) break;
      e = from_plateau(d2.plateaus.front());
      const std::string checks = include_checks(e, d2);
      e.reason = "the plateau at " + radii_text(d2.plateaus.front().radii) + " is not reproduced" +
                 (checks.empty() ? std::string(" by the record's halves") : " (" + checks + ")");
      return e;
    }
    case D2Status::scale_dependent: {
      if (d2.plateaus.size() < 2) break;
      e = from_plateau(d2.plateaus[1]);
      e.include(d2.plateaus[0].slopes.low);
      e.include(d2.plateaus[0].slopes.high);
      e.reason = "the slope changes with scale: " + text(d2.plateaus[1].slope) + " at " +
                 radii_text(d2.plateaus[1].radii) + ", " + text(d2.plateaus[0].slope) + " at " +
                 radii_text(d2.plateaus[0].radii) + "; the value is the smaller scales'";
      return e;
    }
    case D2Status::noise_limited: {
      if (d2.plateaus.empty()) break;
      e = from_plateau(d2.plateaus.front());
      e.reason = "the plateau at " + radii_text(d2.plateaus.front().radii) + " is bounded below by noise at eps = " +
                 (d2.noise_floor ? text(*d2.noise_floor) : std::string("?")) +
                 ": the smaller scales, where D2 is defined, cannot be read";
      return e;
    }
    case D2Status::not_saturated: {
      if (!d2.plateaus.empty()) {
        e = from_plateau(d2.plateaus.front());
        if (d2.steepest_lower_slope) e.include(*d2.steepest_lower_slope);
        e.reason = "the plateau at " + radii_text(d2.plateaus.front().radii) + " is contradicted by m = " +
                   (d2.steepest_lower_dimension ? std::to_string(*d2.steepest_lower_dimension) : std::string("?")) +
                   ", which reads " + (d2.steepest_lower_slope ? text(*d2.steepest_lower_slope) : std::string("?")) +
                   " there";
        return e;
      }
      // No shared plateau: the highest dimensions' own D2(m), where they agree.
      std::vector<std::size_t> top;
      for (std::size_t d = d2.d2_by_dimension.size(); d-- > 0 && top.size() < options.saturation_dimensions;)
        if (d2.d2_by_dimension[d]) top.push_back(d);
      if (top.size() == options.saturation_dimensions) {
        double lo = *d2.d2_by_dimension[top.front()], hi = lo, sum = 0.0;
        for (const auto d : top) {
          lo = std::min(lo, *d2.d2_by_dimension[d]);
          hi = std::max(hi, *d2.d2_by_dimension[d]);
          sum += *d2.d2_by_dimension[d];
        }
        const double mean = sum / static_cast<double>(top.size());
        if (hi - lo <= 2.0 * options.region.tolerance * std::abs(mean)) {
          e.status = EstimateStatus::rough;
          e.value = mean;
          for (const auto d : top)
            if (d2.d2_by_dimension_interval[d]) {
              e.include(d2.d2_by_dimension_interval[d]->low);
              e.include(d2.d2_by_dimension_interval[d]->high);
            }
          e.include(lo);
          e.include(hi);
          e.reason = "D2(m) of m = " + std::to_string(d2.dimension[top.back()]) + ".." +
                     std::to_string(d2.dimension[top.front()]) + " agree (" + text(lo) + " to " + text(hi) +
                     "), but on no common octave of scales";
          return e;
        }
      }
      e.reason = "not saturated: D2(m) still grows with m or the highest dimensions disagree";
      return e;
    }
    case D2Status::no_scaling_region: break;
  }
  e = Estimate{};
  e.reason = std::string(to_string(d2.status)) + ": no plateau of the local slopes to read a value from";
  return e;
}

Estimate with_d2_floor(Estimate e) {
  if (e.value) {
    const double floor = e.status == EstimateStatus::confident ? d2_confident_floor : d2_rough_floor;
    e.include(*e.value - floor);
    e.include(*e.value + floor);
  }
  return e;
}

Estimate d2_answer(const CorrelationDimensionResult& d2, const CorrelationDimensionOptions& options) {
  return with_d2_floor(d2_reading(d2, options));
}

}  // namespace chaos
