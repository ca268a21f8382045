// chaos._core: the pybind11 extension behind the Python package. Every command function takes the
// series as a float64 C-contiguous NumPy array (the pure-Python layer converts anything else once,
// views a matching array as it is), the series' name, column and sampling interval, and a dict of
// the command's parameters; it runs the command's shared computation (chaos/commands/commands.hpp,
// the code behind `chaos X --json`) with the GIL released and returns the command's JSON object as
// Python objects. Invalid input raises ValueError (chaos::InvalidInput is a std::invalid_argument)
// or TypeError (a parameter of the wrong type).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/series.hpp"
#include "commands.hpp"
#include "mechanism/scene.hpp"
#include "mechanism/signals.hpp"
#include "mechanism/simulate.hpp"
#include "mechanism/slider_crank.hpp"
#include "summary_json.hpp"

namespace py = pybind11;
using namespace chaos::cli;

namespace {

using Array = py::array_t<double, py::array::c_style>;

// The data address of the last series handed to a command (the zero-copy test reads it).
std::atomic<std::uintptr_t> last_input_address{0};

const char* const ARRAY = "(array)";

// Raised from the progress hook when Python has a pending signal (Ctrl-C): the computation stops
// and the signal's exception is raised in Python.
struct Interrupted {};

[[noreturn]] void type_error(const std::string& message) { throw py::type_error(message); }
[[noreturn]] void value_error(const std::string& message) { throw py::value_error(message); }

// Parameters: read from the dict by name, None or absent leaves the command's default.
bool has(const py::dict& p, const char* name) { return p.contains(name) && !p[name].is_none(); }

std::size_t to_count(const py::handle& v, const char* name) {
  if (PyBool_Check(v.ptr()) || !PyLong_Check(v.ptr()))
    type_error(std::string(name) + " must be an integer (got " + std::string(py::str(py::type::of(v).attr("__name__"))) + ")");
  int overflow = 0;
  const long long value = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
  if (overflow > 0) value_error(std::string(name) + " is too large");
  if (overflow < 0 || value < 0) value_error(std::string(name) + " must be >= 0 (got " + std::string(py::str(v)) + ")");
  return static_cast<std::size_t>(value);
}

void get(const py::dict& p, const char* name, std::size_t& target) {
  if (has(p, name)) target = to_count(p[name], name);
}
void get(const py::dict& p, const char* name, std::optional<std::size_t>& target) {
  if (has(p, name)) target = to_count(p[name], name);
}
double to_real(const py::handle& v, const char* name) {
  if (PyBool_Check(v.ptr()) || !(PyFloat_Check(v.ptr()) || PyLong_Check(v.ptr()) || py::isinstance<py::float_>(v)))
    type_error(std::string(name) + " must be a number (got " + std::string(py::str(py::type::of(v).attr("__name__"))) + ")");
  const double value = py::cast<double>(v);
  if (std::isnan(value)) value_error(std::string(name) + " must not be NaN");
  return value;
}
void get(const py::dict& p, const char* name, double& target) {
  if (has(p, name)) target = to_real(p[name], name);
}
void get(const py::dict& p, const char* name, std::optional<double>& target) {
  if (has(p, name)) target = to_real(p[name], name);
}
void get(const py::dict& p, const char* name, std::string& target) {
  if (!has(p, name)) return;
  if (!py::isinstance<py::str>(p[name])) type_error(std::string(name) + " must be a string");
  target = py::cast<std::string>(p[name]);
}
void get(const py::dict& p, const char* name, bool& target) {
  if (!has(p, name)) return;
  if (!PyBool_Check(p[name].ptr())) type_error(std::string(name) + " must be True or False");
  target = p[name].cast<bool>();
}
void get(const py::dict& p, const char* name, std::vector<double>& target) {
  if (!has(p, name)) return;
  target.clear();
  for (const auto& v : p[name]) target.push_back(to_real(v, name));
}

// The series: the checks every command applies to what it reads (finite, usable scale).
SeriesInput series(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt) {
  last_input_address = reinterpret_cast<std::uintptr_t>(x.data());
  const std::span<const double> values(x.data(), static_cast<std::size_t>(x.size()));
  if (values.empty()) throw chaos::InvalidInput(chaos::ErrorCode::empty, file + ": the series is empty (no samples)");
  check_series(values, file);
  if (dt && !(std::isfinite(*dt) && *dt > 0.0))
    throw chaos::InvalidInput(chaos::ErrorCode::invalid_parameter, "dt must be finite and > 0");
  return {values, file, column, dt};
}

// nlohmann's JSON to Python objects, as `json.loads` of the command's output would give them
// (NaN and infinities are written as null by the command, so they become None here too).
py::object to_python(const nlohmann::ordered_json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null: return py::none();
    case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(j.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: {
      const double v = j.get<double>();
      return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
    }
    case nlohmann::json::value_t::string: return py::str(j.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list out(j.size());
      std::size_t k = 0;
      for (const auto& v : j) out[k++] = to_python(v);
      return out;
    }
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, v] : j.items()) out[py::str(key)] = to_python(v);
      return out;
    }
    default: return py::none();
  }
}

