#pragma once
// A closed-form benchmark for the Lyapunov exponents of an impacting system: the harmonically
// forced linear oscillator against a rigid stop with Newton's restitution,
//
//   x'' + 2 zeta x' + x = amplitude cos(omega t)      while x < gap,
//   x' -> -restitution x'                              when x reaches gap moving toward it,
//
// (time in units of 1 / the natural frequency; Shaw & Holmes, J. Sound Vib. 90, 129 (1983) study
// this system; the saltation matrix is that of Mueller, Chaos Solitons Fractals 5, 1671 (1995), and
// of Nordmark, J. Sound Vib. 145, 279 (1991) for impacts). Between impacts the flow is linear and
// known exactly; the period-1 impacting orbit (one impact per forcing period T = 2 pi / omega)
// follows in closed form from it, and its Floquet multipliers are the eigenvalues of the exact
// monodromy of the flow over T times the saltation matrix of the impact:
//
//   S = [[-r, 0], [(1 + r) (F(t_i) - gap) / v_i, -r]],     F(t) = amplitude cos(omega t),
//
// v_i > 0 the speed before the impact at t_i (det S = r^2, so the multipliers' product is
// r^2 exp(-2 zeta T)). The exponents are ln|mu_j| / T.
//
// Beside the closed form, two numerical estimates of the same exponents on the stroboscopic map
// (one forcing period): Benettin's renormalisation with the variational equation integrated along
// the trajectory and the saltation matrix applied at every impact, and with finite differences
// (finite_difference_lyapunov.hpp, the method of `mechanism lyapunov`). Both integrate with
// Dormand-Prince 5(4) and locate each impact on its dense output (event_location.hpp).
// docs/reference/mechanism/lyapunov.md, "A closed-form benchmark", gives the table.

#include <array>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mechanism {

struct ImpactOscillator {
  double zeta = 0.05;         // damping ratio, in [0, 1)
  double amplitude = 1.0;     // forcing amplitude (> 0)
  double omega = 2.0;         // forcing frequency (> 0); T = 2 pi / omega
  double gap = 0.0;           // the stop's position (finite)
  double restitution = 0.8;   // r in (0, 1]
  double period() const;
  void validate() const;      // throws InvalidParameter naming the field
};

// A period-1 impacting orbit in closed form.
struct PeriodOneOrbit {
  double impact_time = 0.0;    // t_i in [0, T): when the impact happens, mod T
  double impact_velocity = 0.0;  // v_i > 0, just before it
  std::array<std::array<double, 2>, 2> monodromy{};  // exp(A T) S at the point just before the impact
  std::array<std::complex<double>, 2> multipliers{};  // its eigenvalues, |mu_1| >= |mu_2|
  std::array<double, 2> exponents{};                  // ln|mu_j| / T, descending
  bool stable = false;         // both |mu_j| < 1
};

// Every period-1 impacting orbit (0, 1 or 2 of them): the roots with v_i > 0 of the closed-form
// condition whose trajectory stays below the stop between its impacts (checked on 4000 points of
// the exact solution per period). Descending impact velocity.
std::vector<PeriodOneOrbit> period_one_orbits(const ImpactOscillator& system);

// The exact state (x, x') at time t from (x0, v0) at t0 with no impact in between.
std::array<double, 2> exact_flow(const ImpactOscillator& system, double t0, std::array<double, 2> y0, double t);

struct ImpactLyapunovOptions {
  std::size_t transient = 100;   // periods before averaging
  std::size_t periods = 2000;    // periods averaged (>= 10: the error comes from 10 block means)
  double relative_tolerance = 1e-11, absolute_tolerance = 1e-13;  // Dormand-Prince
  double perturbation = 1e-7;    // finite differences only
  std::uint64_t seed = 1;        // finite differences: the initial directions
  void validate() const;
};

struct ImpactLyapunov {
  std::string status = "completed";  // completed, or failed (message says why)
  std::string message;
  std::array<double, 2> exponents{};       // per unit time, QR order
  std::array<double, 2> standard_error{};  // from 10 block means
  std::size_t impacts = 0;                 // over the averaged periods (saltation_lyapunov only)
  std::size_t periods = 0;
};

// Benettin with the variational equation and the saltation matrix at each impact, from (x, x')
// at t = 0.
ImpactLyapunov saltation_lyapunov(const ImpactOscillator& system, std::array<double, 2> start,
                                  const ImpactLyapunovOptions& options = {});
// Benettin by finite differences (finite_difference_lyapunov.hpp) on the same map.
ImpactLyapunov finite_difference_impact_lyapunov(const ImpactOscillator& system, std::array<double, 2> start,
                                                 const ImpactLyapunovOptions& options = {});

}  // namespace mechanism
