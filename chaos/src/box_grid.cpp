#include "chaos/box_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "chaos/error.hpp"
#include "metric_dispatch.hpp"
#include "numeric.hpp"
#include "spatial/box_grid.hpp"

// Layout: the boxes are spatial::BoxGrid's (box = y * nx + x over coordinates 1 and 0, each holding
// ascending indices), and coords_ copies the coordinates in the grid's order, point after point, so
// a box's points are contiguous in memory (the kd-tree does the same).
//
// The lower bound behind the rings: a point whose box is c > ρ columns (or rows) away from the
// query's has a coordinate at least (c - 1) boxes away, up to the rounding of (x - lo) / box, a
// few ulps of the range: `slack_` covers it, so the bound ρ·box - slack is never too large.

namespace chaos {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

bool within_window(std::size_t i, std::size_t j, std::size_t theiler) noexcept {
  return (i > j ? i - j : j - i) <= theiler;
}

using detail::EuclideanMetric;  // the norms as compile-time policies (metric_dispatch.hpp)
using detail::MaxMetric;

bool before(const Neighbor& a, const Neighbor& b) noexcept {
  return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
}

}  // namespace

struct BoxGrid::Impl {
  DelayEmbedding points;
  Norm norm;
  std::size_t dim;
  std::size_t axes;  // grid coordinates: 1 for m = 1, else 2
  double lo = 0.0, side = 1.0, slack = 0.0;
  std::size_t nx = 1, ny = 1;
  spatial::BoxGrid grid;
  std::vector<double> coords_;

  Impl(const DelayEmbedding& p, Norm n, double box) : points(p), norm(n), dim(p.dimension()), axes(std::min<std::size_t>(dim, 2)) {
    if (!(box > 0.0) || !std::isfinite(box))
      throw InvalidInput(ErrorCode::invalid_parameter,
                         "box-assisted search with box size " + detail::format_number(box) + ": it must be positive and finite");
    const std::size_t count = points.size();
    double hi = lo = count ? points(0, 0) : 0.0;
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t a = 0; a < axes; ++a) {
        lo = std::min(lo, points(i, a));
        hi = std::max(hi, points(i, a));
      }
    slack = 1e-12 * (hi - lo);
    // Boxes per axis, capped so that the grid holds at most max(4 N, 1024) boxes.
    const double cap_boxes = std::max(4.0 * static_cast<double>(count), 1024.0);
    const spatial::GridAxis x_axis = spatial::GridAxis::over(lo, hi, box, axes == 1 ? cap_boxes : std::floor(std::sqrt(cap_boxes)));
    const spatial::GridAxis y_axis = axes == 2 ? x_axis : spatial::GridAxis{lo, x_axis.side, 1};
    side = x_axis.side;
    nx = x_axis.boxes;
    ny = y_axis.boxes;
    grid = spatial::BoxGrid(count, x_axis, y_axis, [&](std::size_t i) { return points(i, 0); },
                            [&](std::size_t i) { return axes == 2 ? points(i, 1) : lo; });
    coords_.resize(count * dim);
    const std::vector<std::size_t>& order = grid.order();
    for (std::size_t pos = 0; pos < count; ++pos)
      for (std::size_t k = 0; k < dim; ++k) coords_[pos * dim + k] = points(order[pos], k);
  }

  std::size_t column_of(std::size_t i) const noexcept { return grid.columns().box_of(points(i, 0)); }
  std::size_t row_of(std::size_t i) const noexcept { return axes == 2 ? grid.rows().box_of(points(i, 1)) : 0; }
  // The last ring that holds any box: beyond it the whole grid has been seen.
  std::size_t last_ring(std::size_t x, std::size_t y) const noexcept {
    return std::max(std::max(x, nx - 1 - x), std::max(y, ny - 1 - y));
  }
  // Lower bound of the distance from the query to any point outside rings 0..rho.
  double reach(std::size_t rho) const noexcept { return static_cast<double>(rho) * side - slack; }

  // Calls f(begin, end) for the position ranges of the boxes of ring rho around (x, y): the rows
  // y - rho and y + rho whole, and the two end columns of the rows between them.
  template <class F>
  void ring(std::size_t x, std::size_t y, std::size_t rho, F&& f) const {
    const auto range = [&](std::size_t row, std::size_t x0, std::size_t x1) {  // x0 <= x1 < nx
      f(grid.start()[row * nx + x0], grid.start()[row * nx + x1 + 1]);
    };
    const std::size_t x0 = x >= rho ? x - rho : 0, x1 = std::min(nx - 1, x + rho);
    if (rho == 0) {
      range(y, x, x);
      return;
    }
    if (y >= rho) range(y - rho, x0, x1);
    if (y + rho < ny) range(y + rho, x0, x1);
    const std::size_t y0 = y >= rho ? y - rho + 1 : 0, y1 = std::min(ny - 1, y + rho - 1);
    for (std::size_t row = y0; row <= y1; ++row) {
      if (x >= rho) range(row, x - rho, x - rho);
      if (x + rho < nx) range(row, x + rho, x + rho);
    }
  }

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

  template <class Metric, std::size_t D>
  std::size_t count(const double* q, std::size_t i, double radius, const NeighborQuery& query) const {
    const std::size_t x = column_of(i), y = row_of(i), last = last_ring(x, y);
    std::size_t found = 0;
    for (std::size_t rho = 0; rho <= last; ++rho) {
      ring(x, y, rho, [&](std::size_t begin, std::size_t end) {
        for (std::size_t pos = begin; pos < end; ++pos) {
          if (within_window(i, grid.order()[pos], query.theiler)) continue;
          const double d = point_distance<Metric, D>(q, pos, radius);
          if (d < radius && !(query.skip_zero_distance && d == 0.0)) ++found;
        }
      });
      if (reach(rho) >= radius) break;
    }
    return found;
  }

  template <class Metric, std::size_t D>
  void nearest(const double* q, std::size_t i, std::size_t k, std::vector<Neighbor>& out,
               const NeighborQuery& query) const {
    const std::size_t x = column_of(i), y = row_of(i), last = last_ring(x, y);
    double bound = infinity;  // the k-th distance once there are k candidates
    std::size_t bound_index = 0;
    for (std::size_t rho = 0; rho <= last; ++rho) {
      ring(x, y, rho, [&](std::size_t begin, std::size_t end) {
        for (std::size_t pos = begin; pos < end; ++pos) {
          const std::size_t j = grid.order()[pos];
          if (within_window(i, j, query.theiler)) continue;
          const double d = point_distance<Metric, D>(q, pos, bound);
          if (query.skip_zero_distance && d == 0.0) continue;
          if (!(d < bound || (d == bound && j < bound_index))) continue;
          const Neighbor n{j, d};
          out.insert(std::upper_bound(out.begin(), out.end(), n, before), n);
          if (out.size() > k) out.pop_back();
          if (out.size() == k) {
            bound = out.back().distance;
            bound_index = out.back().index;
          }
        }
      });
      // Strict: a point beyond can neither beat nor tie the k-th.
      if (out.size() == k && bound < reach(rho)) break;
    }
  }

  template <class F>
  auto dispatch(F&& f) const {
    return detail::dispatch_metric<8>(norm, dim, f);
  }
  template <class F>
  auto with_query(std::size_t i, F&& f) const {
    return detail::with_point(points, i, f);
  }
};