// Runs `compute` without the GIL; the result's JSON comes back as Python objects.
template <class F>
py::object call(F&& compute) {
  nlohmann::ordered_json json;
  {
    py::gil_scoped_release release;
    json = compute();
  }
  return to_python(json);
}

// The progress hook of the correlation sums, the library's one cancellation point: each call (every
// thousandth of the work) checks for a pending signal and stops the sums when there is one; with
// `callback`, it is also handed the fraction done.
std::function<void(double)> progress_hook(py::object callback) {
  auto shared = std::make_shared<py::object>(std::move(callback));
  return [shared](double fraction) {
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) throw Interrupted{};
    if (!shared->is_none()) (*shared)(fraction);
  };
}

py::object mutual(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt, const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  MutualParams params;
  get(p, "max_delay", params.options.max_delay);
  get(p, "boxes", params.options.boxes);
  get(p, "estimator", params.estimator);
  return call([&] { return run_mutual(in, params).report.json(); });
}

py::object autocorrelation(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                           const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  AutocorrelationParams params;
  get(p, "max_lag", params.max_lag);
  return call([&] { return run_autocorrelation(in, params).report.json(); });
}

py::object cao(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt, const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  CaoParams params;
  get(p, "delay", params.options.delay);
  get(p, "min_dimension", params.options.min_dimension);
  get(p, "max_dimension", params.options.max_dimension);
  get(p, "theiler", params.options.theiler);
  get(p, "norm", params.norm);
  get(p, "level", params.options.saturation_level);
  get(p, "change", params.options.saturation_change);
  get(p, "sigmas", params.options.stochastic_sigmas);
  return call([&] { return run_cao(in, params).report.json(); });
}

py::object fnn(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt, const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  FnnParams params;
  get(p, "delay", params.options.delay);
  get(p, "min_dimension", params.options.min_dimension);
  get(p, "max_dimension", params.options.max_dimension);
  get(p, "theiler", params.options.theiler);
  get(p, "rtol", params.options.rtol);
  get(p, "atol", params.options.atol);
  get(p, "norm", params.norm);
  get(p, "threshold", params.options.threshold);
  return call([&] { return run_fnn(in, params).report.json(); });
}

py::object d2(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt, const py::dict& p,
              py::object progress) {
  const SeriesInput in = series(x, file, column, dt);
  D2Params params;
  get(p, "delay", params.sums.delay);
  get(p, "min_dimension", params.sums.min_dimension);
  get(p, "max_dimension", params.sums.max_dimension);
  get(p, "theiler", params.theiler);
  get(p, "min_radius", params.r_min);
  get(p, "max_radius", params.r_max);
  get(p, "radii", params.radii);
  get(p, "radius_list", params.radius_list);
  get(p, "norm", params.norm);
  get(p, "search", params.search);
  get(p, "pairs_per_radius", params.sums.pairs_per_radius);
  get(p, "reference_points", params.sums.reference_points);
  get(p, "seed", params.sums.seed);
  get(p, "threads", params.sums.threads);
  get(p, "tolerance", params.dimension.region.tolerance);
  get(p, "min_points", params.dimension.region.min_points);
  get(p, "saturation_dimensions", params.dimension.saturation_dimensions);
  get(p, "min_pairs", params.dimension.min_pairs);
  get(p, "max_region_fraction", params.dimension.max_region_fraction);
  get(p, "halves", params.halves);
  get(p, "inclusive", params.sums.inclusive);
  params.sums.progress = progress_hook(std::move(progress));
  try {
    return call([&] { return run_d2(in, params).report.json(); });
  } catch (const Interrupted&) {
    throw py::error_already_set();  // the signal handler's exception (KeyboardInterrupt)
  }
}

