#include "chaos/neighbors.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <type_traits>

#include "chaos/detail/parallel.hpp"
#include "chaos/error.hpp"
#include "metric_dispatch.hpp"
#include "spatial/kd_tree.hpp"

// The tree itself (nodes, splits, boxes, the leaf order) is spatial::KdTree. Besides it, the
// embedding is only a view (x[i + k tau]), so reading a point touches `dimension` cache lines far
// apart; the searcher therefore keeps a copy of the coordinates in leaf order, point after point
// (N * m doubles), so a leaf's points are contiguous in memory. Memory is O(N m): linear in N.
//
// A uniform leaf (all points identical) shares one distance to the query among all its points, so
// the Theiler window and the tie rule reduce to binary searches over its sorted indices. This keeps
// quantised series (thousands of equal points) from turning queries quadratic.
//
// Pruning uses the distance from the query to a node's bounding box, a lower bound of the distance
// to every point in it for the maximum norm and for the Euclidean norm alike. All distances are
// accumulated coordinate by coordinate in the order DelayEmbedding::distance uses, so the values
// (and hence the tie rule) equal brute force bit for bit; box bounds are computed with the same
// operations and are exact lower bounds in floating point because rounding is monotone.

namespace chaos {

namespace {

constexpr std::size_t no_child = spatial::KdTree::no_child;

bool within_window(std::size_t i, std::size_t j, std::size_t theiler) noexcept {
  return (i > j ? i - j : j - i) <= theiler;
}

void check_index(std::size_t i, std::size_t size) {
  if (i >= size)
    throw InvalidInput(ErrorCode::invalid_parameter, "neighbour query for point " + std::to_string(i) +
                                                         " but the embedding has only " + std::to_string(size) +
                                                         " points");
}

void check_k(std::size_t k) {
  if (k == 0) throw InvalidInput(ErrorCode::invalid_parameter, "k nearest neighbours with k = 0: k must be at least 1");
}

void check_radius(double radius) {
  if (std::isnan(radius))
    throw InvalidInput(ErrorCode::invalid_parameter, "neighbour count radius is NaN");
}

// The two norms as compile-time policies (metric_dispatch.hpp).
using detail::EuclideanMetric;
using detail::MaxMetric;

constexpr std::size_t not_found = std::numeric_limits<std::size_t>::max();

std::size_t add_sat(std::size_t a, std::size_t b) noexcept { return a > not_found - b ? not_found : a + b; }

}  // namespace

struct KdTree::Impl {
  using Node = spatial::KdTree::Node;

  DelayEmbedding points;
  Norm norm;
  std::size_t dim;
  spatial::KdTree tree;
  std::vector<double> coords_;  // coordinate k of the point at position p: coords_[p * dim + k]

  Impl(const DelayEmbedding& p, Norm n, std::size_t leaf_size, std::size_t threads);

  // A query: its point, coordinates, options and the best candidate so far.
  struct Search {
    const double* q;
    std::size_t i;
    const NeighborQuery& query;
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_index = not_found;
    bool improved_by(double d, std::size_t j) const noexcept { return d < best || (d == best && j < best_index); }
    void offer(double d, std::size_t j) noexcept {
      best = d;
      best_index = j;
    }
  };

  // A k-nearest query: the best k candidates so far, in the order (distance, index). Once there are
  // k of them, `best` and `best_index` are the k-th, the candidate a newcomer must beat, so the
  // pruning and the tie rule of a nearest query serve unchanged.
  struct KSearch {
    const double* q;
    std::size_t i;
    const NeighborQuery& query;
    std::size_t k;
    std::vector<Neighbor>& found;
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_index = not_found;
    bool improved_by(double d, std::size_t j) const noexcept { return d < best || (d == best && j < best_index); }
    void offer(double d, std::size_t j) {
      const auto before = [](const Neighbor& a, const Neighbor& b) {
        return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
      };
      found.insert(std::upper_bound(found.begin(), found.end(), Neighbor{j, d}, before), Neighbor{j, d});
      if (found.size() > k) found.pop_back();
      if (found.size() == k) {
        best = found.back().distance;
        best_index = found.back().index;
      }
    }
  };

