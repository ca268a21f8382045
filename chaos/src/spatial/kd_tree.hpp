#pragma once
// The library's kd-tree: the points permuted into leaf order, the nodes, and each node's tight
// bounding box and range of point indices. The searches that walk it (nearest neighbours and counts
// in neighbors.cpp, the candidate scans of the correlation sum) keep their own copy of the
// coordinates in leaf order, laid out for their loops: point after point for distances with an
// early exit, coordinate after coordinate for the vector scans.
//
// Splits are by position: at the median (std::nth_element on the coordinate of widest spread among
// at most 64 evenly spaced points of the node), moved to the nearer end of the block of points equal
// to the median value when both children still get at least a quarter of the points. So the tree
// stays balanced (depth <= log_{4/3} N + 1) whatever the data, equal coordinates cannot produce an
// empty side, and in quantised data the points sharing a value end up in the same subtree. A node
// whose points are all identical is not split: it becomes a "uniform" leaf with its indices sorted.
// The build is iterative (an explicit work list), so no recursion however the data look. With
// threads, the subtrees below the top levels are built in parallel and then numbered as one thread
// numbers them: the same tree, node for node.
//
// Boxes are computed exactly afterwards, bottom-up, from the coordinates in leaf order: a box is a
// lower bound of the distance to every point inside for the maximum and the Euclidean norm alike,
// and exact in floating point because rounding is monotone.

#include <algorithm>
#include <cstddef>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "chaos/detail/parallel.hpp"

namespace chaos::spatial {

class KdTree {
 public:
  static constexpr std::size_t no_child = 0;  // the root is never a child, so 0 marks a leaf

  struct Node {
    std::size_t begin = 0, end = 0;            // range of positions in leaf order
    std::size_t min_index = 0, max_index = 0;  // smallest and largest point index inside
    std::size_t left = no_child;               // children are left and left + 1; no_child: a leaf
    std::size_t parent = 0;                    // the root's parent is itself
    std::size_t split_dim = 0;                 // children: left has coordinate <= split_value,
    double split_value = 0.0;                  //           right has coordinate >= split_value
    bool uniform = false;  // every point identical; index[begin, end) sorted ascending
  };

  KdTree() = default;

  // The tree of `count` points over their first `dims` coordinates, at(i, k) being coordinate k of
  // point i, with at most `leaf_size` points per leaf (uniform leaves excepted). The boxes are not
  // filled yet: fit_boxes() does that from the caller's copy of the coordinates in leaf order.
  // `threads` build the subtrees below the top levels in parallel; the tree is the same for any number.
  template <class At>
  KdTree(std::size_t count, std::size_t dims, std::size_t leaf_size, const At& at, std::size_t threads = 1);

  // Fills the boxes and index ranges from at_position(p, k), coordinate k of the point at position p
  // in leaf order (the same values as at(index[p], k)).
  template <class AtPosition>
  void fit_boxes(const AtPosition& at_position);

  std::size_t dims() const noexcept { return dims_; }
  const std::vector<std::size_t>& index() const noexcept { return index_; }  // point at each position
  const std::vector<Node>& nodes() const noexcept { return nodes_; }
  const std::vector<std::size_t>& leaf_of() const noexcept { return leaf_of_; }  // leaf holding each point
  // lo and hi of coordinate k of node n: box(n)[2 k] and box(n)[2 k + 1].
  const double* box(std::size_t node) const noexcept { return box_.data() + 2 * node * dims_; }

  std::size_t memory_bytes() const noexcept {
    return (index_.capacity() + leaf_of_.capacity()) * sizeof(std::size_t) + nodes_.capacity() * sizeof(Node) +
           box_.capacity() * sizeof(double);
  }

 private:
  using Keyed = std::pair<double, std::size_t>;  // a coordinate and its point's index
  // Smaller trees take a few milliseconds (10^5 points: 40 ms); they are built on the calling thread.
  static constexpr std::size_t parallel_points = 1 << 15;
  // Splits the nodes of `nodes` from its first on, down to leaves. A node of at most `defer` points is
  // left unsplit and listed in `deferred` (where given). Positions are those of index_ and keyed, so
  // threads growing disjoint nodes write disjoint parts.
  template <class At>
  void grow(std::vector<Node>& nodes, std::size_t leaf_size, const At& at, std::vector<Keyed>& keyed,
            std::size_t defer = 0, std::vector<std::size_t>* deferred = nullptr);

