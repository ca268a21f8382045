#include "chaos/nonlinearity_test.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/neighbors.hpp"
#include "chaos/random.hpp"
#include "chaos/series.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

// Points whose future lies inside the series.
std::size_t predicted_points(std::size_t n, const PredictionErrorOptions& o) {
  const std::size_t span = (o.dimension - 1) * o.delay + o.horizon;
  return n > span ? n - span : 0;
}

// k nearest neighbours of every point, exactly, by a sweep along the first coordinate: points are
// sorted by x_i, and from each query the candidates are taken outwards in order of |x_j - x_i|,
// which is a lower bound of the distance in both norms. The sweep stops once that bound exceeds
// the k-th distance found. Ties in distance go to the smaller index, so the answer is unique.
class NeighbourSweep {
 public:
  struct Neighbor {
    std::size_t index;
    double distance;
  };

  NeighbourSweep(const DelayEmbedding& points, Norm norm) : points_(points), norm_(norm) {
    const std::size_t p = points.size();
    sorted_.resize(p);
    std::iota(sorted_.begin(), sorted_.end(), std::size_t{0});
    std::sort(sorted_.begin(), sorted_.end(), [&](std::size_t a, std::size_t b) {
      const double xa = points(a, 0), xb = points(b, 0);
      return xa < xb || (xa == xb && a < b);
    });
    position_.resize(p);
    for (std::size_t r = 0; r < p; ++r) position_[sorted_[r]] = r;
  }

  // The k nearest admissible neighbours of point i (|i - j| > theiler), unordered, into `out`.
  void find(std::size_t i, std::size_t k, std::size_t theiler, std::vector<Neighbor>& out) const {
    out.clear();
    const auto worse = [](const Neighbor& a, const Neighbor& b) {  // max-heap on (distance, index)
      return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
    };
    const double xi = points_(i, 0);
    const std::size_t p = sorted_.size();
    std::size_t left = position_[i], right = position_[i] + 1;  // next candidates: left - 1, right
    for (;;) {
      const bool has_left = left > 0, has_right = right < p;
      if (!has_left && !has_right) break;
      const double gap_left = has_left ? xi - points_(sorted_[left - 1], 0) : HUGE_VAL;
      const double gap_right = has_right ? points_(sorted_[right], 0) - xi : HUGE_VAL;
      const bool take_left = gap_left <= gap_right;
      const double gap = take_left ? gap_left : gap_right;
      // Every further candidate is at least `gap` away; equal distance may still win on index.
      if (out.size() == k && gap > out.front().distance) break;
      const std::size_t j = take_left ? sorted_[--left] : sorted_[right++];
      if ((j > i ? j - i : i - j) <= theiler) continue;
      const Neighbor candidate{j, points_.distance(i, j, norm_)};
      if (out.size() < k) {
        out.push_back(candidate);
        std::push_heap(out.begin(), out.end(), worse);
      } else if (worse(candidate, out.front())) {
        std::pop_heap(out.begin(), out.end(), worse);
        out.back() = candidate;
        std::push_heap(out.begin(), out.end(), worse);
      }
    }
  }

 private:
  const DelayEmbedding& points_;
  Norm norm_;
  std::vector<std::size_t> sorted_, position_;
};

// The sweep visits, for each query, at least every point with the same first coordinate: the sum
// of c^2 over the groups of c equal first coordinates. Above this many per point on average
// (heavily quantised data) the kd-tree is used instead; untied data (c = 1) always sweep.
constexpr std::size_t tied_sweep_limit = 64;

std::size_t first_coordinate_ties(const DelayEmbedding& points) {
  std::vector<double> first(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) first[i] = points(i, 0);
  std::sort(first.begin(), first.end());
  std::size_t total = 0;
  for (std::size_t g = 0, end = 0; g < first.size(); g = end) {
    for (end = g; end < first.size() && first[end] == first[g];) ++end;
    total += (end - g) * (end - g);
  }
  return total;
}

double population_std(std::span<const double> x) {
  double mean = 0.0;
  for (const double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double ss = 0.0;
  for (const double v : x) ss += (v - mean) * (v - mean);
  return std::sqrt(ss / static_cast<double>(x.size()));
}

std::size_t minimum_length(const PredictionErrorOptions& o) {
  return (o.dimension - 1) * o.delay + o.horizon + o.neighbours + 2 * o.theiler + 1;
}

}  // namespace

const char* to_string(NonlinearityStatistic statistic) noexcept {
  switch (statistic) {
    case NonlinearityStatistic::time_reversal_asymmetry: return "time_reversal_asymmetry";
    case NonlinearityStatistic::prediction_error: return "prediction_error";
  }
  return "unknown";
}

const char* to_string(Alternative alternative) noexcept {
  switch (alternative) {
    case Alternative::two_sided: return "two_sided";
    case Alternative::smaller: return "smaller";
    case Alternative::larger: return "larger";
  }
  return "unknown";
}

