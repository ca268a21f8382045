#include "chaos/lyapunov.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/lyapunov_local_maps.hpp"
#include "chaos/neighbors.hpp"
#include "chaos/series.hpp"
#include "chaos/detail/parallel.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

[[noreturn]] void refuse(const std::string& message) { throw InvalidInput(ErrorCode::invalid_parameter, message); }

// Reference points are handled in blocks of this many, whatever the thread count; each block's
// partial sums are added in block order, so the result does not depend on the threads. Blocks are
// processed in rounds of at most round_blocks, which bounds the memory of the partial sums.
constexpr std::size_t block_size = 512;
constexpr std::size_t round_blocks = 256;

// Kantz's default radius keeps the mean neighbourhood at or below this many points.
constexpr double default_neighbours = 20.0;

// The sum of ln d over the terms of each step. ln was the costliest operation of a divergence
// curve (`perf` on the zoo's Lorenz case: 35% of its time, against 31% for the rest of the curves'
// work), so each d is split exactly into a mantissa in [0.5, 1) and a power of two; the powers are
// summed as integers and the mantissas multiplied, with one ln per step for every `batch`
// reference points. A product of at most 64 such mantissas lies in [2^-64, 1], far from underflow,
// and carries at most 64 roundings of 2^-53 each: an error below 1e-14 in the ln of the batch, the
// size of the roundings a sum of the 64 separate logarithms makes.
struct Partial {
  static constexpr std::size_t batch = 64;
  std::vector<double> sum;             // sum of ln(mantissa products) flushed so far
  std::vector<double> product;         // mantissas not yet flushed
  std::vector<std::int64_t> exponent;  // sum of the binary exponents
  std::vector<std::size_t> terms, zeros;
  std::size_t used = 0, pending = 0, capped = 0, tied = 0, pairs = 0;
  double neighbours = 0.0;
  explicit Partial(std::size_t steps)
      : sum(steps + 1, 0.0), product(steps + 1, 1.0), exponent(steps + 1, 0), terms(steps + 1, 0), zeros(steps + 1, 0) {}
  void clear() {
    std::fill(sum.begin(), sum.end(), 0.0);
    std::fill(product.begin(), product.end(), 1.0);
    std::fill(exponent.begin(), exponent.end(), 0);
    std::fill(terms.begin(), terms.end(), 0);
    std::fill(zeros.begin(), zeros.end(), 0);
    used = pending = capped = tied = pairs = 0;
    neighbours = 0.0;
  }
  // ln d joins step k's sum (d > 0).
  void add_log(std::size_t k, double d) {
    const auto bits = std::bit_cast<std::uint64_t>(d);
    const auto field = static_cast<std::int64_t>(bits >> 52);  // d > 0: no sign bit
    if (field == 0 || field == 0x7ff) {  // subnormal, or not finite (ln d as std::log would give it)
      int e = 0;
      product[k] *= std::isfinite(d) ? std::frexp(d, &e) : d;
      exponent[k] += e;
    } else {
      product[k] *= std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3fe0000000000000ULL);
      exponent[k] += field - 1022;
    }
    ++terms[k];
  }
  // ln d[k] joins step k's sum for k = 0..steps, or counts a zero where d[k] = 0 (d >= 0). Where
  // every d[k] is a normal number, as in nearly every call, the split needs no branch. (Measured
  // against calling add_log for each k: no gain above the noise; the second loop repeats add_log's
  // normal case and could go.)
  void add_logs(const double* d) {
    const std::size_t n = sum.size();
    bool normal = true;
    for (std::size_t k = 0; k < n; ++k) normal &= d[k] >= std::numeric_limits<double>::min() && d[k] <= std::numeric_limits<double>::max();
    if (!normal) {
      for (std::size_t k = 0; k < n; ++k)
        if (d[k] > 0.0)
          add_log(k, d[k]);
        else
          ++zeros[k];
      return;
    }
    double* const prod = product.data();
    std::int64_t* const ex = exponent.data();
    std::size_t* const count = terms.data();
    for (std::size_t k = 0; k < n; ++k) {
      const auto bits = std::bit_cast<std::uint64_t>(d[k]);
      prod[k] *= std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3fe0000000000000ULL);
      ex[k] += static_cast<std::int64_t>(bits >> 52) - 1022;
      ++count[k];
    }
  }
  // Called after each reference point: at most `batch` factors per product.
  void reference_done() {
    if (++pending == batch) flush();
  }
  void flush() {
    for (std::size_t k = 0; k < sum.size(); ++k)
      if (product[k] != 1.0) {
        sum[k] += std::log(product[k]);
        product[k] = 1.0;
      }
    pending = 0;
  }
  // Adds a flushed partial (its products all 1).
  void add(const Partial& p) {
    for (std::size_t k = 0; k < sum.size(); ++k) {
      sum[k] += p.sum[k];
      exponent[k] += p.exponent[k];
      terms[k] += p.terms[k];
      zeros[k] += p.zeros[k];
    }
    used += p.used;
    capped += p.capped;
    tied += p.tied;
    pairs += p.pairs;
    neighbours += p.neighbours;
  }
  // The mean of ln d at step k, over its terms (terms[k] > 0).
  double mean_log(std::size_t k) const {
    return (sum[k] + static_cast<double>(exponent[k]) * std::numbers::ln2) / static_cast<double>(terms[k]);
  }
};

// The distances |X_{i+k} - X_{j+k}|, k = 0..steps, of a pair of delay vectors, into d. The
// per-sample differences e_t = |y_{i+t} - y_{j+t}| are formed once and each distance combines m of
// them, coordinate by coordinate in the order DelayEmbedding::distance uses (so the values are the
// same to the last bit); the loops over k are contiguous and vectorise, where reading every
// distance through the view would touch m strided samples per step.
struct PairDistances {
  std::vector<double> e, d;
  void compute(std::span<const double> y, std::size_t i, std::size_t j, std::size_t m, std::size_t tau,
               std::size_t steps, Norm norm) {
    const std::size_t samples = steps + 1 + (m - 1) * tau;
    e.resize(samples);
    d.assign(steps + 1, 0.0);
    const double* a = y.data() + i;
    const double* b = y.data() + j;
    for (std::size_t t = 0; t < samples; ++t) e[t] = std::abs(a[t] - b[t]);
    for (std::size_t l = 0; l < m; ++l) {
      const double* el = e.data() + l * tau;
      if (norm == Norm::max)
        for (std::size_t k = 0; k <= steps; ++k) d[k] = std::max(d[k], el[k]);
      else
        for (std::size_t k = 0; k <= steps; ++k) d[k] += el[k] * el[k];
    }
    if (norm == Norm::euclidean)
      for (std::size_t k = 0; k <= steps; ++k) d[k] = std::sqrt(d[k]);
  }
};

