#pragma once
// The seed's correlation-dimension analysis (its Section 7, Fig. 7) of one scalar series: chaos
// analyze's pipeline (chaos/automatic_analysis.hpp), so a study point and `chaos analyze` on the
// same series report the same delay, Theiler window, embedding dimension and D2, with the study's
// switches:
//   - no Lyapunov exponents from the series (the study takes them from the equations);
//   - Cao's method up to max_dimension;
//   - no stationarity rule: the record is whole periods of a driven mechanism after its transient;
//   - when asked (surrogates > 0), the rank-order test for nonlinearity against K IAAFT surrogates
//     in Cao's embedding (chaos::embedded_nonlinearity_test, as `chaos analyze`): rejected means the
//     series is more predictable than every linear stochastic imitation;
// plus the seed's figure curves: I(delay) as far as the delay search went, and C(eps, m) with the
// plateau per m for m = 1..max_dimension. A constant series (a slider resting on the guide) is
// reported as such, with no estimates.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace study {

// The revision of the rules above. A sweep writes it into its spec (sweep.hpp), so `study sweep
// --resume` refuses a directory whose finished points were analysed under other rules: their
// numbers would not be comparable with the new points'. Raise it with every change here that can
// change a point's result.
//   1  (not written in the spec) the delay searched up to max_delay only
//   2  the delay search goes on to two Theiler windows where max_delay finds no minimum
//   3  chaos analyze's pipeline: its delay rules, D2 from m = 1..Cao's m + 3 (not max_dimension)
//      and none where Cao's E1 does not saturate
inline constexpr int analysis_rules_revision = 3;

struct AnalysisOptions {
  std::size_t periods = 5;        // crank revolutions analysed, at the end of the run (the seed: 5)
  double interval = 1e-5;         // s between samples of the analysed series
  // > 0: sample the series this many times per crank revolution instead (a sweep over speed then
  // analyses every point at the same resolution of its period); `interval` is then ignored.
  std::size_t samples_per_period = 0;
  std::size_t max_delay = 100;    // the delay's first search, samples (chaos::DelaySearch)
  std::size_t boxes = 16;         // mutual-information histogram bins per axis
  std::size_t max_dimension = 12; // Cao and the figure curves up to this m (the seed's Fig. 7d: 1..12)
  std::size_t radii = 40;         // D2 radii, log-spaced from range/1000 to range/4
  std::size_t given_delay = 0;    // > 0: use this delay instead of the MI minimum (the seed's 18)
  // > 0: the surrogate test for nonlinearity with this many IAAFT surrogates (one-sided, so 19 is a
  // test at 5%), on the first test_length samples, surrogates drawn from seed.
  std::size_t surrogates = 0;
  std::size_t test_length = 4096;
  std::uint64_t seed = 1;
};

struct SeriesAnalysis {
  std::string status;             // "ok", or why the pipeline stopped
  std::size_t samples = 0;
  double interval = 0.0;
  std::optional<std::size_t> delay;   // samples
  std::string delay_source;           // "given", or the rule that chose it
  std::size_t delay_searched = 0;     // the largest delay the search examined (0: given)
  std::size_t theiler = 0;            // samples
  std::string theiler_source;         // the rule that set it, in words
  std::vector<std::size_t> dimension; // Cao's m
  std::vector<double> E1, E2;
  std::optional<std::size_t> embedding_dimension;  // Cao's E1 saturation (none: not saturated or stochastic)
  double e2_deviation = 0.0;          // max |E2(m) - 1|: 0 for a stochastic series (Cao 1997)
  std::string d2_status = "not computed";  // chaos::D2Status as text (saturated, not_saturated, not_reproduced, ...)
  std::optional<double> d2, d2_low, d2_high;
  std::vector<std::optional<double>> d2_by_dimension;  // per m = 1..max_dimension
  // The surrogate test: "rejected" (not a linear Gaussian process), "not rejected", "not asked", or
  // why it did not run.
  std::string nonlinearity = "not asked";
  std::optional<std::size_t> nonlinearity_rank;  // 1: the data's prediction error is below every surrogate's
  std::size_t surrogates = 0;                    // K used
  // The curves behind the numbers (seed Fig. 7 b, d, e): I(delay) for delay 0..delay_searched
  // (0..max_delay for a given delay) in nats,
  // and C(eps, m) on the radii for m = 1..max_dimension.
  std::vector<double> mutual_information;
  std::vector<double> radius;
  std::vector<std::vector<double>> correlation_sum;
};

SeriesAnalysis analyse_series_with_curves(std::span<const double> series, double interval, const AnalysisOptions& options);

}  // namespace study
