#include "chaos/models/generate.hpp"

#include <array>
#include <cmath>
#include <set>

#include "chaos/error.hpp"

namespace chaos {

namespace {

constexpr std::array<std::pair<SystemKind, const char*>, 11> kNames{{
    {SystemKind::lorenz, "lorenz"},
    {SystemKind::rossler, "rossler"},
    {SystemKind::henon, "henon"},
    {SystemKind::logistic, "logistic"},
    {SystemKind::ikeda, "ikeda"},
    {SystemKind::mackey_glass, "mackey_glass"},
    {SystemKind::sine, "sine"},
    {SystemKind::quasi_periodic, "quasi_periodic"},
    {SystemKind::white_noise, "white_noise"},
    {SystemKind::uniform_noise, "uniform_noise"},
    {SystemKind::ar1, "ar1"},
}};

// Sampling keys shared by the flows; their defaults are the ones FlowSampling's callers use.
std::vector<SystemParameter> flow_sampling(const FlowSampling& s) {
  return {{"dt", s.dt, "sampling interval (time units)"},
          {"step", s.step, "RK4 integration step (time units); dt must be a whole multiple"},
          {"transient", s.transient, "time discarded before sampling starts"}};
}

std::vector<SystemParameter> with(std::vector<SystemParameter> a, const std::vector<SystemParameter>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::size_t whole(double value, const std::string& name) {
  if (!(value >= 0.0) || value != std::floor(value) || value > 1e15)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "parameter " + name + " must be a non-negative whole number (got " + std::to_string(value) + ")");
  return static_cast<std::size_t>(value);
}

}  // namespace

const char* to_string(SystemKind system) noexcept {
  for (const auto& [kind, name] : kNames)
    if (kind == system) return name;
  return "unknown";
}

std::optional<SystemKind> system_from_name(std::string_view name) noexcept {
  for (const auto& [kind, n] : kNames)
    if (name == n) return kind;
  return std::nullopt;
}

std::vector<SystemKind> all_systems() {
  std::vector<SystemKind> out;
  for (const auto& entry : kNames) out.push_back(entry.first);
  return out;
}

std::vector<SystemParameter> system_parameters(SystemKind system) {
  switch (system) {
    case SystemKind::lorenz: {
      const LorenzParameters p;
      return with({{"sigma", p.sigma, "Prandtl number"}, {"rho", p.rho, "Rayleigh number"}, {"beta", p.beta, "geometric factor"}},
                  flow_sampling(FlowSampling{}));
    }
    case SystemKind::rossler: {
      const RosslerParameters p;
      return with({{"a", p.a, ""}, {"b", p.b, ""}, {"c", p.c, ""}}, flow_sampling(FlowSampling{0.1, 0.01, 500.0}));
    }
    case SystemKind::henon: {
      const HenonParameters p;
      return {{"a", p.a, ""}, {"b", p.b, ""}, {"transient", 1000, "iterations discarded"}};
    }
    case SystemKind::logistic: {
      const LogisticParameters p;
      return {{"r", p.r, "growth rate"}, {"transient", 1000, "iterations discarded"}};
    }
    case SystemKind::ikeda: {
      const IkedaParameters p;
      return {{"mu", p.mu, "dissipation (Jacobian determinant mu^2)"}, {"a", p.a, ""}, {"b", p.b, ""},
              {"transient", 1000, "iterations discarded"}};
    }
    case SystemKind::mackey_glass: {
      const MackeyGlassParameters p;
      return {{"beta", p.beta, ""}, {"gamma", p.gamma, ""}, {"n", p.n, "exponent"}, {"tau", p.tau, "delay (time units)"},
              {"dt", 1.0, "sampling interval (time units)"},
              {"steps_per_delay", 170, "RK4 steps per delay tau"},
              {"transient", 1000.0, "time discarded before sampling starts"}};
    }
    case SystemKind::sine:
      return {{"frequency", 1.0, "cycles per time unit"}, {"dt", 0.01, "sampling interval"}};
    case SystemKind::quasi_periodic:
      return {{"f1", 1.0, "first frequency"}, {"f2", 1.6180339887498949, "second frequency (golden mean: incommensurate)"},
              {"dt", 0.05, "sampling interval"}};
    case SystemKind::white_noise:
    case SystemKind::uniform_noise:
      return {};
    case SystemKind::ar1:
      return {{"phi", 0.9, "lag-1 coefficient, |phi| < 1"}};
  }
  return {};
}

Trajectory generate(const GenerateRequest& request) {
  // Resolve the parameters: defaults, then overrides, refusing unknown names.
  std::map<std::string, double> p;
  for (const auto& parameter : system_parameters(request.system)) p[parameter.name] = parameter.default_value;
  for (const auto& [name, value] : request.parameters) {
    if (!p.count(name)) {
      std::string valid;
      for (const auto& [known, unused] : p) valid += (valid.empty() ? "" : ", ") + known;
      throw InvalidInput(ErrorCode::invalid_parameter,
                         std::string("system ") + to_string(request.system) + " has no parameter '" + name +
                             "' (valid: " + (valid.empty() ? "none" : valid) + ")");
    }
    if (!std::isfinite(value))
      throw InvalidInput(ErrorCode::invalid_parameter, "parameter " + name + " must be finite");
    p[name] = value;
  }
  const std::size_t n = request.length;
  switch (request.system) {
    case SystemKind::lorenz:
      return lorenz(n, {p["sigma"], p["rho"], p["beta"]}, {p["dt"], p["step"], p["transient"]});
    case SystemKind::rossler:
      return rossler(n, {p["a"], p["b"], p["c"]}, {p["dt"], p["step"], p["transient"]});
    case SystemKind::henon:
      return henon(n, {p["a"], p["b"]}, whole(p["transient"], "transient"));
    case SystemKind::logistic:
      return logistic(n, {p["r"]}, whole(p["transient"], "transient"), request.seed);
    case SystemKind::ikeda:
      return ikeda(n, {p["mu"], p["a"], p["b"]}, whole(p["transient"], "transient"));
    case SystemKind::mackey_glass:
      return mackey_glass(n, {p["beta"], p["gamma"], p["n"], p["tau"]}, p["dt"],
                          whole(p["steps_per_delay"], "steps_per_delay"), p["transient"]);
    case SystemKind::sine:
      return sine(n, p["frequency"], p["dt"]);
    case SystemKind::quasi_periodic:
      return quasi_periodic(n, p["f1"], p["f2"], p["dt"]);
    case SystemKind::white_noise:
      return white_noise(n, request.seed);
    case SystemKind::uniform_noise:
      return uniform_noise(n, request.seed);
    case SystemKind::ar1:
      return ar1(n, p["phi"], request.seed);
  }
  throw InvalidInput(ErrorCode::invalid_parameter, "unknown system");
}

}  // namespace chaos
