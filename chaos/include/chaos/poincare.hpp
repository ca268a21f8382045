#pragma once
// Poincaré sections of sampled trajectories, and the histogram that turns a set of section points
// into a probability density (one column of a bifurcation diagram's PDF, as the seed's Fig. 4b and 5).
//
//   stroboscopic_section  every `period`-th sample from `phase` on: the section of a system driven
//                         with a period that is a whole number of samples;
//   hyperplane_section    the crossings of one component through a level (x_k = c) by a flow
//                         sampled every dt: each crossing is located on the cubic through the four
//                         samples around it (Lagrange interpolation, error O(dt^4) for a smooth
//                         flow; linear at the ends of the record), and every component is
//                         interpolated there; return times are the differences of crossing times;
//   distinct_values       how many branches a section has: values are sorted and split where two
//                         neighbours differ by more than a tolerance (period-k orbits give k);
//   probability_density   a histogram normalised to unit integral over [low, high].
//
// The same sections for samples that arrive one at a time (a simulation's observer) are in
// section_stream.hpp; densities over a parameter sweep (bifurcation diagrams) in bifurcation.hpp.

#include <cstddef>
#include <span>
#include <vector>

namespace chaos {

// Samples phase, phase + period, phase + 2 period, ... Refuses period = 0 and phase >= size.
std::vector<double> stroboscopic_section(std::span<const double> series, std::size_t period, std::size_t phase = 0);

enum class CrossingDirection { upward, downward, both };

struct HyperplaneOptions {
  std::size_t component = 0;  // k in x_k = level
  double level = 0.0;
  CrossingDirection direction = CrossingDirection::upward;
};

struct HyperplaneSection {
  std::vector<double> times;                // crossing times (dt units, from sample 0)
  std::vector<std::vector<double>> points;  // points[j]: every component at crossing j
  std::vector<double> return_times;         // times[j + 1] - times[j]
};

// components[k][n]: component k at sample n (all the same length, at least 2), dt > 0. Refuses
// ragged or non-finite input and a component index out of range.
HyperplaneSection hyperplane_section(const std::vector<std::vector<double>>& components, double dt,
                                     const HyperplaneOptions& options = {});

// The number of groups of values that lie within `tolerance` of their neighbours (after sorting).
std::size_t distinct_values(std::span<const double> values, double tolerance);

struct Histogram {
  std::vector<double> edges;    // bins + 1 edges from low to high
  std::vector<double> density;  // per bin: count / (in-range count x width); integrates to 1
  std::size_t in_range = 0;     // values counted (low <= v <= high)
  std::size_t out_of_range = 0;
};

// Equal-width bins over [low, high] (the last bin closed). Refuses bins = 0, low >= high,
// non-finite values and an empty input.
Histogram probability_density(std::span<const double> values, std::size_t bins, double low, double high);

}  // namespace chaos
