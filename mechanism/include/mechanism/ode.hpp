#pragma once
// The vocabulary shared by the integrators (Boost.Odeint's system / stepper / observer split, with a
// C++20 concept in place of its overloads). A *system* is any type with a const member
//   rhs(t, x, dxdt)
// that writes dx/dt at (t, x) into dxdt. The steppers pass a dxdt already sized like x, so a system
// should assign into it element by element (or with a same-size Eigen expression) and never
// reallocate: the simulator calls rhs tens of millions of times. Discrete memory a system keeps
// (contact flags, the velocity at impact, ...) may be changed by the caller between steps; the
// stepper must then be told with invalidate(), because it reuses f(t, x) from the previous step.

#include <Eigen/Core>

namespace mechanism {

using State = Eigen::VectorXd;

template <class S>
concept OdeSystem = requires(const S& s, double t, const State& x, State& dxdt) {
  s.rhs(t, x, dxdt);
};

// Optional: a system whose step-end state has components that will be discarded between steps
// (a LuGre bristle deflection is reset to zero when its contact opens) writes weight 0 for them
// and 1 for the others; the adaptive stepper leaves the discarded ones out of its error norm, so
// it does not shrink the step to resolve a value nobody keeps.
template <class S>
concept ErrorWeightedSystem = OdeSystem<S> && requires(const S& s, double t, const State& x, State& w) {
  s.error_weights(t, x, w);
};

// Optional, for speed: an ErrorWeightedSystem that gives dx/dt and the weights at the same (t, x)
// from one evaluation. The adaptive stepper weighs its error at the step end, where it also
// evaluates dx/dt for the next step's first stage (FSAL), so this saves one evaluation per step.
// Both outputs must equal what rhs() and error_weights() give at (t, x).
template <class S>
concept WeightedRhsSystem =
    ErrorWeightedSystem<S> && requires(const S& s, double t, const State& x, State& dxdt, State& w) {
      s.rhs_and_error_weights(t, x, dxdt, w);
    };

namespace detail {

// Out of line (mechanism/src/integrators.cpp) so that the throwing path stays out of the inlined
// stepping code. Throws InvalidParameter(key, value formatted to round-trip, rule).
[[noreturn]] void throw_invalid(const char* key, double value, const char* rule);

// Bit-for-bit equality of two states of any size: how a stepper decides that the caller handed it
// back the state it produced, so that f(t1, x1) may serve as the next step's first stage.
inline bool same_state(const State& a, const State& b) { return a.size() == b.size() && a == b; }

}  // namespace detail
}  // namespace mechanism