// Work space of one thread.
struct Scratch {
  PairDistances pair;
  std::vector<std::size_t> neighbourhood, kept, thinned;
  std::vector<double> mean, weight;
  std::vector<std::pair<double, std::size_t>> by_distance;
};

// The distance of delay vectors i and j (k = 0 of PairDistances::compute, the same operations).
double start_distance(std::span<const double> y, std::size_t i, std::size_t j, std::size_t m, std::size_t tau,
                      Norm norm) {
  double d = 0.0;
  for (std::size_t l = 0; l < m; ++l) {
    const double e = std::abs(y[i + l * tau] - y[j + l * tau]);
    d = norm == Norm::max ? std::max(d, e) : d + e * e;
  }
  return norm == Norm::euclidean ? std::sqrt(d) : d;
}

// Kantz: thins each group of more than `cap` members at one exact distance from reference i to
// `cap` of them, evenly spaced in index order (G[floor(r |G| / cap)]), into s.thinned, with
// s.weight[r] = |G| / cap for the kept ones of a thinned group and 1 otherwise, all in index order.
// False, touching nothing, when no group is that large: the caller then averages as before.
bool thin_ties(std::span<const double> y, std::size_t i, const std::vector<std::size_t>& members, std::size_t m,
               std::size_t tau, Norm norm, std::size_t cap, Scratch& s) {
  if (cap == 0 || members.size() <= cap) return false;
  s.by_distance.clear();
  for (const std::size_t j : members) s.by_distance.emplace_back(start_distance(y, i, j, m, tau, norm), j);
  // Is any distance shared by more than `cap` members? Tied data have a few distinct distances, so
  // they are counted in a short list; past 16 distinct ones the sort below decides.
  std::array<std::pair<double, std::size_t>, 16> seen;
  std::size_t distinct = 0;
  bool any = false, many = false;
  for (const auto& [d, j] : s.by_distance) {
    std::size_t at = 0;
    while (at < distinct && seen[at].first != d) ++at;
    if (at == distinct) {
      if (distinct == seen.size()) {
        many = true;
        break;
      }
      seen[distinct++] = {d, 0};
    }
    if (++seen[at].second > cap) any = true;
  }
  if (!many && !any) return false;
  if (!many) {
    // Members come in index order, so each group's r-th member is met in order: keep the ones at
    // ranks floor(t |G| / cap), t = 0, 1, ..., and the kept list is in index order too.
    std::array<std::size_t, 16> rank{}, next{};
    s.thinned.clear();
    s.weight.clear();
    for (const auto& [d, j] : s.by_distance) {
      std::size_t g = 0;
      while (seen[g].first != d) ++g;
      const std::size_t size = seen[g].second;
      if (size <= cap) {
        s.thinned.push_back(j);
        s.weight.push_back(1.0);
      } else if (rank[g]++ == next[g] * size / cap) {
        ++next[g];
        s.thinned.push_back(j);
        s.weight.push_back(static_cast<double>(size) / static_cast<double>(cap));
      }
    }
    return true;
  }
  std::sort(s.by_distance.begin(), s.by_distance.end());  // by distance, then index
  for (std::size_t g = 0, end = 0; g < s.by_distance.size(); g = end) {
    for (end = g; end < s.by_distance.size() && s.by_distance[end].first == s.by_distance[g].first;) ++end;
    any = any || end - g > cap;
  }
  if (!any) return false;
  // Keep (index, weight) pairs, then restore index order so the sum runs as the plain one does.
  std::vector<std::pair<std::size_t, double>> kept;
  for (std::size_t g = 0, end = 0; g < s.by_distance.size(); g = end) {
    for (end = g; end < s.by_distance.size() && s.by_distance[end].first == s.by_distance[g].first;) ++end;
    const std::size_t size = end - g;
    if (size <= cap) {
      for (std::size_t r = g; r < end; ++r) kept.emplace_back(s.by_distance[r].second, 1.0);
    } else {
      const double weight = static_cast<double>(size) / static_cast<double>(cap);
      for (std::size_t r = 0; r < cap; ++r) kept.emplace_back(s.by_distance[g + r * size / cap].second, weight);
    }
  }
  std::sort(kept.begin(), kept.end());
  s.thinned.resize(kept.size());
  s.weight.resize(kept.size());
  for (std::size_t r = 0; r < kept.size(); ++r) {
    s.thinned[r] = kept[r].first;
    s.weight[r] = kept[r].second;
  }
  return true;
}

// Runs work(reference index, partial, scratch) for every reference point, in blocks, on `threads`
// threads, and adds the blocks' partial sums in block order. An exception in a worker is
// rethrown here after every thread has stopped. The fraction of blocks done is reported to
// `progress`, when set, on the calling thread.
template <class Work>
Partial for_each_reference(const std::vector<std::size_t>& references, std::size_t steps, std::size_t threads,
                           const std::function<void(double)>& progress, const Work& work) {
  const std::size_t blocks = (references.size() + block_size - 1) / block_size;
  std::vector<Partial> partials(std::min(blocks, round_blocks), Partial(steps));
  std::vector<Scratch> scratch(detail::worker_count(threads, partials.size()));
  Partial total(steps);
  for (std::size_t first = 0; first < blocks; first += round_blocks) {
    const std::size_t count = std::min(round_blocks, blocks - first);
    for (std::size_t b = 0; b < count; ++b) partials[b].clear();
    detail::parallel_tasks(threads, count, [&](std::size_t b, std::size_t worker) {
      const std::size_t begin = (first + b) * block_size;
      const std::size_t end = std::min(references.size(), begin + block_size);
      for (std::size_t r = begin; r < end; ++r) {
        work(references[r], partials[b], scratch[worker]);
        partials[b].reference_done();
      }
      partials[b].flush();
    }, &progress, {first, blocks});
    for (std::size_t b = 0; b < count; ++b) total.add(partials[b]);
  }
  return total;
}

