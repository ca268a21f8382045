#pragma once
// Cao's method for the minimum embedding dimension (Cao 1997, Physica D 110, 43; seed Eq. 34-35).
// For each m, every point X_i(m), i < N - m tau, finds its nearest neighbour X_n(m) (max norm by
// default, Theiler window excluded) and
//   a(i, m) = |X_i(m+1) - X_n(m+1)| / |X_i(m) - X_n(m)|,   E(m)  = mean of a(i, m),
//   E*(m)   = mean of |x_{i+m tau} - x_{n+m tau}|,
//   E1(m)   = E(m+1)/E(m),   E2(m) = E*(m+1)/E*(m).
// Ties: a neighbour at distance 0 (quantised data) would make a(i, m) infinite; as in Cao (1997)
// and TISEAN, the nearest neighbour at a positive distance is used instead, and a point whose
// every admissible candidate is at distance 0 is left out (counted in `points_without_neighbor`).

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "chaos/norm.hpp"

namespace chaos {

struct CaoOptions {
  std::size_t delay = 1;          // -d
  std::size_t min_dimension = 1;  // -m
  std::size_t max_dimension = 10; // -M: E1 and E2 are reported for m = min .. max
  std::size_t theiler = 0;        // -t
  Norm norm = Norm::max;
  // Saturation rule: the embedding dimension is the smallest m whose E1(m') >= 1 - tolerance for
  // every m' >= m in the range.
  double saturation_tolerance = 0.1;
  void validate() const;
};

struct CaoResult {
  std::vector<std::size_t> dimension;  // m = min .. max
  std::vector<double> E, E_star;       // E(m), E*(m) for the same m (plus one more internally)
  std::vector<double> E1, E2;          // E1(m), E2(m)
  std::optional<std::size_t> embedding_dimension;  // nullopt: "not saturated" within the range
  double max_E2_deviation = 0.0;       // max |E2(m) - 1|: near 0 for a stochastic series
  std::vector<std::size_t> points_without_neighbor;  // per m, see Ties above
};

CaoResult cao(std::span<const double> x, const CaoOptions& options = {});

}  // namespace chaos