  // D is the dimension when known at compile time (0: use `dim`), so the short loops over
  // coordinates unroll; see dispatch().
  template <std::size_t D>
  std::size_t dims() const noexcept {
    return D != 0 ? D : dim;
  }

  // Distance from q to the point at position pos; with early exit, any value > limit means "> limit".
  template <class Metric, std::size_t D>
  double point_distance(const double* q, std::size_t pos, double limit) const noexcept {
    const std::size_t m = dims<D>();
    const double* c = &coords_[pos * m];
    double acc = 0.0;
    for (std::size_t k = 0; k < m; ++k) {
      acc = Metric::add(acc, std::abs(q[k] - c[k]));
      if constexpr (Metric::early_exit)
        if (acc > limit) return acc;
    }
    return Metric::finish(acc);
  }

  // Lower bound of the distance from q to any point of the node's box (0 inside it); with early
  // exit, any value > limit means "> limit".
  template <class Metric, std::size_t D>
  double box_distance(const double* q, std::size_t node, double limit) const noexcept {
    const std::size_t m = dims<D>();
    const double* box = tree.box(node);
    double acc = 0.0;
    for (std::size_t k = 0; k < m; ++k) {
      const double lo = box[2 * k], hi = box[2 * k + 1];
      const double d = q[k] < lo ? lo - q[k] : (q[k] > hi ? q[k] - hi : 0.0);
      acc = Metric::add(acc, d);
      if constexpr (Metric::early_exit)
        if (acc > limit) return acc;
    }
    return Metric::finish(acc);
  }

  // True when the box is the single point q: every point in it is at distance exactly 0.
  template <class Metric, std::size_t D>
  bool box_is_query(const double* q, std::size_t node) const noexcept {
    const std::size_t m = dims<D>();
    const double* box = tree.box(node);
    for (std::size_t k = 0; k < m; ++k)
      if (box[2 * k] != q[k] || box[2 * k + 1] != q[k]) return false;
    return true;
  }

  // Upper bound of the distance from q to any point of the box (its farthest corner).
  template <class Metric, std::size_t D>
  double box_far_distance(const double* q, std::size_t node) const noexcept {
    const std::size_t m = dims<D>();
    const double* box = tree.box(node);
    double acc = 0.0;
    for (std::size_t k = 0; k < m; ++k)
      acc = Metric::add(acc, std::max(std::abs(q[k] - box[2 * k]), std::abs(q[k] - box[2 * k + 1])));
    return Metric::finish(acc);
  }

  // True when every point of the node lies inside the Theiler window of i (nothing admissible).
  static bool all_excluded(const Node& node, std::size_t i, std::size_t theiler) noexcept {
    return within_window(i, node.min_index, theiler) && within_window(i, node.max_index, theiler);
  }
  // True when some index of the node may lie inside the window (the ranges overlap).
  static bool window_touches(const Node& node, std::size_t i, std::size_t theiler) noexcept {
    return node.min_index <= add_sat(i, theiler) && i <= add_sat(node.max_index, theiler);
  }

  // Smallest index of a sorted (uniform) leaf outside the Theiler window of i, or not_found.
  std::size_t first_admissible(const Node& node, std::size_t i, std::size_t theiler) const noexcept {
    const auto first = tree.index().begin() + static_cast<std::ptrdiff_t>(node.begin);
    const auto last = tree.index().begin() + static_cast<std::ptrdiff_t>(node.end);
    if (!within_window(i, *first, theiler)) return *first;
    // The smallest index is inside the window, so none lies below it: the answer is past i + theiler.
    const auto it = std::upper_bound(first, last, add_sat(i, theiler));
    return it == last ? not_found : *it;
  }

