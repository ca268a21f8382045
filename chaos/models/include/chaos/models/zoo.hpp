#pragma once
// A zoo of published chaotic systems, one list in a stable order: flows (autonomous, forced with a
// phase variable, delay) and maps, each with its equations, the parameters of its original paper,
// an initial condition in the basin of its attractor, a default sampling, and the literature and
// dysts values to compare with (references/zoo.tsv). The five chaotic reference systems of
// systems.hpp (lorenz, rossler, henon, logistic, ikeda) and mackey_glass are entries too and
// delegate to their generators and spectra, so their numbers are exactly those of
// chaos::generate and chaos::spectrum.
//
// Equations are written once as templates over the scalar type; Jacobians come from forward-mode
// dual numbers, so they agree with the equations by construction. Forced flows carry their phase
// phi (dphi/dt = omega) as a state variable, which makes them autonomous and gives the spectrum
// its exact zero exponent along the phase.
//
//   const ZooEntry* e = find_zoo_system("lorenz84");
//   Trajectory t = zoo_trajectory(*e, 10000, {{"F", 6.0}});
//   LyapunovSpectrum s = zoo_spectrum(*e);

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "chaos/models/generate.hpp"
#include "chaos/models/lyapunov_spectrum.hpp"
#include "chaos/models/systems.hpp"

namespace chaos {

namespace detail {
struct ZooModel;  // the equations (private: chaos/models/src/zoo_model.hpp)
// The Mackey-Glass scheme the delay spectrum linearises, run on doubles (beta, gamma, n, tau in
// p), sampled every per_sample steps after skip steps: for the test that it is chaos::mackey_glass.
std::vector<double> delay_orbit(const std::vector<double>& p, std::size_t steps_per_delay, std::size_t skip,
                                std::size_t per_sample, std::size_t n);
}

enum class ZooKind { flow, map };
const char* to_string(ZooKind kind) noexcept;

// A model parameter: its name as accepted by -p name=value, its default and what it means.
struct ZooParameter {
  std::string name;
  double value = 0.0;
  std::string meaning;
};

// Values quoted from one source for the entry's default parameters. NaN (or empty) = not given.
struct ZooValues {
  std::vector<double> exponents;  // the spectrum as published, descending (may be only lambda1)
  double kaplan_yorke = std::numeric_limits<double>::quiet_NaN();
  double d2 = std::numeric_limits<double>::quiet_NaN();
  double d2_error = std::numeric_limits<double>::quiet_NaN();  // the +- the source gives
  std::string source;  // short citation
  std::string note;    // e.g. "dysts uses other parameters: not comparable"
  bool empty() const noexcept { return exponents.empty() && !(kaplan_yorke == kaplan_yorke) && !(d2 == d2); }
  double lambda1() const noexcept {
    return exponents.empty() ? std::numeric_limits<double>::quiet_NaN() : exponents.front();
  }
};

struct ZooEntry {
  std::string name;  // snake_case, the name `chaos generate` and `chaos spectrum` accept
  ZooKind kind = ZooKind::flow;
  std::size_t dimension = 0;           // state variables (the phase of a forced flow included)
  std::vector<std::string> variables;  // component names, dimension of them
  std::vector<ZooParameter> parameters;
  std::vector<double> initial_state;   // empty for logistic (seeded) and mackey_glass (history)
  std::string equations;               // the equations in text
  std::string citation;                // the original paper: authors, journal, year

  // Default sampling. Flows: RK4 at `step`, sampled every `dt`, after `transient` time units.
  // Maps: `map_transient` iterations discarded, dt = 1.
  double dt = 1.0;
  double step = 1.0;
  double transient = 0.0;
  std::size_t map_transient = 1000;
  std::size_t component = 0;  // the scalar analysed by default

  // Default spectrum settings, chosen so that the spectrum is converged (docs/validation/zoo-spectra.md).
  FlowSpectrumOptions flow_spectrum;
  MapSpectrumOptions map_spectrum;

