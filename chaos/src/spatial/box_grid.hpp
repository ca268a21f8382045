#pragma once
// The library's box grid: points sorted into boxes over two coordinates (Grassberger 1990; the
// boxes of TISEAN), numbered row by row, box = row * columns + column, with the columns over one
// coordinate and the rows over another. A counting sort fills the boxes, so each box holds its
// points in ascending index order, and the boxes' points are contiguous in `order`.
//
// The searches that walk it keep their own rules: the neighbour search (box_grid.cpp) looks at the
// boxes around a query ring by ring; the correlation sum's exact walk uses one column and rows at
// least r_max high, sorts each row by coordinate 0 and sweeps pairs of adjacent rows.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace chaos::spatial {

// One axis of a grid: `boxes` boxes of width `side` from `lo`. A value's box is
// floor((v - lo) / side), clamped to the axis (the clamp only meets rounding); with an infinite side
// every value is in box 0.
struct GridAxis {
  double lo = 0.0;
  double side = std::numeric_limits<double>::infinity();
  std::size_t boxes = 1;

  std::size_t box_of(double v) const noexcept {
    const double c = std::floor((v - lo) / side);
    return c <= 0.0 ? 0 : std::min(static_cast<std::size_t>(c), boxes - 1);
  }

  // Boxes of width `side` (positive) over [lo, hi], at most max_boxes of them (at least 2): the side
  // is enlarged to (hi - lo) / (max_boxes - 1) when more would be needed.
  static GridAxis over(double lo, double hi, double side, double max_boxes) noexcept {
    const double range = hi - lo;
    double per_axis = std::floor(range / side) + 1.0;
    if (per_axis > max_boxes) {
      per_axis = max_boxes;
      side = range / (max_boxes - 1.0);
    }
    return {lo, side, static_cast<std::size_t>(per_axis)};
  }
};

class BoxGrid {
 public:
  BoxGrid() = default;

  // `count` points, column_value(i) and row_value(i) being point i's coordinates along the two axes.
  template <class ColumnValue, class RowValue>
  BoxGrid(std::size_t count, GridAxis columns, GridAxis rows, const ColumnValue& column_value, const RowValue& row_value)
      : columns_(columns), rows_(rows) {
    const std::size_t boxes = columns.boxes * rows.boxes;
    // Each point's box is computed twice (count, then place): cheaper than storing N of them.
    const auto box = [&](std::size_t i) { return rows.box_of(row_value(i)) * columns.boxes + columns.box_of(column_value(i)); };
    start_.assign(boxes + 1, 0);
    for (std::size_t i = 0; i < count; ++i) ++start_[box(i) + 1];
    for (std::size_t b = 0; b < boxes; ++b) start_[b + 1] += start_[b];
    std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
    order_.resize(count);
    for (std::size_t i = 0; i < count; ++i) order_[next[box(i)]++] = i;
  }

  const GridAxis& columns() const noexcept { return columns_; }
  const GridAxis& rows() const noexcept { return rows_; }
  std::size_t boxes() const noexcept { return columns_.boxes * rows_.boxes; }
  // Box b's points are order()[start()[b] .. start()[b + 1]).
  const std::vector<std::size_t>& start() const noexcept { return start_; }
  const std::vector<std::size_t>& order() const noexcept { return order_; }
  // The same positions, for a caller that reorders the points inside each box.
  std::vector<std::size_t>& order() noexcept { return order_; }

  std::size_t memory_bytes() const noexcept { return (start_.capacity() + order_.capacity()) * sizeof(std::size_t); }

 private:
  GridAxis columns_, rows_;
  std::vector<std::size_t> start_, order_;
};

}  // namespace chaos::spatial
