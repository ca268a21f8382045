// The zoo registry: the entry lists of zoo_flows.cpp and zoo_maps.cpp, the literature and dysts
// values of references/zoo.tsv (compiled in), and generation and spectra by entry.

#include "chaos/models/zoo.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "chaos/error.hpp"
#include "chaos/format.hpp"
#include "zoo_model.hpp"

namespace chaos {

namespace {

constexpr const char* kZooTable =
#include "zoo_table.inc"
    ;

std::string num(double v) { return format_number(v, Precision::shortest); }

double parse_number(const std::string& text) {
  if (text.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::stod(text);
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> out;
  std::string cell;
  std::stringstream in(line);
  while (std::getline(in, cell, separator)) out.push_back(cell);
  if (!line.empty() && line.back() == separator) out.emplace_back();
  return out;
}

// Rows: system, kind (literature | dysts), exponents (comma separated), kaplan_yorke, d2,
// d2_error, source, note. A malformed table is a build error in spirit: it throws at first use.
void attach_values(std::vector<ZooEntry>& entries) {
  std::stringstream in(kZooTable);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    const auto cells = split(line, '\t');
    if (cells.size() < 8) throw std::logic_error("references/zoo.tsv: a row has fewer than 8 cells: " + line);
    auto it = std::find_if(entries.begin(), entries.end(), [&](const ZooEntry& e) { return e.name == cells[0]; });
    if (it == entries.end()) throw std::logic_error("references/zoo.tsv names an unknown system: " + cells[0]);
    ZooValues v;
    for (const auto& x : split(cells[2], ','))
      if (!x.empty()) v.exponents.push_back(std::stod(x));
    v.kaplan_yorke = parse_number(cells[3]);
    v.d2 = parse_number(cells[4]);
    v.d2_error = parse_number(cells[5]);
    v.source = cells[6];
    v.note = cells[7];
    if (cells[1] == "literature") {
      it->literature = std::move(v);
    } else if (cells[1] == "dysts") {
      it->dysts_name = v.source;
      it->dysts = std::move(v);
    } else {
      throw std::logic_error("references/zoo.tsv: kind must be literature or dysts: " + line);
    }
  }
}

std::vector<ZooEntry> build_zoo() {
  std::vector<ZooEntry> all = detail::zoo_flow_entries();
  auto maps = detail::zoo_map_entries();
  for (auto& m : maps) all.push_back(std::move(m));
  attach_values(all);
  return all;
}

bool is_sampling_key(const ZooEntry& e, const std::string& name) {
  if (e.kind == ZooKind::map) return name == "transient";
  if (e.delay) return name == "dt" || name == "transient" || name == "steps_per_delay";
  return name == "dt" || name == "step" || name == "transient";
}

std::size_t whole(double value, const std::string& name) {
  if (!(value >= 0.0) || value != std::floor(value) || value > 1e15)
    refuse_parameter("parameter " + name + " must be a non-negative whole number (got " + num(value) + ")");
  return static_cast<std::size_t>(value);
}

using Delegate = detail::ZooModel::Delegate;

std::optional<SystemKind> delegate_kind(Delegate d) {
  switch (d) {
    case Delegate::lorenz: return SystemKind::lorenz;
    case Delegate::rossler: return SystemKind::rossler;
    case Delegate::henon: return SystemKind::henon;
    case Delegate::logistic: return SystemKind::logistic;
    case Delegate::ikeda: return SystemKind::ikeda;
    default: return std::nullopt;
  }
}

// The whole multiple of `step` nearest `interval`, refusing one that is not a multiple.
std::size_t steps_in(double interval, double step, const std::string& what) {
  const double k = std::round(interval / step);
  if (k < 1.0 || std::abs(k * step - interval) > 1e-9 * interval || k > 1e15)
    refuse_parameter("zoo: " + what + " = " + num(interval) + " must be a whole multiple of the step " + num(step));
  return static_cast<std::size_t>(k);
}

void require_bounded(const ZooEntry& e, double v, const std::string& where) {
  if (std::isfinite(v) && std::abs(v) <= 1e100) return;
  refuse_parameter(e.name + ": the solution left every bounded region at " + where + " (value " + num(v) +
         "); the parameters have no bounded attractor from the documented initial condition" +
         (e.kind == ZooKind::flow ? ", or the step is too large for the integrator" : ""));
}

// One classical RK4 step of dx/dt = f(x) in d variables, written as flow_spectrum writes it
// (x + (h/2) k1, ..., x + h/6 (k1 + 2 k2 + 2 k3 + k4)) so both follow the same orbit.
struct Rk4 {
  const detail::ZooModel& model;
  const double* p;
  std::size_t d;
  std::vector<double> k1, k2, k3, k4, y;
  Rk4(const detail::ZooModel& m, const double* parameters, std::size_t dimension)
      : model(m), p(parameters), d(dimension), k1(d), k2(d), k3(d), k4(d), y(d) {}
  void step(std::vector<double>& x, double h) {
    model.evaluate(x.data(), k1.data(), p);
    for (std::size_t i = 0; i < d; ++i) y[i] = x[i] + 0.5 * h * k1[i];
    model.evaluate(y.data(), k2.data(), p);
    for (std::size_t i = 0; i < d; ++i) y[i] = x[i] + 0.5 * h * k2[i];
    model.evaluate(y.data(), k3.data(), p);
    for (std::size_t i = 0; i < d; ++i) y[i] = x[i] + h * k3[i];
    model.evaluate(y.data(), k4.data(), p);
    for (std::size_t i = 0; i < d; ++i) x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
};

std::map<std::string, double> model_overrides(const ZooEntry& e, const std::map<std::string, double>& overrides,
                                              std::map<std::string, double>& sampling) {
  std::map<std::string, double> model;
  for (const auto& [name, value] : overrides) {
    if (is_sampling_key(e, name)) {
      if (!std::isfinite(value)) refuse_parameter(e.name + ": parameter " + name + " must be finite (got " + num(value) + ")");
      sampling[name] = value;
    } else {
      model[name] = value;
    }
  }
  return model;
}

double trace(const std::vector<double>& j, std::size_t d) {
  double t = 0.0;
  for (std::size_t i = 0; i < d; ++i) t += j[i * d + i];
  return t;
}

}  // namespace

const char* to_string(ZooKind kind) noexcept { return kind == ZooKind::flow ? "flow" : "map"; }

namespace detail {

namespace {

// The fields every entry has, whatever its kind.
ZooEntry zoo_entry(ZooKind kind, std::string name, std::vector<std::string> variables,
                   std::vector<ZooParameter> parameters, std::vector<double> initial_state, std::string equations,
                   std::string citation, std::shared_ptr<const ZooModel> model) {
  ZooEntry e;
  e.name = std::move(name);
  e.kind = kind;
  e.dimension = variables.size();
  e.variables = std::move(variables);
  e.parameters = std::move(parameters);
  e.initial_state = std::move(initial_state);
  e.equations = std::move(equations);
  e.citation = std::move(citation);
  e.model = std::move(model);
  return e;
}

}  // namespace

ZooEntry zoo_flow(std::string name, std::vector<std::string> variables, std::vector<ZooParameter> parameters,
                  std::vector<double> initial_state, double dt, double step, double transient, std::string equations,
                  std::string citation, std::shared_ptr<const ZooModel> model) {
  ZooEntry e = zoo_entry(ZooKind::flow, std::move(name), std::move(variables), std::move(parameters),
                         std::move(initial_state), std::move(equations), std::move(citation), std::move(model));
  e.dt = dt;
  e.step = step;
  e.transient = transient;
  return e;
}

ZooEntry zoo_map(std::string name, std::vector<std::string> variables, std::vector<ZooParameter> parameters,
                 std::vector<double> initial_state, std::size_t transient, std::string equations, std::string citation,
                 std::shared_ptr<const ZooModel> model) {
  ZooEntry e = zoo_entry(ZooKind::map, std::move(name), std::move(variables), std::move(parameters),
                         std::move(initial_state), std::move(equations), std::move(citation), std::move(model));
  e.map_transient = transient;
  return e;
}

}  // namespace detail

const std::vector<ZooEntry>& zoo_systems() {
  static const std::vector<ZooEntry> entries = build_zoo();
  return entries;
}

const ZooEntry* find_zoo_system(std::string_view name) noexcept {
  for (const auto& e : zoo_systems())
    if (e.name == name) return &e;
  return nullptr;
}

std::string zoo_names() {
  std::string out;
  for (const auto& e : zoo_systems()) out += (out.empty() ? "" : ", ") + e.name;
  return out;
}

const ZooEntry& zoo_system(std::string_view name) {
  if (const ZooEntry* e = find_zoo_system(name)) return *e;
  refuse_parameter("unknown system '" + std::string(name) + "' (valid: " + zoo_names() + ")");
}

std::vector<double> zoo_parameters(const ZooEntry& entry, const std::map<std::string, double>& overrides) {
  std::vector<double> p;
  for (const auto& parameter : entry.parameters) p.push_back(parameter.value);
  for (const auto& [name, value] : overrides) {
    const auto it = std::find_if(entry.parameters.begin(), entry.parameters.end(),
                                 [&](const ZooParameter& q) { return q.name == name; });
    if (it == entry.parameters.end()) {
      std::string valid;
      for (const auto& q : entry.parameters) valid += (valid.empty() ? "" : ", ") + q.name;
      refuse_parameter("system " + entry.name + " has no model parameter '" + name + "' (valid: " +
             (valid.empty() ? "none" : valid) + ")");
    }
    if (!std::isfinite(value))
      refuse_parameter("system " + entry.name + ": parameter " + name + " must be finite (got " + num(value) + ")");
    p[static_cast<std::size_t>(it - entry.parameters.begin())] = value;
  }
  return p;
}

Trajectory zoo_trajectory(const ZooEntry& entry, std::size_t n, const std::map<std::string, double>& overrides,
                          std::uint64_t seed) {
  if (n == 0) refuse_parameter(entry.name + ": the number of samples n must be at least 1 (got n = 0)");
  std::map<std::string, double> sampling;
  const auto model_values = model_overrides(entry, overrides, sampling);
  std::vector<double> p;
  try {
    p = zoo_parameters(entry, model_values);
  } catch (const InvalidInput& e) {
    const char* keys = entry.kind == ZooKind::map ? "transient" : entry.delay ? "dt, steps_per_delay, transient" : "dt, step, transient";
    throw InvalidInput(e.code(), std::string(e.what()) + "; sampling settings: " + keys);
  }
  const auto d = entry.model->delegate;
  if (const auto kind = delegate_kind(d)) {
    GenerateRequest request;
    request.system = *kind;
    request.length = n;
    request.parameters = overrides;
    request.seed = seed;
    return generate(request);
  }
  if (d == Delegate::mackey_glass) {
    const double dt = sampling.count("dt") ? sampling["dt"] : entry.dt;
    const double transient = sampling.count("transient") ? sampling["transient"] : entry.transient;
    const std::size_t spd = sampling.count("steps_per_delay")
                                ? whole(sampling["steps_per_delay"], "steps_per_delay")
                                : static_cast<std::size_t>(std::lround(entry.parameters[3].value / entry.step));
    return mackey_glass(n, {p[0], p[1], p[2], p[3]}, dt, spd, transient);
  }

  Trajectory out;
  out.names = entry.variables;
  out.components.assign(entry.dimension, std::vector<double>(n));
  std::vector<double> x = entry.initial_state;
  const std::size_t dim = entry.dimension;
  if (entry.kind == ZooKind::map) {
    const std::size_t transient =
        sampling.count("transient") ? whole(sampling["transient"], "transient") : entry.map_transient;
    std::vector<double> next(dim);
    std::size_t iteration = 0;
    const auto iterate = [&] {
      entry.model->evaluate(x.data(), next.data(), p.data());
      x.swap(next);
      ++iteration;
      for (const double v : x) require_bounded(entry, v, "iteration " + std::to_string(iteration));
    };
    for (std::size_t i = 0; i < transient; ++i) iterate();
    for (std::size_t k = 0; k < n; ++k) {
      if (k > 0) iterate();
      for (std::size_t c = 0; c < dim; ++c) out.components[c][k] = x[c];
    }
    out.dt = 1.0;
    return out;
  }
  const double dt = sampling.count("dt") ? sampling["dt"] : entry.dt;
  const double h = sampling.count("step") ? sampling["step"] : entry.step;
  const double transient = sampling.count("transient") ? sampling["transient"] : entry.transient;
  FlowSampling check{dt, h, transient};
  try {
    check.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(e.code(), entry.name + ": " + e.what());
  }
  const std::size_t per_sample = steps_in(dt, h, "sampling interval dt");
  const auto skip = static_cast<std::size_t>(std::round(transient / h));
  Rk4 rk4(*entry.model, p.data(), dim);
  for (std::size_t i = 0; i < skip; ++i) rk4.step(x, h);
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0)
      for (std::size_t i = 0; i < per_sample; ++i) rk4.step(x, h);
    for (std::size_t c = 0; c < dim; ++c) {
      require_bounded(entry, x[c], "t = " + num(transient + static_cast<double>(k) * dt));
      // The phase of a forced flow is written modulo 2 pi; the integration keeps it unwrapped.
      const bool phase = entry.forced && c + 1 == dim;
      out.components[c][k] = phase ? detail::wrap(x[c], 2.0 * std::numbers::pi) : x[c];
    }
  }
  out.dt = dt;
  return out;
}

