#include "chaos/cao.hpp"

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

}  // namespace

void CaoOptions::validate() const {
  if (delay == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "cao: delay tau must be at least 1 sample (got tau = 0)");
  if (min_dimension == 0)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "cao: minimum embedding dimension must be at least 1 (got m = 0)");
  if (min_dimension > max_dimension)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "cao: minimum embedding dimension must not exceed the maximum (got min m = " +
                           std::to_string(min_dimension) + " > max m = " + std::to_string(max_dimension) + ")");
  if (threads == 0) throw InvalidInput(ErrorCode::invalid_parameter, "cao: threads must be at least 1 (got 0)");
  if (!(saturation_level > 0.0 && saturation_level < 1.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "cao: saturation level must lie strictly between 0 and 1 (got " + number(saturation_level) + ")");
  if (!(saturation_change > 0.0 && saturation_change < 1.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "cao: saturation change must lie strictly between 0 and 1 (got " + number(saturation_change) + ")");
  if (!(stochastic_sigmas > 0.0) || !std::isfinite(stochastic_sigmas))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "cao: stochastic_sigmas must be positive and finite (got " + number(stochastic_sigmas) + ")");
  if (norm != Norm::max && norm != Norm::euclidean)
    throw InvalidInput(ErrorCode::invalid_parameter, "cao: unknown norm");
}

