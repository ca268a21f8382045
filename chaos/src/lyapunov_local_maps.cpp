#include "chaos/lyapunov_local_maps.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <sstream>
#include <utility>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/format.hpp"
#include "chaos/neighbors.hpp"
#include "chaos/series.hpp"
#include "chaos/detail/parallel.hpp"
#include "lyapunov_local_maps_detail.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

// The chain's maps are fitted in rounds of this many (in parallel, each map on its own), then the
// tangent vector goes through them in order on one thread: the fits do not depend on the thread
// count and the product is sequential, so the result is the same for any thread count. A round
// bounds the memory of the stored maps (m^2 doubles each, per fit choice); its size does not
// change the result.
constexpr std::size_t round_maps = 16384;

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

struct FittedMap {
  Matrix map;            // m x m
  double residual = 0.0;
  std::size_t rank = 0;
};

// The least-squares fit of a chain point's neighbourhood: its neighbours X_j and their images
// X_{j+s} (both read from `e`, which holds the s further points), centred on their means, and the
// singular value decomposition of the centred neighbours. One fit serves every cutoff.
struct Neighbourhood {
  Matrix a, b;
  Eigen::JacobiSVD<Matrix> svd;
  void fit(const DelayEmbedding& e, std::span<const Neighbor> neighbours, std::size_t s) {
    const std::size_t m = e.dimension(), k = neighbours.size();
    a.resize(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(m));
    b.resize(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(m));
    for (std::size_t r = 0; r < k; ++r) {
      const std::size_t j = neighbours[r].index;
      for (std::size_t c = 0; c < m; ++c) {
        a(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = e(j, c);
        b(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = e(j + s, c);
      }
    }
    // Affine fit: centre both clouds on their means, then fit the linear part.
    a.rowwise() -= a.colwise().mean();
    b.rowwise() -= b.colwise().mean();
    svd.compute(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  }
};

// The map of a fitted neighbourhood over its singular directions above `cutoff` times the largest.
void map_from(const Neighbourhood& n, std::size_t m, double cutoff, FittedMap& out) {
  const Vector& sigma = n.svd.singularValues();
  out.map.setZero(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
  out.rank = 0;
  if (sigma.size() == 0 || !(sigma(0) > 0.0)) {
    out.residual = 1.0;
    return;
  }
  // M^T = V_r S_r^-1 U_r^T B over the kept directions; M maps a displacement to its image.
  Matrix mt = Matrix::Zero(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
  for (Eigen::Index d = 0; d < sigma.size(); ++d) {
    if (!(sigma(d) >= cutoff * sigma(0))) break;  // descending
    mt += n.svd.matrixV().col(d) * ((n.svd.matrixU().col(d).transpose() * n.b) / sigma(d));
    ++out.rank;
  }
  out.map = mt.transpose();
  const double spread = n.b.squaredNorm();
  out.residual = spread > 0.0 ? std::sqrt((n.b - n.a * mt).squaredNorm() / spread) : 0.0;
}

}  // namespace

const char* to_string(LocalMapStatus status) noexcept {
  switch (status) {
    case LocalMapStatus::consistent: return "consistent";
    case LocalMapStatus::inconsistent: return "inconsistent";
    case LocalMapStatus::not_deterministic: return "not_deterministic";
    case LocalMapStatus::not_positive: return "not_positive";
  }
  return "unknown";
}

void LocalMapOptions::validate() const {
  if (dimension < 1) refuse_parameter("Lyapunov exponent (local maps): embedding dimension m must be at least 1 (got m = 0)");
  if (delay < 1) refuse_parameter("Lyapunov exponent (local maps): delay tau must be at least 1 sample (got tau = 0)");
  if (threads < 1) refuse_parameter("Lyapunov exponent (local maps): threads must be at least 1 (got 0)");
  if (neighbours != 0 && neighbours < detail::add_sat(dimension, 1))
    refuse_parameter("Lyapunov exponent (local maps): an affine map in m = " + std::to_string(dimension) +
           " dimensions needs at least m + 1 = " + std::to_string(dimension + 1) + " neighbours (got k = " +
           std::to_string(neighbours) + ")");
  if (!(max_residual > 0.0 && max_residual <= 1.0))
    refuse_parameter("Lyapunov exponent (local maps): the residual threshold must lie in (0, 1] (got " +
           detail::format_number(max_residual) + ")");
  if (!(cutoff > 0.0 && cutoff < 1.0))
    refuse_parameter("Lyapunov exponent (local maps): the singular-value cutoff must lie in (0, 1) (got " +
           detail::format_number(cutoff) + ")");
}

namespace {

// What a run may change without changing its chain (m, tau, w, s) or its neighbour search.
struct FitChoice {
  std::size_t neighbours;  // k
  double cutoff;
  double max_residual;
};

// Refuses what local_map_exponent refuses (options, series, length); returns the step s and k.
std::pair<std::size_t, std::size_t> checked_step_and_neighbours(std::span<const double> x,
                                                               const LocalMapOptions& options) {
  options.validate();
  const std::string what = "largest Lyapunov exponent (local maps)";
  require_finite(x, what);
  require_not_constant(x, what);
  const std::size_t m = options.dimension, tau = options.delay, w = options.theiler;
  const std::size_t s = options.step != 0 ? options.step : std::max<std::size_t>(1, (tau + 1) / 2);
  const std::size_t k = options.neighbours != 0 ? options.neighbours : detail::mul_sat(5, m);
  const std::size_t span = detail::mul_sat(m - 1, tau);
  const std::size_t minimum =
      detail::add_sat(detail::add_sat(span, s), detail::add_sat(detail::mul_sat(2, w), detail::add_sat(k, 2)));
  require_length(x, minimum, what,
                 "N >= (m-1) tau + s + 2 w + k + 2 with m = " + std::to_string(m) + ", tau = " + std::to_string(tau) +
                     ", s = " + std::to_string(s) + ", w = " + std::to_string(w) + ", k = " + std::to_string(k) +
                     ", so that every point of the chain has k neighbours outside its Theiler window");
  return {s, k};
}

// The tangent vector carried through one run's maps in chain order, and what the run reports.
class TangentWalk {
 public:
  TangentWalk(std::size_t m, std::size_t chain, double max_residual)
      : v_(Vector::Constant(static_cast<Eigen::Index>(m), 1.0 / std::sqrt(static_cast<double>(m)))),
        max_residual_(max_residual) {
    logs_.reserve(chain);
    residuals_.reserve(chain);
  }

  void take(const FittedMap& f) {
    residuals_.push_back(f.residual);
    rank_sum_ += static_cast<double>(f.rank);
    if (f.rank == 0) {  // a neighbourhood with no extent: nothing to learn, the vector goes on
      ++restarts_;
      return;
    }
    const Vector image = f.map * v_;
    const double growth = image.norm();
    if (!(growth > 0.0) || !std::isfinite(growth)) {
      // The vector lies outside the directions this map was fitted on (the previous image left
      // the local tangent space). It restarts along the map's strongest direction; this step is
      // not averaged.
      ++restarts_;
      const Eigen::JacobiSVD<Matrix> svd(f.map, Eigen::ComputeFullV);
      v_ = svd.matrixV().col(0);
      return;
    }
    v_ = image / growth;
    if (f.residual > max_residual_) {
      // The linear model does not describe this neighbourhood (a fold or a discontinuity inside
      // it: on the cat map, neighbourhoods across the wrap stretched by their split image and
      // read 16% high). The vector goes on in the map's direction; its growth is not averaged.
      ++poor_fits_;
      return;
    }
    logs_.push_back(std::log(growth));
  }

  LocalMapEstimate finish(std::size_t s, std::size_t k) {
    LocalMapEstimate out;
    out.step = s;
    out.neighbours = k;
    out.restarts = restarts_;
    out.poor_fits = poor_fits_;
    out.maps = logs_.size();  // 0 when no map fitted well: lambda stays 0 and the checks refuse it
    const auto mean = [](auto begin, auto end) {
      double sum = 0.0;
      for (auto it = begin; it != end; ++it) sum += *it;
      return end == begin ? 0.0 : sum / static_cast<double>(end - begin);
    };
    const double per_step = 1.0 / static_cast<double>(s);
    out.lambda = mean(logs_.begin(), logs_.end()) * per_step;
    const auto half = logs_.begin() + static_cast<std::ptrdiff_t>(logs_.size() / 2);
    out.first_half = mean(logs_.begin(), half) * per_step;
    out.second_half = mean(half, logs_.end()) * per_step;
    std::sort(residuals_.begin(), residuals_.end());
    out.median_residual = residuals_[residuals_.size() / 2];
    out.residual_q90 = residuals_[residuals_.size() * 9 / 10];
    out.residual_q99 = residuals_[residuals_.size() * 99 / 100];
    out.mean_rank = rank_sum_ / static_cast<double>(residuals_.size());
    return out;
  }

 private:
  Vector v_;
  double max_residual_;
  std::vector<double> logs_, residuals_;
  double rank_sum_ = 0.0;
  std::size_t restarts_ = 0, poor_fits_ = 0;
};

// One chain of a series: options' m, tau, w and norm, step s. The rescaled series, the embedding
// of the points whose image exists and its kd-tree, built once for every run on the chain.
struct Chain {
  std::size_t m, s;
  NeighborQuery query;
  std::vector<double> y;
  std::size_t points;
  DelayEmbedding candidates, images;
  KdTree tree;
  std::size_t length;  // chain points 0, s, 2s, ... < points, at most options.max_maps

  Chain(std::span<const double> x, const LocalMapOptions& options, std::size_t step)
      : m(options.dimension), s(step), query{options.theiler, true},
        // The exact power-of-two rescaling keeps the fits' sums of squares finite for any
        // magnitude; the maps do not depend on the scale.
        y(detail::scaled_by_power_of_two(x, detail::scale_exponent(x))),
        points(x.size() - detail::mul_sat(m - 1, options.delay) - s),  // points whose image X_{j+s} exists
        candidates(y, m, options.delay, points),
        images(y, m, options.delay),  // the same coordinates, with the s further points
        tree(candidates, options.norm, 8, options.threads),
        length(options.max_maps != 0 ? std::min((points + s - 1) / s, options.max_maps) : (points + s - 1) / s) {}
  Chain(const Chain&) = delete;  // the embeddings view y
  Chain& operator=(const Chain&) = delete;
};

// Runs on one chain that differ only in their fit choices, each as local_map_exponent would make
// it alone. The neighbours of each chain point are searched once, for the largest k: the k nearest
// are the first k of the k_max nearest (both are the start of one order, by distance and then by
// index), so every run fits exactly the neighbours its own search would find. The neighbourhood of
// each k is fitted (centred, decomposed) once for all the runs with that k, and each run's map is
// formed from that decomposition with its own cutoff, as a run alone forms it; runs with the same
// k and cutoff share the map itself. So the estimates equal separate runs bit for bit. The
// variants of largest_lyapunov_local_maps that keep the chain (k, cutoff, residual limit) cost one
// search and one decomposition per neighbourhood size. The choices must have passed
// checked_step_and_neighbours.
std::vector<LocalMapEstimate> estimates_on_chain(const Chain& chain, std::span<const FitChoice> choices,
                                                 std::size_t threads) {
  const std::size_t m = chain.m, s = chain.s;
  std::size_t k_max = 0;
  for (const FitChoice& c : choices) k_max = std::max(k_max, c.neighbours);
  // For each choice: the first choice with its k (whose neighbourhood fit it uses), and the first
  // with its k and cutoff (whose map it copies), indices into `choices`.
  const std::size_t runs = choices.size();
  std::vector<std::size_t> fit_of(runs), map_of(runs);
  for (std::size_t c = 0; c < runs; ++c) {
    fit_of[c] = map_of[c] = c;
    for (std::size_t d = 0; d < c; ++d)
      if (choices[d].neighbours == choices[c].neighbours) {
        fit_of[c] = fit_of[d];
        if (choices[d].cutoff == choices[c].cutoff) {
          map_of[c] = map_of[d];
          break;
        }
      }
  }

  const std::size_t round = std::max<std::size_t>(1, round_maps / runs);
  std::vector<TangentWalk> walks;
  walks.reserve(runs);
  for (const FitChoice& c : choices) walks.emplace_back(m, chain.length, c.max_residual);
  std::vector<FittedMap> fitted(std::min(chain.length, round) * runs);  // [point in round * runs + run]
  struct Workspace {  // one per worker
    std::vector<Neighbor> found;
    std::vector<Neighbourhood> fits;  // one per choice that fits its own neighbourhood
  };
  std::vector<Workspace> workspace(detail::worker_count(threads, std::min(chain.length, round)));
  for (Workspace& ws : workspace) ws.fits.resize(runs);

  // A round's neighbourhoods are searched in the tree's leaf order (as all_nearest does, neighbors.hpp),
  // each written to its place in the chain, so the maps and their walk are those of chain order.
  std::vector<std::size_t> leaf_position(chain.points);
  {
    const auto leaves = chain.tree.leaf_order();
    for (std::size_t p = 0; p < leaves.size(); ++p) leaf_position[leaves[p]] = p;
  }
  std::vector<std::size_t> search_order;
  for (std::size_t first = 0; first < chain.length; first += round) {
    const std::size_t count = std::min(round, chain.length - first);
    search_order.resize(count);
    std::iota(search_order.begin(), search_order.end(), std::size_t{0});
    std::sort(search_order.begin(), search_order.end(), [&](std::size_t a, std::size_t b) {
      return leaf_position[(first + a) * s] < leaf_position[(first + b) * s];
    });
    detail::parallel_tasks(threads, count, [&](std::size_t task, std::size_t worker) {
      Workspace& ws = workspace[worker];
      const std::size_t r = search_order[task];
      const std::size_t i = (first + r) * s;
      chain.tree.k_nearest(i, k_max, ws.found, chain.query);
      for (std::size_t c = 0; c < runs; ++c) {
        const std::size_t k = std::min(choices[c].neighbours, ws.found.size());
        FittedMap& f = fitted[r * runs + c];
        if (k < m + 1) {
          f.map.setZero(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
          f.rank = 0;
          f.residual = 1.0;
          continue;
        }
        if (map_of[c] != c) {
          f = fitted[r * runs + map_of[c]];
          continue;
        }
        if (fit_of[c] == c) ws.fits[c].fit(chain.images, std::span<const Neighbor>(ws.found.data(), k), s);
        map_from(ws.fits[fit_of[c]], m, choices[c].cutoff, f);
      }
    });

    for (std::size_t c = 0; c < runs; ++c)
      for (std::size_t r = 0; r < count; ++r) walks[c].take(fitted[r * runs + c]);
  }
  std::vector<LocalMapEstimate> out;
  out.reserve(runs);
  for (std::size_t c = 0; c < runs; ++c) out.push_back(walks[c].finish(s, choices[c].neighbours));
  return out;
}

}  // namespace

LocalMapEstimate local_map_exponent(std::span<const double> x, const LocalMapOptions& options) {
  const auto [s, k] = checked_step_and_neighbours(x, options);
  const FitChoice choice{k, options.cutoff, options.max_residual};
  const Chain chain(x, options, s);
  return estimates_on_chain(chain, std::span<const FitChoice>(&choice, 1), options.threads).front();
}

LocalMapResult largest_lyapunov_local_maps(std::span<const double> x, const LocalMapOptions& options,
                                           std::optional<double> dt, double tolerance) {
  return detail::local_maps_run(x, options, dt, tolerance, nullptr, nullptr);
}

namespace detail {

LocalMapResult local_maps_run(std::span<const double> x, const LocalMapOptions& options, std::optional<double> dt,
                              double tolerance, const LocalMapEstimate* known_base,
                              std::optional<LocalMapEstimate>* next_dimension_base) {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    refuse_parameter("Lyapunov exponent (local maps): the agreement tolerance must be positive and finite (got " +
           detail::format_number(tolerance) + ")");
  if (dt && !(std::isfinite(*dt) && *dt > 0.0))
    refuse_parameter("Lyapunov exponent (local maps): the sampling interval must be positive and finite (got " +
           detail::format_number(*dt) + ")");
  LocalMapResult result;
  result.dt = dt;
  result.tolerance = tolerance;
  const double max_residual = options.max_residual;
  const std::size_t m = options.dimension;
  // The base and the variants that keep its chain share one embedding and kd-tree.
  const auto [step, base_k] = checked_step_and_neighbours(x, options);
  std::optional<Chain> chain;
  if (known_base) {
    result.base = *known_base;
  } else {
    chain.emplace(x, options, step);
    const FitChoice choice{base_k, options.cutoff, options.max_residual};
    result.base = estimates_on_chain(*chain, std::span<const FitChoice>(&choice, 1), options.threads).front();
  }
  const std::size_t k = result.base.neighbours;
  result.variants.push_back({"base", m, options.delay, k, result.base.lambda});
  // The status below reads the variants only when the base passes its own tests (its maps explain
  // the data, its exponent is positive); otherwise they would be computed for nothing (on a map at
  // m = 8, ten times the base's cost).
  const bool deterministic = !(result.base.median_residual > max_residual || result.base.maps == 0);
  const bool positive = result.base.lambda > 0.0;

  // The variants use the base's step, so they estimate the same quantity. A variant the series is
  // too short for (one more dimension, more neighbours) is a variant that cannot confirm the base.
  // Those that keep the base's chain are computed together, on one neighbour search (see
  // estimates_on_one_chain), the others one by one; the list keeps the order below.
  struct Planned {
    const char* name;
    LocalMapOptions options;
    bool computable = false;
    bool same_chain = false;
    double lambda = 0.0;
  };
  std::vector<Planned> planned;
  std::string missing;
  const auto plan = [&](const char* name, std::size_t dimension, std::size_t neighbours, double cutoff,
                        double residual_limit, std::size_t delay) {
    Planned p{name, options};
    p.options.step = result.base.step;
    p.options.dimension = dimension;
    p.options.delay = delay;
    p.options.neighbours = neighbours;
    p.options.cutoff = cutoff;
    p.options.max_residual = residual_limit;
    p.same_chain = dimension == m && delay == options.delay;
    try {
      checked_step_and_neighbours(x, p.options);
      p.computable = true;
    } catch (const InvalidInput& e) {
      if (missing.empty()) missing = std::string("the variant '") + name + "' could not be computed: " + e.what();
    }
    planned.push_back(std::move(p));
  };
  const double c = options.cutoff;
  const double r = max_residual;
  const std::size_t tau = options.delay;
  if (deterministic && positive) {
    plan("k = 3m", m, 3 * m, c, r, tau);  // 3m >= m + 1; the base refused any m too large for the series
    plan("k = 8m", m, 8 * m, c, r, tau);
    plan("m + 1", m + 1, 5 * (m + 1), c, r, tau);
    plan("cutoff / 2", m, k, c / 2.0, r, tau);
    plan("cutoff x 2", m, k, std::min(2.0 * c, (1.0 + c) / 2.0), r, tau);
    // Which maps are averaged is a choice too. On Mackey-Glass (tau = 30, m = 6) a fifth of the maps
    // were poor fits, every other variant agreed within 3%, and the value read 17% above lambda_1 from
    // the equations; averaging the maps up to twice the residual limit moves it by 12%.
    plan("residual limit x 2", m, k, c, std::min(2.0 * r, 1.0), tau);
    // The delay is the user's choice, and lambda_1 does not depend on it: the delay vectors of one
    // system at two delays are smooth changes of coordinates of each other. The fitted maps do depend
    // on it. At tau = 2, the generalised Henon map's delay vectors need x_{j+1} = (a - x_{j+2}^2 -
    // x_{j+4}) / b with b = 0.1 for their one-step map, and every other variant agreed on 8 times
    // lambda_1; Rucklidge at twice its mutual-information delay read 22% high with all of them within
    // 4% (docs/reference/lyapunov-maps.md). At tau = 1 (maps, where it is the natural delay) there is no smaller
    // one, and no delay variant is run.
    if (tau >= 2) {
      const std::size_t shift = std::max<std::size_t>(1, (tau + 2) / 4);  // round(tau / 4), at least 1
      plan("delay - tau/4", m, k, c, r, tau - shift);
      plan("delay + tau/4", m, k, c, r, tau + shift);
    }
  }
  std::vector<FitChoice> shared;
  for (const Planned& p : planned)
    if (p.computable && p.same_chain) shared.push_back({p.options.neighbours, p.options.cutoff, p.options.max_residual});
  if (!shared.empty()) {
    if (!chain) chain.emplace(x, options, result.base.step);
    const std::vector<LocalMapEstimate> estimates = estimates_on_chain(*chain, shared, options.threads);
    std::size_t next = 0;
    for (Planned& p : planned)
      if (p.computable && p.same_chain) p.lambda = estimates[next++].lambda;
  }
  chain.reset();
  for (Planned& p : planned)
    if (p.computable && !p.same_chain) {
      const LocalMapEstimate e = local_map_exponent(x, p.options);
      p.lambda = e.lambda;
      // The m + 1 variant is, to the last bit, the base of a run at m + 1 with the same step, cutoff
      // and residual limit and the default k = 5 (m + 1): local_maps_with_next_dimension reuses it.
      if (next_dimension_base && p.options.dimension == m + 1 && p.options.delay == tau &&
          (options.neighbours == 0 || options.neighbours == p.options.neighbours))
        *next_dimension_base = e;
    }
  for (const Planned& p : planned)
    if (p.computable) result.variants.push_back({p.name, p.options.dimension, p.options.delay, p.options.neighbours, p.lambda});
  result.variants.push_back({"first half", m, tau, k, result.base.first_half});
  result.variants.push_back({"second half", m, tau, k, result.base.second_half});

  const double base = result.base.lambda;
  double low = base, high = base;
  const LocalMapVariant* worst = &result.variants.front();
  for (const auto& v : result.variants) {
    low = std::min(low, v.lambda);
    high = std::max(high, v.lambda);
    if (std::abs(v.lambda - base) > std::abs(worst->lambda - base)) worst = &v;
  }
  std::ostringstream why;
  const auto t = [](double v) { return format_number(v, Precision::title); };
  if (!deterministic) {
    result.status = LocalMapStatus::not_deterministic;
    why << "the local linear maps leave a median " << t(result.base.median_residual * 100.0)
        << "% of the neighbourhoods' image spread unexplained (at most " << t(max_residual * 100.0)
        << "% allowed): at this scale the series does not behave as a deterministic map";
  } else if (!positive) {
    result.status = LocalMapStatus::not_positive;
    why << "the mean log growth of the tangent vector is " << t(base)
        << " per sample, not positive: no exponential divergence";
  } else if (!missing.empty()) {
    result.status = LocalMapStatus::inconsistent;
    why << missing;
  } else if (std::abs(worst->lambda - base) > tolerance * base) {
    result.status = LocalMapStatus::inconsistent;
    why << "the variant '" << worst->name << "' gives " << t(worst->lambda) << " per sample against the base's " << t(base)
        << " (" << t((worst->lambda / base - 1.0) * 100.0) << "%; at most " << t(tolerance * 100.0)
        << "% allowed): the estimate depends on the estimator's choices";
  } else {
    result.status = LocalMapStatus::consistent;
    result.lambda = base;
    result.lambda_interval = Interval{low, high};
    why << "all " << result.variants.size() - 1
        << " variants (neighbourhood size, m + 1, singular-value cutoff, residual limit, "
        << (tau >= 2 ? "delay +- tau/4, " : "") << "halves of the chain) lie within "
        << t(tolerance * 100.0) << "% of the base estimate, and the maps explain the neighbourhoods' images";
    if (dt) {
      result.lambda_per_time = base / *dt;
      result.lambda_per_time_interval = Interval{low / *dt, high / *dt};
    }
  }
  result.explanation = why.str();
  return result;
}

}  // namespace detail

}  // namespace chaos
