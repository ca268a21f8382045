#pragma once
// The automatic choices: one rule for each parameter an estimator needs and the user did not give.
// `chaos analyze`, the zoo, every command and Python function called without a delay, Theiler
// window or dimension, the study and the validation table call these functions and nothing else,
// so the same series gets the same choices wherever it is analysed. Each choice comes with the
// rule that made it, in words, for the output.
//
//   delay     1 when the autocorrelation falls below 1/e within one sample (maps, coarsely sampled
//             flows: later "minima" of the information are its noise); else the first minimum of
//             the mutual information (Fraser & Swinney 1986, Phys. Rev. A 33:1134) up to max_delay
//             samples; where the information falls without a minimum, the autocorrelation's first
//             zero crossing; where neither lies within max_delay, the same two rules once more up
//             to `windows` Theiler windows of the record (a finely sampled flow's delay in samples
//             grows with the sampling rate, a fixed cap does not); both searches at most N / 10.
//   Theiler   the longer of the autocorrelation's 1/e time and half a dominant oscillation period
//             (time_scales.hpp: Theiler 1986; Kantz & Schreiber 2004, ch. 6), and at least the
//             delay: where the information is still falling at lags beyond the correlation time,
//             samples closer in time than the delay are still dependent, and as neighbours they
//             would pose as recurrences of the attractor.
//   dimension the least m at which Cao's E1 saturates (Cao 1997, Physica D 110:43), at the chosen
//             delay and window, over at most the first 10^5 samples (E1 and E2 are means over the
//             points, settled long before 10^5; over 10^6 they cost 9 s for the same m:
//             docs/reference/cao.md); none for a stochastic series or one that does not saturate.
//   radii     40 radii log-spaced from range/1000 to range/4 (TISEAN's d2 defaults for the lower
//             end; above a quarter of the range C(eps) is near 1 and carries no scaling).
//   Lyapunov  the divergence curve followed for 20 of the longer of the correlation time and the
//             dominant period (at least 20 steps, at most N / 10), local slopes over whole periods,
//             fitted over m, m + 1, m + 2 at once, at most 10^4 evenly spaced reference points,
//             Kantz neighbourhoods of at most 1000 members (lyapunov.hpp, max_neighbours).

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "chaos/cao.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/lyapunov_local_maps.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/time_scales.hpp"

namespace chaos {

// How far the delay is searched.
struct DelaySearch {
  std::size_t max_delay = 100;  // the first search, samples (capped at N / 10)
  std::size_t windows = 2;      // nothing within max_delay: on to this many Theiler windows (0: stop)
  std::size_t boxes = 16;       // of the mutual information's histogram, per axis
};

struct DelayChoice {
  std::optional<std::size_t> delay;  // none: no rule gives one (`stopped` says why)
  std::string source;                // the rule that gave it
  std::size_t searched = 0;          // the largest delay examined (0: the autocorrelation rule gave 1)
  std::string stopped;
  // The information curve of the last search, I(0..searched), for a plot or an output that shows
  // where the delay came from; empty where the autocorrelation rule gave 1.
  MutualInformationResult information;
};
// The largest delays of the two searches: min(max_delay, N / 10), then min(windows * Theiler
// window, N / 10); the second search is made only where it goes further than the first.
struct DelaySearchLimits {
  std::size_t first = 1, second = 0;
};
DelaySearchLimits delay_search_limits(std::size_t n, const TimeScales& scales, const DelaySearch& search = {});
// `scales` = time_scales(x).
DelayChoice choose_delay(std::span<const double> x, const TimeScales& scales, const DelaySearch& search = {});

struct TheilerChoice {
  std::size_t window = 0;
  std::string source;
};
TheilerChoice choose_theiler_window(const TimeScales& scales, std::size_t delay);

struct DimensionChoice {
  std::optional<std::size_t> dimension;  // none: `stopped` says why
  CaoResult cao;
  std::size_t samples = 0;  // the samples Cao's method read: the first min(N, dimension_samples)
  std::string stopped;
};
inline constexpr std::size_t dimension_samples = 100000;
// "Cao's E1 saturation", with the samples it read where they are fewer than the record's n.
std::string dimension_rule(std::size_t samples, std::size_t n);
// `threads` share Cao's neighbour searches (the result is the same for any number).
DimensionChoice choose_embedding_dimension(std::span<const double> x, std::size_t delay, std::size_t theiler,
                                           std::size_t max_dimension = 10,
                                           std::function<void(double)> progress = nullptr, std::size_t threads = 1);

// The radii above over the range of x: the smallest and the largest, then the log-spaced grid.
struct RadiusRange {
  double smallest = 0.0, largest = 0.0;
};
RadiusRange choose_radius_range(std::span<const double> x);
std::vector<double> choose_radii(std::span<const double> x, std::size_t count = 40);
// The correlation sums D2 is read from: m = 1..max_dimension on choose_radii(x, radii).
CorrelationSumOptions choose_correlation_sum_options(std::span<const double> x, std::size_t delay, std::size_t theiler,
                                                     std::size_t max_dimension, std::size_t radii = 40);

// The steps a divergence curve is followed (rule above); `correlation_time` = scales.theiler.
std::size_t choose_lyapunov_steps(std::size_t correlation_time, std::size_t period, std::size_t n);
inline constexpr std::size_t default_max_neighbours = 1000;
LyapunovOptions choose_lyapunov_options(const TimeScales& scales, std::size_t n, std::size_t dimension,
                                        std::size_t delay, std::size_t theiler, LyapunovMethod method);
LyapunovFitOptions choose_lyapunov_fit(const TimeScales& scales);
// Local maps at (m, tau, w), the estimator's own defaults otherwise.
LocalMapOptions choose_local_map_options(std::size_t dimension, std::size_t delay, std::size_t theiler);

// What a command needs to embed a series: the given values are kept, the others chosen by the rules
// above, each with its source ("given" or the rule).
struct EmbeddingChoice {
  // The series' time scales, where a rule needed them (a delay or window left out): with both given
  // they are not computed (an autocorrelation by FFT that the estimate does not use).
  std::optional<TimeScales> scales;
  std::size_t delay = 1;
  std::string delay_source;
  std::size_t theiler = 0;
  std::string theiler_source;
  std::optional<std::size_t> dimension;  // set by choose_embedding only
  std::string dimension_source;
  bool fallback = false;  // a left-out value had no rule's answer: a fallback stands in (its source says why)
};
// Where no rule gives a value (a random walk has no information minimum, noise no Cao dimension, a
// handful of samples no statistics at all), the estimator's conventional default stands in for it
// (TISEAN's: delay 1, m = 2) and the source says so and why: the estimate then reports in its own
// status what the data show at that embedding, and a series too short for it is refused by the
// estimator's own rule.
inline constexpr std::size_t fallback_delay = 1;
inline constexpr std::size_t fallback_dimension = 2;
EmbeddingChoice choose_delay_and_window(std::span<const double> x, std::optional<std::size_t> delay,
                                        std::optional<std::size_t> theiler, const DelaySearch& search = {});
// ... and the dimension (Cao's method up to max_dimension when it is left out, on `threads`;
// `progress` is called with Cao's fraction done, and may throw to stop it).
EmbeddingChoice choose_embedding(std::span<const double> x, std::optional<std::size_t> delay,
                                 std::optional<std::size_t> theiler, std::optional<std::size_t> dimension,
                                 const DelaySearch& search = {}, std::size_t max_dimension = 10,
                                 std::function<void(double)> progress = nullptr, std::size_t threads = 1);

}  // namespace chaos
