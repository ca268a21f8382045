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
#include <functional>
#include <string>
#include <vector>

#include "chaos/norm.hpp"

namespace chaos {

struct CaoOptions {
  std::size_t delay = 1;          // -d
  std::size_t min_dimension = 1;  // -m
  std::size_t max_dimension = 10; // -M: E1 and E2 are reported for m = min .. max
  std::size_t theiler = 0;        // -t
  Norm norm = Norm::max;
  // Saturation ("E1 stops changing", Cao 1997): the smallest m with E1(m) >= saturation_level
  // from which every later step |E1(m'+1) - E1(m')| <= saturation_change; at least one later step
  // must be observed, so m = max alone never counts. The level keeps a slow, steady rise far below
  // 1 (as for noise or too small an N) from passing as saturation.
  double saturation_level = 0.8;
  double saturation_change = 0.1;
  // Stochastic series (Cao 1997): E2(m) = 1 for every m. Judged against E2's own sampling error:
  // stochastic when every |E2(m) - 1| <= stochastic_sigmas standard errors.
  double stochastic_sigmas = 4.0;
  std::size_t threads = 1;  // share the neighbour searches; results identical for any number
  // Called with the fraction done (0 to 1), for a progress display; the result does not depend on it.
  std::function<void(double)> progress = nullptr;
  void validate() const;
};

struct CaoResult {
  std::vector<std::size_t> dimension;  // m = min .. max
  std::vector<double> E, E_star;       // E(m), E*(m) for the same m (E*(m) in the units of x)
  std::vector<double> E1, E2;          // E1(m), E2(m)
  std::vector<double> E2_standard_error;  // from the spread of |x_{i+m tau} - x_{n+m tau}|
  std::optional<std::size_t> e1_saturation;  // where E1 stops changing; nullopt: "not saturated"
  bool stochastic = false;             // E2 consistent with 1 for every m: no deterministic structure
  // The minimum embedding dimension: e1_saturation, unless the series is stochastic (a random
  // series has no finite embedding dimension). nullopt in either case.
  std::optional<std::size_t> embedding_dimension;
  double max_E2_deviation = 0.0;       // max |E2(m) - 1|
  std::vector<std::size_t> points_without_neighbor;  // per m, see Ties above
  // A sentence when most pairs of samples tie (quantised data; ties_note, series.hpp), else empty.
  std::string value_ties;
};

CaoResult cao(std::span<const double> x, const CaoOptions& options = {});

// The saturation rule of CaoOptions applied to an E1 curve (dimension[k], E1[k]); nullopt when E1
// never settles within the range.
std::optional<std::size_t> e1_saturation(std::span<const std::size_t> dimension, std::span<const double> E1,
                                         double level, double change);

}  // namespace chaos