std::vector<std::size_t> reference_indices(std::size_t points, std::size_t wanted) {
  const std::size_t n = wanted == 0 ? points : std::min(wanted, points);
  std::vector<std::size_t> out(n);
  for (std::size_t r = 0; r < n; ++r)
    // Evenly spaced over 0..points-1, exact in integers and all distinct (r < n <= points, so
    // r * points fits in 64 bits for any series that fits in memory).
    out[r] = r * points / n;
  return out;
}

}  // namespace

const char* to_string(LyapunovMethod method) noexcept {
  switch (method) {
    case LyapunovMethod::rosenstein: return "rosenstein";
    case LyapunovMethod::kantz: return "kantz";
  }
  return "unknown";
}

const char* to_string(LyapunovStatus status) noexcept {
  switch (status) {
    case LyapunovStatus::linear_region: return "linear_region";
    case LyapunovStatus::no_linear_region: return "no_linear_region";
    case LyapunovStatus::not_diverging: return "not_diverging";
    case LyapunovStatus::no_neighbours: return "no_neighbours";
    case LyapunovStatus::unconfirmed: return "unconfirmed";
    case LyapunovStatus::not_reproduced: return "not_reproduced";
  }
  return "unknown";
}

void LyapunovOptions::validate() const {
  if (dimension < 1) refuse("Lyapunov exponent: embedding dimension m must be at least 1 (got m = 0)");
  if (delay < 1) refuse("Lyapunov exponent: delay tau must be at least 1 sample (got tau = 0)");
  if (steps < 1) refuse("Lyapunov exponent: the divergence must be followed for at least 1 step (got steps = 0)");
  if (threads < 1) refuse("Lyapunov exponent: threads must be at least 1 (got 0)");
  if (radius && !(std::isfinite(*radius) && *radius > 0.0))
    refuse("Lyapunov exponent (Kantz): the neighbourhood radius eps must be positive and finite (got eps = " +
           detail::format_number(*radius) + ")");
  if (min_neighbours < 1) refuse("Lyapunov exponent (Kantz): min_neighbours must be at least 1 (got 0)");
}

void LyapunovFitOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    refuse("Lyapunov fit: tolerance must be positive and finite (got " + detail::format_number(tolerance) + ")");
  if (min_steps == 1) refuse("Lyapunov fit: a linear region needs at least 2 steps (got min_steps = 1)");
  if (dimensions < 1) refuse("Lyapunov fit: at least 1 embedding dimension must be fitted (got dimensions = 0)");
  if (!(min_rise >= 0.0) || !std::isfinite(min_rise))
    refuse("Lyapunov fit: the minimum rise must be finite and >= 0 (got " + detail::format_number(min_rise) + ")");
}

namespace {

// What the curves of one series at one embedding (m, tau, K, w, norm, reference points) share,
// whatever the method: the rescaled series, the embedding, its kd-tree and the reference points in
// the tree's leaf order. Built once, it serves Rosenstein's and Kantz's curves alike, and each
// curve is bit for bit the one divergence_curve computes alone (the same values, visited in the
// same order).
struct Embedded {
  int exponent;
  std::vector<double> y;
  double log_scale;
  std::size_t points;
  DelayEmbedding candidates;  // reference points and neighbours
  KdTree tree;
  std::vector<std::size_t> references;