BoxGrid::BoxGrid(const DelayEmbedding& points, Norm norm, double box) : impl_(std::make_unique<Impl>(points, norm, box)) {}
BoxGrid::~BoxGrid() = default;
BoxGrid::BoxGrid(BoxGrid&&) noexcept = default;
BoxGrid& BoxGrid::operator=(BoxGrid&&) noexcept = default;

double BoxGrid::box_for(const DelayEmbedding& points, double per_box) {
  const std::size_t axes = std::min<std::size_t>(points.dimension(), 2);
  double lo = infinity, hi = -infinity;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t a = 0; a < axes; ++a) {
      lo = std::min(lo, points(i, a));
      hi = std::max(hi, points(i, a));
    }
  if (!(hi > lo)) return 1.0;
  const double boxes = std::max(1.0, static_cast<double>(points.size()) / std::max(per_box, 1.0));
  return (hi - lo) / std::max(1.0, std::ceil(axes == 1 ? boxes : std::sqrt(boxes)));
}

std::size_t BoxGrid::count_within(std::size_t i, double radius, const NeighborQuery& query) const {
  const Impl& g = *impl_;
  if (std::isnan(radius)) throw InvalidInput(ErrorCode::invalid_parameter, "neighbour count radius is NaN");
  return g.with_query(i, [&](const double* q) {
    return g.dispatch([&]<class Metric, std::size_t D>() { return g.count<Metric, D>(q, i, radius, query); });
  });
}

void BoxGrid::k_nearest(std::size_t i, std::size_t k, std::vector<Neighbor>& out, const NeighborQuery& query) const {
  const Impl& g = *impl_;
  if (k == 0) throw InvalidInput(ErrorCode::invalid_parameter, "k nearest neighbours with k = 0: k must be at least 1");
  out.clear();
  g.with_query(i, [&](const double* q) {
    return g.dispatch([&]<class Metric, std::size_t D>() {
      g.nearest<Metric, D>(q, i, k, out, query);
      return 0;
    });
  });
}

double BoxGrid::box() const noexcept { return impl_->side; }
std::size_t BoxGrid::boxes() const noexcept { return impl_->nx * impl_->ny; }

std::size_t BoxGrid::memory_bytes() const noexcept {
  const Impl& g = *impl_;
  return g.grid.memory_bytes() + g.coords_.capacity() * sizeof(double);
}

}  // namespace chaos