  // Number of indices of a sorted (uniform) leaf inside the Theiler window of i.
  std::size_t count_excluded(const Node& node, std::size_t i, std::size_t theiler) const noexcept {
    const auto first = tree.index().begin() + static_cast<std::ptrdiff_t>(node.begin);
    const auto last = tree.index().begin() + static_cast<std::ptrdiff_t>(node.end);
    const std::size_t lower = i > theiler ? i - theiler : 0;
    return static_cast<std::size_t>(std::upper_bound(first, last, add_sat(i, theiler)) -
                                    std::lower_bound(first, last, lower));
  }

  template <class Metric, std::size_t D, class S>
  void scan_leaf(const Node& node, S& s) const {
    if (node.uniform) {
      // One distance for all; the tie rule wants the smallest admissible indices.
      const double d = point_distance<Metric, D>(s.q, node.begin, s.best);
      if (d > s.best || (s.query.skip_zero_distance && d == 0.0)) return;
      if constexpr (std::is_same_v<S, Search>) {
        const std::size_t j = first_admissible(node, s.i, s.query.theiler);
        if (j != not_found && s.improved_by(d, j)) s.offer(d, j);
      } else {
        // Ascending indices at one distance: once one fails to improve, all later ones fail.
        for (std::size_t pos = node.begin; pos < node.end; ++pos) {
          const std::size_t j = tree.index()[pos];
          if (within_window(s.i, j, s.query.theiler)) continue;
          if (!s.improved_by(d, j)) break;
          s.offer(d, j);
        }
      }
      return;
    }
    for (std::size_t pos = node.begin; pos < node.end; ++pos) {
      const std::size_t j = tree.index()[pos];
      if (within_window(s.i, j, s.query.theiler)) continue;
      const double d = point_distance<Metric, D>(s.q, pos, s.best);
      if (s.query.skip_zero_distance && d == 0.0) continue;
      if (s.improved_by(d, j)) s.offer(d, j);
    }
  }

  // A node can be skipped when it cannot hold a better candidate: all its points are in the
  // Theiler window, its box is farther than the best (or as far, with only larger indices), or,
  // with skip_zero_distance, all its points coincide with the query.
  template <class Metric, std::size_t D, class S>
  bool prunable(std::size_t node_id, const S& s) const noexcept {
    const Node& node = tree.nodes()[node_id];
    if (all_excluded(node, s.i, s.query.theiler)) return true;
    const double d = box_distance<Metric, D>(s.q, node_id, s.best);
    if (d > s.best || (d == s.best && node.min_index > s.best_index)) return true;
    return s.query.skip_zero_distance && d == 0.0 && box_is_query<Metric, D>(s.q, node_id);
  }

  // Depth-first search of a subtree, nearer child (by the split plane) first. Recursion depth is
  // the tree depth, at most log_{4/3}(N) + 1 because every child holds at least a quarter.
  template <class Metric, std::size_t D, class S>
  void nearest_in(std::size_t node_id, S& s) const {
    const Node& node = tree.nodes()[node_id];
    if (node.left == no_child) {
      scan_leaf<Metric, D>(node, s);
      return;
    }
    const bool left_first = s.q[node.split_dim] <= node.split_value;
    const std::size_t first = left_first ? node.left : node.left + 1;
    const std::size_t second = left_first ? node.left + 1 : node.left;
    if (!prunable<Metric, D>(first, s)) nearest_in<Metric, D>(first, s);
    if (!prunable<Metric, D>(second, s)) nearest_in<Metric, D>(second, s);
  }

  // The query is a point of the tree, so the search starts in its own leaf and climbs: at each
  // level the sibling subtree is searched unless it can be pruned. Every leaf lies in one of those
  // siblings, so this is exhaustive, and it skips the root-to-leaf descent, where most of the time
  // of a top-down search goes (the boxes on the path contain the query and cannot prune).
  template <class Metric, std::size_t D, class S>
  void nearest_from_leaf(S& s) const {
    std::size_t node_id = tree.leaf_of()[s.i];
    scan_leaf<Metric, D>(tree.nodes()[node_id], s);
    while (node_id != 0) {
      const std::size_t parent = tree.nodes()[node_id].parent;
      const std::size_t sibling = node_id == tree.nodes()[parent].left ? node_id + 1 : node_id - 1;
      if (!prunable<Metric, D>(sibling, s)) nearest_in<Metric, D>(sibling, s);
      node_id = parent;
    }
  }