void PredictionErrorOptions::validate() const {
  if (dimension < 1) refuse_parameter("prediction error: dimension must be at least 1 (got 0)");
  if (delay < 1) refuse_parameter("prediction error: delay must be at least 1 sample (got 0)");
  if (horizon < 1) refuse_parameter("prediction error: horizon must be at least 1 sample (got 0)");
  if (neighbours < 1) refuse_parameter("prediction error: neighbours must be at least 1 (got 0)");
  if (norm != Norm::max && norm != Norm::euclidean)
    refuse_parameter("prediction error: unknown norm " + std::to_string(static_cast<int>(norm)));
}

double prediction_error(std::span<const double> given, const PredictionErrorOptions& o) {
  o.validate();
  // Squared errors and the variance: on the series divided by a power of two where its magnitude
  // needs it (exact: the same neighbours, and the error is a ratio).
  const int exponent = detail::standardising_exponent(given);
  std::vector<double> scaled;
  if (exponent != 0) scaled = detail::scaled_by_power_of_two(given, exponent);
  const std::span<const double> x = exponent != 0 ? std::span<const double>(scaled) : given;
  const std::string what = "prediction error";
  require_length(x, minimum_length(o), what,
                 "m = " + std::to_string(o.dimension) + ", tau = " + std::to_string(o.delay) + ", horizon = " +
                     std::to_string(o.horizon) + ", k = " + std::to_string(o.neighbours) + " and theiler = " +
                     std::to_string(o.theiler) + " need N >= (m - 1) tau + horizon + k + 2 theiler + 1, so every "
                     "point has k admissible neighbours");
  require_finite(x, what);
  require_not_constant(x, what);
  const std::size_t p = predicted_points(x.size(), o);
  const DelayEmbedding points(x, o.dimension, o.delay, p);
  const std::size_t ahead = (o.dimension - 1) * o.delay + o.horizon;
  double sum = 0.0;
  const auto add_error = [&](std::size_t i, double prediction, std::size_t count) {
    const double e = prediction / static_cast<double>(count) - x[i + ahead];
    sum += e * e;
  };
  if (first_coordinate_ties(points) > tied_sweep_limit * p) {
    // Quantised data: the sweep would visit every point sharing the query's first coordinate.
    // The kd-tree finds the same neighbours (same distances, same tie rule) at the cost of untied
    // data; only the order of the prediction's sum differs (rounding).
    const KdTree tree(points, o.norm);
    const NeighborQuery query{o.theiler, false};
    std::vector<Neighbor> found;
    for (std::size_t i = 0; i < p; ++i) {
      tree.k_nearest(i, o.neighbours, found, query);
      double prediction = 0.0;
      for (const auto& nb : found) prediction += x[nb.index + ahead];
      add_error(i, prediction, found.size());
    }
  } else {
    const NeighbourSweep sweep(points, o.norm);
    std::vector<NeighbourSweep::Neighbor> found;
    for (std::size_t i = 0; i < p; ++i) {
      sweep.find(i, o.neighbours, o.theiler, found);
      double prediction = 0.0;
      for (const auto& nb : found) prediction += x[nb.index + ahead];
      add_error(i, prediction, found.size());
    }
  }
  return std::sqrt(sum / static_cast<double>(p)) / population_std(x);
}

double time_reversal_asymmetry(std::span<const double> given, std::size_t delay) {
  const std::string what = "time reversal asymmetry";
  if (delay < 1) refuse_parameter(what + ": delay must be at least 1 sample (got 0)");
  require_length(given, delay + 1, what, "delay = " + std::to_string(delay) + " needs N > delay, so one increment exists");
  require_finite(given, what);
  // Cubes of increments: on the series divided by a power of two where its magnitude needs it.
  const int exponent = detail::standardising_exponent(given);
  std::vector<double> scaled;
  if (exponent != 0) scaled = detail::scaled_by_power_of_two(given, exponent);
  const std::span<const double> x = exponent != 0 ? std::span<const double>(scaled) : given;
  double s2 = 0.0, s3 = 0.0;
  for (std::size_t t = 0; t + delay < x.size(); ++t) {
    const double d = x[t + delay] - x[t];
    s2 += d * d;
    s3 += d * d * d;
  }
  if (s2 == 0.0) return 0.0;
  const double m = static_cast<double>(x.size() - delay);
  return (s3 / m) / std::pow(s2 / m, 1.5);
}

void NonlinearityTestOptions::validate() const {
  if (statistic != NonlinearityStatistic::time_reversal_asymmetry &&
      statistic != NonlinearityStatistic::prediction_error)
    refuse_parameter("nonlinearity test: unknown statistic " + std::to_string(static_cast<int>(statistic)));
  if (alternative != Alternative::two_sided && alternative != Alternative::smaller &&
      alternative != Alternative::larger)
    refuse_parameter("nonlinearity test: unknown alternative " + std::to_string(static_cast<int>(alternative)));
  if (surrogates < 1) refuse_parameter("nonlinearity test: at least 1 surrogate is needed (got 0)");
  if (alternative == Alternative::two_sided && surrogates < 2)
    refuse_parameter("nonlinearity test: a two-sided test needs at least 2 surrogates (got 1): with one, the data's value lies "
           "below or above it unless they tie, so every series would be rejected (size 2/(K+1) = 1)");
  if (surrogates > max_surrogates)
    refuse_parameter("nonlinearity test: at most " + std::to_string(max_surrogates) + " surrogates (got " +
           std::to_string(surrogates) + ")");
  if (time_reversal_delay < 1) refuse_parameter("nonlinearity test: time_reversal_delay must be at least 1 sample (got 0)");
  surrogate.validate();
  prediction.validate();
}