FlowSystem zoo_flow_system(const ZooEntry& entry, const std::map<std::string, double>& overrides) {
  if (entry.kind != ZooKind::flow || entry.delay || !entry.model->evaluate)
    refuse_parameter("zoo_flow_system: " + entry.name + " is not an ordinary differential equation of the zoo");
  const auto p = std::make_shared<std::vector<double>>(zoo_parameters(entry, overrides));
  const auto model = entry.model;
  FlowSystem s;
  s.dimension = entry.dimension;
  s.field = [model, p](std::span<const double> x, std::span<double> dx) { model->evaluate(x.data(), dx.data(), p->data()); };
  s.jacobian = [model, p](std::span<const double> x, std::span<double> j) { model->jacobian(x.data(), j.data(), p->data()); };
  return s;
}

MapSystem zoo_map_system(const ZooEntry& entry, const std::map<std::string, double>& overrides) {
  if (entry.kind != ZooKind::map || !entry.model->evaluate) refuse_parameter("zoo_map_system: " + entry.name + " is not a map of the zoo");
  const auto p = std::make_shared<std::vector<double>>(zoo_parameters(entry, overrides));
  const auto model = entry.model;
  MapSystem s;
  s.dimension = entry.dimension;
  s.map = [model, p](std::span<const double> x, std::span<double> next) { model->evaluate(x.data(), next.data(), p->data()); };
  s.jacobian = [model, p](std::span<const double> x, std::span<double> j) { model->jacobian(x.data(), j.data(), p->data()); };
  return s;
}