  template <class Metric, std::size_t D>
  std::size_t count_in(std::size_t node_id, const double* q, std::size_t i, double radius,
                       const NeighborQuery& query) const {
    const Node& node = tree.nodes()[node_id];
    if (all_excluded(node, i, query.theiler)) return 0;
    const double near = box_distance<Metric, D>(q, node_id, radius);
    if (!(near < radius)) return 0;
    if (query.skip_zero_distance && near == 0.0 && box_is_query<Metric, D>(q, node_id)) return 0;
    const bool touches = window_touches(node, i, query.theiler);
    if (node.uniform)  // all points at one distance, inside the radius (the box is the point)
      return (node.end - node.begin) - (touches ? count_excluded(node, i, query.theiler) : 0);
    // Whole node inside the radius, clear of the window and of distance 0: count it at once.
    if (!touches && (!query.skip_zero_distance || near > 0.0) && box_far_distance<Metric, D>(q, node_id) < radius)
      return node.end - node.begin;
    if (node.left == no_child) {
      std::size_t count = 0;
      for (std::size_t pos = node.begin; pos < node.end; ++pos) {
        if (within_window(i, tree.index()[pos], query.theiler)) continue;
        const double d = point_distance<Metric, D>(q, pos, radius);
        if (d < radius && !(query.skip_zero_distance && d == 0.0)) ++count;
      }
      return count;
    }
    return count_in<Metric, D>(node.left, q, i, radius, query) + count_in<Metric, D>(node.left + 1, q, i, radius, query);
  }

  // Appends the admissible points of the subtree closer than `radius`: the traversal of count_in,
  // collecting indices instead of counting them.
  template <class Metric, std::size_t D>
  void collect_in(std::size_t node_id, const double* q, std::size_t i, double radius, const NeighborQuery& query,
                  std::vector<std::size_t>& out) const {
    const Node& node = tree.nodes()[node_id];
    if (all_excluded(node, i, query.theiler)) return;
    const double near = box_distance<Metric, D>(q, node_id, radius);
    if (!(near < radius)) return;
    if (query.skip_zero_distance && near == 0.0 && box_is_query<Metric, D>(q, node_id)) return;
    const bool touches = window_touches(node, i, query.theiler);
    const bool whole = node.uniform || (!touches && (!query.skip_zero_distance || near > 0.0) &&
                                        box_far_distance<Metric, D>(q, node_id) < radius);
    if (whole || node.left == no_child) {
      for (std::size_t pos = node.begin; pos < node.end; ++pos) {
        const std::size_t j = tree.index()[pos];
        if (within_window(i, j, query.theiler)) continue;
        if (whole) {
          out.push_back(j);
          continue;
        }
        const double d = point_distance<Metric, D>(q, pos, radius);
        if (d < radius && !(query.skip_zero_distance && d == 0.0)) out.push_back(j);
      }
      return;
    }
    collect_in<Metric, D>(node.left, q, i, radius, query, out);
    collect_in<Metric, D>(node.left + 1, q, i, radius, query, out);
  }

  // As nearest_from_leaf: the query's own leaf, then the sibling of each node on the way up. Every
  // leaf lies in exactly one of these subtrees, and for small radii nearly all siblings are pruned
  // by their boxes at once, so the descent from the root is skipped.
  template <class Metric, std::size_t D>
  void collect_from_leaf(const double* q, std::size_t i, double radius, const NeighborQuery& query,
                         std::vector<std::size_t>& out) const {
    std::size_t node_id = tree.leaf_of()[i];
    collect_in<Metric, D>(node_id, q, i, radius, query, out);
    while (node_id != 0) {
      const std::size_t parent = tree.nodes()[node_id].parent;
      const std::size_t sibling = node_id == tree.nodes()[parent].left ? node_id + 1 : node_id - 1;
      collect_in<Metric, D>(sibling, q, i, radius, query, out);
      node_id = parent;
    }
  }

