#pragma once
// What every invariant the library estimates (lambda_1, D2) reports beside its detailed status: a
// value, an interval that says what it covers, and how sharp the answer is.
//   confident: the interval is narrow (lambda_1: half-width at most 10% of the value; D2: at most
//              0.1) and every cross-check that was run passed;
//   rough:     a value, but its interval is wider, or a cross-check disagrees; the reason names which;
//   none:      no fit exists (no positive divergence, no scaling region, too short, not
//              deterministic), and the reason says why.
// A value is never withheld where a fit exists: a doubtful one is `rough`, not missing. The interval
// is the spread of the estimate over the estimator's own reasonable choices (fit range, embedding
// dimension, the halves of the record, the other estimator), not a regression's standard error;
// docs/reference/lyapunov.md states how well it holds on the zoo.

#include <optional>
#include <string>

#include "chaos/scaling_region.hpp"

namespace chaos {

enum class EstimateStatus { confident, rough, none };
const char* to_string(EstimateStatus status) noexcept;

struct Estimate {
  EstimateStatus status = EstimateStatus::none;
  std::optional<double> value;
  std::optional<Interval> interval;  // holds the value
  std::string reason;                // one sentence: what made it confident, rough or none

  // Half the interval's width relative to |value| (0 without an interval or a value of 0).
  double relative_half_width() const noexcept;
  // Widens the interval to hold v as well (a value without an interval gets [v, v] first).
  void include(double v) noexcept;
  // From confident to rough, the reason extended by why; rough and none are left as they are,
  // apart from the reason.
  void downgrade(const std::string& why);
};

// The same estimate with its value and interval multiplied by factor > 0 (per sample to per time
// unit: factor 1 / dt).
Estimate scaled(Estimate estimate, double factor);

}  // namespace chaos
