// Divergence curves of a delay embedding (Rosenstein; Kantz), and runs of both methods that share one
// embedding, kd-tree and reference order. The fit is lyapunov_fit.cpp, the checks lyapunov_checks.cpp.

#include "chaos/lyapunov.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <span>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/neighbors.hpp"
#include "chaos/series.hpp"
#include "chaos/detail/parallel.hpp"
#include "lyapunov_ties.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

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
  std::vector<std::size_t> neighbourhood, kept;
  std::vector<double> mean, kept_weight;
  std::vector<std::pair<double, std::size_t>> by_distance;
  lyapunov_detail::Thinned thinned;
  lyapunov_detail::ClassNeighbourhood classes;
};

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
  if (dimension < 1) refuse_parameter("Lyapunov exponent: embedding dimension m must be at least 1 (got m = 0)");
  if (delay < 1) refuse_parameter("Lyapunov exponent: delay tau must be at least 1 sample (got tau = 0)");
  if (steps < 1) refuse_parameter("Lyapunov exponent: the divergence must be followed for at least 1 step (got steps = 0)");
  if (threads < 1) refuse_parameter("Lyapunov exponent: threads must be at least 1 (got 0)");
  if (radius && !(std::isfinite(*radius) && *radius > 0.0))
    refuse_parameter("Lyapunov exponent (Kantz): the neighbourhood radius eps must be positive and finite (got eps = " +
           detail::format_number(*radius) + ")");
  if (min_neighbours < 1) refuse_parameter("Lyapunov exponent (Kantz): min_neighbours must be at least 1 (got 0)");
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
  lyapunov_detail::DelayVectors vectors;

  Embedded(std::span<const double> x, const LyapunovOptions& options)
      // An exact power-of-two rescaling keeps Euclidean sums of squares finite for any magnitude;
      // ln d then shifts by exponent * ln 2, added back at the end.
      : exponent(detail::scale_exponent(x)),
        y(detail::scaled_by_power_of_two(x, exponent)),
        log_scale(exponent * std::log(2.0)),
        points(x.size() - detail::mul_sat(options.dimension - 1, options.delay) - options.steps),
        candidates(y, options.dimension, options.delay, points),
        tree(candidates, options.norm, 8, options.threads),
        vectors{y, options.dimension, options.delay, options.norm} {
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
    // Neighbour counts at radius r on at most 1000 evenly spaced reference points.
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
    double eps = 0.0;
    std::optional<Census> at_eps;
    if (options.radius) {
      eps = std::ldexp(*options.radius, -exponent);
    } else {
      // range / 1000, then adjusted on the census' reference points: doubled while
      // fewer than half of them have min_neighbours neighbours (a curve from a few rare close
      // returns is not representative of the attractor), else halved while they have more than
      // default_neighbours on average and would keep that coverage (the cost grows with the
      // neighbourhood, the precision hardly does: the average over reference points dominates;
      // and a smaller eps leaves more room for growth). Powers of two keep eps exactly
      // range / 1000 * 2^h.
      const auto [lo, hi] = std::minmax_element(y.begin(), y.end());
      eps = (*hi - *lo) / 1000.0;
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
      at_eps = c;
    }
    curve.radius = std::ldexp(eps, exponent);
    const lyapunov_detail::DelayVectors& vectors = e.vectors;
    // On quantised data, the points grouped by their delay vector, so that a neighbourhood is a few
    // whole groups instead of a list of most of the points (lyapunov_ties.hpp). Only where scanning
    // the groups costs less than listing: a reference point meets every group once, and a listed
    // neighbourhood costs its members, so at most 4 times the census' mean neighbourhood (and an
    // average of 4 points a group); untied data stop the grouping after that many probes.
    if (!at_eps) at_eps = census(eps);
    const auto max_classes = static_cast<std::size_t>(std::min(static_cast<double>(points / 4), 4.0 * at_eps->mean));
    const std::optional<lyapunov_detail::IdenticalVectors> identical =
        lyapunov_detail::identical_vectors(vectors, points, max_classes);
    const bool by_class = identical.has_value();
    total = for_each_reference(references, steps, options.threads, options.progress, [&](std::size_t i, Partial& p, Scratch& s) {
      // The neighbourhood: listed by the tree, or on quantised data as whole classes of one delay
      // vector (the same members, counted instead of listed).
      std::size_t found = 0;
      if (by_class) {
        lyapunov_detail::class_neighbourhood(*identical, vectors, i, eps, w, s.classes);
        found = s.classes.found;
      } else {
        tree.within(i, eps, s.neighbourhood, query);
        found = s.neighbourhood.size();
      }
      if (found < options.min_neighbours || found == 0) return;
      ++p.used;
      p.neighbours += static_cast<double>(found);
      // Tie groups larger than max_tied_neighbours are represented by that many members, weighted
      // (lyapunov_ties.hpp); the rest of the neighbourhood is followed member by member.
      const std::size_t tie_cap = options.max_tied_neighbours;
      const bool tied = by_class ? lyapunov_detail::thin_classes(*identical, s.classes, tie_cap, s.thinned)
                                 : lyapunov_detail::thin_ties(vectors, i, s.neighbourhood, tie_cap, s.by_distance,
                                                              s.thinned);
      if (!tied && by_class) lyapunov_detail::list_members(*identical, s.classes, s.neighbourhood);
      if (tied) ++p.tied;
      std::span<const std::size_t> members = tied ? std::span<const std::size_t>(s.thinned.index) : s.neighbourhood;
      std::span<const double> weights = tied ? std::span<const double>(s.thinned.weight) : std::span<const double>();
      // What is left above max_neighbours is represented by that many of its members, evenly spaced
      // in time (index order): a mean that does not favour the nearest ones, at a cost bounded per
      // reference point.
      if (options.max_neighbours != 0 && members.size() > options.max_neighbours) {
        const std::size_t size = members.size(), cap = options.max_neighbours;
        s.kept.resize(cap);
        s.kept_weight.resize(weights.empty() ? 0 : cap);
        for (std::size_t r = 0; r < cap; ++r) {
          s.kept[r] = members[r * size / cap];
          if (!weights.empty()) s.kept_weight[r] = weights[r * size / cap];
        }
        members = s.kept;
        if (!weights.empty()) weights = s.kept_weight;
        ++p.capped;
      }
      p.pairs += members.size();
      s.mean.assign(steps + 1, 0.0);
      double size = 0.0;
      if (weights.empty()) {
        size = static_cast<double>(members.size());
        for (const std::size_t j : members) {
          s.pair.compute(y, i, j, m, tau, steps, options.norm);
          for (std::size_t k = 0; k <= steps; ++k) s.mean[k] += s.pair.d[k];
        }
      } else {
        for (std::size_t r = 0; r < members.size(); ++r) {
          size += weights[r];
          s.pair.compute(y, i, members[r], m, tau, steps, options.norm);
          for (std::size_t k = 0; k <= steps; ++k) s.mean[k] += weights[r] * s.pair.d[k];
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
    refuse_parameter("Lyapunov exponent: the sampling interval dt must be positive and finite (got dt = " +
           detail::format_number(*dt) + ")");
  fit.validate();
  if (runs.empty()) return {};
  for (const LyapunovOptions& o : runs) {
    o.validate();
    if (!same_embedding(o, runs.front()))
      refuse_parameter("Lyapunov exponent: runs that share their embeddings need the same m, delay, Theiler window, steps, norm "
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