  bool hyperchaotic = false;  // two or more positive exponents
  bool forced = false;        // non-autonomous, with its phase as the last variable
  bool delay = false;         // delay differential equation (the state is a history)
  bool rotating = false;      // phase-coherent Rossler-type rotation about a centre
  bool conservative = false;  // volume preserving: no attractor, D2 bands do not apply
  bool constant_divergence = false;  // trace J (flows) or ln|det J| (maps) independent of x
  // The trace (flows) or ln|det J| (maps) in closed form at the default parameters when constant.
  double divergence = std::numeric_limits<double>::quiet_NaN();

  ZooValues literature;  // published values (references/zoo.tsv, kind literature)
  ZooValues dysts;       // dysts' own estimates (references/zoo.tsv, kind peer-output)
  std::string dysts_name;  // its name in dysts, empty when dysts lacks it

  std::shared_ptr<const detail::ZooModel> model;
};

// Every entry, in a stable order (flows first, then maps).
const std::vector<ZooEntry>& zoo_systems();
// The entry with this name, or nullptr.
const ZooEntry* find_zoo_system(std::string_view name) noexcept;
// Like find_zoo_system, but an unknown name throws InvalidInput listing the valid names.
const ZooEntry& zoo_system(std::string_view name);
// The names, comma separated, for messages and --help.
std::string zoo_names();

// The model parameters with the overrides applied (by name, in the entry's order). An unknown
// name or a non-finite value is refused with the rule and the valid names.
std::vector<double> zoo_parameters(const ZooEntry& entry, const std::map<std::string, double>& overrides = {});

// Sampling overrides accepted by zoo_trajectory besides the model parameters: for flows dt, step,
// transient (time units); for maps transient (iterations); for mackey_glass also steps_per_delay.
// `seed` is used by the logistic map's start only.
Trajectory zoo_trajectory(const ZooEntry& entry, std::size_t n, const std::map<std::string, double>& overrides = {},
                          std::uint64_t seed = 1);

// Settings of zoo_spectrum; unset fields take the entry's defaults.
struct ZooSpectrumOptions {
  std::optional<FlowSpectrumOptions> flow;
  std::optional<MapSpectrumOptions> map;
  // Delay systems: the number of leading exponents (1..8) and the RK4 steps per delay.
  std::size_t delay_exponents = 6;
  std::optional<std::size_t> steps_per_delay;
  std::uint64_t seed = 1;  // logistic start
};

// The Lyapunov spectrum from the equations (model parameters only as overrides; sampling keys are
// refused). Flows and maps go through flow_spectrum / map_spectrum with the dual-number Jacobian;
// the delegating entries call the reference spectra of lyapunov_spectrum.hpp. Delay systems: the
// leading exponents of the discretised delay equation (the RK4 scheme of chaos::mackey_glass on
// its step grid, whose history is the state), by tangent dynamics of that scheme carried with dual
// numbers and Gram-Schmidt every 5 time units.
LyapunovSpectrum zoo_spectrum(const ZooEntry& entry, const std::map<std::string, double>& overrides = {},
                              const ZooSpectrumOptions& options = {});

// The equations as a FlowSystem / MapSystem (with the dual-number Jacobian) at the given
// parameters, for tests and for callers that drive the spectrum themselves. Refused for delay
// systems and for the wrong kind.
FlowSystem zoo_flow_system(const ZooEntry& entry, const std::map<std::string, double>& overrides = {});
MapSystem zoo_map_system(const ZooEntry& entry, const std::map<std::string, double>& overrides = {});

// The exact identity for the sum of the exponents along the orbit zoo_spectrum follows (same
// initial state, transient and length): flows, the time average of trace J, averaged over the
// RK4 stages with the RK4 weights; maps, the mean of ln |det J|. Refused for delay systems and for
// the logistic map (whose generator re-draws collapsed orbits).
double zoo_mean_divergence(const ZooEntry& entry, const std::map<std::string, double>& overrides = {},
                           const ZooSpectrumOptions& options = {});

}  // namespace chaos