py::object lyapunov(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                    const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  LyapunovParams params;
  get(p, "method", params.method);
  get(p, "dimension", params.options.dimension);
  get(p, "delay", params.options.delay);
  get(p, "theiler", params.theiler);
  get(p, "steps", params.steps);
  get(p, "period", params.period);
  get(p, "dimensions", params.fit.dimensions);
  get(p, "radius", params.options.radius);
  get(p, "min_neighbours", params.options.min_neighbours);
  get(p, "reference_points", params.options.reference_points);
  get(p, "norm", params.norm);
  get(p, "threads", params.options.threads);
  get(p, "tolerance", params.fit.tolerance);
  get(p, "half_width", params.fit.half_width);
  get(p, "min_steps", params.fit.min_steps);
  get(p, "min_rise", params.fit.min_rise);
  return call([&] { return run_lyapunov(in, params).report.json(); });
}

py::object analyze(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                   const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  AnalyzeParams params;
  get(p, "delay", params.delay);
  get(p, "theiler", params.theiler);
  get(p, "max_delay", params.max_delay);
  get(p, "boxes", params.boxes);
  get(p, "max_dimension", params.max_dimension);
  get(p, "test_length", params.test_length);
  get(p, "surrogates", params.surrogates);
  get(p, "seed", params.seed);
  return call([&] { return run_analyze(in, params).report.json(); });
}

py::object surrogates(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                      const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  SurrogatesParams params;
  get(p, "method", params.method);
  get(p, "count", params.count);
  get(p, "seed", params.seed);
  get(p, "max_iterations", params.options.max_iterations);
  get(p, "tolerance", params.options.tolerance);
  get(p, "end_match", params.end_match);
  get(p, "max_trim", params.end.max_trim);
  return call([&] { return run_surrogates(in, params).report.json(); });
}

py::object nonlinearity(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                        const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  NonlinearityParams params;
  get(p, "count", params.options.surrogates);
  get(p, "seed", params.options.seed);
  get(p, "statistic", params.statistic);
  get(p, "alternative", params.alternative);
  get(p, "method", params.method);
  get(p, "max_iterations", params.options.surrogate.max_iterations);
  get(p, "delay", params.delay);
  get(p, "dimension", params.options.prediction.dimension);
  get(p, "theiler", params.options.prediction.theiler);
  get(p, "horizon", params.options.prediction.horizon);
  get(p, "neighbours", params.options.prediction.neighbours);
  get(p, "norm", params.norm);
  get(p, "end_match", params.end_match);
  return call([&] { return run_nonlinearity(in, params).report.json(); });
}

py::object density(const Array& parameter, const Array& value, const std::string& file, std::size_t parameter_column,
                   std::size_t value_column, const py::dict& p) {
  DensityParams params;
  get(p, "bins", params.bins);
  get(p, "max_bins", params.max_bins);
  get(p, "kde", params.kde);
  get(p, "bandwidth", params.bandwidth);
  get(p, "low", params.low);
  get(p, "high", params.high);
  get(p, "padding", params.padding);
  check_density_params(params);
  const SeriesInput x = series(parameter, file, parameter_column, std::nullopt);
  const SeriesInput y = series(value, file, value_column, std::nullopt);
  return call([&] {
    return run_density(x.values, y.values, file, parameter_column, value_column, params).report.json();
  });
}

// -p name=value, repeatable: a dict {name: value}.
void get_settings(const py::dict& p, std::map<std::string, double>& target) {
  if (!has(p, "parameter")) return;
  if (!py::isinstance<py::dict>(p["parameter"])) type_error("parameter must be a dict of name: value");
  for (const auto& [name, value] : py::reinterpret_borrow<py::dict>(p["parameter"])) {
    if (!py::isinstance<py::str>(name)) type_error("parameter names must be strings");
    target[py::cast<std::string>(name)] = to_real(value, "parameter");
  }
}

py::object spectrum(const std::string& system, const py::dict& p) {
  SpectrumParams params;
  params.system = system;
  get_settings(p, params.parameters);
  get(p, "time", params.time);
  get(p, "step", params.step);
  get(p, "interval", params.flow_interval);
  get(p, "transient", params.flow_transient);
  get(p, "iterations", params.iterations);
  get(p, "map_interval", params.map_interval);
  get(p, "map_transient", params.map_transient);
  get(p, "seed", params.seed);
  get(p, "exponents", params.delay_exponents);
  get(p, "identity", params.identity);
  return call([&] { return run_spectrum(params).report.json(); });
}