  Embedded(std::span<const double> x, const LyapunovOptions& options)
      // An exact power-of-two rescaling keeps Euclidean sums of squares finite for any magnitude;
      // ln d then shifts by exponent * ln 2, added back at the end.
      : exponent(detail::scale_exponent(x)),
        y(detail::scaled_by_power_of_two(x, exponent)),
        log_scale(exponent * std::log(2.0)),
        points(x.size() - detail::mul_sat(options.dimension - 1, options.delay) - options.steps),
        candidates(y, options.dimension, options.delay, points),
        tree(candidates, options.norm) {
    // Reference points are visited in the tree's leaf order, so consecutive queries touch the same
    // nodes (in index order a chaotic series jumps across the whole tree at every query, and the
    // searches wait on memory). The order is fixed by the data, so the sums stay deterministic.
    std::vector<char> chosen(points, 0);
    for (const std::size_t i : reference_indices(points, options.reference_points)) chosen[i] = 1;
    for (const std::size_t i : tree.leaf_order())
      if (chosen[i]) references.push_back(i);
  }
  Embedded(const Embedded&) = delete;  // candidates views y
  Embedded& operator=(const Embedded&) = delete;
};

// Refuses what divergence_curve refuses: options, the series' values and its length.
void check_curve_input(std::span<const double> x, const LyapunovOptions& options) {
  options.validate();
  const std::string what = std::string("largest Lyapunov exponent (") + to_string(options.method) + ")";
  require_finite(x, what);
  require_not_constant(x, what);
  const std::size_t m = options.dimension, tau = options.delay, steps = options.steps, w = options.theiler;
  // P = N - (m-1) tau - K points have all K future steps; P >= 2w + 3 leaves every reference point
  // at least one candidate outside its Theiler window.
  require_length(x, minimum_length(options), what,
                 "N >= (m-1) tau + steps + 2 w + 3 with m = " + std::to_string(m) + ", tau = " + std::to_string(tau) +
                     ", steps = " + std::to_string(steps) + ", w = " + std::to_string(w) +
                     ", so that every reference point can be followed for all steps and has a candidate outside "
                     "the Theiler window");
}

DivergenceCurve curve_on(const Embedded& e, const LyapunovOptions& options) {
  const std::size_t m = options.dimension, tau = options.delay, steps = options.steps, w = options.theiler;
  const int exponent = e.exponent;
  const std::vector<double>& y = e.y;
  const double log_scale = e.log_scale;
  const std::size_t points = e.points;
  const KdTree& tree = e.tree;
  const std::vector<std::size_t>& references = e.references;
  const NeighborQuery query{w, true};

  DivergenceCurve curve;
  curve.method = options.method;
  curve.points = points;
  curve.reference_points = references.size();
  Partial total(steps);
  if (options.method == LyapunovMethod::rosenstein) {
    total = for_each_reference(references, steps, options.threads, options.progress, [&](std::size_t i, Partial& p, Scratch& s) {
      const auto neighbour = tree.nearest(i, query);
      if (!neighbour) return;
      ++p.used;
      ++p.pairs;
      p.neighbours += 1.0;
      s.pair.compute(y, i, neighbour->index, m, tau, steps, options.norm);
      p.add_logs(s.pair.d.data());
    });
  } else {
    double eps = 0.0;
    if (options.radius) {
      eps = std::ldexp(*options.radius, -exponent);
    } else {
      // range / 1000, then adjusted on at most 1000 evenly spaced reference points: doubled while
      // fewer than half of them have min_neighbours neighbours (a curve from a few rare close
      // returns is not representative of the attractor), else halved while they have more than
      // default_neighbours on average and would keep that coverage (the cost grows with the
      // neighbourhood, the precision hardly does: the average over reference points dominates;
      // and a smaller eps leaves more room for growth). Powers of two keep eps exactly
      // range / 1000 * 2^h.
      const auto [lo, hi] = std::minmax_element(y.begin(), y.end());
      eps = (*hi - *lo) / 1000.0;
      const std::vector<std::size_t> sample = reference_indices(points, std::min<std::size_t>(1000, points));
      struct Census {
        double mean = 0.0, covered = 0.0;  // mean neighbours, fraction with min_neighbours
      };
      const auto census = [&](double r) {
        Census c;
        for (const std::size_t i : sample) {
          const std::size_t count = tree.count_within(i, r, query);
          c.mean += static_cast<double>(count);
          c.covered += count >= options.min_neighbours ? 1.0 : 0.0;
        }
        c.mean /= static_cast<double>(sample.size());
        c.covered /= static_cast<double>(sample.size());
        return c;
      };
      Census c = census(eps);
      // Beyond the embedded set's diameter every point is already a neighbour, so doubling on
      // cannot cover more (min_neighbours above the points' count: 60 censuses of every pair).
      const double diameter =
          (*hi - *lo) * (options.norm == Norm::euclidean ? std::sqrt(static_cast<double>(m)) : 1.0);
      for (int doublings = 0; c.covered < 0.5 && doublings < 60 && eps <= diameter; ++doublings)
        c = census(eps *= 2.0);
      for (int halvings = 0; c.mean > default_neighbours && halvings < 60; ++halvings) {
        const Census smaller = census(eps / 2.0);
        if (smaller.covered < 0.5) break;
        eps /= 2.0;
        c = smaller;
      }
    }
    curve.radius = std::ldexp(eps, exponent);
    total = for_each_reference(references, steps, options.threads, options.progress, [&](std::size_t i, Partial& p, Scratch& s) {
      tree.within(i, eps, s.neighbourhood, query);
      if (s.neighbourhood.size() < options.min_neighbours || s.neighbourhood.empty()) return;
      ++p.used;
      p.neighbours += static_cast<double>(s.neighbourhood.size());
      // A neighbourhood above max_neighbours is represented by that many of its members, evenly
      // spaced in time (index order): its mean distance from a sample that does not favour the
      // nearest ones, at a cost bounded per reference point.
      const std::vector<std::size_t>* members = &s.neighbourhood;
      if (options.max_neighbours != 0 && s.neighbourhood.size() > options.max_neighbours) {
        const std::size_t found = s.neighbourhood.size(), cap = options.max_neighbours;
        s.kept.resize(cap);
        for (std::size_t r = 0; r < cap; ++r) s.kept[r] = s.neighbourhood[r * found / cap];
        members = &s.kept;
        ++p.capped;
      }
      s.mean.assign(steps + 1, 0.0);
      const double size = static_cast<double>(members->size());
      if (thin_ties(y, i, *members, m, tau, options.norm, options.max_tied_neighbours, s)) {
        ++p.tied;
        p.pairs += s.thinned.size();
        for (std::size_t r = 0; r < s.thinned.size(); ++r) {
          s.pair.compute(y, i, s.thinned[r], m, tau, steps, options.norm);
          for (std::size_t k = 0; k <= steps; ++k) s.mean[k] += s.weight[r] * s.pair.d[k];
        }
      } else {
        p.pairs += members->size();
        for (const std::size_t j : *members) {
          s.pair.compute(y, i, j, m, tau, steps, options.norm);
          for (std::size_t k = 0; k <= steps; ++k) s.mean[k] += s.pair.d[k];
        }
      }
      // The sum of distances is 0 only if every one is: then the mean has no logarithm (a zero).
      for (std::size_t k = 0; k <= steps; ++k) s.mean[k] /= size;
      p.add_logs(s.mean.data());
    });
  }
  curve.step.resize(steps + 1);
  curve.divergence.resize(steps + 1);
  for (std::size_t k = 0; k <= steps; ++k) {
    curve.step[k] = k;
    if (total.terms[k] > 0) curve.divergence[k] = total.mean_log(k) + log_scale;
  }
  curve.terms = std::move(total.terms);
  curve.zero_distances = std::move(total.zeros);
  curve.references_used = total.used;
  curve.capped_neighbourhoods = total.capped;
  curve.tied_neighbourhoods = total.tied;
  curve.pairs_followed = total.pairs;
  curve.mean_neighbours = total.used > 0 ? total.neighbours / static_cast<double>(total.used) : 0.0;
  if (curve.divergence[0]) curve.mean_initial_distance = std::exp(*curve.divergence[0]);
  return curve;
}

}  // namespace

DivergenceCurve divergence_curve(std::span<const double> x, const LyapunovOptions& options) {
  check_curve_input(x, options);
  const Embedded e(x, options);
  return curve_on(e, options);
}

LyapunovFit fit_divergence(const DivergenceCurve& curve, const LyapunovFitOptions& options) {
  return fit_divergence(std::vector<DivergenceCurve>{curve}, options);
}