CaoResult cao(std::span<const double> x, const CaoOptions& options) {
  options.validate();
  require_finite(x, "cao");
  require_not_constant(x, "cao");
  const std::size_t tau = options.delay, w = options.theiler;
  // E1(max) needs E(max + 1), which needs coordinate x[i + (max+1) tau]; and every point i among
  // the N - (max+1) tau used there must have a candidate j outside its window |i - j| <= w.
  const std::size_t top = add_sat(options.max_dimension, 1);
  const std::size_t minimum = add_sat(add_sat(mul_sat(top, tau), mul_sat(2, w)), 2);
  require_length(x, minimum, "cao",
                 "E1(m) for m up to " + std::to_string(options.max_dimension) + " needs E(m) up to m = " +
                     std::to_string(top) + ", i.e. the coordinate x[i + m*tau] with tau = " + std::to_string(tau) +
                     ", and every point needs a candidate outside the Theiler window w = " + std::to_string(w) +
                     ": N >= m*tau + 2*w + 2 = " + std::to_string(top) + "*" + std::to_string(tau) + " + 2*" +
                     std::to_string(w) + " + 2");

  // Exact power-of-two rescaling: no neighbour or ratio changes, sums of squares stay finite.
  const int exponent = detail::scale_exponent(x);
  const std::vector<double> y = detail::scaled_by_power_of_two(x, exponent);
  const std::size_t n = y.size();
  const std::size_t count = options.max_dimension - options.min_dimension + 1;

  // E and E* for m = min .. max + 1 (the last one only feeds E1(max) and E2(max)).
  std::vector<double> e(count + 1), e_star(count + 1), e_star_relative_error(count + 1);
  std::vector<std::size_t> without(count + 1);
  const NeighborQuery query{w, true};  // the tie rule: nearest at a positive distance
  for (std::size_t k = 0; k <= count; ++k) {
    const std::size_t m = options.min_dimension + k;
    const std::size_t points = n - m * tau;  // every i with x[i + m tau] inside the series
    const DelayEmbedding embedded(y, m, tau, points);
    const DelayEmbedding extended(y, m + 1, tau, points);
    const KdTree tree(embedded, options.norm, 8, options.threads);
    std::function<void(double)> progress;
    if (options.progress)
      progress = [&](double done) { options.progress((static_cast<double>(k) + done) / static_cast<double>(count + 1)); };
    const std::vector<std::optional<Neighbor>> nearest = all_nearest(tree, query, progress, options.threads);
    double sum_a = 0.0, sum_star = 0.0, sum_star_squares = 0.0;
    std::size_t used = 0;
    for (std::size_t i = 0; i < points; ++i) {
      if (!nearest[i]) {
        ++without[k];
        continue;
      }
      const std::size_t j = nearest[i]->index;
      sum_a += extended.distance(i, j, options.norm) / nearest[i]->distance;
      const double step = std::abs(y[i + m * tau] - y[j + m * tau]);
      sum_star += step;
      sum_star_squares += step * step;
      ++used;
    }
    if (used == 0)
      throw InvalidInput(ErrorCode::constant,
                         "cao: in m = " + std::to_string(m) + " dimensions (tau = " + std::to_string(tau) +
                             ", w = " + std::to_string(w) + ") none of the " + std::to_string(points) +
                             " points has a neighbour at a positive distance outside the Theiler window, so E(m) "
                             "is undefined; the embedded series takes a single value there");
    e[k] = sum_a / static_cast<double>(used);
    e_star[k] = sum_star / static_cast<double>(used);
    // Standard error of the mean over the points, relative to the mean (neighbour pairs overlap,
    // so this treats them as independent: an approximation, hence the generous sigma threshold).
    const double variance = std::max(0.0, sum_star_squares / static_cast<double>(used) - e_star[k] * e_star[k]);
    e_star_relative_error[k] =
        e_star[k] > 0.0 ? std::sqrt(variance / static_cast<double>(used)) / e_star[k] : 0.0;
  }

  CaoResult result;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t m = options.min_dimension + k;
    // a(i, m) >= 1 for every point (a distance cannot shrink when a coordinate is added), so
    // E(m) >= 1 and E1 is always defined; E*(m) = 0 would leave E2(m) undefined.
    if (e_star[k] == 0.0)
      throw InvalidInput(ErrorCode::constant,
                         "cao: E*(m) = 0 at m = " + std::to_string(m) + " (tau = " + std::to_string(tau) +
                             "): every nearest neighbour has exactly the next value x[i + m*tau] of its reference "
                             "point, so E2(m) = E*(m+1)/E*(m) is undefined; the series is exactly predictable "
                             "from m delay coordinates (e.g. an exactly repeating sequence)");
    result.dimension.push_back(m);
    result.E.push_back(e[k]);
    result.E_star.push_back(std::ldexp(e_star[k], exponent));  // back to the units of x
    result.E1.push_back(e[k + 1] / e[k]);
    result.E2.push_back(e_star[k + 1] / e_star[k]);
    result.points_without_neighbor.push_back(without[k]);
    result.max_E2_deviation = std::max(result.max_E2_deviation, std::abs(result.E2.back() - 1.0));
    result.E2_standard_error.push_back(result.E2.back() * std::hypot(e_star_relative_error[k], e_star_relative_error[k + 1]));
  }
  result.e1_saturation =
      e1_saturation(result.dimension, result.E1, options.saturation_level, options.saturation_change);
  result.stochastic = true;
  for (std::size_t k = 0; k < count; ++k)
    result.stochastic = result.stochastic &&
                        std::abs(result.E2[k] - 1.0) <= options.stochastic_sigmas * result.E2_standard_error[k];
  if (!result.stochastic) result.embedding_dimension = result.e1_saturation;
  result.value_ties = ties_note(value_ties(x));
  return result;
}

std::optional<std::size_t> e1_saturation(std::span<const std::size_t> dimension, std::span<const double> E1,
                                         double level, double change) {
  // E1 has reached the level and every later step is small (Cao's "stops changing"); the last
  // dimension alone has no later step to show it.
  for (std::size_t k = 0; k + 1 < E1.size(); ++k) {
    if (E1[k] < level) continue;
    bool settled = true;
    for (std::size_t later = k; later + 1 < E1.size() && settled; ++later)
      settled = std::abs(E1[later + 1] - E1[later]) <= change;
    if (settled) return dimension[k];
  }
  return std::nullopt;
}

}  // namespace chaos