// chaos generate: the JSON without the components, which come back as arrays (name, values) in the
// order the command writes them.
py::tuple generate(const std::string& system, const py::dict& p) {
  GenerateParams params;
  params.system = system;
  get(p, "length", params.length);
  get(p, "seed", params.seed);
  get(p, "components", params.components);
  get_settings(p, params.parameters);
  std::optional<GenerateRun> run;
  {
    py::gil_scoped_release release;
    run.emplace(run_generate(params, {}, false));
  }
  py::list components;
  for (const std::size_t k : run->chosen) {
    const auto& values = run->trajectory.components[k];
    components.append(py::make_tuple(run->trajectory.names[k],
                                     Array(static_cast<py::ssize_t>(values.size()), values.data())));
  }
  return py::make_tuple(to_python(run->report.json()), components);
}

// The series of a file, read as the command reads it (-c -x -l --dt), with the same checks.
py::tuple read_file(const std::string& path, const py::object& column, std::size_t skip, std::optional<std::size_t> length,
               std::optional<double> dt) {
  chaos::ReadOptions options;
  if (py::isinstance<py::str>(column))
    options.column_name = column.cast<std::string>();
  else
    options.column = to_count(column, "column");
  options.skip = skip;
  if (length) options.length = *length;
  options.dt = dt;
  chaos::Series s;
  {
    py::gil_scoped_release release;
    s = chaos::read_series(path, options);
    check_series(s.values, path);
  }
  Array values(static_cast<py::ssize_t>(s.values.size()));
  std::copy(s.values.begin(), s.values.end(), values.mutable_data());
  return py::make_tuple(values, s.column, s.dt ? py::object(py::float_(*s.dt)) : py::object(py::none()));
}

// The number of points of the delay embedding of x, validated as the library validates it.
std::size_t embedding_points(const Array& x, const py::handle& dimension, const py::handle& delay) {
  const std::span<const double> values(x.data(), static_cast<std::size_t>(x.size()));
  check_series(values, "(array)");
  return chaos::DelayEmbedding(values, to_count(dimension, "dimension"), to_count(delay, "delay")).size();
}

// The simulator: a scene is TOML text plus "key=value" overrides, resolved by the library's reader
// (unknown keys, wrong types and impossible values raise ValueError with its message).
mechanism::Scene resolve_scene(const std::string& toml, const std::vector<std::string>& overrides,
                               const std::string& source) {
  return mechanism::read_scene(toml, overrides, source);
}

std::string scene_toml(const std::string& toml, const std::vector<std::string>& overrides, const std::string& source) {
  return mechanism::to_toml(resolve_scene(toml, overrides, source));
}

std::vector<std::string> scene_warnings(const std::string& toml, const std::vector<std::string>& overrides,
                                        const std::string& source) {
  return mechanism::scene_warnings(resolve_scene(toml, overrides, source));
}

