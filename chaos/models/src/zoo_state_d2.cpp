#include "chaos/models/zoo_state_d2.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "chaos/correlation_dimension.hpp"
#include "chaos/d2_answer.hpp"
#include "chaos/error.hpp"
#include "chaos/random.hpp"

namespace chaos {

namespace {

double range_of(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi - *lo;
}

}  // namespace

std::vector<std::vector<double>> zoo_state(const ZooEntry& entry, std::size_t n) {
  if (entry.delay) return {};
  Trajectory t = zoo_trajectory(entry, n);
  std::vector<std::vector<double>> state = std::move(t.components);
  if (entry.forced && state.size() >= 2) {
    const std::vector<double> phase = std::move(state.back());
    state.pop_back();
    double largest = 0.0;
    for (const auto& c : state) largest = std::max(largest, range_of(c));
    const double a = 0.5 * largest;
    std::vector<double> cosine(phase.size()), sine(phase.size());
    for (std::size_t i = 0; i < phase.size(); ++i) {
      cosine[i] = a * std::cos(phase[i]);
      sine[i] = a * std::sin(phase[i]);
    }
    state.push_back(std::move(cosine));
    state.push_back(std::move(sine));
  }
  return state;
}

std::vector<StateCoding> state_codings(const std::vector<std::vector<double>>& components, bool map) {
  std::vector<StateCoding> out;
  if (components.empty()) return out;
  if (components.size() > 1) {
    double largest = 0.0;
    for (const auto& c : components) largest = std::max(largest, range_of(c));
    StateCoding scaled{"common range", {}};
    for (const auto& c : components) {
      const double range = range_of(c);
      const double factor = range > 0.0 ? largest / range : 1.0;
      std::vector<double> v(c.size());
      for (std::size_t i = 0; i < c.size(); ++i) v[i] = c[i] * factor;
      scaled.components.push_back(std::move(v));
    }
    out.push_back(std::move(scaled));
  }
  const std::size_t n = components.front().size();
  if (map && n >= 2) {
    StateCoding graph{"with its image", {}};
    for (const std::size_t shift : {std::size_t{0}, std::size_t{1}})
      for (const auto& c : components)
        graph.components.emplace_back(c.begin() + static_cast<std::ptrdiff_t>(shift),
                                      c.begin() + static_cast<std::ptrdiff_t>(shift + n - 1));
    out.push_back(std::move(graph));
  }
  return out;
}

std::vector<double> state_radii(const std::vector<std::vector<double>>& components, std::size_t count) {
  double range = 0.0;
  for (const auto& c : components) range = std::max(range, range_of(c));
  if (!(range > 0.0))
    throw InvalidInput(ErrorCode::invalid_parameter, "state radii: the state does not vary (range 0)");
  return log_radii(range / 1000.0, range / 4.0, count);
}

std::vector<CorrelationSumResult> state_correlation_sums(const std::vector<std::vector<double>>& components,
                                                         const std::vector<double>& radii,
                                                         std::span<const std::size_t> theilers,
                                                         std::uint64_t pairs_per_radius, std::uint64_t seed) {
  if (components.empty() || components.front().empty())
    throw InvalidInput(ErrorCode::invalid_parameter, "state correlation sums: no points");
  if (radii.empty() || !std::is_sorted(radii.begin(), radii.end()) || !(radii.front() > 0.0))
    throw InvalidInput(ErrorCode::invalid_parameter, "state correlation sums: the radii must be positive and increasing");
  if (theilers.empty()) throw InvalidInput(ErrorCode::invalid_parameter, "state correlation sums: no Theiler window");
  const std::size_t n = components.front().size(), dims = components.size(), windows = theilers.size();
  for (const auto& c : components)
    if (c.size() != n) throw InvalidInput(ErrorCode::invalid_parameter, "state correlation sums: components differ in length");
  const std::size_t w_min = *std::min_element(theilers.begin(), theilers.end());
  const std::size_t w_first = static_cast<std::size_t>(std::min_element(theilers.begin(), theilers.end()) - theilers.begin());
  // Points in the order of the first component; a pair farther apart than the largest radius still
  // counted in it is farther apart than that radius in the maximum norm and is never compared.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  const std::vector<double>& first = components.front();
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return first[a] < first[b]; });
  std::vector<double> point(n * dims);  // row-major, in that order
  std::vector<std::size_t> position(n);
  for (std::size_t a = 0; a < n; ++a) {
    position[order[a]] = a;
    for (std::size_t c = 0; c < dims; ++c) point[a * dims + c] = components[c][order[a]];
  }
  // Reference points: every point in time order (exact, each unordered pair once, j > i), or, with
  // a cap, in a seeded random order with partners on both sides, each radius closed once the
  // smallest window has counted pairs_per_radius pairs within it (TISEAN d2's -N; Grassberger 1990).
  const bool capped = pairs_per_radius > 0;
  // The pairs of one reference point share its local density, so a radius is not closed before
  // this many reference points have been counted, however many pairs they brought.
  const std::size_t minimum_reference_points = 5000;
  std::vector<std::uint32_t> reference(n);
  std::iota(reference.begin(), reference.end(), 0u);
  if (capped) {
    Random random(seed);
    for (std::size_t k = n; k > 1; --k) std::swap(reference[k - 1], reference[random.below(k)]);
  }
  // hist[q][g]: pairs outside window q whose distance has g radii at or below it.
  std::vector<std::vector<std::uint64_t>> hist(windows, std::vector<std::uint64_t>(radii.size(), 0));
  std::vector<std::uint64_t> examined_so_far(windows, 0);
  std::vector<std::vector<std::uint64_t>> pairs(windows, std::vector<std::uint64_t>(radii.size(), 0)),
      examined(windows, std::vector<std::uint64_t>(radii.size(), 0));
  std::size_t open = radii.size();  // radii 0..open-1 are still counted
  const auto close_from = [&](std::size_t k) {  // records radii k..open-1 as they stand
    for (std::size_t q = 0; q < windows; ++q) {
      std::uint64_t sum = 0;
      for (std::size_t g = 0; g < open; ++g) {
        sum += hist[q][g];
        if (g >= k) {
          pairs[q][g] = sum;
          examined[q][g] = examined_so_far[q];
        }
      }
    }
    open = k;
  };
  for (std::size_t t = 0; t < n && open > 0; ++t) {
    const std::size_t i = reference[t];
    const std::size_t a = position[i];
    const double r_open = radii[open - 1];
    const double* p = &point[a * dims];
    const auto visit = [&](std::size_t b) {
      const std::size_t j = order[b];
      const std::size_t gap = i > j ? i - j : j - i;
      if (gap <= w_min) return;
      const double* q = &point[b * dims];
      double d = std::abs(q[0] - p[0]);
      for (std::size_t c = 1; c < dims && d < r_open; ++c) d = std::max(d, std::abs(q[c] - p[c]));
      if (!(d < r_open)) return;
      const std::size_t g = static_cast<std::size_t>(std::upper_bound(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(open), d) - radii.begin());
      for (std::size_t w = 0; w < windows; ++w)
        if (gap > theilers[w]) ++hist[w][g];
    };
    for (std::size_t b = a + 1; b < n && point[b * dims] - p[0] < r_open; ++b)
      if (capped || order[b] > i) visit(b);
    for (std::size_t b = a; b-- > 0 && p[0] - point[b * dims] < r_open;)
      if (capped || order[b] > i) visit(b);
    for (std::size_t w = 0; w < windows; ++w) {
      // Partners j of i outside the window: j > i + w, and with a cap also j < i - w.
      const std::size_t after = n - 1 - i > theilers[w] ? n - 1 - i - theilers[w] : 0;
      const std::size_t before = capped && i > theilers[w] ? i - theilers[w] : 0;
      examined_so_far[w] += after + before;
    }
    if (!capped || t + 1 < minimum_reference_points) continue;
    // The radii within which the smallest window has counted the cap are closed (a suffix: the
    // counts grow with the radius).
    std::uint64_t counted = 0;
    for (std::size_t g = 0; g < open; ++g) {
      counted += hist[w_first][g];
      if (counted >= pairs_per_radius) {
        close_from(g);
        break;
      }
    }
  }
  if (open > 0) close_from(0);
  double range = 0.0;
  for (const auto& c : components) range = std::max(range, range_of(c));
  std::vector<CorrelationSumResult> out;
  for (std::size_t w = 0; w < windows; ++w) {
    CorrelationSumResult r;
    r.dimension = {dims};
    r.radius = radii;
    std::vector<double> c(radii.size());
    for (std::size_t k = 0; k < radii.size(); ++k)
      c[k] = examined[w][k] > 0 ? static_cast<double>(pairs[w][k]) / static_cast<double>(examined[w][k]) : 0.0;
    r.correlation_sum = {c};
    r.pairs = {pairs[w]};
    r.examined = {examined[w]};
    r.points = n;
    r.range = range;
    out.push_back(std::move(r));
  }
  return out;
}

Estimate state_d2_reference(const CorrelationSumResult& sums) {
  CorrelationDimensionOptions options;
  options.saturation_dimensions = 1;
  return d2_reading(correlation_dimension(sums, options), options);
}

}  // namespace chaos