LyapunovSpectrum zoo_spectrum(const ZooEntry& entry, const std::map<std::string, double>& overrides,
                              const ZooSpectrumOptions& options) {
  for (const auto& [name, value] : overrides)
    if (is_sampling_key(entry, name))
      refuse_parameter("zoo spectrum: " + name + " is a sampling setting of " + entry.name +
             ", not a model parameter; set the spectrum's own options instead");
  const std::vector<double> p = zoo_parameters(entry, overrides);
  const FlowSpectrumOptions flow = options.flow.value_or(entry.flow_spectrum);
  const MapSpectrumOptions map = options.map.value_or(entry.map_spectrum);
  const auto d = entry.model->delegate;
  if (const auto kind = delegate_kind(d)) {
    SpectrumRequest request;
    request.system = *kind;
    request.parameters = overrides;
    request.flow = flow;
    request.map = map;
    request.seed = options.seed;
    return spectrum(request);
  }
  if (d == Delegate::mackey_glass) {
    const std::size_t spd = options.steps_per_delay.value_or(
        static_cast<std::size_t>(std::lround(entry.parameters[3].value / entry.step)));
    return detail::delay_spectrum(p, spd, options.delay_exponents, flow);
  }
  if (entry.kind == ZooKind::flow) return flow_spectrum(zoo_flow_system(entry, overrides), entry.initial_state, flow);
  return map_spectrum(zoo_map_system(entry, overrides), entry.initial_state, map);
}