// Runs the scene; returns the summary (as `mechanism simulate --json` writes it), the signal names
// and units, the time series (one row per signal) and the stroboscopic samples (one row per signal,
// the revolution numbers apart). Ctrl-C stops the run at its next progress report (about every
// percent of the simulated time).
py::dict simulate_scene(const std::string& toml, const std::vector<std::string>& overrides, const std::string& source,
                        std::optional<bool> stroboscopic, py::object progress) {
  mechanism::Scene scene = resolve_scene(toml, overrides, source);
  if (stroboscopic) scene.run.stroboscopic = *stroboscopic;
  auto callback = std::make_shared<py::object>(std::move(progress));
  std::vector<std::vector<double>> series, strobe;
  std::vector<double> revolutions;
  nlohmann::ordered_json summary;
  mechanism::SignalTable table;
  {
    py::gil_scoped_release release;
    mechanism::SliderCrank system(scene);
    table = mechanism::signal_table(system);
    series.resize(table.names.size());
    strobe.resize(table.names.size());
    std::vector<double> values;
    mechanism::SimulationObserver observer;
    observer.sample = [&](double t, const mechanism::State& x, const mechanism::Evaluation& ev) {
      mechanism::signal_values(system, t, x, ev, values);
      for (std::size_t c = 0; c < values.size(); ++c) series[c].push_back(values[c]);
    };
    if (scene.run.stroboscopic)
      observer.stroboscopic = [&](std::size_t revolution, double t, const mechanism::State& x,
                                  const mechanism::Evaluation& ev) {
        mechanism::signal_values(system, t, x, ev, values);
        revolutions.push_back(static_cast<double>(revolution));
        for (std::size_t c = 0; c < values.size(); ++c) strobe[c].push_back(values[c]);
      };
    observer.progress = [callback](double fraction) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) throw Interrupted{};
      if (!callback->is_none()) (*callback)(fraction);
    };
    try {
      const mechanism::SimulationSummary s = mechanism::simulate(system, observer);
      summary = mechanism::simulation_summary_json(s, system);
    } catch (const Interrupted&) {
      py::gil_scoped_acquire acquire;
      throw py::error_already_set();
    }
  }
  const auto matrix = [](const std::vector<std::vector<double>>& rows) {
    const std::size_t n = rows.empty() ? 0 : rows.front().size();
    py::array_t<double> out({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(n)});
    double* data = out.mutable_data();
    for (const auto& row : rows) data = std::copy(row.begin(), row.end(), data);
    return out;
  };
  py::dict out;
  out["summary"] = to_python(summary);
  out["names"] = table.names;
  out["units"] = table.units;
  out["series"] = matrix(series);
  out["stroboscopic"] = matrix(strobe);
  out["revolution"] = py::array_t<double>(static_cast<py::ssize_t>(revolutions.size()), revolutions.data());
  out["stroboscopic_run"] = scene.run.stroboscopic;
  return out;
}

// The time of the library's own work for one command, without the Python layer: the shared
// computation and its JSON, `repeats` times (scripts/python_timing.py subtracts it from a call's time
// to get the call overhead).
double compute_seconds(const std::string& command, const Array& x, const py::dict& p, std::size_t repeats) {
  const SeriesInput in = series(x, ARRAY, 1, std::nullopt);
  std::function<void()> work;
  AutocorrelationParams a;
  MutualParams m;
  D2Params d;
  if (command == "autocorrelation") {
    get(p, "max_lag", a.max_lag);
    work = [&] { (void)run_autocorrelation(in, a).report.json().size(); };
  } else if (command == "mutual") {
    get(p, "max_delay", m.options.max_delay);
    get(p, "boxes", m.options.boxes);
    work = [&] { (void)run_mutual(in, m).report.json().size(); };
  } else if (command == "d2") {
    get(p, "delay", d.sums.delay);
    get(p, "max_dimension", d.sums.max_dimension);
    get(p, "theiler", d.theiler);
    work = [&] { (void)run_d2(in, d).report.json().size(); };
  } else {
    value_error("compute_seconds: autocorrelation, mutual or d2");
  }
  py::gil_scoped_release release;
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < repeats; ++k) work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / static_cast<double>(repeats);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "The chaos library's commands on NumPy arrays (see the chaos package).";
  m.def("mutual", &mutual);
  m.def("autocorrelation", &autocorrelation);
  m.def("cao", &cao);
  m.def("fnn", &fnn);
  m.def("d2", &d2);
  m.def("lyapunov", &lyapunov);
  m.def("analyze", &analyze);
  m.def("surrogates", &surrogates);
  m.def("generate", &generate);
  m.def("spectrum", &spectrum);
  m.def("density", &density);
  m.def("nonlinearity", &nonlinearity);
  m.def("read", &read_file, py::arg("path"), py::arg("column") = 1, py::arg("skip") = 0, py::arg("length") = py::none(),
        py::arg("dt") = py::none());
  m.def("builtin_series", [](std::size_t length) {
    chaos::Series s = builtin_series(length);
    Array values(static_cast<py::ssize_t>(s.values.size()));
    std::copy(s.values.begin(), s.values.end(), values.mutable_data());
    return py::make_tuple(values, *s.dt);
  });
  m.attr("builtin_series_name") = builtin_series_name;
  m.def("embedding_points", &embedding_points);
  m.def("default_scene_toml", [] { return std::string(mechanism::default_scene_toml()); });
  m.def("scene_toml", &scene_toml);
  m.def("scene_warnings", &scene_warnings);
  m.def("simulate", &simulate_scene);
  m.def("_compute_seconds", &compute_seconds);
  m.def("_last_input_address", [] { return static_cast<std::uintptr_t>(last_input_address); });
}
