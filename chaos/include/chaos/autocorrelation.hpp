#pragma once
// Sample autocorrelation r(k) = c(k)/c(0), c(k) = (1/N) sum_{t} (x_t - mean)(x_{t+k} - mean), the
// biased (positive semi-definite) estimator, computed by FFT with zero padding to at least 2N so
// the correlation is linear, not circular (Wiener-Khinchin).

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace chaos {

struct AutocorrelationResult {
  std::vector<double> correlation;  // r(0) = 1, r(1), ..., r(max_lag)
};

AutocorrelationResult autocorrelation(std::span<const double> x, std::size_t max_lag);

// The first lag k >= 1 with r(k) <= 0, or nullopt when r stays positive up to max_lag.
std::optional<std::size_t> first_zero_crossing(const AutocorrelationResult& result);
// The first lag (linearly interpolated, in samples) where r falls to 1/e, or nullopt.
std::optional<double> decorrelation_time(const AutocorrelationResult& result);

}  // namespace chaos