LyapunovFit fit_divergence(const std::vector<DivergenceCurve>& curves, const LyapunovFitOptions& options) {
  options.validate();
  if (curves.empty()) refuse("Lyapunov fit: no divergence curve to fit");
  for (const auto& c : curves)
    if (c.step != curves.front().step) refuse("Lyapunov fit: the curves of one fit must cover the same steps");
  LyapunovFit fit;
  const DivergenceCurve& curve = curves.front();
  const std::size_t last = curve.step.empty() ? 0 : curve.step.back();
  // Each local slope spans at least one whole oscillation period, so a rotating flow's periodic
  // modulation of the divergence averages out instead of breaking the tolerance.
  const bool secants = options.period > 1 && options.half_width == 0;
  fit.half_width = options.half_width != 0 ? options.half_width
                   : secants               ? (options.period + 1) / 2
                                           : std::max<std::size_t>(2, last / 25);
  fit.min_steps = options.min_steps != 0 ? options.min_steps : std::max(3 * fit.half_width + 1, options.period + 1);
  const ScalingRegionOptions region_options{options.tolerance, true, fit.min_steps, fit.half_width};
  std::vector<double> x(curve.step.size());
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = static_cast<double>(curve.step[k]);
  std::vector<std::vector<std::optional<double>>> slopes;
  for (const auto& c : curves) {
    if (secants) {
      // Over a whole period the periodic part of the curve returns to its value, so the secant
      // (y[k+after] - y[k-before]) / P with before + after = P (the mean of the short local slopes
      // over the period) cancels it exactly; a least-squares line over the same window would not.
      const std::size_t before = options.period / 2, after = options.period - before;
      std::vector<std::optional<double>> secant(x.size());
      for (std::size_t k = before; k + after < x.size(); ++k)
        if (c.divergence[k - before] && c.divergence[k + after])
          secant[k] = (*c.divergence[k + after] - *c.divergence[k - before]) / (x[k + after] - x[k - before]);
      slopes.push_back(std::move(secant));
    } else {
      slopes.push_back(local_slopes(x, c.divergence, fit.half_width));
    }
  }
  fit.local_slope = slopes.front();
  std::ostringstream why;
  for (const auto& c : curves)
    if (c.references_used == 0) {
      fit.status = LyapunovStatus::no_neighbours;
      why << "none of the " << c.reference_points << " reference points has a neighbour"
          << (c.method == LyapunovMethod::kantz ? " within eps" : "") << " outside the Theiler window";
      fit.explanation = why.str();
      fit.estimate.reason = fit.explanation;
      return fit;
    }
  // Only a rising curve carries a positive exponent, and these methods estimate nothing else: the
  // straight stretch is searched among steps with a positive local slope. (A saturated plateau
  // whose slopes were exactly 0 would otherwise count as perfectly straight.)
  std::vector<std::vector<std::optional<double>>> rising(slopes.size(), std::vector<std::optional<double>>(x.size()));
  bool rises = false;
  for (std::size_t c = 0; c < slopes.size(); ++c)
    for (std::size_t k = 0; k < x.size(); ++k)
      if (slopes[c][k] && *slopes[c][k] > 0.0) {
        rising[c][k] = slopes[c][k];
        rises = true;
      }
  if (!rises) {
    fit.status = LyapunovStatus::not_diverging;
    why << "no local slope of the divergence curve is positive: no exponential divergence";
    fit.explanation = why.str();
    fit.estimate.reason = fit.explanation;
    return fit;
  }
  // Among the straight stretches, the one across which the curve rises most wins, and it must rise
  // by min_rise: the growth of the separation is the evidence for an exponential divergence.
  std::vector<double> level(x.size(), 0.0);
  for (std::size_t k = 0; k < x.size(); ++k) {
    std::size_t n = 0;
    for (const auto& c : curves)
      if (c.divergence[k]) {
        level[k] += *c.divergence[k];
        ++n;
      }
    if (n > 0) level[k] /= static_cast<double>(n);
  }
  const auto search = [&](double tolerance, double min_rise) {
    ScalingRegionOptions o = region_options;
    o.tolerance = tolerance;
    o.min_support_gain = min_rise;
    return find_scaling_region(x, rising, o, level);
  };
  // The least-squares slope of each curve over steps [first, last] (indices into the curve).
  const auto slopes_over = [&](std::size_t from, std::size_t to, double fallback) {
    std::vector<double> out;
    for (const auto& c : curves) out.push_back(fit_slope(x, c.divergence, from, to).value_or(fallback));
    return out;
  };
  // The estimate from a stretch: the mean of the curves' slopes; the interval spans every curve's
  // slope over the stretch and over each half of it (where the curve bends, the halves differ).
  const auto estimate_over = [&](const ScalingRegion& r, EstimateStatus status, const std::string& reason) {
    Estimate e;
    const std::vector<double> whole = slopes_over(r.first, r.last, r.slope);
    double sum = 0.0;
    for (const double s : whole) sum += s;
    const double value = sum / static_cast<double>(whole.size());
    if (!(value > 0.0)) {
      e.reason = "the straightest rising stretch (steps " + std::to_string(curve.step[r.first]) + ".." +
                 std::to_string(curve.step[r.last]) + ") has a least-squares slope <= 0: no exponential divergence";
      return e;
    }
    e.value = value;
    for (const double s : whole) e.include(s);
    const std::size_t mid = r.first + (r.last - r.first) / 2;
    if (mid - r.first >= 2 && r.last - mid >= 2)
      for (const auto& part : {std::pair{r.first, mid}, std::pair{mid, r.last}})
        for (const double s : slopes_over(part.first, part.second, value)) e.include(s);
    e.status = status;
    e.reason = reason;
    if (status == EstimateStatus::confident && e.relative_half_width() > 0.1) {
      e.status = EstimateStatus::rough;
      e.reason += "; the slopes over the stretch, its halves and the embedding dimensions spread by more than 10%";
    }
    return e;
  };
  // Where the strict rule finds no linear region, the answer comes from the loosest rung that has one.
  const double loose_rise = std::min(1.0, options.min_rise);
  const auto loose_estimate = [&](const std::string& strict_verdict) {
    const struct {
      double tolerance;
      EstimateStatus status;
    } rungs[] = {{options.tolerance, EstimateStatus::confident},
                 {2 * options.tolerance, EstimateStatus::rough},
                 {3 * options.tolerance, EstimateStatus::rough}};
    for (const auto& rung : rungs)
      if (const auto r = search(rung.tolerance, loose_rise)) {
        std::ostringstream s;
        s << "local slopes within " << rung.tolerance * 100 << "% over steps " << curve.step[r->first] << ".."
          << curve.step[r->last] << ", rising by " << loose_rise << " e-fold or more (" << strict_verdict << ")";
        fit.estimate = estimate_over(*r, rung.status, s.str());
        if (fit.estimate.value) return;
      }
    fit.estimate = Estimate{};
    fit.estimate.reason = strict_verdict + "; no stretch rising by " + format_number(loose_rise, Precision::title) +
                          " e-fold has local slopes within " + format_number(300 * options.tolerance, Precision::title) +
                          "% of their mean either";
  };
  const auto region = search(options.tolerance, options.min_rise);
  if (!region) {
    fit.status = LyapunovStatus::no_linear_region;
    why << "no stretch of at least " << fit.min_steps << " steps rising by " << options.min_rise
        << " e-folds or more has positive local slopes within " << options.tolerance * 100 << "% of their mean";
    if (curves.size() > 1) why << " in all " << curves.size() << " embedding dimensions at once";
    why << ": the divergence curve has no linear region";
    if (curves.size() > 1) why << " that does not depend on m";
    fit.explanation = why.str();
    loose_estimate(std::string("strictly, ") + to_string(fit.status));
    return fit;
  }
  fit.first_step = curve.step[region->first];
  fit.last_step = curve.step[region->last];
  double sum = 0.0, lo = region->slope_min, hi = region->slope_max, low_fit = INFINITY, high_fit = -INFINITY;
  for (const double slope : slopes_over(region->first, region->last, region->slope)) {
    fit.lambda_by_curve.push_back(slope);
    sum += slope;
    low_fit = std::min(low_fit, slope);
    high_fit = std::max(high_fit, slope);
  }
  const double slope = sum / static_cast<double>(curves.size());
  if (!(low_fit > 0.0)) {  // local slopes all positive but a least-squares line is not: refuse to guess
    fit.status = LyapunovStatus::not_diverging;
    why << "the straightest stretch (steps " << *fit.first_step << ".." << *fit.last_step << ") has slope "
        << low_fit << " <= 0: no exponential divergence";
    fit.first_step.reset();
    fit.last_step.reset();
    fit.lambda_by_curve.clear();
    fit.explanation = why.str();
    fit.estimate.reason = fit.explanation;
    return fit;
  }
  if (high_fit - low_fit > options.tolerance * slope) {  // the dimensions disagree on the slope itself
    fit.status = LyapunovStatus::no_linear_region;
    why << "the embedding dimensions disagree on the slope over steps " << *fit.first_step << ".." << *fit.last_step
        << " (" << low_fit << " to " << high_fit << " per sample, more than " << options.tolerance * 100
        << "% apart)";
    fit.first_step.reset();
    fit.last_step.reset();
    fit.lambda_by_curve.clear();
    fit.explanation = why.str();
    fit.estimate = estimate_over(*region, EstimateStatus::rough, "strictly, no_linear_region: " + fit.explanation);
    return fit;
  }
  const double rise = slope * (x[region->last] - x[region->first]);
  if (rise < options.min_rise) {
    fit.status = LyapunovStatus::no_linear_region;
    why << "the straightest stretch (steps " << *fit.first_step << ".." << *fit.last_step << ", slope " << slope
        << " per sample) rises by only " << rise << " e-folds, fewer than the " << options.min_rise
        << " needed to identify an exponential divergence (follow the curve longer with more steps, or it is "
        << "a piece of the initial transient)";
    fit.first_step.reset();
    fit.last_step.reset();
    fit.lambda_by_curve.clear();
    fit.explanation = why.str();
    loose_estimate(std::string("strictly, ") + to_string(fit.status));
    return fit;
  }
  fit.status = LyapunovStatus::linear_region;
  fit.lambda = slope;
  fit.lambda_interval = Interval{std::min({lo, low_fit}), std::max({hi, high_fit})};
  why << "local slopes agree within " << options.tolerance * 100 << "% over steps " << *fit.first_step << ".."
      << *fit.last_step;
  if (curves.size() > 1) why << " in " << curves.size() << " embedding dimensions";
  if (options.period > 1) why << " (local slopes over " << 2 * fit.half_width + 1 << " steps: a whole oscillation period)";
  fit.explanation = why.str();
  fit.estimate = estimate_over(*region, EstimateStatus::confident, fit.explanation);
  return fit;
}

