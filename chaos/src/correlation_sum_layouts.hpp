#pragma once
// The points of a correlation-sum problem copied in a search structure's order, one contiguous
// array per coordinate, which is what the candidate scans read: the grid of rows and the kd-tree.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "correlation_sum_problem.hpp"
#include "spatial/kd_tree.hpp"

namespace chaos::correlation_detail {

// Points copied in a search structure's order, one contiguous array per coordinate, which is what
// the candidate scans read (the grid and the kd-tree each lay the points out their way).
struct PointLayout {
  std::size_t size = 0;
  std::vector<double> coords;  // coordinate k of the point at position p: coords[k * size + p]
  std::vector<std::size_t> index;  // the embedded point at position p
  const double* coordinate(std::size_t k) const noexcept { return coords.data() + k * size; }
};

// m >= 2: a grid over the first two coordinates. Points are grouped into rows by coordinate 1
// (row height h >= r_max) and sorted by coordinate 0 within a row. A pair closer than r_max in any
// m >= 2 has acc(coordinate difference) < t_max in coordinates 0 and 1 (the accumulator only
// grows), hence differs by less than h in coordinate 1 and lies in the same or adjacent rows, and
// it lies inside the coordinate-0 window of the other point. Each unordered pair is visited once,
// from its lower row (same row: from the earlier position).
struct Grid : PointLayout {
  struct Row {
    std::int64_t id;
    std::size_t begin, end;
  };
  std::vector<Row> rows;
  struct Chunk {
    std::size_t row, begin, end;
  };
  std::vector<Chunk> chunks;
};

// The grid of rows for the problem's r_max, in chunks of at most chunk_points positions.
Grid build_grid(const Problem& pb);

// ---------------------------------------------------------------------------------------------
// kd-tree: one traversal per point for every radius and every m >= 2.
//
// The tree splits the first c = max(2, min_m) coordinates: a pair that counts in some m >= min_m
// has acc < t_max in those coordinates already (the accumulator only grows). The tree is
// spatial::KdTree with at most `leaf_points` points per leaf; the points are copied in leaf order, every coordinate contiguous, as the grid copies them, so a leaf is a run of
// positions that the grid's candidate scan filters level by level and bins for every m at once. A
// point visits the leaves whose box lies within t_max of it in the c coordinates (a lower bound
// of every accumulator inside, as rounding is monotone), and in the exact walk only the positions
// after its own, so each unordered pair is examined once. m = 1 and the Theiler window are done as
// in the box-assisted walk.
struct KdLayout : PointLayout {
  static constexpr std::size_t leaf_points = 128;
  spatial::KdTree tree;                // over the c split coordinates
  std::vector<std::size_t> position;  // the position of each embedded point

  // Lower bound of the accumulator in the c split coordinates from the point at position p to
  // any point of node n.
  template <class N>
  double near(std::size_t n, std::size_t p) const noexcept {
    const double* b = tree.box(n);
    double acc = 0.0;
    for (std::size_t k = 0; k < tree.dims(); ++k) {
      const double q = coordinate(k)[p], lo = b[2 * k], hi = b[2 * k + 1];
      acc = N::add(acc, q < lo ? lo - q : (q > hi ? q - hi : 0.0));
    }
    return acc;
  }
};

// The kd-tree over the first max(2, min_m) coordinates of the problem's points.
KdLayout build_kd(const Problem& pb);

}  // namespace chaos::correlation_detail
