// Exact correlation sums of one series at several Theiler windows from one walk: the exact walk at
// the smallest window, then the pairs of each larger window's extra lags taken out again.

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "chaos/correlation_sum.hpp"
#include "chaos/error.hpp"
#include "correlation_sum_problem.hpp"
#include "chaos/detail/parallel.hpp"

namespace chaos {

namespace {

using namespace correlation_detail;

// The pairs whose lag j - i falls in (windows[s - 1], windows[s]] for s = 1 .. S - 1 (windows sorted,
// distinct) and that are closer than the largest radius, binned per segment s and dimension:
// h[((s - 1) * nm + mi) * nr + bin] (below t_max a bin is at most nr - 1). The accumulators are those
// of every exact walk (coordinate 0 first, then one more per dimension), so each pair lands in the
// bin the walk gave it. window_pairs enumerates lags 1 .. w the same way for the grid and kd-tree.
template <class N>
Histogram lag_band_pairs(const Problem& pb, const std::vector<std::size_t>& windows) {
  const std::size_t segments = windows.size() - 1;
  const std::size_t tasks = (pb.points + chunk_points - 1) / chunk_points;
  const AccBins::Lookup bins = pb.bins->lookup();
  std::vector<Histogram> parts(detail::worker_count(pb.threads, tasks), Histogram(segments * pb.nm * pb.nr, 0));
  detail::parallel_tasks(pb.threads, tasks, [&](std::size_t t, std::size_t worker) {
    Count* h = parts[worker].data();
    const std::size_t end = std::min(pb.points, (t + 1) * chunk_points);
    for (std::size_t i = t * chunk_points; i < end; ++i)
      for (std::size_t s = 1; s <= segments; ++s) {
        Count* hs = h + (s - 1) * pb.nm * pb.nr;
        for (std::size_t j = i + windows[s - 1] + 1; j <= i + windows[s] && j < pb.points; ++j) {
          double acc = N::add(0.0, std::abs(pb.at(i, 0) - pb.at(j, 0)));
          for (std::size_t m = 1; m <= pb.max_m; ++m) {
            if (m > 1) acc = N::add(acc, std::abs(pb.at(i, m - 1) - pb.at(j, m - 1)));
            if (!(acc < pb.t_max)) break;  // beyond every radius here and in every higher dimension
            if (m >= pb.min_m) ++hs[(m - pb.min_m) * pb.nr + bins.inside(acc)];
          }
        }
      }
  });
  return sum_histograms(parts);
}


}  // namespace

std::vector<CorrelationSumResult> correlation_sums_over_theiler_windows(std::span<const double> x,
                                                                        const CorrelationSumOptions& options,
                                                                        std::span<const std::size_t> theilers) {
  if (theilers.empty())
    throw InvalidInput(ErrorCode::invalid_parameter, "correlation sums over Theiler windows: no window given");
  if (options.pairs_per_radius != 0 || options.reference_points != 0)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "correlation sums over Theiler windows: exact counts only (got a pair cap of " +
                           std::to_string(options.pairs_per_radius) + " and " +
                           std::to_string(options.reference_points) + " reference points; both must be 0)");
  // Each window is checked as correlation_sum checks it (the largest is the strictest on N).
  std::vector<std::unique_ptr<Prepared>> prepared;
  for (const std::size_t w : theilers) {
    CorrelationSumOptions o = options;
    o.theiler = w;
    prepared.push_back(std::make_unique<Prepared>());
    prepare(*prepared.back(), x, o);
  }
  std::vector<std::size_t> windows(theilers.begin(), theilers.end());
  std::sort(windows.begin(), windows.end());
  windows.erase(std::unique(windows.begin(), windows.end()), windows.end());

  // The exact walk at the smallest window, then the pairs of each larger window's extra lags.
  const std::size_t smallest =
      static_cast<std::size_t>(std::find(theilers.begin(), theilers.end(), windows.front()) - theilers.begin());
  const Problem& pb = prepared[smallest]->pb;
  const Totals base = exact_totals(pb, options.search);
  const Histogram band = windows.size() < 2 ? Histogram{}
                         : options.norm == Norm::max ? lag_band_pairs<MaxNorm>(pb, windows)
                                                     : lag_band_pairs<EuclideanNorm>(pb, windows);
  std::vector<CorrelationSumResult> out;
  out.reserve(theilers.size());
  for (std::size_t q = 0; q < theilers.size(); ++q) {
    const std::size_t segment =
        static_cast<std::size_t>(std::lower_bound(windows.begin(), windows.end(), theilers[q]) - windows.begin());
    Totals totals;
    totals.pairs = base.pairs;
    for (std::size_t mi = 0; mi < pb.nm; ++mi)
      for (std::size_t s = 1; s <= segment; ++s) {
        const Count* h = band.data() + ((s - 1) * pb.nm + mi) * pb.nr;
        Count closer = 0;  // pairs of this segment closer than radius k
        for (std::size_t k = 0; k < pb.nr; ++k) totals.pairs[mi][k] -= closer += h[k];
      }
    const std::size_t span = pb.points - theilers[q] - 1;  // validated by prepare: P >= w + 2
    totals.examined.assign(pb.nm, std::vector<Count>(pb.nr, static_cast<Count>(span) * static_cast<Count>(span + 1) / 2));
    out.push_back(assemble(*prepared[q], std::move(totals), 0));
  }
  return out;
}

}  // namespace chaos
