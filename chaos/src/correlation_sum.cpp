#include "chaos/correlation_sum.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "chaos/error.hpp"
#include "chaos/series.hpp"
#include "correlation_sum_problem.hpp"
#include "numeric.hpp"

// The public entry points and the checks of their options. The counting itself: the exact walk
// (correlation_sum_exact.cpp), the reference-point walk (correlation_sum_reference.cpp) and the
// candidate scan they share (correlation_sum_scan.cpp), over the problem of correlation_sum_problem.hpp.

namespace chaos {

namespace correlation_detail {

using detail::add_sat;
using detail::mul_sat;

double threshold(Norm norm, double r) {
  if (norm == Norm::max) return r;
  std::uint64_t lo = 0, hi = std::bit_cast<std::uint64_t>(infinity);  // sqrt(inf) >= r always
  while (lo < hi) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (std::sqrt(std::bit_cast<double>(mid)) >= r)
      hi = mid;
    else
      lo = mid + 1;
  }
  return std::bit_cast<double>(lo);
}

void require_subset(std::size_t points, std::size_t offset, std::size_t count) {
  if (count > points)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "correlation sum: reference_points must not exceed the " + std::to_string(points) +
                           " embedded points N - (m-1)*tau (got " + std::to_string(count) + ")");
  if (offset > 0 && (count == 0 || offset > points || count > points - offset))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "correlation sum: a reference offset needs a subset that fits after it: offset + reference_points "
                       "<= the " + std::to_string(points) + " embedded points (got offset " + std::to_string(offset) +
                           ", reference_points " + std::to_string(count) + ")");
}

void prepare(Prepared& p, std::span<const double> x, const CorrelationSumOptions& options) {
  options.validate();
  require_finite(x, "correlation sum");
  require_not_constant(x, "correlation sum");
  const std::size_t tau = options.delay, w = options.theiler, top = options.max_dimension;
  const std::size_t minimum = add_sat(add_sat(mul_sat(top - 1, tau), w), 2);
  require_length(x, minimum, "correlation sum",
                 "the reference set i < N - (m-1)*tau for m up to " + std::to_string(top) + " with tau = " +
                     std::to_string(tau) + " needs at least one pair outside the Theiler window w = " +
                     std::to_string(w) + ": N >= (m-1)*tau + w + 2 = " + std::to_string(top - 1) + "*" +
                     std::to_string(tau) + " + " + std::to_string(w) + " + 2");
  p.options = options;

  // For the Euclidean norm the series and radii are multiplied by a power of two that brings
  // max |x| into [0.5, 1): exact, so every comparison d < r keeps its outcome, while squares can
  // neither overflow nor underflow. The maximum norm needs no squares and is used as given.
  std::vector<double> radii = options.radii;
  std::span<const double> y = x;
  if (options.norm == Norm::euclidean) {
    double largest = 0.0;
    for (const double v : x) largest = std::max(largest, std::abs(v));
    int exponent = 0;
    std::frexp(largest, &exponent);
    p.scaled.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) p.scaled[i] = std::ldexp(x[i], -exponent);
    for (double& r : radii) r = std::ldexp(r, -exponent);
    y = p.scaled;
  }

  // d <= r is d < r+, the next double above r (d is a double): the counting loops keep their strict
  // comparison. For the Euclidean norm this comes after the exact power-of-two scaling above.
  if (options.inclusive)
    for (double& r : radii) r = std::nextafter(r, infinity);

  std::vector<double> thresholds(radii.size());
  for (std::size_t k = 0; k < radii.size(); ++k) thresholds[k] = threshold(options.norm, radii[k]);
  p.bins.emplace(thresholds);
  Problem& pb = p.pb;
  pb.y = y;
  pb.radii = radii;
  pb.thresholds = thresholds;
  pb.r_max = radii.back();
  pb.t_max = thresholds.back();
  pb.tau = tau;
  pb.w = w;
  pb.points = x.size() - (top - 1) * tau;
  pb.min_m = options.min_dimension;
  pb.max_m = top;
  pb.nm = top - options.min_dimension + 1;
  pb.nr = radii.size();
  pb.norm = options.norm;
  pb.threads = options.threads;
  pb.bins = &*p.bins;
  pb.progress = p.options.progress ? &p.options.progress : nullptr;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  p.range = *hi - *lo;
  p.ties = value_ties(x);
}