std::size_t minimum_length(const LyapunovOptions& options, std::size_t dimensions) {
  const std::size_t highest = detail::add_sat(options.dimension, dimensions > 0 ? dimensions - 1 : 0);
  const std::size_t span = detail::mul_sat(highest > 0 ? highest - 1 : 0, options.delay);
  return detail::add_sat(detail::add_sat(span, options.steps), detail::add_sat(detail::mul_sat(2, options.theiler), 3));
}

namespace {

// The options of runs that may share their embeddings: the same m, tau, w, K, norm and reference points.
bool same_embedding(const LyapunovOptions& a, const LyapunovOptions& b) {
  return a.dimension == b.dimension && a.delay == b.delay && a.theiler == b.theiler && a.steps == b.steps &&
         a.norm == b.norm && a.reference_points == b.reference_points;
}

}  // namespace

std::vector<LyapunovResult> largest_lyapunov_runs(std::span<const double> x, const std::vector<LyapunovOptions>& runs,
                                                  const LyapunovFitOptions& fit, std::optional<double> dt) {
  if (dt && !(std::isfinite(*dt) && *dt > 0.0))
    refuse("Lyapunov exponent: the sampling interval dt must be positive and finite (got dt = " +
           detail::format_number(*dt) + ")");
  fit.validate();
  if (runs.empty()) return {};
  for (const LyapunovOptions& o : runs) {
    o.validate();
    if (!same_embedding(o, runs.front()))
      refuse("Lyapunov exponent: runs that share their embeddings need the same m, delay, Theiler window, steps, norm "
             "and reference points");
  }
  const LyapunovOptions& options = runs.front();
  // The highest dimension needs the longest series: refuse it before the lower curves are
  // computed (a huge --dimensions would otherwise compute curve after curve until one is refused).
  const std::size_t highest = detail::add_sat(options.dimension, fit.dimensions - 1);
  require_length(x, minimum_length(options, fit.dimensions),
                 "largest Lyapunov exponent",
                 "N >= (m-1) tau + steps + 2 w + 3 for the highest of the " + std::to_string(fit.dimensions) +
                     " dimensions fitted, m = " + std::to_string(highest) + ", with tau = " + std::to_string(options.delay) +
                     ", steps = " + std::to_string(options.steps) + ", w = " + std::to_string(options.theiler));
  // Each dimension is embedded once (one rescaled series, one kd-tree, one reference order) and
  // every run's curve is computed on it; Kantz's radius is found afresh for each dimension by the
  // same rule, as in a run alone.
  std::vector<std::vector<DivergenceCurve>> curves(runs.size());
  std::vector<std::size_t> dimensions;
  for (std::size_t extra = 0; extra < fit.dimensions; ++extra) {
    LyapunovOptions at_m = options;
    at_m.dimension = options.dimension + extra;
    for (const LyapunovOptions& o : runs) {
      LyapunovOptions c = o;
      c.dimension = at_m.dimension;
      check_curve_input(x, c);
    }
    const Embedded e(x, at_m);
    for (std::size_t r = 0; r < runs.size(); ++r) {
      LyapunovOptions o = runs[r];
      o.dimension = at_m.dimension;
      curves[r].push_back(curve_on(e, o));
    }
    dimensions.push_back(at_m.dimension);
  }
  std::vector<LyapunovResult> results(runs.size());
  const std::string ties = ties_note(value_ties(x));
  for (std::size_t r = 0; r < runs.size(); ++r) {
    LyapunovResult& result = results[r];
    result.curve = curves[r].front();
    result.dimensions = dimensions;
    result.fit = fit_divergence(curves[r], fit);
    if (!ties.empty()) result.fit.explanation += "; " + ties;
    result.options = runs[r];
    if (runs[r].method == LyapunovMethod::kantz) result.options.radius = result.curve.radius;
    result.dt = dt;
    if (dt && result.fit.lambda) {
      result.lambda_per_time = *result.fit.lambda / *dt;
      result.lambda_per_time_interval =
          Interval{result.fit.lambda_interval->low / *dt, result.fit.lambda_interval->high / *dt};
    }
    if (dt && result.fit.first_step)
      result.fit_range_time = Interval{static_cast<double>(*result.fit.first_step) * *dt,
                                       static_cast<double>(*result.fit.last_step) * *dt};
  }
  return results;
}

