#pragma once
// Locating the time at which a scalar event function g(t) (a contact gap evaluated on a stepper's
// dense output) changes sign inside a step [t0, t1].
//
// Method: the Illinois variant of regula falsi (M. Dowell & P. Jarratt, "A modified regula falsi
// method for computing the root of an equation", BIT 11 (1971) 168-174): the secant through the two
// bracket ends, and when the same end is kept twice in a row its g value is halved so that it moves
// too (order about 1.442 instead of plain regula falsi's linear convergence). Safeguards:
// every trial point is kept at least time_tolerance/2 inside the bracket, and if three iterations
// have not halved the bracket the next point is the midpoint, so the cost is never worse than
// about three times bisection. The bracket is kept throughout: the answer is always between two
// points with opposite signs of g.
//
// Only sign changes between the step ends are seen: a contact that opens and closes inside one
// step, or a gap that touches zero without crossing it (grazing), leaves g(t0), g(t1) with the same
// sign and is not an event here. locate_crossing refuses such a "bracket" (InvalidParameter) rather
// than return a time that is not a crossing.

#include <cstddef>
#include <functional>

namespace mechanism {

// The final bracket: g(before) has the sign of g0, g(after) the sign of g1 (or is exactly zero, in
// which case before == after), after - before <= time_tolerance unless the two are adjacent doubles.
struct CrossingBracket {
  double before = 0, after = 0;
  double g_before = 0, g_after = 0;
  std::size_t evaluations = 0;  // calls of g
};

// g0 = g(t0), g1 = g(t1) of opposite signs, or one of them zero (then that end is returned at no
// cost). Requires t0 < t1, time_tolerance > 0, everything finite; g must stay finite (else
// InvalidParameter "g").
CrossingBracket bracket_crossing(const std::function<double(double)>& g, double t0, double t1, double g0, double g1,
                                 double time_tolerance);

// The crossing time within time_tolerance: the bracket's `after` end, the first time at which g has
// taken g1's sign (or is zero). Stepping the state exactly there puts it just past the switching
// surface, so the event is seen as having happened and is not detected a second time.
double locate_crossing(const std::function<double(double)>& g, double t0, double t1, double g0, double g1,
                       double time_tolerance);

}  // namespace mechanism