CorrelationSumResult assemble(const Prepared& p, Totals totals, std::size_t reference_points) {
  const Problem& pb = p.pb;
  CorrelationSumResult result;
  for (std::size_t m = pb.min_m; m <= pb.max_m; ++m) result.dimension.push_back(m);
  result.radius = p.options.radii;
  result.correlation_sum.assign(pb.nm, std::vector<double>(pb.nr, 0.0));
  for (std::size_t mi = 0; mi < pb.nm; ++mi)
    for (std::size_t k = 0; k < pb.nr; ++k)
      if (totals.examined[mi][k] > 0)
        result.correlation_sum[mi][k] =
            static_cast<double>(totals.pairs[mi][k]) / static_cast<double>(totals.examined[mi][k]);
  result.pairs = std::move(totals.pairs);
  result.examined = std::move(totals.examined);
  result.group_pairs = std::move(totals.group_pairs);
  result.group_examined = std::move(totals.group_examined);
  result.points = reference_points > 0 ? reference_points : pb.points;
  result.range = p.range;
  result.ties = p.ties;
  return result;
}

}  // namespace correlation_detail

namespace {
const auto number = [](double v) { return format_number(v); };
using namespace correlation_detail;
}  // namespace

const char* to_string(CorrelationSearch search) noexcept {
  switch (search) {
    case CorrelationSearch::brute_force: return "brute_force";
    case CorrelationSearch::kd_tree: return "kd_tree";
    case CorrelationSearch::box_assisted: return "box_assisted";
  }
  return "unknown";
}

void CorrelationSumOptions::validate() const {
  const auto refuse = [](const std::string& message) {
    throw InvalidInput(ErrorCode::invalid_parameter, "correlation sum: " + message);
  };
  if (delay == 0) refuse("delay tau must be at least 1 sample (got tau = 0)");
  if (min_dimension == 0) refuse("minimum embedding dimension must be at least 1 (got m = 0)");
  if (min_dimension > max_dimension)
    refuse("minimum embedding dimension must not exceed the maximum (got min m = " + std::to_string(min_dimension) +
           " > max m = " + std::to_string(max_dimension) + ")");
  if (threads == 0) refuse("the number of threads must be at least 1 (got 0)");
  if (jackknife_groups < 2 || jackknife_groups > 1024)
    refuse("the jackknife needs 2 to 1024 groups of reference points (got " + std::to_string(jackknife_groups) + ")");
  if (norm != Norm::max && norm != Norm::euclidean) refuse("unknown norm");
  if (search != CorrelationSearch::brute_force && search != CorrelationSearch::kd_tree &&
      search != CorrelationSearch::box_assisted)
    refuse("unknown search mode");
  if (radii.empty()) refuse("at least one radius is needed (got none)");
  for (std::size_t k = 0; k < radii.size(); ++k) {
    if (!std::isfinite(radii[k]) || !(radii[k] > 0.0))
      refuse("radii must be finite and positive (got radius[" + std::to_string(k) + "] = " + number(radii[k]) + ")");
    if (inclusive && radii[k] == std::numeric_limits<double>::max())
      refuse("with inclusive counting (d <= eps) a radius must be below the largest double (got radius[" +
             std::to_string(k) + "] = " + number(radii[k]) + ")");
    if (k > 0 && !(radii[k] > radii[k - 1]))
      refuse("radii must be strictly increasing (got radius[" + std::to_string(k) + "] = " + number(radii[k]) +
             " after radius[" + std::to_string(k - 1) + "] = " + number(radii[k - 1]) + ")");
  }
}

