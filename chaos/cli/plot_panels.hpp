#pragma once
// The gnuplot panels that a single command draws alone (mutual, cao, fnn, d2) and `chaos analyze`
// draws together in its 2x2 figure. Each writes its settings, its plot line and its inline data to
// `s`; the caller writes what surrounds it (grid, multiplot, and between panels the reset of what a
// panel set: arrows, labels, objects, log scales, ranges and offsets).

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>

#include "chaos/cao.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/fnn.hpp"
#include "chaos/mutual_information.hpp"

namespace chaos::cli {

// I(tau) against the delay (in time units when `dt` is given), `mark` (a delay in samples) shown by
// a dashed line and a circle with the key `mark_title`.
void mutual_information_panel(std::ostream& s, const MutualInformationResult& result,
                              const std::optional<std::size_t>& mark, const std::string& mark_title,
                              const std::string& title,
                              const std::optional<double>& dt = std::nullopt, double point_size = 0.4);
// E1(m) and E2(m) against m, the level 1 and the saturation dimension marked.
void cao_panel(std::ostream& s, const CaoResult& result, const std::string& title, double point_size = 0.8);
// The false fraction against m, the threshold and the dimension chosen marked.
void fnn_panel(std::ostream& s, const FnnResult& result, double threshold, const std::string& title,
               double point_size = 0.8);
// The local slopes d ln C / d ln eps per m (a dimension without any slope left out), the scaling
// region shaded and D2 marked; with no slope at all, an empty frame that says so.
void local_slopes_panel(std::ostream& s, const CorrelationDimensionResult& d2, const std::string& title,
                        double point_size = 0.4);

}  // namespace chaos::cli
