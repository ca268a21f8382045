#pragma once
// Reference systems with known invariants, used by `chaos generate`, the tests and the benchmarks.
// Each generator documents its integrator, internal step, sampling interval, transient and the
// initial condition; stochastic ones take an explicit seed. Results are bit-reproducible.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace chaos {

// A sampled trajectory: components[k][n] is component k at sample n, taken every dt time units
// (dt = 1 for maps and discrete noise).
struct Trajectory {
  std::vector<std::string> names;  // component names, e.g. {"x", "y", "z"}
  std::vector<std::vector<double>> components;
  double dt = 1.0;
  std::size_t size() const noexcept { return components.empty() ? 0 : components.front().size(); }
};

// Sampling of a flow: integrated with classical RK4 at `step`, sampled every `dt` (a whole multiple
// of the step), after discarding `transient` time units.
struct FlowSampling {
  double dt = 0.01;
  double step = 0.001;
  double transient = 100.0;
  void validate() const;
};

struct LorenzParameters { double sigma = 10.0, rho = 28.0, beta = 8.0 / 3.0; };
struct RosslerParameters { double a = 0.2, b = 0.2, c = 5.7; };
struct HenonParameters { double a = 1.4, b = 0.3; };
struct LogisticParameters { double r = 4.0; };
struct IkedaParameters { double mu = 0.9, a = 0.4, b = 6.0; };
// dx/dt = beta x(t - tau) / (1 + x(t - tau)^n) - gamma x(t), the form of Mackey & Glass (1977)
// used by Grassberger & Procaccia (1983).
struct MackeyGlassParameters { double beta = 0.2, gamma = 0.1, n = 10.0, tau = 17.0; };

Trajectory lorenz(std::size_t n, const LorenzParameters& p = {}, const FlowSampling& s = {});
Trajectory rossler(std::size_t n, const RosslerParameters& p = {},
                   const FlowSampling& s = {0.1, 0.01, 500.0});
Trajectory henon(std::size_t n, const HenonParameters& p = {}, std::size_t transient = 1000);
Trajectory logistic(std::size_t n, const LogisticParameters& p = {}, std::size_t transient = 1000,
                    std::uint64_t seed = 1);
Trajectory ikeda(std::size_t n, const IkedaParameters& p = {}, std::size_t transient = 1000);
// Delay equation: RK4 at step tau/steps_per_delay with the history kept on the step grid and the
// half-step delayed values taken by cubic Hermite interpolation; constant initial history 1.2.
Trajectory mackey_glass(std::size_t n, const MackeyGlassParameters& p = {}, double dt = 1.0,
                        std::size_t steps_per_delay = 170, double transient = 1000.0);
// x(t) = sin(2 pi f t), sampled every dt.
Trajectory sine(std::size_t n, double frequency = 1.0, double dt = 0.01);
// x(t) = sin(2 pi f1 t) + sin(2 pi f2 t) with incommensurate f2/f1 (default the golden mean).
Trajectory quasi_periodic(std::size_t n, double f1 = 1.0, double f2 = 1.6180339887498949,
                          double dt = 0.05);
Trajectory white_noise(std::size_t n, std::uint64_t seed = 1);
// Independent samples uniform in [0, 1): in any delay embedding with a Theiler window of at least
// m - 1 the pairs are pairs of independent uniform points in the unit cube (D2 = m).
Trajectory uniform_noise(std::size_t n, std::uint64_t seed = 1);
// x[t] = phi x[t-1] + e[t], e ~ N(0, 1), started from the stationary distribution.
Trajectory ar1(std::size_t n, double phi = 0.9, std::uint64_t seed = 1);

}  // namespace chaos