double zoo_mean_divergence(const ZooEntry& entry, const std::map<std::string, double>& overrides,
                           const ZooSpectrumOptions& options) {
  if (entry.delay || entry.model->delegate == Delegate::logistic || !entry.model->evaluate)
    refuse_parameter("zoo_mean_divergence: not available for " + entry.name);
  const std::vector<double> p = zoo_parameters(entry, overrides);
  const std::size_t dim = entry.dimension;
  std::vector<double> x = entry.initial_state, j(dim * dim);
  if (entry.kind == ZooKind::flow) {
    // The schedule of flow_spectrum: whole intervals of whole steps, the transient rounded to intervals.
    const FlowSpectrumOptions o = options.flow.value_or(entry.flow_spectrum);
    o.validate();
    const std::size_t per = steps_in(o.renormalisation_interval, o.step, "renormalisation_interval");
    const auto transient = static_cast<std::size_t>(std::round(o.transient / o.renormalisation_interval)) * per;
    const std::size_t steps = steps_in(o.time, o.renormalisation_interval, "time") * per;
    const double h = o.step;
    Rk4 rk4(*entry.model, p.data(), dim);
    std::vector<double> y(dim);
    for (std::size_t i = 0; i < transient; ++i) rk4.step(x, h);
    double sum = 0.0;
    for (std::size_t s = 0; s < steps; ++s) {
      // trace J at the four RK4 stages, weighted as RK4 weights its slopes.
      double t = 0.0;
      entry.model->jacobian(x.data(), j.data(), p.data());
      t += trace(j, dim);
      entry.model->evaluate(x.data(), rk4.k1.data(), p.data());
      for (std::size_t i = 0; i < dim; ++i) y[i] = x[i] + 0.5 * h * rk4.k1[i];
      entry.model->jacobian(y.data(), j.data(), p.data());
      t += 2.0 * trace(j, dim);
      entry.model->evaluate(y.data(), rk4.k2.data(), p.data());
      for (std::size_t i = 0; i < dim; ++i) y[i] = x[i] + 0.5 * h * rk4.k2[i];
      entry.model->jacobian(y.data(), j.data(), p.data());
      t += 2.0 * trace(j, dim);
      entry.model->evaluate(y.data(), rk4.k3.data(), p.data());
      for (std::size_t i = 0; i < dim; ++i) y[i] = x[i] + h * rk4.k3[i];
      entry.model->jacobian(y.data(), j.data(), p.data());
      t += trace(j, dim);
      sum += t / 6.0;
      rk4.step(x, h);
    }
    return sum / static_cast<double>(steps);  // each step weighs h: (sum h) / (steps h)
  }
  const MapSpectrumOptions o = options.map.value_or(entry.map_spectrum);
  o.validate();
  const std::size_t per = o.renormalisation_interval;
  const std::size_t transient = (o.transient + per / 2) / per * per;
  const std::size_t iterations = o.iterations / per * per;
  std::vector<double> next(dim);
  for (std::size_t i = 0; i < transient; ++i) {
    entry.model->evaluate(x.data(), next.data(), p.data());
    x.swap(next);
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < iterations; ++i) {
    entry.model->jacobian(x.data(), j.data(), p.data());
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> m(
        j.data(), static_cast<Eigen::Index>(dim), static_cast<Eigen::Index>(dim));
    sum += std::log(std::abs(m.determinant()));
    entry.model->evaluate(x.data(), next.data(), p.data());
    x.swap(next);
  }
  return sum / static_cast<double>(iterations);
}

}  // namespace chaos
