#include "study/series_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "chaos/automatic_analysis.hpp"
#include "chaos/cao.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/nonlinearity_test.hpp"
#include "chaos/time_scales.hpp"

namespace study {

SeriesAnalysis analyse_series(std::span<const double> x, double interval, const AnalysisOptions& options) {
  SeriesAnalysis r;
  r.samples = x.size();
  r.interval = interval;
  if (options.surrogates > 0) r.nonlinearity = "not run: the pipeline stopped before it";
  if (x.size() < 4) {
    r.status = "series too short: " + std::to_string(x.size()) + " samples";
    return r;
  }
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double range = *hi - *lo;
  // A range at the level of rounding of the values is no signal to embed.
  if (!(range > 1e-12 * std::max(std::abs(*lo), std::abs(*hi))) || range == 0.0) {
    r.status = "constant series: no delay, embedding or dimension";
    return r;
  }
  std::string stage = "autocorrelation";
  try {
    // The library's time scales (time_scales.hpp), as chaos analyze and the zoo use them: they set
    // the Theiler window below and how far the delay search goes on.
    const chaos::TimeScales scales = chaos::time_scales(x);
    stage = "mutual information";
    chaos::MutualInformationOptions mi;
    mi.boxes = options.boxes;
    const std::size_t first = std::min(options.max_delay, x.size() / 2);
    // Where the first search finds no minimum, the same search once more up to two Theiler windows
    // (at most N / 10), as chaos::automatic_delay does it: a fixed number of samples is no time
    // scale of the record (at the seed's sampling Fig. 12's minima lie at 12-104 samples,
    // docs/reproduction.md). Only the information decides, as in the seed.
    const std::size_t second = std::min(x.size() / 10, 2 * scales.theiler);
    const auto search = [&](std::size_t limit) {
      mi.max_delay = limit;
      r.delay_searched = limit;
      const chaos::MutualInformationResult information = chaos::mutual_information(x, mi);
      r.mutual_information = information.information;
      return chaos::first_minimum(information);
    };
    if (options.given_delay) {
      search(first);  // the curve, for the plots
      r.delay_searched = 0;
      r.delay = options.given_delay;
      r.delay_source = "given";
    } else if ((r.delay = search(first))) {
      r.delay_source = "first mutual-information minimum";
    } else if (second > first && (r.delay = search(second))) {
      r.delay_source = "first mutual-information minimum (none up to " + std::to_string(first) +
                       "; searched on to two Theiler windows, " + std::to_string(second) + ")";
    }
    if (!r.delay) {
      r.status = "no mutual-information minimum for delays 1.." + std::to_string(r.delay_searched);
      return r;
    }
    // The library's window: the 1/e time or half the dominant oscillation period, the longer; here
    // at least the delay too.
    r.theiler = std::max(*r.delay, scales.theiler);
    r.theiler_source = *r.delay > scales.theiler ? "the delay, longer than " + scales.theiler_source : scales.theiler_source;

    stage = "Cao's method";
    chaos::CaoOptions cao;
    cao.delay = *r.delay;
    cao.theiler = r.theiler;
    cao.max_dimension = options.max_dimension;
    const chaos::CaoResult c = chaos::cao(x, cao);
    r.dimension = c.dimension;
    r.E1 = c.E1;
    r.E2 = c.E2;
    r.embedding_dimension = c.embedding_dimension;
    r.e2_deviation = c.max_E2_deviation;

    stage = "correlation sums";
    chaos::CorrelationSumOptions cs;
    cs.delay = *r.delay;
    cs.theiler = r.theiler;
    cs.max_dimension = options.max_dimension;
    cs.radii = chaos::log_radii(range / 1000.0, range / 4.0, options.radii);
    const chaos::CorrelationSumResult sums = chaos::correlation_sum(x, cs);
    r.radius = sums.radius;
    r.correlation_sum = sums.correlation_sum;
    chaos::CorrelationDimensionResult d = chaos::correlation_dimension(sums);
    stage = "the halves check";
    chaos::check_record_halves(d, x, cs);  // a saturated D2 must be reproduced by both halves
    r.d2_status = chaos::to_string(d.status);
    r.d2 = d.d2;
    if (d.d2_interval) {
      r.d2_low = d.d2_interval->low;
      r.d2_high = d.d2_interval->high;
    }
    r.d2_by_dimension = d.d2_by_dimension;
    if (options.surrogates > 0) {
      stage = "the surrogate test";
      if (r.embedding_dimension) {
        const chaos::EmbeddedNonlinearityTest t = chaos::embedded_nonlinearity_test(
            x, options.test_length, *r.embedding_dimension, *r.delay, r.theiler, options.surrogates, options.seed);
        r.nonlinearity = t.result.test.rejected ? "rejected" : "not rejected";
        r.nonlinearity_rank = t.result.test.rank;
        r.surrogates = options.surrogates;
      } else {
        r.nonlinearity = "not run: no Cao dimension to embed in";
      }
    }
    r.status = "ok";
  } catch (const std::invalid_argument& e) {
    // The estimators refuse a series they cannot handle (too short for the embedding, ...): the
    // point keeps what was found before and says where it stopped.
    r.status = "stopped at " + stage + ": " + e.what();
  }
  return r;
}

}  // namespace study