LyapunovResult largest_lyapunov(std::span<const double> x, const LyapunovOptions& options,
                                const LyapunovFitOptions& fit, std::optional<double> dt) {
  return std::move(largest_lyapunov_runs(x, std::vector<LyapunovOptions>{options}, fit, dt).front());
}

namespace {

std::string verdict(const char* name, const LyapunovFit& fit) {
  std::ostringstream s;
  s << name << " ";
  if (fit.lambda)
    s << "gives " << format_number(*fit.lambda, Precision::title) << " per sample (steps " << *fit.first_step << ".."
      << *fit.last_step << ")";
  else
    s << "has " << to_string(fit.status);
  return s.str();
}

void withdraw(LyapunovFit& fit, const std::string& why, LyapunovStatus status = LyapunovStatus::unconfirmed) {
  fit.status = status;
  fit.explanation = why + " (the estimate alone: " + fit.explanation + ")";
  fit.lambda.reset();
  fit.lambda_interval.reset();
  fit.first_step.reset();
  fit.last_step.reset();
  fit.lambda_by_curve.clear();
}

void require_cross_check_tolerance(double tolerance) {
  if (!(std::isfinite(tolerance) && tolerance > 0.0))
    refuse("Lyapunov cross-check: the tolerance must be positive and finite (got " + detail::format_number(tolerance) + ")");
}

// Two exponents agree when they differ by at most `tolerance` times their mean.
bool agree(double a, double b, double tolerance) { return std::abs(a - b) <= tolerance * 0.5 * (a + b); }

// The answers of two estimators of one series checked against each other: an answer the other does
// not share (no value, or more than the tolerance apart) is rough. The intervals stay each
// estimator's own; combine_lyapunov spans both.
void check_estimates(LyapunovFit& rosenstein, LyapunovFit& kantz, double tolerance) {
  Estimate& a = rosenstein.estimate;
  Estimate& b = kantz.estimate;
  if (!a.value && !b.value) return;
  if (a.value && b.value) {
    const double va = *a.value, vb = *b.value;
    if (agree(va, vb, tolerance)) return;
    const std::string why = "Rosenstein gives " + format_number(va, Precision::title) + " and Kantz " +
                            format_number(vb, Precision::title) + " per sample, more than " +
                            format_number(tolerance * 100, Precision::title) + "% apart";
    a.downgrade(why);
    b.downgrade(why);
    return;
  }
  (a.value ? a : b).downgrade(std::string(a.value ? "Kantz" : "Rosenstein") + " finds no value (" +
                              to_string((a.value ? kantz : rosenstein).status) + ")");
}

// An answer checked against the local-map exponent, the independent estimate: rough beside maps
// that find the data not deterministic or not diverging, or whose value (consistent) or base
// estimate (inconsistent) lies more than the tolerance away.
void check_estimate(Estimate& e, const LocalMapResult& maps, double tolerance) {
  if (!e.value) return;
  const std::string name = "the local linear maps ";
  switch (maps.status) {
    case LocalMapStatus::not_deterministic:
      e.downgrade(name + "leave " + format_number(maps.base.median_residual * 100, Precision::title) +
                  "% of the neighbourhoods' image spread unexplained: not deterministic at the neighbours' scale, "
                  "where noise slows the divergence");
      return;
    case LocalMapStatus::not_positive:
      e.downgrade(name + "find no exponential divergence at the neighbourhoods' scale");
      return;
    case LocalMapStatus::consistent:
      if (maps.lambda && !agree(*e.value, *maps.lambda, tolerance))
        e.downgrade(name + "give " + format_number(*maps.lambda, Precision::title) + " per sample, more than " +
                    format_number(tolerance * 100, Precision::title) + "% away");
      return;
    case LocalMapStatus::inconsistent:
      // The variants spread, so their base estimate is only a rough third opinion: an answer it
      // puts more than the tolerance away is rough (Ueda x at N = 10^5: Rosenstein and Kantz agree
      // on 0.078, 24% below lambda_1, where the maps' base reads 0.095).
      if (maps.base.maps > 0 && !agree(*e.value, maps.base.lambda, tolerance))
        e.downgrade("the local linear maps' base estimate (their variants disagree) gives " +
                    format_number(maps.base.lambda, Precision::title) + " per sample, more than " +
                    format_number(tolerance * 100, Precision::title) + "% away");
      return;
  }
}

// A result whose fit was withdrawn loses its per-time values too.
void withdraw_per_time(LyapunovResult& r) {
  if (r.fit.lambda) return;
  r.lambda_per_time.reset();
  r.lambda_per_time_interval.reset();
  r.fit_range_time.reset();
}

}  // namespace

void cross_check(LyapunovFit& rosenstein, LyapunovFit& kantz, double tolerance) {
  require_cross_check_tolerance(tolerance);
  check_estimates(rosenstein, kantz, tolerance);
  const bool r = rosenstein.status == LyapunovStatus::linear_region, k = kantz.status == LyapunovStatus::linear_region;
  if (!r && !k) return;
  if (r && k) {
    if (agree(*rosenstein.lambda, *kantz.lambda, tolerance)) return;
  }
  std::ostringstream why;
  why << "the two estimators disagree: " << verdict("Rosenstein", rosenstein) << ", " << verdict("Kantz", kantz);
  if (r && k) why << ", more than " << tolerance * 100 << "% apart";
  why << "; a slope only one estimator supports is not trusted";
  if (r) withdraw(rosenstein, why.str());
  if (k) withdraw(kantz, why.str());
}

