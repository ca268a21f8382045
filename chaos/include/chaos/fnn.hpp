#pragma once
// False nearest neighbours (Kennel, Brown & Abarbanel 1992, Phys. Rev. A 45, 3403). The nearest
// neighbour n of X_i(m) (Theiler window excluded) is false in m + 1 dimensions if
//   |x_{i+m tau} - x_{n+m tau}| / R_m(i) > Rtol          (criterion 1), or
//   R_{m+1}(i) / R_A > Atol, R_A the standard deviation of the series (criterion 2).
// Distances are Euclidean by default, as in Kennel et al.; ties at distance 0 are skipped as in Cao.

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "chaos/norm.hpp"

namespace chaos {

struct FnnOptions {
  std::size_t delay = 1;
  std::size_t min_dimension = 1;
  std::size_t max_dimension = 10;
  std::size_t theiler = 0;
  double rtol = 10.0;
  double atol = 2.0;
  Norm norm = Norm::euclidean;
  // The embedding dimension is the smallest m whose false fraction is at most this.
  double threshold = 0.01;
  std::size_t threads = 1;  // share the neighbour searches; results identical for any number
  // Called with the fraction done (0 to 1), for a progress display; the result does not depend on it.
  std::function<void(double)> progress = nullptr;
  void validate() const;
};

struct FnnResult {
  std::vector<std::size_t> dimension;
  std::vector<double> false_fraction;
  std::optional<std::size_t> embedding_dimension;  // nullopt: the fraction never fell to threshold
  // A sentence when most pairs of samples tie (quantised data; ties_note, series.hpp), else empty.
  std::string value_ties;
};

FnnResult false_nearest_neighbors(std::span<const double> x, const FnnOptions& options = {});

}  // namespace chaos