  std::size_t dims_ = 0;
  std::vector<std::size_t> index_;
  std::vector<Node> nodes_;
  std::vector<double> box_;
  std::vector<std::size_t> leaf_of_;
};

template <class At>
void KdTree::grow(std::vector<Node>& nodes, std::size_t leaf_size, const At& at, std::vector<Keyed>& keyed,
                  std::size_t defer, std::vector<std::size_t>* deferred) {
  // The split coordinate is the one of widest spread among at most `sample` evenly spaced points of
  // the node (all of them in small nodes): that choice only shapes the tree.
  constexpr std::size_t sample = 64;
  const std::size_t dims = dims_;
  std::vector<double> lo(dims), hi(dims);
  const auto widest = [&](std::size_t begin, std::size_t end, std::size_t stride, std::size_t& split) {
    std::fill(lo.begin(), lo.end(), std::numeric_limits<double>::infinity());
    std::fill(hi.begin(), hi.end(), -std::numeric_limits<double>::infinity());
    for (std::size_t pos = begin; pos < end; pos += stride)
      for (std::size_t k = 0; k < dims; ++k) {
        const double v = at(index_[pos], k);
        lo[k] = std::min(lo[k], v);
        hi[k] = std::max(hi[k], v);
      }
    double spread = 0.0;
    for (std::size_t k = 0; k < dims; ++k)
      if (hi[k] - lo[k] > spread) {
        spread = hi[k] - lo[k];
        split = k;
      }
    return spread;
  };
  std::vector<std::size_t> work{0};
  while (!work.empty()) {
    const std::size_t id = work.back();
    work.pop_back();
    const std::size_t begin = nodes[id].begin, end = nodes[id].end, size = end - begin;
    if (size <= defer && deferred) {
      deferred->push_back(id);
      continue;
    }
    const std::size_t stride = size > sample ? size / sample : 1;
    std::size_t split = 0;
    double spread = widest(begin, end, stride, split);
    if (spread == 0.0 && stride > 1) spread = widest(begin, end, 1, split);  // are they really all equal?
    if (spread == 0.0 || size <= leaf_size) {
      nodes[id].uniform = spread == 0.0;
      if (nodes[id].uniform)
        std::sort(index_.begin() + static_cast<std::ptrdiff_t>(begin), index_.begin() + static_cast<std::ptrdiff_t>(end));
      continue;
    }
    // The selection runs on (coordinate, index) pairs gathered once per node: one scattered read of
    // the coordinates per point instead of one per comparison. The algorithms see the same keys in
    // the same order as they would through the index, so the permutation, and the tree, are the same.
    for (std::size_t pos = begin; pos < end; ++pos) keyed[pos] = {at(index_[pos], split), index_[pos]};
    const auto first = keyed.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto last = keyed.begin() + static_cast<std::ptrdiff_t>(end);
    auto middle = first + static_cast<std::ptrdiff_t>(size / 2);
    std::nth_element(first, middle, last, [](const Keyed& a, const Keyed& b) { return a.first < b.first; });
    // Points equal to the median coordinate v may lie on both sides. Quantised data have thousands
    // of them, and smearing them over both children leaves many mixed nodes that a query must open.
    // So gather the block of v's and cut at the nearer end of it, unless that would leave either
    // child with less than a quarter of the points (depth stays below log_{4/3} N + 1).
    const double v = middle->first;
    const auto block_begin = std::partition(first, middle, [v](const Keyed& a) { return a.first < v; });
    const auto block_end = std::partition(middle, last, [v](const Keyed& a) { return a.first == v; });
    const auto quarter = static_cast<std::ptrdiff_t>(std::max<std::size_t>(size / 4, 1));
    const auto lower_cut = block_begin, upper_cut = block_end;
    if (middle - lower_cut <= upper_cut - middle) {
      if (lower_cut - first >= quarter) middle = lower_cut;
      else if (last - upper_cut >= quarter) middle = upper_cut;
    } else {
      if (last - upper_cut >= quarter) middle = upper_cut;
      else if (lower_cut - first >= quarter) middle = lower_cut;
    }
    for (std::size_t pos = begin; pos < end; ++pos) index_[pos] = keyed[pos].second;
    const std::size_t mid = begin + static_cast<std::size_t>(middle - first);
    nodes[id].left = nodes.size();
    nodes[id].split_dim = split;
    nodes[id].split_value = v;
    nodes.push_back(Node{begin, mid});
    nodes.push_back(Node{mid, end});
    nodes[nodes.size() - 2].parent = id;
    nodes[nodes.size() - 1].parent = id;
    work.push_back(nodes[id].left + 1);
    work.push_back(nodes[id].left);
  }
}

template <class At>
KdTree::KdTree(std::size_t count, std::size_t dims, std::size_t leaf_size, const At& at, std::size_t threads)
    : dims_(dims) {
  if (leaf_size == 0) leaf_size = 1;
  index_.resize(count);
  std::iota(index_.begin(), index_.end(), std::size_t{0});
  if (count == 0) return;
  std::vector<Keyed> keyed(count);
  nodes_.push_back(Node{0, count});
  if (threads <= 1 || count < parallel_points) {
    grow(nodes_, leaf_size, at, keyed);
  } else {
    // The top of the tree on this thread, down to nodes of at most count / (2 threads) points; the
    // subtrees below them in parallel, each over its own positions of index_ and keyed; then every
    // node numbered as the one-thread build numbers it (the splits are the same, and so the tree).
    std::vector<std::size_t> deferred;
    grow(nodes_, leaf_size, at, keyed, count / (2 * threads), &deferred);
    std::vector<std::vector<Node>> subtrees(deferred.size());
    detail::parallel_tasks(threads, deferred.size(), [&](std::size_t t, std::size_t) {
      subtrees[t].push_back(nodes_[deferred[t]]);  // unsplit: the top's grow left it a leaf
      grow(subtrees[t], leaf_size, at, keyed);
    });
    constexpr std::size_t top = std::numeric_limits<std::size_t>::max();
    std::vector<std::size_t> subtree_of(nodes_.size(), top);
    for (std::size_t t = 0; t < deferred.size(); ++t) subtree_of[deferred[t]] = t;
    std::vector<Node> numbered;
    std::size_t total = nodes_.size();
    for (const auto& subtree : subtrees) total += subtree.size();
    numbered.reserve(total);
    numbered.push_back(Node{});
    struct From {
      std::size_t to, tree, id;  // the new number; the source: top (nodes_) or a subtree, and its number there
    };
    std::vector<From> work{{0, top, 0}};
    while (!work.empty()) {
      From f = work.back();
      work.pop_back();
      if (f.tree == top && subtree_of[f.id] != top) f = {f.to, subtree_of[f.id], 0};
      const std::vector<Node>& source = f.tree == top ? nodes_ : subtrees[f.tree];
      Node node = source[f.id];
      node.parent = numbered[f.to].parent;
      const std::size_t source_left = node.left;
      if (source_left != no_child) {
        node.left = numbered.size();
        numbered.push_back(Node{});
        numbered.push_back(Node{});
        numbered[node.left].parent = numbered[node.left + 1].parent = f.to;
        work.push_back({node.left + 1, f.tree, source_left + 1});
        work.push_back({node.left, f.tree, source_left});
      }
      numbered[f.to] = node;
    }
    nodes_ = std::move(numbered);
  }
  leaf_of_.resize(count);
  for (std::size_t id = 0; id < nodes_.size(); ++id)
    if (nodes_[id].left == no_child)
      for (std::size_t pos = nodes_[id].begin; pos < nodes_[id].end; ++pos) leaf_of_[index_[pos]] = id;
}

template <class AtPosition>
void KdTree::fit_boxes(const AtPosition& at_position) {
  constexpr std::size_t not_found = std::numeric_limits<std::size_t>::max();
  const std::size_t dim = dims_;
  // Children before parents (children are numbered after them).
  box_.resize(2 * nodes_.size() * dim);
  for (std::size_t id = nodes_.size(); id-- > 0;) {
    Node& node = nodes_[id];
    double* box = &box_[2 * id * dim];
    if (node.left == no_child) {
      for (std::size_t k = 0; k < dim; ++k) {
        box[2 * k] = std::numeric_limits<double>::infinity();
        box[2 * k + 1] = -std::numeric_limits<double>::infinity();
      }
      node.min_index = not_found;
      node.max_index = 0;
      for (std::size_t pos = node.begin; pos < node.end; ++pos) {
        node.min_index = std::min(node.min_index, index_[pos]);
        node.max_index = std::max(node.max_index, index_[pos]);
        for (std::size_t k = 0; k < dim; ++k) {
          const double c = at_position(pos, k);
          box[2 * k] = std::min(box[2 * k], c);
          box[2 * k + 1] = std::max(box[2 * k + 1], c);
        }
      }
      continue;
    }
    const double* a = &box_[2 * node.left * dim];
    const double* b = &box_[2 * (node.left + 1) * dim];
    for (std::size_t k = 0; k < dim; ++k) {
      box[2 * k] = std::min(a[2 * k], b[2 * k]);
      box[2 * k + 1] = std::max(a[2 * k + 1], b[2 * k + 1]);
    }
    node.min_index = std::min(nodes_[node.left].min_index, nodes_[node.left + 1].min_index);
    node.max_index = std::max(nodes_[node.left].max_index, nodes_[node.left + 1].max_index);
  }
}

}  // namespace chaos::spatial