  // Runs f.template operator()<Metric, D>() with the norm and, for common dimensions, D = dim.
  template <class F>
  auto dispatch(F&& f) const {
    return detail::dispatch_metric<12>(norm, dim, f);
  }

  // The query point's coordinates, read once from the view; on the stack for usual dimensions.
  template <class F>
  auto with_query(std::size_t i, F&& f) const {
    return detail::with_point(points, i, f);
  }
};

KdTree::Impl::Impl(const DelayEmbedding& p, Norm n, std::size_t leaf_size, std::size_t threads)
    : points(p), norm(n), dim(p.dimension()),
      // Split coordinates are read from the view: the series (N doubles) is more cache-friendly
      // than any N x m copy. The boxes are fitted from the copy in leaf order.
      tree(p.size(), dim, leaf_size, [&p](std::size_t i, std::size_t k) { return p(i, k); }, threads) {
  const std::size_t count = points.size();
  coords_.resize(count * dim);
  for (std::size_t pos = 0; pos < count; ++pos)
    for (std::size_t k = 0; k < dim; ++k) coords_[pos * dim + k] = points(tree.index()[pos], k);
  tree.fit_boxes([this](std::size_t pos, std::size_t k) { return coords_[pos * dim + k]; });
}

KdTree::KdTree(const DelayEmbedding& points, Norm norm, std::size_t leaf_size, std::size_t threads)
    : impl_(std::make_unique<Impl>(points, norm, leaf_size, threads)) {}
KdTree::~KdTree() = default;
KdTree::KdTree(KdTree&&) noexcept = default;
KdTree& KdTree::operator=(KdTree&&) noexcept = default;

const DelayEmbedding& KdTree::points() const noexcept { return impl_->points; }
Norm KdTree::norm() const noexcept { return impl_->norm; }
std::span<const std::size_t> KdTree::leaf_order() const noexcept { return impl_->tree.index(); }

std::optional<Neighbor> KdTree::nearest(std::size_t i, const NeighborQuery& query) const {
  const Impl& t = *impl_;
  check_index(i, t.points.size());
  return t.with_query(i, [&](const double* q) -> std::optional<Neighbor> {
    Impl::Search s{q, i, query};
    t.dispatch([&]<class Metric, std::size_t D>() {
      t.nearest_from_leaf<Metric, D>(s);
      return 0;
    });
    if (s.best_index == not_found) return std::nullopt;
    return Neighbor{s.best_index, s.best};
  });
}

void KdTree::k_nearest(std::size_t i, std::size_t k, std::vector<Neighbor>& out, const NeighborQuery& query) const {
  const Impl& t = *impl_;
  check_index(i, t.points.size());
  check_k(k);
  out.clear();
  t.with_query(i, [&](const double* q) {
    Impl::KSearch s{q, i, query, k, out};
    return t.dispatch([&]<class Metric, std::size_t D>() {
      t.nearest_from_leaf<Metric, D>(s);
      return 0;
    });
  });
}

std::size_t KdTree::memory_bytes() const noexcept {
  const Impl& t = *impl_;
  return t.tree.memory_bytes() + t.coords_.capacity() * sizeof(double);
}

std::size_t KdTree::count_within(std::size_t i, double radius, const NeighborQuery& query) const {
  const Impl& t = *impl_;
  check_index(i, t.points.size());
  check_radius(radius);
  return t.with_query(i, [&](const double* q) {
    return t.dispatch([&]<class Metric, std::size_t D>() { return t.count_in<Metric, D>(0, q, i, radius, query); });
  });
}

void KdTree::within(std::size_t i, double radius, std::vector<std::size_t>& out, const NeighborQuery& query) const {
  const Impl& t = *impl_;
  check_index(i, t.points.size());
  check_radius(radius);
  out.clear();
  t.with_query(i, [&](const double* q) {
    return t.dispatch([&]<class Metric, std::size_t D>() {
      t.collect_from_leaf<Metric, D>(q, i, radius, query, out);
      return 0;
    });
  });
  // Leaf order -> index order: a canonical answer. A large answer (most of the points, as a radius
  // just above the spacing of quantised data gives) is ordered through a bitmap of the points in
  // O(points / 64 + answer) instead of a sort: the same list.
  const std::size_t points = t.points.size();
  if (out.size() < 64 || out.size() * 16 < points) {
    std::sort(out.begin(), out.end());
    return;
  }
  std::vector<std::uint64_t> bits((points + 63) / 64, 0);
  for (const std::size_t j : out) bits[j / 64] |= std::uint64_t{1} << (j % 64);
  out.clear();
  for (std::size_t w = 0; w < bits.size(); ++w)
    for (std::uint64_t word = bits[w]; word != 0; word &= word - 1)
      out.push_back(w * 64 + static_cast<std::size_t>(std::countr_zero(word)));
}

std::vector<std::optional<Neighbor>> all_nearest(const KdTree& tree, const NeighborQuery& query,
                                                 const std::function<void(double)>& progress, std::size_t threads) {
  const std::span<const std::size_t> order = tree.leaf_order();
  std::vector<std::optional<Neighbor>> out(order.size());
  // Tasks of consecutive positions in leaf order, so a worker's searches stay close in space.
  constexpr std::size_t chunk = 4096;
  const std::size_t tasks = (order.size() + chunk - 1) / chunk;
  if (progress) progress(0.0);  // parallel_tasks reports only as tasks end, so never for one task
  detail::parallel_tasks(threads, tasks, [&](std::size_t t, std::size_t) {
    const std::size_t end = std::min(order.size(), (t + 1) * chunk);
    for (std::size_t p = t * chunk; p < end; ++p) out[order[p]] = tree.nearest(order[p], query);
  }, &progress);
  return out;
}

std::optional<Neighbor> nearest_brute_force(const DelayEmbedding& points, std::size_t i, Norm norm,
                                            const NeighborQuery& query) {
  check_index(i, points.size());
  std::optional<Neighbor> best;
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (within_window(i, j, query.theiler)) continue;
    const double d = points.distance(i, j, norm);
    if (query.skip_zero_distance && d == 0.0) continue;
    if (!best || d < best->distance) best = Neighbor{j, d};  // ascending j: the first of equals wins
  }
  return best;
}

