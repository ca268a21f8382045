#pragma once
// The time scales of a series that the automatic choices rest on, from its autocorrelation
// (autocorrelation.hpp): the 1/e decorrelation time, the half period of a dominant oscillation,
// the correlation time the Theiler window is built from (choose.hpp), and whether the record is
// long enough against its own correlation to be treated as stationary.
//
// Theiler window: temporally correlated neighbours bias D2 and Lyapunov estimates (Theiler 1986,
// Phys. Rev. A 34:2427); it must cover the time over which the series stays correlated. The 1/e
// time alone is too short for an oscillating signal: its correlation returns after one period.
// Kantz & Schreiber (2004, Nonlinear Time Series Analysis, 2nd ed., ch. 6) advise at least half a
// period there, so the window is max(ceil(1/e time), half period).
//
// Stationarity: a record whose autocorrelation has not fallen to 1/e within a quarter of its length
// holds fewer than about four independent stretches. A random walk, a trend or 1/f^2 noise look like
// this at any length; their statistics drift with the record and no invariant of an attractor can
// be read from them (their increments can be analysed instead).

#include <cstddef>
#include <optional>
#include <span>
#include <string>

namespace chaos {

struct TimeScales {
  std::size_t max_lag = 0;                         // lags examined: min(N/4, 5000)
  std::optional<double> decorrelation_time;        // 1/e time, samples
  std::optional<std::size_t> first_zero_crossing;  // samples
  std::optional<std::size_t> half_period;          // of a dominant oscillation, samples
  // The correlation time the Theiler window is built from, samples: max(ceil(1/e time), half
  // period). choose_theiler_window (choose.hpp) makes it at least the delay.
  std::size_t theiler = 0;
  std::string theiler_source;                      // why, in words
  bool stationary = true;                          // false: fewer than 50 correlation times
  std::string stationarity_explanation;            // empty when stationary
  // The period of the dominant oscillation (2 half periods), 0 when there is none.
  std::size_t period() const noexcept { return half_period ? 2 * *half_period : 0; }
};

inline constexpr double min_correlation_times = 50.0;

// Refuses (InvalidInput) series shorter than 3 samples, non-finite or constant ones.
TimeScales time_scales(std::span<const double> x);

}  // namespace chaos
