#include "chaos/fnn.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/neighbors.hpp"
#include "chaos/series.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

using detail::add_sat;
using detail::mul_sat;
const auto number = [](double v) { return format_number(v); };

// Population standard deviation (Kennel et al.'s R_A), two-pass for accuracy.
double standard_deviation(const std::vector<double>& y) {
  double mean = 0.0;
  for (const double v : y) mean += v;
  mean /= static_cast<double>(y.size());
  double sum = 0.0;
  for (const double v : y) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(y.size()));
}

}  // namespace

void FnnOptions::validate() const {
  if (threads == 0) throw InvalidInput(ErrorCode::invalid_parameter, "fnn: threads must be at least 1 (got 0)");
  if (delay == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "fnn: delay tau must be at least 1 sample (got tau = 0)");
  if (min_dimension == 0)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "fnn: minimum embedding dimension must be at least 1 (got m = 0)");
  if (min_dimension > max_dimension)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "fnn: minimum embedding dimension must not exceed the maximum (got min m = " +
                           std::to_string(min_dimension) + " > max m = " + std::to_string(max_dimension) + ")");
  if (!(rtol > 0.0 && std::isfinite(rtol)))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "fnn: distance ratio threshold Rtol must be finite and positive (got " + number(rtol) + ")");
  if (!(atol > 0.0 && std::isfinite(atol)))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "fnn: attractor size threshold Atol must be finite and positive (got " + number(atol) + ")");
  if (!(threshold >= 0.0 && threshold < 1.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "fnn: false-neighbour threshold must lie in [0, 1) (got " + number(threshold) + ")");
  if (norm != Norm::max && norm != Norm::euclidean)
    throw InvalidInput(ErrorCode::invalid_parameter, "fnn: unknown norm");
}

FnnResult false_nearest_neighbors(std::span<const double> x, const FnnOptions& options) {
  options.validate();
  require_finite(x, "fnn");
  require_not_constant(x, "fnn");
  const std::size_t tau = options.delay, w = options.theiler;
  // Testing dimension m needs the coordinate x[i + m tau], and every point i < N - m tau must have a
  // candidate j outside its window |i - j| <= w.
  const std::size_t minimum = add_sat(add_sat(mul_sat(options.max_dimension, tau), mul_sat(2, w)), 2);
  require_length(x, minimum, "fnn",
                 "testing m = " + std::to_string(options.max_dimension) +
                     " needs the coordinate x[i + m*tau] with tau = " + std::to_string(tau) +
                     ", and every point needs a candidate outside the Theiler window w = " + std::to_string(w) +
                     ": N >= m*tau + 2*w + 2 = " + std::to_string(options.max_dimension) + "*" +
                     std::to_string(tau) + " + 2*" + std::to_string(w) + " + 2");

  const std::vector<double> y = detail::scaled_by_power_of_two(x, detail::scale_exponent(x));
  const double attractor_size = standard_deviation(y);
  const std::size_t n = y.size();
  const NeighborQuery query{w, true};  // ties at distance 0 are skipped, as in Cao's method

  FnnResult result;
  for (std::size_t m = options.min_dimension; m <= options.max_dimension; ++m) {
    const std::size_t points = n - m * tau;  // every i with x[i + m tau] inside the series
    const DelayEmbedding embedded(y, m, tau, points);
    const DelayEmbedding extended(y, m + 1, tau, points);
    const KdTree tree(embedded, options.norm, 8, options.threads);
    std::function<void(double)> progress;
    if (options.progress)
      progress = [&](double done) {
        options.progress((static_cast<double>(m - options.min_dimension) + done) /
                         static_cast<double>(options.max_dimension - options.min_dimension + 1));
      };
    const std::vector<std::optional<Neighbor>> nearest = all_nearest(tree, query, progress, options.threads);
    std::size_t tested = 0, false_count = 0;
    for (std::size_t i = 0; i < points; ++i) {
      const auto& neighbour = nearest[i];
      if (!neighbour) continue;
      const std::size_t j = neighbour->index;
      ++tested;
      // Criterion 1: the new coordinate separates the pair by more than Rtol times R_m.
      const bool far_apart = std::abs(y[i + m * tau] - y[j + m * tau]) / neighbour->distance > options.rtol;
      // Criterion 2: in m + 1 dimensions the pair is as far apart as the attractor is large.
      const bool beyond_attractor = extended.distance(i, j, options.norm) / attractor_size > options.atol;
      if (far_apart || beyond_attractor) ++false_count;
    }
    if (tested == 0)
      throw InvalidInput(ErrorCode::constant,
                         "fnn: in m = " + std::to_string(m) + " dimensions (tau = " + std::to_string(tau) +
                             ", w = " + std::to_string(w) + ") none of the " + std::to_string(points) +
                             " points has a neighbour at a positive distance outside the Theiler window, so the "
                             "false fraction is undefined; the embedded series takes a single value there");
    const double fraction = static_cast<double>(false_count) / static_cast<double>(tested);
    result.dimension.push_back(m);
    result.false_fraction.push_back(fraction);
    if (!result.embedding_dimension && fraction <= options.threshold) result.embedding_dimension = m;
  }
  result.value_ties = ties_note(value_ties(x));
  return result;
}

}  // namespace chaos