void cross_check(LyapunovResult& rosenstein, LyapunovResult& kantz, double tolerance) {
  cross_check(rosenstein.fit, kantz.fit, tolerance);
  withdraw_per_time(rosenstein);
  withdraw_per_time(kantz);
}

void cross_check(LyapunovFit& fit, LyapunovMethod method, const LocalMapResult& local_maps, double tolerance) {
  require_cross_check_tolerance(tolerance);
  check_estimate(fit.estimate, local_maps, tolerance);
  if (fit.status != LyapunovStatus::linear_region) return;
  const std::string name = method == LyapunovMethod::rosenstein ? "Rosenstein" : "Kantz";
  std::ostringstream why;
  if (local_maps.status == LocalMapStatus::not_deterministic) {
    // The nearest neighbours the divergence curves start from are the neighbourhoods the maps fit.
    why << "the local linear maps leave " << format_number(local_maps.base.median_residual * 100, Precision::title)
        << "% of their neighbourhoods' image spread unexplained (not_deterministic): at the scale of the nearest "
        << "neighbours the data are not deterministic (measurement noise), and there the divergence curve "
        << "rises more slowly than lambda_1 before it bends into saturation (" << verdict(name.c_str(), fit)
        << "; Henon x with 1% noise reads 15% low by both Rosenstein and Kantz, which agree with each other)";
    withdraw(fit, why.str());
    return;
  }
  if (local_maps.status != LocalMapStatus::consistent || !local_maps.lambda) {
    // Rosenstein and Kantz can agree with each other and both be wrong (both start from the same
    // nearest neighbours): Sprott F x with 1% noise, m = 6, reads 15% low by both, halves agreeing,
    // beside maps whose variants disagree (docs/notes/zoo-notes.md, section 4). So a slope needs the
    // independent estimate's positive confirmation, not only the absence of a contradiction.
    why << "the local linear maps do not confirm this slope: they are " << to_string(local_maps.status)
        << (local_maps.status == LocalMapStatus::not_positive ? " (no exponential divergence at the neighbourhoods' scale)"
                                                              : " (their variants disagree, so they give no value)")
        << "; a divergence-curve slope is trusted only where the local-map exponent, consistent over its variants, "
        << "agrees with it (" << verdict(name.c_str(), fit) << ")";
    withdraw(fit, why.str());
    return;
  }
  if (agree(*fit.lambda, *local_maps.lambda, tolerance)) return;
  why << "the local-map exponent contradicts this slope: " << verdict(name.c_str(), fit) << ", local maps give "
      << format_number(*local_maps.lambda, Precision::title) << " per sample (consistent over their variants), more than "
      << format_number(tolerance * 100, Precision::title)
      << "% apart; a divergence-curve slope that the local maps contradict is not trusted";
  withdraw(fit, why.str());
}

void cross_check(LyapunovResult& result, const LocalMapResult& local_maps, double tolerance) {
  cross_check(result.fit, result.options.method, local_maps, tolerance);
  withdraw_per_time(result);
}

void cross_check_without_local_maps(LyapunovFit& fit, LyapunovMethod method, const std::string& refusal) {
  if (fit.estimate.value) fit.estimate.downgrade("the local linear maps could not confirm it: " + refusal);
  if (fit.status != LyapunovStatus::linear_region) return;
  withdraw(fit, std::string("no local-map exponent to confirm this slope (") +
                    (method == LyapunovMethod::rosenstein ? "Rosenstein" : "Kantz") +
                    "): the local linear maps were not run: " + refusal +
                    "; a divergence-curve slope is trusted only where the local maps confirm it");
}

void cross_check_without_local_maps(LyapunovResult& result, const std::string& refusal) {
  cross_check_without_local_maps(result.fit, result.options.method, refusal);
  withdraw_per_time(result);
}

void require_reproduced_by_halves(LyapunovFit& full, const LyapunovFit& first, const LyapunovFit& second,
                                  double tolerance) {
  require_cross_check_tolerance(tolerance);
  if (full.estimate.value) {
    // An answer that neither half gives, or that a half puts more than twice the tolerance away, is
    // rough. A half is a record of half the length, whose value scatters more than the whole's: it
    // checks the answer, and does not widen its interval.
    const double value = *full.estimate.value;
    bool some = false, apart = false;
    for (const LyapunovFit* half : {&first, &second})
      if (half->estimate.value) {
        some = true;
        apart = apart || !agree(value, *half->estimate.value, 2 * tolerance);
      }
    if (!some)
      full.estimate.downgrade("neither half of the record gives a value");
    else if (apart)
      full.estimate.downgrade("a half of the record gives a value more than " +
                              format_number(200 * tolerance, Precision::title) + "% away");
  }
  if (full.status != LyapunovStatus::linear_region) return;
  const bool a = first.status == LyapunovStatus::linear_region, b = second.status == LyapunovStatus::linear_region;
  const bool contradicted = (a && !agree(*full.lambda, *first.lambda, tolerance)) ||
                            (b && !agree(*full.lambda, *second.lambda, tolerance));
  if ((a || b) && !contradicted) return;
  std::ostringstream why;
  why << "the halves of the record do not reproduce this slope: " << verdict("the first half", first) << ", "
      << verdict("the second half", second);
  if (contradicted) why << ", more than " << tolerance * 100 << "% from the whole record's";
  why << "; a straight stretch that no part of the record shows on its own is not trusted (a longer record may "
      << "settle it)";
  withdraw(full, why.str(), LyapunovStatus::not_reproduced);
}

void require_reproduced_by_halves(LyapunovResult& full, const LyapunovResult& first, const LyapunovResult& second,
                                  double tolerance) {
  require_reproduced_by_halves(full.fit, first.fit, second.fit, tolerance);
  withdraw_per_time(full);
}

LyapunovResult largest_lyapunov_rosenstein(std::span<const double> x, LyapunovOptions options,
                                           const LyapunovFitOptions& fit, std::optional<double> dt) {
  options.method = LyapunovMethod::rosenstein;
  return largest_lyapunov(x, options, fit, dt);
}

LyapunovResult largest_lyapunov_kantz(std::span<const double> x, LyapunovOptions options,
                                      const LyapunovFitOptions& fit, std::optional<double> dt) {
  options.method = LyapunovMethod::kantz;
  return largest_lyapunov(x, options, fit, dt);
}

}  // namespace chaos
