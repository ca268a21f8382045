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
// Half the period of a dominant oscillation: the first local minimum of r after its first zero
// crossing, when r goes below -min_depth there and the crossing comes within max_ratio 1/e times
// (for a sinusoid r(k) = cos(2 pi k / P): 1/e at 0.19 P, zero at P/4, the minimum -1 at P/2).
// nullopt for a series whose correlation decays without oscillating (noise, AR(1), Lorenz x,
// whose slow lobe switching puts the first zero far beyond the decay) or when the minimum lies
// beyond max_lag. Kantz & Schreiber (2004, ch. 6) advise a Theiler window of at least this.
std::optional<std::size_t> oscillation_half_period(const AutocorrelationResult& result, double min_depth = 0.1,
                                                   double max_ratio = 4.0);

}  // namespace chaos