RankTest rank_test(double data_statistic, std::span<const double> surrogate_statistics, Alternative alternative) {
  if (surrogate_statistics.empty()) refuse_parameter("rank test: no surrogate statistics given");
  if (std::isnan(data_statistic)) refuse_parameter("rank test: the data's statistic is NaN");
  for (std::size_t k = 0; k < surrogate_statistics.size(); ++k)
    if (std::isnan(surrogate_statistics[k]))
      refuse_parameter("rank test: the statistic of surrogate " + std::to_string(k) + " is NaN");
  RankTest r;
  for (const double s : surrogate_statistics) {
    // The header's tie rule; equal infinities tie, an infinity and a finite value do not.
    const double scale = std::max(std::abs(s), std::abs(data_statistic));
    const double tolerance = std::max(rank_tie_relative * scale, rank_tie_absolute);
    if (s == data_statistic || (std::isfinite(scale) && std::abs(s - data_statistic) <= tolerance))
      ++r.ties;
    else if (s < data_statistic)
      ++r.below;
    else
      ++r.above;
  }
  const std::size_t k = surrogate_statistics.size();
  // With one surrogate every untied rank is extreme on one side or the other: a two-sided test
  // that rejects every series, whatever it is (size 2/(K+1) = 1).
  if (alternative == Alternative::two_sided && k < 2)
    refuse_parameter("rank test: a two-sided test needs at least 2 surrogate statistics (got 1): with one it rejects every "
           "untied series (size 2/(K+1) = 1)");
  r.rank = r.below + 1;
  const double sides = alternative == Alternative::two_sided ? 2.0 : 1.0;
  r.significance = sides / static_cast<double>(k + 1);
  const bool lowest = r.above == k, highest = r.below == k;
  switch (alternative) {
    case Alternative::smaller: r.rejected = lowest; break;
    case Alternative::larger: r.rejected = highest; break;
    case Alternative::two_sided: r.rejected = lowest || highest; break;
  }
  return r;
}

NonlinearityTestResult nonlinearity_test(std::span<const double> x, const NonlinearityTestOptions& options) {
  options.validate();
  const auto statistic = [&options](std::span<const double> series) {
    return options.statistic == NonlinearityStatistic::prediction_error
               ? prediction_error(series, options.prediction)
               : time_reversal_asymmetry(series, options.time_reversal_delay);
  };
  // Refuses short, non-finite and constant input. Its IAAFT iterations report to options.progress.
  std::size_t k = 0;
  SurrogateOptions each = options.surrogate;
  each.progress = options.progress;
  SurrogateGenerator generator(x, with_progress_over(each, k, options.surrogates));
  NonlinearityTestResult out;
  out.options = options;
  out.data_statistic = statistic(x);
  Random seeds(options.seed);
  out.surrogate_statistics.reserve(options.surrogates);
  for (; k < options.surrogates; ++k) {
    const Surrogate s = generator.generate(seeds.next());
    out.surrogate_statistics.push_back(statistic(s.values));
    out.surrogate_iterations.push_back(s.iterations);
    out.surrogate_spectral_deviations.push_back(s.spectral_deviation);
    if (s.status == SurrogateStatus::max_iterations) ++out.surrogates_not_converged;
    if (options.progress) options.progress(static_cast<double>(k + 1) / static_cast<double>(options.surrogates));
  }
  out.test = rank_test(out.data_statistic, out.surrogate_statistics, options.alternative);
  out.value_ties = ties_note(value_ties(x));
  return out;
}

EmbeddedNonlinearityTest embedded_nonlinearity_test(std::span<const double> x, std::size_t length,
                                                    std::size_t dimension, std::size_t delay, std::size_t theiler,
                                                    std::size_t surrogates, std::uint64_t seed,
                                                    std::function<void(double)> progress) {
  const std::span<const double> head = x.first(std::min(x.size(), length));
  EmbeddedNonlinearityTest out;
  out.segment = end_match(head);
  NonlinearityTestOptions t;
  t.statistic = NonlinearityStatistic::prediction_error;
  t.alternative = Alternative::smaller;
  t.surrogates = surrogates;
  t.seed = seed;
  t.prediction.dimension = dimension;
  t.prediction.delay = delay;
  t.prediction.theiler = theiler;
  t.progress = std::move(progress);
  out.result = nonlinearity_test(head.subspan(out.segment.offset, out.segment.length), t);
  return out;
}

}  // namespace chaos
