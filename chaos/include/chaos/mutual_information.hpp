#pragma once
// Average mutual information I(tau) between x(t) and x(t + tau) (seed Eq. 31, in nats), the usual
// way to choose the embedding delay (Fraser & Swinney 1986): the first local minimum of I(tau).

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace chaos {

enum class MutualInformationEstimator {
  equal_width,   // TISEAN's `mutual`: the series rescaled to [0, 1] and cut into `boxes` equal boxes
  equiprobable,  // boxes of equal occupancy (rank-based), insensitive to outliers and to scaling
};

struct MutualInformationOptions {
  std::size_t max_delay = 20;  // TISEAN -D
  std::size_t boxes = 16;      // TISEAN -b
  MutualInformationEstimator estimator = MutualInformationEstimator::equal_width;
  void validate() const;
};

struct MutualInformationResult {
  std::vector<std::size_t> delay;   // 0 .. max_delay
  std::vector<double> information;  // I(delay) in nats, >= 0
};

MutualInformationResult mutual_information(std::span<const double> x,
                                           const MutualInformationOptions& options = {});

// The first local minimum: the smallest delay d in 1 .. max_delay - 1 with I(d - 1) > I(d) <= I(d + 1).
// nullopt means "no minimum within the range": the caller must not fall back to the last lag.
std::optional<std::size_t> first_minimum(const MutualInformationResult& result);

}  // namespace chaos
