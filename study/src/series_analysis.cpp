#include "study/series_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "chaos/automatic_analysis.hpp"
#include "chaos/cao.hpp"
#include "chaos/choose.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/nonlinearity_test.hpp"

namespace study {

SeriesAnalysis analyse_series_with_curves(std::span<const double> x, double interval, const AnalysisOptions& options) {
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
  std::string stage = "the automatic analysis";
  try {
    // chaos analyze's pipeline with the study's switches: no Lyapunov exponents (the study takes
    // them from the equations), Cao up to the study's largest dimension, and no stationarity rule:
    // the record is a whole number of periods of a driven mechanism after its transient, which
    // the rule (a correlation time under 1/50 of the record) would reject for a regular motion.
    chaos::AutomaticAnalysisOptions o;
    if (options.given_delay) o.delay = options.given_delay;
    o.delay_search.max_delay = options.max_delay;
    o.delay_search.boxes = options.boxes;
    o.max_dimension = options.max_dimension;
    o.radii = options.radii;
    o.check_stationarity = false;
    o.rosenstein = o.kantz = o.local_maps = false;
    const chaos::AutomaticAnalysis a = chaos::analyse_series(x, std::nullopt, o);
    r.delay = a.delay;
    r.delay_source = a.delay_source;
    r.delay_searched = a.delay_searched;
    r.theiler = a.theiler;
    r.theiler_source = a.theiler_source;
    if (a.cao) {
      r.dimension = a.cao->dimension;
      r.E1 = a.cao->E1;
      r.E2 = a.cao->E2;
      r.embedding_dimension = a.cao->embedding_dimension;
      r.e2_deviation = a.cao->max_E2_deviation;
    }
    if (a.d2) {
      r.d2_status = chaos::to_string(a.d2->status);
      r.d2 = a.d2->d2;
      if (a.d2->d2_interval) {
        r.d2_low = a.d2->d2_interval->low;
        r.d2_high = a.d2->d2_interval->high;
      }
    }

    // The seed's figure curves (Fig. 7 b, d, e): the information up to where the search went, and
    // C(eps, m) with D2 per m for m = 1..max_dimension on the pipeline's radii. These are for the
    // figures only: the D2 above is the pipeline's, read from m = 1..Cao's m + 3.
    stage = "mutual information";
    if (!a.delay_information.information.empty()) {
      r.mutual_information = a.delay_information.information;
    } else {  // the autocorrelation gave delay 1 without a search
      chaos::MutualInformationOptions mi;
      mi.boxes = options.boxes;
      mi.max_delay = std::max<std::size_t>(1, std::min(options.max_delay, x.size() / 10));
      r.mutual_information = chaos::mutual_information(x, mi).information;
    }
    if (!r.delay) {
      r.status = a.stopped;
      return r;
    }
    stage = "correlation sums";
    const chaos::CorrelationSumResult sums = chaos::correlation_sum(
        x, chaos::choose_correlation_sum_options(x, *r.delay, r.theiler, options.max_dimension, options.radii));
    r.radius = sums.radius;
    r.correlation_sum = sums.correlation_sum;
    r.d2_by_dimension = chaos::correlation_dimension(sums).d2_by_dimension;
    if (!a.stopped.empty()) {
      r.status = a.stopped;
      return r;
    }
    if (options.surrogates > 0) {
      stage = "the surrogate test";
      const chaos::EmbeddedNonlinearityTest t = chaos::embedded_nonlinearity_test(
          x, options.test_length, *r.embedding_dimension, *r.delay, r.theiler, options.surrogates, options.seed);
      r.nonlinearity = t.result.test.rejected ? "rejected" : "not rejected";
      r.nonlinearity_rank = t.result.test.rank;
      r.surrogates = options.surrogates;
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