std::vector<Neighbor> k_nearest_brute_force(const DelayEmbedding& points, std::size_t i, std::size_t k, Norm norm,
                                            const NeighborQuery& query) {
  check_index(i, points.size());
  check_k(k);
  std::vector<Neighbor> best;  // sorted by (distance, index); j ascends, so equals keep their order
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (within_window(i, j, query.theiler)) continue;
    const double d = points.distance(i, j, norm);
    if (query.skip_zero_distance && d == 0.0) continue;
    if (best.size() == k && !(d < best.back().distance)) continue;
    const auto it = std::upper_bound(best.begin(), best.end(), d,
                                     [](double value, const Neighbor& n) { return value < n.distance; });
    best.insert(it, Neighbor{j, d});
    if (best.size() > k) best.pop_back();
  }
  return best;
}

std::size_t count_within_brute_force(const DelayEmbedding& points, std::size_t i, double radius, Norm norm,
                                     const NeighborQuery& query) {
  check_index(i, points.size());
  check_radius(radius);
  std::size_t count = 0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (within_window(i, j, query.theiler)) continue;
    const double d = points.distance(i, j, norm);
    if (d < radius && !(query.skip_zero_distance && d == 0.0)) ++count;
  }
  return count;
}

std::vector<std::size_t> within_brute_force(const DelayEmbedding& points, std::size_t i, double radius, Norm norm,
                                            const NeighborQuery& query) {
  check_index(i, points.size());
  check_radius(radius);
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (within_window(i, j, query.theiler)) continue;
    const double d = points.distance(i, j, norm);
    if (d < radius && !(query.skip_zero_distance && d == 0.0)) out.push_back(j);
  }
  return out;
}

}  // namespace chaos