std::vector<double> log_radii(double r_min, double r_max, std::size_t n) {
  const auto refuse = [](const std::string& message) {
    throw InvalidInput(ErrorCode::invalid_parameter, "log_radii: " + message);
  };
  if (!(std::isfinite(r_min) && r_min > 0.0 && std::isfinite(r_max) && r_max > 0.0))
    refuse("radii must be finite and positive (got r_min = " + number(r_min) + ", r_max = " + number(r_max) + ")");
  if (n == 0) refuse("the number of radii must be at least 1 (got 0)");
  // A log grid finer than this resolves nothing more in the local slopes; the cap keeps a
  // mistyped count from asking for more memory than there is.
  constexpr std::size_t max_radii = 10000;
  if (n > max_radii)
    refuse("the number of radii must be at most " + std::to_string(max_radii) + " (got " + std::to_string(n) + ")");
  if (n == 1) {
    if (r_min != r_max)
      refuse("one radius needs r_min = r_max (got r_min = " + number(r_min) + ", r_max = " + number(r_max) + ")");
    return {r_min};
  }
  if (!(r_min < r_max))
    refuse("r_min must be smaller than r_max for " + std::to_string(n) + " radii (got r_min = " + number(r_min) +
           ", r_max = " + number(r_max) + ")");
  std::vector<double> r(n);
  const double a = std::log(r_min), step = (std::log(r_max) - a) / static_cast<double>(n - 1);
  for (std::size_t k = 0; k < n; ++k) r[k] = std::exp(a + step * static_cast<double>(k));
  r.front() = r_min;  // the ends exactly as given
  r.back() = r_max;
  for (std::size_t k = 1; k < n; ++k)
    if (!(r[k] > r[k - 1]))
      refuse(std::to_string(n) + " radii between " + number(r_min) + " and " + number(r_max) +
             " are not distinct in double precision");
  return r;
}

CorrelationSumResult correlation_sum(std::span<const double> x, const CorrelationSumOptions& options) {
  Prepared p;
  prepare(p, x, options);
  require_subset(p.pb.points, options.reference_offset, options.reference_points);
  if (options.pairs_per_radius == 0 && options.reference_points == 0) {
    Totals totals = exact_totals(p.pb, options.search);
    return assemble(p, std::move(totals), 0);
  }
  // A cap without a subset: every point is a reference point, in the seeded order.
  const std::size_t count = options.reference_points > 0 ? options.reference_points : p.pb.points;
  const std::unique_ptr<ReferenceCounter> counter = make_counter(p.pb, options);
  return assemble(p, subset_totals(p.pb, *counter, options, options.reference_offset, count),
                  options.reference_points);
}

struct CorrelationSumSubsets::State {
  Prepared prepared;
  std::unique_ptr<ReferenceCounter> counter;
};

CorrelationSumSubsets::CorrelationSumSubsets(std::span<const double> x, const CorrelationSumOptions& options)
    : state_(std::make_unique<State>()) {
  prepare(state_->prepared, x, options);
  state_->counter = make_counter(state_->prepared.pb, options);
}

CorrelationSumSubsets::~CorrelationSumSubsets() = default;

std::size_t CorrelationSumSubsets::points() const noexcept { return state_->prepared.pb.points; }

CorrelationSumResult CorrelationSumSubsets::count(std::size_t reference_offset, std::size_t reference_points) const {
  const Prepared& p = state_->prepared;
  if (reference_points == 0)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "correlation sum subsets: a subset needs at least one reference point (got 0)");
  require_subset(p.pb.points, reference_offset, reference_points);
  return assemble(p, subset_totals(p.pb, *state_->counter, p.options, reference_offset, reference_points),
                  reference_points);
}

}  // namespace chaos
