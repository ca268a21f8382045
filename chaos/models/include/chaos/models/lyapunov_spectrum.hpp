#pragma once
// The full Lyapunov spectrum of a system known by its equations, by tangent dynamics with QR
// re-orthonormalisation (Benettin, Galgani, Giorgilli & Strelcyn 1980, Meccanica 15:9; Shimada &
// Nagashima 1979; Geist, Parlitz & Lauterborn 1990, Prog. Theor. Phys. 83:875): d tangent vectors
// Y are carried along the orbit, every renormalisation interval Y = Q R is factorised and the
// exponents are the averages of ln |R_ii|. Flows integrate the state and the variational equation
// dY/dt = J(x) Y together with classical RK4 (the same stages, so Y is exactly the Jacobian of the
// numerical RK4 map); maps multiply Jacobians. Exponents are base e: per time unit for flows, per
// iteration for maps. The Kaplan-Yorke (Lyapunov) dimension comes with every spectrum.
//
// The reference systems use the equations, parameter structs and initial conditions of
// chaos/models/systems.hpp; any other system is given as a vector field (or map) with its Jacobian.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "chaos/models/generate.hpp"
#include "chaos/models/systems.hpp"

namespace chaos {

// Flows: RK4 at `step`; QR every `renormalisation_interval` (a whole multiple of the step); the
// first `transient` time units (rounded to whole intervals) evolve state and tangent vectors without
// being averaged, so the vectors start the average aligned with the attractor's directions; the
// exponents average over `time` (a whole multiple of the interval).
struct FlowSpectrumOptions {
  double step = 0.01;
  double renormalisation_interval = 0.1;
  double transient = 100.0;
  double time = 10'000.0;
  void validate() const;
};

// Maps: QR every `renormalisation_interval` iterations; `transient` iterations are discarded as
// for flows; the exponents average over `iterations` (a whole multiple of the interval).
struct MapSpectrumOptions {
  std::size_t renormalisation_interval = 1;
  std::size_t transient = 1'000;
  std::size_t iterations = 1'000'000;
  void validate() const;
};

struct LyapunovSpectrum {
  std::vector<double> exponents;      // descending; per time unit (flows) or per iteration (maps)
  double sum = 0.0;                   // sum of the exponents: the mean of ln |det| per unit
  double kaplan_yorke_dimension = 0.0;
  std::variant<FlowSpectrumOptions, MapSpectrumOptions> settings;  // the options used
  std::vector<double> initial_state;  // the state the transient started from
  std::size_t renormalisations = 0;   // QR factorisations averaged (after the transient)
  double averaging_length = 0.0;      // time units (flows) or iterations (maps) averaged
};

// D_KY = j + (lambda_1 + ... + lambda_j) / |lambda_{j+1}| with j the largest index whose partial
// sum is >= 0 (Kaplan & Yorke 1979); 0 when lambda_1 < 0, d when the whole sum is >= 0. The
// exponents are sorted internally, so any order is accepted. Empty or non-finite input is refused.
double kaplan_yorke_dimension(std::span<const double> exponents);

// A flow dx/dt = f(x) in `dimension` variables: `field(x, dxdt)` and `jacobian(x, J)` with J
// row-major, J[i * dimension + j] = d f_i / d x_j.
struct FlowSystem {
  std::size_t dimension = 0;
  std::function<void(std::span<const double> x, std::span<double> dxdt)> field;
  std::function<void(std::span<const double> x, std::span<double> jacobian)> jacobian;
};

// A map x' = g(x): `map(x, next)` and `jacobian(x, J)` row-major as for flows.
struct MapSystem {
  std::size_t dimension = 0;
  std::function<void(std::span<const double> x, std::span<double> next)> map;
  std::function<void(std::span<const double> x, std::span<double> jacobian)> jacobian;
};

// Any flow or map from `initial_state`. An orbit that leaves every bounded region (|x| > 1e100 or
// non-finite) is refused with the time or iteration where it happened.
LyapunovSpectrum flow_spectrum(const FlowSystem& system, std::span<const double> initial_state,
                               const FlowSpectrumOptions& options = {});
LyapunovSpectrum map_spectrum(const MapSystem& system, std::span<const double> initial_state,
                              const MapSpectrumOptions& options = {});

// The reference systems, from the initial conditions their generators use: (1, 1, 1) for the
// flows, (0, 0) for Henon and Ikeda, x0 uniform in (0, 1) drawn with `seed` for the logistic map
// (whose orbit, including the generator's rule against collapsing onto 0 or an unstable fixed
// point in floating point, is exactly that of chaos::logistic with the same seed).
LyapunovSpectrum lorenz_spectrum(const LorenzParameters& parameters = {}, const FlowSpectrumOptions& options = {});
LyapunovSpectrum rossler_spectrum(const RosslerParameters& parameters = {}, const FlowSpectrumOptions& options = {});
LyapunovSpectrum henon_spectrum(const HenonParameters& parameters = {}, const MapSpectrumOptions& options = {});
LyapunovSpectrum ikeda_spectrum(const IkedaParameters& parameters = {}, const MapSpectrumOptions& options = {});
LyapunovSpectrum logistic_spectrum(const LogisticParameters& parameters = {}, const MapSpectrumOptions& options = {},
                                   std::uint64_t seed = 1);

// The spectrum of a reference system named as in generate.hpp, for the command line and the
// reference table: `parameters` overrides the model parameters by name (sigma, rho, beta for
// Lorenz; a, b, c for Rossler; a, b for Henon; r for the logistic map; mu, a, b for Ikeda; the
// generators' sampling settings dt, step and transient are not model parameters and are refused,
// as is any unknown name, with the list of valid ones). `flow` is used for the flows, `map` for the
// maps, `seed` for the logistic start. Systems without equations here (Mackey-Glass, sine, noise,
// ...) are refused.
struct SpectrumRequest {
  SystemKind system = SystemKind::lorenz;
  std::map<std::string, double> parameters;
  FlowSpectrumOptions flow;
  MapSpectrumOptions map;
  std::uint64_t seed = 1;
};
LyapunovSpectrum spectrum(const SpectrumRequest& request);
// The systems `spectrum` accepts, and whether each is a flow.
bool has_spectrum(SystemKind system) noexcept;
bool is_flow(SystemKind system) noexcept;

}  // namespace chaos
