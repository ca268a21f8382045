#include "correlation_sum_layouts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <boost/sort/pdqsort/pdqsort.hpp>

#include "spatial/box_grid.hpp"

namespace chaos::correlation_detail {

Grid build_grid(const Problem& pb) {
  const std::size_t n = pb.points;
  double lo = infinity, hi = -infinity;
  for (std::size_t i = 0; i < n; ++i) {
    lo = std::min(lo, pb.at(i, 1));
    hi = std::max(hi, pb.at(i, 1));
  }
  // The row of a value is floor((v - lo) / h), computed in floating point. With at most 2^30 rows
  // the quotient's rounding error is below 2^-22 rows, and the margin 1 + 2^-20 on h keeps two
  // values less than r_max (1 + 2^-50) apart in rows that differ by at most one. More rows than
  // max(4 n, 1024) only cost memory: the rows are then made higher, which keeps that property.
  // h may be infinite (a radius beyond all distances): one row.
  const double h = std::max(pb.r_max, (hi - lo) * 0x1p-30) * (1.0 + 0x1p-20);
  const spatial::GridAxis rows = spatial::GridAxis::over(lo, hi, h, std::max(4.0 * static_cast<double>(n), 1024.0));
  spatial::BoxGrid boxes(n, spatial::GridAxis{}, rows, [](std::size_t) { return 0.0; },
                         [&pb](std::size_t i) { return pb.at(i, 1); });
  // Each row (in index order from the counting sort) sorted by (c0, i), on copies of c0 beside the
  // indices: about half the time of sorting (row, c0, i) triples, which is most of the grid's build
  // and counts in `chaos d2 --fast` (Lorenz x 10^5: 10 of 100 ms).
  struct Key {
    double c0;
    std::size_t i;
  };
  const auto by_c0 = [](const Key& a, const Key& b) { return a.c0 != b.c0 ? a.c0 < b.c0 : a.i < b.i; };
  std::vector<Key> keys(n);
  const std::vector<std::size_t>& order = boxes.order();
  for (std::size_t p = 0; p < n; ++p) keys[p] = {pb.at(order[p], 0), order[p]};
  Grid g;
  const std::vector<std::size_t>& start = boxes.start();
  for (std::size_t r = 0; r < rows.boxes; ++r) {
    if (start[r] == start[r + 1]) continue;
    g.rows.push_back({static_cast<std::int64_t>(r), start[r], start[r + 1]});
    boost::sort::pdqsort_branchless(keys.begin() + static_cast<std::ptrdiff_t>(start[r]),
                                    keys.begin() + static_cast<std::ptrdiff_t>(start[r + 1]), by_c0);
  }
  g.size = n;
  g.coords.resize(n * pb.max_m);
  g.index.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t i = keys[p].i;
    g.index[p] = i;
    for (std::size_t k = 0; k < pb.max_m; ++k) g.coords[k * n + p] = pb.at(i, k);
  }
  for (std::size_t t = 0; t < g.rows.size(); ++t)
    for (std::size_t b = g.rows[t].begin; b < g.rows[t].end; b += chunk_points)
      g.chunks.push_back({t, b, std::min(g.rows[t].end, b + chunk_points)});
  return g;
}

KdLayout build_kd(const Problem& pb) {
  const std::size_t n = pb.points, c = std::max<std::size_t>(2, pb.min_m);
  KdLayout t;
  t.tree = spatial::KdTree(n, c, KdLayout::leaf_points, [&pb](std::size_t i, std::size_t k) { return pb.at(i, k); }, pb.threads);
  t.size = n;
  t.index = t.tree.index();
  t.coords.resize(n * pb.max_m);
  t.position.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    t.position[t.index[p]] = p;
    for (std::size_t k = 0; k < pb.max_m; ++k) t.coords[k * n + p] = pb.at(t.index[p], k);
  }
  t.tree.fit_boxes([&t](std::size_t p, std::size_t k) { return t.coordinate(k)[p]; });
  return t;
}

}  // namespace chaos::correlation_detail
