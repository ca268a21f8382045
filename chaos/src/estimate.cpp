#include "chaos/estimate.hpp"

#include <algorithm>
#include <cmath>

namespace chaos {

const char* to_string(EstimateStatus status) noexcept {
  switch (status) {
    case EstimateStatus::confident: return "confident";
    case EstimateStatus::rough: return "rough";
    case EstimateStatus::none: return "none";
  }
  return "unknown";
}

double Estimate::relative_half_width() const noexcept {
  if (!value || !interval || *value == 0.0) return 0.0;
  return 0.5 * (interval->high - interval->low) / std::abs(*value);
}

void Estimate::include(double v) noexcept {
  if (!interval) interval = Interval{v, v};
  interval->low = std::min(interval->low, v);
  interval->high = std::max(interval->high, v);
}

void Estimate::downgrade(const std::string& why) {
  if (status == EstimateStatus::confident) status = EstimateStatus::rough;
  reason = reason.empty() ? why : reason + "; " + why;
}

Estimate scaled(Estimate estimate, double factor) {
  if (estimate.value) *estimate.value *= factor;
  if (estimate.interval) estimate.interval = Interval{estimate.interval->low * factor, estimate.interval->high * factor};
  return estimate;
}

}  // namespace chaos
