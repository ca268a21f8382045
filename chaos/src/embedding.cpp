#include "chaos/embedding.hpp"

#include <string>

#include "chaos/error.hpp"

namespace chaos {

namespace {
void check_parameters(std::size_t n, std::size_t dimension, std::size_t delay) {
  if (dimension == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "embedding dimension m must be at least 1 (got m = 0)");
  if (delay == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "delay tau must be at least 1 sample (got tau = 0)");
  if (DelayEmbedding::points_for(n, dimension, delay) < 2)
    throw InvalidInput(ErrorCode::too_short,
                       "series too short to embed: N = " + std::to_string(n) + " samples, but m = " +
                           std::to_string(dimension) + " and tau = " + std::to_string(delay) +
                           " need N > (m-1)*tau + 1 = " + std::to_string((dimension - 1) * delay + 1));
}
}  // namespace

DelayEmbedding::DelayEmbedding(std::span<const double> series, std::size_t dimension, std::size_t delay)
    : series_(series), dimension_(dimension), delay_(delay) {
  check_parameters(series.size(), dimension, delay);
  points_ = points_for(series.size(), dimension, delay);
}

DelayEmbedding::DelayEmbedding(std::span<const double> series, std::size_t dimension, std::size_t delay,
                               std::size_t points)
    : DelayEmbedding(series, dimension, delay) {
  if (points > points_)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "requested " + std::to_string(points) + " embedded points but only " +
                           std::to_string(points_) + " exist for N = " + std::to_string(series.size()) +
                           ", m = " + std::to_string(dimension) + ", tau = " + std::to_string(delay));
  points_ = points;
}

}  // namespace chaos
