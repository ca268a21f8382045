#include "nanoflann_search.hpp"

#include <nanoflann.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace chaos::cli {

namespace {

bool within_window(std::size_t i, std::size_t j, std::size_t theiler) noexcept {
  return (i > j ? i - j : j - i) <= theiler;
}

// nanoflann's dataset adaptor: the embedding as a view.
struct View {
  const DelayEmbedding* points;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t k) const { return (*points)(i, k); }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // let nanoflann compute it
  }
};

using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, View, double, std::size_t>,
                                                  View, -1, std::size_t>;

// Result set that counts the admissible candidates nanoflann offers (those below `limit`).
struct CountSet {
  double limit;
  std::size_t i, theiler, count = 0;
  std::size_t size() const { return count; }
  bool full() const { return true; }
  double worstDist() const { return limit; }
  bool addPoint(double, std::size_t j) {
    if (!within_window(i, j, theiler)) ++count;
    return true;
  }
};

// Result set that keeps the k best admissible candidates by (squared distance, index).
struct NearestSet {
  std::size_t k, i, theiler;
  std::vector<Neighbor>& found;
  std::size_t size() const { return found.size(); }
  bool full() const { return found.size() == k; }
  double worstDist() const { return full() ? found.back().distance : std::numeric_limits<double>::max(); }
  bool addPoint(double d2, std::size_t j) {
    if (within_window(i, j, theiler)) return true;
    const Neighbor n{j, d2};
    const auto before = [](const Neighbor& a, const Neighbor& b) {
      return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
    };
    found.insert(std::upper_bound(found.begin(), found.end(), n, before), n);
    if (found.size() > k) found.pop_back();
    return true;
  }
};

}  // namespace

struct NanoflannSearch::Impl {
  DelayEmbedding points;
  View view;
  Index index;
  Impl(const DelayEmbedding& p, std::size_t leaf_size)
      : points(p),
        view{&points},
        index(static_cast<int>(p.dimension()), view, nanoflann::KDTreeSingleIndexAdaptorParams(leaf_size)) {}

  template <class F>
  auto with_query(std::size_t i, F&& f) const {
    constexpr std::size_t stack_dim = 32;
    double stack[stack_dim];
    std::vector<double> heap;
    double* q = stack;
    if (points.dimension() > stack_dim) {
      heap.resize(points.dimension());
      q = heap.data();
    }
    for (std::size_t k = 0; k < points.dimension(); ++k) q[k] = points(i, k);
    return f(static_cast<const double*>(q));
  }
};

NanoflannSearch::NanoflannSearch(const DelayEmbedding& points, std::size_t leaf_size)
    : impl_(std::make_unique<Impl>(points, leaf_size)) {}
NanoflannSearch::~NanoflannSearch() = default;
NanoflannSearch::NanoflannSearch(NanoflannSearch&&) noexcept = default;
NanoflannSearch& NanoflannSearch::operator=(NanoflannSearch&&) noexcept = default;

std::size_t NanoflannSearch::count_within(std::size_t i, double radius, std::size_t theiler) const {
  return impl_->with_query(i, [&](const double* q) {
    CountSet set{squared_threshold(radius), i, theiler};
    impl_->index.findNeighbors(set, q, nanoflann::SearchParams());
    return set.count;
  });
}

void NanoflannSearch::k_nearest(std::size_t i, std::size_t k, std::vector<Neighbor>& out, std::size_t theiler) const {
  out.clear();
  impl_->with_query(i, [&](const double* q) {
    NearestSet set{k, i, theiler, out};
    impl_->index.findNeighbors(set, q, nanoflann::SearchParams());
    return 0;
  });
  for (Neighbor& n : out) n.distance = std::sqrt(n.distance);
}

std::size_t NanoflannSearch::memory_bytes() const { return impl_->index.usedMemory(impl_->index); }

double squared_threshold(double r) {
  if (!(r > 0.0)) return 0.0;
  std::uint64_t lo = 0, hi = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::infinity());
  while (lo < hi) {  // non-negative doubles are ordered like their bit patterns, and sqrt is monotone
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (std::sqrt(std::bit_cast<double>(mid)) >= r)
      hi = mid;
    else
      lo = mid + 1;
  }
  return std::bit_cast<double>(lo);
}

}  // namespace chaos::cli
