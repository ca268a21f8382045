#pragma once
// The finite-record D2 reference of a zoo system: what the attractor itself shows at the same N,
// Theiler window and scales as a delay embedding of one of its components.
//
// A D2 band around a zero-scale value (Sprott's extrapolations, D_KY) holds a finite record to a
// different quantity: a plateau at N = 10^4-10^5 sits below the extrapolation on many attractors,
// in the state itself as much as in any embedding (Rossler reads 1.88-1.95 in its own state at
// N = 2*10^4, dysts' full-state estimate at N = 9000 is 1.797, TISEAN's plateau on Rossler x
// 1.80-1.89, against Sprott's 2.01; docs/notes/zoo-state-space.md). So the reference is computed
// from the equations: the correlation sums of the full state (every component, maximum norm) over
// the same N samples, with the same Theiler window and the same radii relative to the set's
// diameter (range/1000 to range/4, as choose_radii), read by the same plateau rules
// (correlation_dimension.hpp with the state as its one "dimension") and answered as d2_answer does.
// No embedding is involved, so the reference shares none of the embedding's choices (delay,
// dimension, saturation), only the record.
//
// The reading must not depend on how the state is written down. D2 is invariant under a smooth change
// of coordinates, but a plateau at finite N and scales is not: with each component scaled to a
// common range, Sprott E reads 1.733 instead of 1.575, Sprott's jerk flow 1.276 instead of 1.748 and
// Moore-Spiegel 1.668 instead of 1.314 at N = 10^5 (docs/notes/zoo-state-space.md), and the Ricker
// map's state, a tenth of whose values lie within 0.0072 of 0 in a range of 3, reads 0.54 where the
// map's graph (x_i, x_{i+1}) stretches that cluster 27-fold. So the reference is also read in other
// codings of the same samples (state_codings); where one of them differs from the state's own by
// more than the band's 0.1, or shows no plateau, the reading belongs to the coordinates, not to the
// attractor, and the zoo holds the row to its fallback band instead (zoo_suite.hpp).
//
// The state: every variable of the equations, except that a forced flow's phase phi (which grows
// without bound) becomes (A cos phi, A sin phi), with A half the largest range of the other
// variables: a smooth embedding of the circle it lives on, which keeps D2, at a scale comparable
// with the rest. Delay equations have a function as their state: no reference (empty).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "chaos/correlation_sum.hpp"
#include "chaos/estimate.hpp"
#include "chaos/models/zoo.hpp"

namespace chaos {

// The state of n samples of the system at its default sampling (the samples of zoo_trajectory), as
// components [variable][sample]; empty for a delay equation.
std::vector<std::vector<double>> zoo_state(const ZooEntry& entry, std::size_t n);

// Correlation sums of the points (component c of point i: components[c][i]) under the maximum
// norm, counting d < r outside a Theiler window |i - j| > w, one result per window in `theilers`;
// each result has one "dimension": the number of components. Pairs are compared in the order of the
// first component, so only those closer than the largest radius in it are.
//   pairs_per_radius = 0: exact, every pair i < j once (the counts equal brute force; a test).
//   pairs_per_radius > 0: reference points in a seeded random order, each with its partners on both
//     sides; a radius stops counting once the smallest window has counted that many pairs within
//     it, and its C is the pairs over the pairs examined until then (TISEAN d2's -N pair cap;
//     Grassberger, Phys. Lett. A 148, 63 (1990)). Large radii close after a few reference points,
//     so the cost is that of the small radii. The relative error of C(r) is about 1/sqrt(cap).
std::vector<CorrelationSumResult> state_correlation_sums(const std::vector<std::vector<double>>& components,
                                                         const std::vector<double>& radii,
                                                         std::span<const std::size_t> theilers,
                                                         std::uint64_t pairs_per_radius = 0, std::uint64_t seed = 1);

// A way of writing down the same states: its name, as the report gives it, and its components.
struct StateCoding {
  std::string name;
  std::vector<std::vector<double>> components;
};

// The codings the reference is read in besides the state's own: every component scaled to the
// largest one's range (a linear change of coordinates; only where there are two or more), and, for
// a map, each state beside its image, (s_i, s_{i+1}) for i < n - 1 (the graph of the map, a smooth
// embedding of the same attractor; a flow sampled finely moves too little in one sample for this
// coding to differ from its own, so flows are not read in it).
std::vector<StateCoding> state_codings(const std::vector<std::vector<double>>& components, bool map);

// The radii of the reference for n samples of a state: choose_radii's grid (range/1000 to range/4,
// `count` radii) for the state's max-norm range (the largest range of its components).
std::vector<double> state_radii(const std::vector<std::vector<double>>& components, std::size_t count = 40);

// The reference D2 from a state's correlation sums: the plateau of its local slopes, read as
// correlation_dimension reads one dimension, as an answer before the floors (d2_reading,
// d2_answer.hpp): its interval is what the plateau itself reads, to which the zoo's band adds 0.1.
Estimate state_d2_reference(const CorrelationSumResult& sums);

}  // namespace chaos
