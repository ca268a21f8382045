#include "chaos/mutual_information.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <string>

#include "chaos/error.hpp"
#include "chaos/series.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

// A joint histogram has boxes^2 cells; beyond this most cells stay empty for any realistic N and
// the table no longer fits in cache.
constexpr std::size_t max_boxes = 1024;

// Equal width (TISEAN `mutual`): v = (x - min) / (max - min) in [0, 1], box = min(boxes - 1,
// floor(v boxes)); the maximum falls in the last box.
std::vector<std::uint32_t> equal_width_boxes(std::span<const double> x, std::size_t boxes) {
  const auto [lo_it, hi_it] = std::minmax_element(x.begin(), x.end());
  double lo = *lo_it, hi = *hi_it;
  double scale = 1.0;
  // A range beyond the largest double (data spanning about +-1e308) is rescaled by the exact
  // factor 1/2 first, so the box of every sample is unchanged.
  if (!std::isfinite(hi - lo)) scale = 0.5;
  lo *= scale;
  hi *= scale;
  const double range = hi - lo;
  const double b = static_cast<double>(boxes);
  std::vector<std::uint32_t> box(x.size());
  for (std::size_t t = 0; t < x.size(); ++t) {
    const double v = (x[t] * scale - lo) / range;
    box[t] = static_cast<std::uint32_t>(std::min(boxes - 1, static_cast<std::size_t>(v * b)));
  }
  return box;
}

// Equiprobable: sample t of rank r (0-based, equal values ordered by their index t) goes to box
// floor(r boxes / N), so box occupancies differ by at most one. Only the order of the values
// matters, hence the invariance under any strictly increasing transform.
std::vector<std::uint32_t> equiprobable_boxes(std::span<const double> x, std::size_t boxes) {
  const std::size_t n = x.size();
  // Sorting (value, index) pairs orders equal values by index and keeps the comparisons local.
  std::vector<std::pair<double, std::uint32_t>> order(n);
  for (std::size_t t = 0; t < n; ++t) order[t] = {x[t], static_cast<std::uint32_t>(t)};
  std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> box(n);
  for (std::size_t r = 0; r < n; ++r) box[order[r].second] = static_cast<std::uint32_t>(r * boxes / n);
  return box;
}

// I = sum_ij p_ij ln(p_ij / (p_i p_j)) over the pairs (box[t], box[t + tau]), t < N - tau, with both
// marginals taken from the same pairs. In counts: (1/M) sum c_ij ln(c_ij M / (a_i b_j)). The ratio
// is formed from integers below 2^53, so a joint table that is exactly the product of its
// marginals gives exactly 0.
double information_at(const std::vector<std::uint32_t>& box, std::size_t boxes, std::size_t tau,
                      std::vector<std::uint64_t>& joint, std::vector<std::uint64_t>& first,
                      std::vector<std::uint64_t>& second) {
  std::fill(joint.begin(), joint.end(), 0);
  const std::size_t pairs = box.size() - tau;
  const std::uint32_t* a = box.data();
  const std::uint32_t* b = box.data() + tau;
  for (std::size_t t = 0; t < pairs; ++t) ++joint[a[t] * boxes + b[t]];
  std::fill(first.begin(), first.end(), 0);
  std::fill(second.begin(), second.end(), 0);
  for (std::size_t i = 0; i < boxes; ++i)
    for (std::size_t j = 0; j < boxes; ++j) {
      first[i] += joint[i * boxes + j];
      second[j] += joint[i * boxes + j];
    }
  const double m = static_cast<double>(pairs);
  double sum = 0.0;
  for (std::size_t i = 0; i < boxes; ++i) {
    if (first[i] == 0) continue;
    for (std::size_t j = 0; j < boxes; ++j) {
      const std::uint64_t c = joint[i * boxes + j];
      if (c == 0) continue;
      const double cd = static_cast<double>(c);
      sum += cd * std::log(cd * m / (static_cast<double>(first[i]) * static_cast<double>(second[j])));
    }
  }
  return sum / m;
}

}  // namespace

void MutualInformationOptions::validate() const {
  if (max_delay < 1)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "mutual information: max_delay must be at least 1 sample (got 0)");
  if (boxes < 2 || boxes > max_boxes)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "mutual information: boxes must be in 2.." + std::to_string(max_boxes) + " (got " +
                           std::to_string(boxes) + ")");
}

MutualInformationResult mutual_information(std::span<const double> x, const MutualInformationOptions& options) {
  options.validate();
  const std::string what = "mutual information";
  // At the largest delay N - max_delay pairs remain; fewer pairs than boxes per axis cannot fill
  // even the marginal partition.
  require_length(x, detail::add_sat(options.max_delay, options.boxes), what,
                 "max_delay = " + std::to_string(options.max_delay) + " and boxes = " +
                     std::to_string(options.boxes) + " need N >= max_delay + boxes, so the largest delay "
                     "keeps at least one pair per box");
  if (x.size() > UINT32_MAX)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       what + ": at most 2^32 - 1 samples are supported (got " + std::to_string(x.size()) + ")");
  require_finite(x, what);
  require_not_constant(x, what);

  const std::size_t boxes = options.boxes;
  const auto box = options.estimator == MutualInformationEstimator::equal_width ? equal_width_boxes(x, boxes)
                                                                                 : equiprobable_boxes(x, boxes);
  std::vector<std::uint64_t> joint(boxes * boxes), first(boxes), second(boxes);
  MutualInformationResult result;
  result.delay.resize(options.max_delay + 1);
  result.information.resize(options.max_delay + 1);
  for (std::size_t tau = 0; tau <= options.max_delay; ++tau) {
    result.delay[tau] = tau;
    result.information[tau] = information_at(box, boxes, tau, joint, first, second);
  }
  return result;
}

std::optional<std::size_t> first_minimum(const MutualInformationResult& result) {
  const auto& info = result.information;
  if (result.delay.size() != info.size())
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "first_minimum: the result has " + std::to_string(result.delay.size()) + " delays but " +
                           std::to_string(info.size()) + " information values");
  // Strict descent into d, then no rise out of it: a plateau after a descent counts at its start.
  for (std::size_t d = 1; d + 1 < info.size(); ++d)
    if (info[d - 1] > info[d] && info[d] <= info[d + 1]) return result.delay[d];
  return std::nullopt;
}

}  // namespace chaos
