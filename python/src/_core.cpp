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
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/series.hpp"
#include "commands.hpp"
#include "mechanism/scene.hpp"
#include "mechanism/signals.hpp"
#include "mechanism/simulate.hpp"
#include "mechanism/slider_crank.hpp"
#include "study/error.hpp"
#include "study/grid.hpp"
#include "study/result_store.hpp"
#include "study/run_sweep.hpp"
#include "study/sweep.hpp"
#include "summary_json.hpp"
#include "sweep_parameters.hpp"

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

// A NumPy integer scalar (np.int64(3), an element of an integer array) counts as an integer; NumPy's
// bool does not, as Python's does not.
bool is_numpy_integer(const py::handle& v) {
  static PyObject* const integer = py::object(py::module_::import("numpy").attr("integer")).release().ptr();
  return PyObject_IsInstance(v.ptr(), integer) == 1;
}

std::size_t to_count(const py::handle& v, const char* name) {
  if (PyBool_Check(v.ptr()) || !(PyLong_Check(v.ptr()) || is_numpy_integer(v)))
    type_error(std::string(name) + " must be an integer (got " + std::string(py::str(py::type::of(v).attr("__name__"))) + ")");
  const py::object number = py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()));
  if (!number) throw py::error_already_set();
  int overflow = 0;
  const long long value = PyLong_AsLongLongAndOverflow(number.ptr(), &overflow);
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
void get(const py::dict& p, const char* name, std::vector<std::size_t>& target) {
  if (!has(p, name)) return;
  target.clear();
  for (const auto& v : p[name]) target.push_back(to_count(v, name));
}
void get(const py::dict& p, const char* name, std::vector<std::string>& target) {
  if (!has(p, name)) return;
  if (py::isinstance<py::str>(p[name])) type_error(std::string(name) + " must be a list of strings, not one string");
  target.clear();
  for (const auto& v : p[name]) {
    if (!py::isinstance<py::str>(v)) type_error(std::string(name) + " must hold strings");
    target.push_back(v.cast<std::string>());
  }
}
// name=value settings (-p name=value, repeatable): a dict {name: value}.
void get(const py::dict& p, const char* name, std::map<std::string, double>& target) {
  if (!has(p, name)) return;
  if (!py::isinstance<py::dict>(p[name])) type_error(std::string(name) + " must be a dict of name: value");
  for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(p[name])) {
    if (!py::isinstance<py::str>(key)) type_error(std::string(name) + " names must be strings");
    target[py::cast<std::string>(key)] = to_real(value, name);
  }
}

// A command's keyword arguments, read by its parameter table (parameter_table.hpp).
template <class Params>
void read_parameters(const py::dict& p, Params& params, const ParameterTable<Params>& table) {
  for (const auto& parameter : table)
    std::visit([&](auto* field) { get(p, parameter.name.c_str(), *field); }, parameter.field(params));
}

// A field's value as Python's default: None for a field left out (an empty optional, list or map).
py::object python_value(const ParameterField& field) {
  return std::visit(
      [](const auto* value) -> py::object {
        using T = std::remove_cv_t<std::remove_pointer_t<decltype(value)>>;
        if constexpr (std::is_same_v<T, std::optional<std::size_t>> || std::is_same_v<T, std::optional<double>>)
          return *value ? py::cast(**value) : py::none();
        else if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>)
          return py::cast(*value);
        else
          return value->empty() ? py::none() : py::cast(*value);
      },
      field);
}

// The table as python/src/chaos/__init__.py builds the functions' signatures from it: (name,
// default, flags) per parameter, in the table's order.
template <class Params>
py::list describe(const ParameterTable<Params>& table) {
  Params defaults;
  py::list out;
  for (const auto& parameter : table)
    out.append(py::make_tuple(parameter.name,
                              parameter.default_described ? py::none() : python_value(parameter.field(defaults)),
                              parameter.flags));
  return out;
}

py::list parameters(const std::string& command) {
  if (command == "mutual") return describe(mutual_parameters());
  if (command == "autocorrelation") return describe(autocorrelation_parameters());
  if (command == "cao") return describe(cao_parameters());
  if (command == "fnn") return describe(fnn_parameters());
  if (command == "d2") return describe(d2_parameters());
  if (command == "lyapunov") return describe(lyapunov_parameters());
  if (command == "lyapunov_maps") return describe(lyapunov_maps_parameters());
  if (command == "analyze") return describe(analyze_parameters());
  if (command == "surrogates") return describe(surrogates_parameters());
  if (command == "nonlinearity") return describe(nonlinearity_parameters());
  if (command == "generate") return describe(generate_parameters());
  if (command == "spectrum") return describe(spectrum_parameters());
  if (command == "density") return describe(density_parameters());
  if (command == "section") return describe(section_parameters());
  if (command == "validate") return describe(validate_parameters());
  if (command == "zoo") return describe(zoo_parameters());
  if (command == "zoo_series") return describe(zoo_series_parameters());
  if (command == "study_sweep") return describe(study::sweep_parameters());
  value_error("no parameter table for '" + command + "'");
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

// Runs `compute` without the GIL; the result's JSON comes back as Python objects. A progress hook
// that found a pending signal (Interrupted) stops the computation, and the signal's exception
// (KeyboardInterrupt for Ctrl-C) is raised.
template <class F>
py::object call(F&& compute) {
  nlohmann::ordered_json json;
  try {
    py::gil_scoped_release release;
    json = compute();
  } catch (const Interrupted&) {
    throw py::error_already_set();
  }
  return to_python(json);
}

// A command's progress hook (options.progress), the library's cancellation point: each call (every
// thousandth of the correlation sums, every 4096 points of Cao and FNN, every block of reference
// points of the divergence curve, every IAAFT iteration) checks for a pending signal and stops the
// computation when there is one; with `callback`, it is also handed the fraction done.
std::function<void(double)> progress_hook(py::object callback) {
  auto shared = std::make_shared<py::object>(std::move(callback));
  return [shared](double fraction) {
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) throw Interrupted{};
    if (!shared->is_none()) (*shared)(fraction);
  };
}

// The same for analyze's steps: the callback is handed the step's name and the fraction of it done.
std::function<void(const std::string&, double)> step_progress_hook(py::object callback) {
  auto shared = std::make_shared<py::object>(std::move(callback));
  return [shared](const std::string& step, double fraction) {
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) throw Interrupted{};
    if (!shared->is_none()) (*shared)(step, fraction);
  };
}

py::object mutual(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt, const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  MutualParams params;
  read_parameters(p, params, mutual_parameters());
  return call([&] { return run_mutual(in, params).report.json(); });
}

py::object autocorrelation(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                           const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  AutocorrelationParams params;
  read_parameters(p, params, autocorrelation_parameters());
  return call([&] { return run_autocorrelation(in, params).report.json(); });
}

py::object cao(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
               const py::dict& p, py::object progress) {
  const SeriesInput in = series(x, file, column, dt);
  CaoParams params;
  read_parameters(p, params, cao_parameters());
  params.options.progress = progress_hook(std::move(progress));
  return call([&] { return run_cao(in, params).report.json(); });
}

py::object fnn(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
               const py::dict& p, py::object progress) {
  const SeriesInput in = series(x, file, column, dt);
  FnnParams params;
  read_parameters(p, params, fnn_parameters());
  params.options.progress = progress_hook(std::move(progress));
  return call([&] { return run_fnn(in, params).report.json(); });
}

py::object d2(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt, const py::dict& p,
              py::object progress) {
  const SeriesInput in = series(x, file, column, dt);
  D2Params params;
  read_parameters(p, params, d2_parameters());
  params.sums.progress = progress_hook(std::move(progress));
  params.halves_progress = params.sums.progress;  // again from 0 for each half (Ctrl-C is noticed there too)
  return call([&] { return run_d2(in, params).report.json(); });
}

py::object lyapunov(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                    const py::dict& p, py::object progress) {
  const SeriesInput in = series(x, file, column, dt);
  LyapunovParams params;
  read_parameters(p, params, lyapunov_parameters());
  // With the cross-check the other method's curve is the second half of the work.
  const std::function<void(double)> hook = progress_hook(std::move(progress));
  if (hook) params.choice_progress = [hook](double) { hook(0.0); };  // Cao's method: Ctrl-C is noticed there
  if (hook && params.cross_check) {
    params.options.progress = [hook](double f) { hook(0.5 * f); };
    params.check_progress = [hook](double f) { hook(0.5 + 0.5 * f); };
    // The local maps report no fraction of their own: the hook only sees that the work goes on
    // (and Ctrl-C is noticed) before them, before their run at m + 1 and after them.
    params.maps_progress = [hook](double) { hook(1.0); };
  } else {
    params.options.progress = hook;
  }
  return call([&] { return run_lyapunov(in, params).report.json(); });
}

py::object lyapunov_maps(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                         const py::dict& p) {
  const SeriesInput in = series(x, file, column, dt);
  LyapunovMapsParams params;
  read_parameters(p, params, lyapunov_maps_parameters());
  return call([&] { return run_lyapunov_maps(in, params).report.json(); });
}

py::tuple analyze(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                   const py::dict& p, py::object progress) {
  const SeriesInput in = series(x, file, column, dt);
  AnalyzeParams params;
  read_parameters(p, params, analyze_parameters());
  params.progress = step_progress_hook(std::move(progress));
  params.mutual_curve = true;  // the information curve, for the plot (the JSON does not change)
  nlohmann::ordered_json json, evidence = nlohmann::ordered_json::object();
  try {
    py::gil_scoped_release release;
    AnalyzeRun run = run_analyze(in, params);
    json = std::move(run.report.json());
    // What `chaos analyze --plot` draws beyond the JSON: the information curve and the local
    // slopes of the correlation sums.
    if (run.mutual)
      evidence["mutual"] = {{"delay", run.mutual->delay}, {"mutual_information", run.mutual->information}};
    if (run.fnn) evidence["fnn_threshold"] = run.fnn_options.threshold;
    if (const auto& d = run.analysis.d2) {
      nlohmann::ordered_json slopes = nlohmann::ordered_json::array();
      for (const auto& row : d->local_slope) {
        nlohmann::ordered_json r = nlohmann::ordered_json::array();
        for (const auto& v : row) r.push_back(optional_json(v));
        slopes.push_back(std::move(r));
      }
      evidence["d2"] = {{"dimension", d->dimension}, {"radius", d->radius}, {"local_slope", std::move(slopes)},
                        {"scaling_region", interval_json(d->scaling_region)}};
    }
  } catch (const Interrupted&) {
    throw py::error_already_set();
  }
  return py::make_tuple(to_python(json), to_python(evidence));
}

py::object surrogates(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                      const py::dict& p, py::object progress) {
  const SeriesInput in = series(x, file, column, dt);
  SurrogatesParams params;
  read_parameters(p, params, surrogates_parameters());
  params.options.progress = progress_hook(std::move(progress));
  return call([&] { return run_surrogates(in, params).report.json(); });
}

py::object nonlinearity(const Array& x, const std::string& file, std::size_t column, std::optional<double> dt,
                        const py::dict& p, py::object progress) {
  const SeriesInput in = series(x, file, column, dt);
  NonlinearityParams params;
  read_parameters(p, params, nonlinearity_parameters());
  params.options.progress = progress_hook(std::move(progress));
  const std::function<void(double)> hook = params.options.progress;
  params.choice_progress = [hook](double) { hook(0.0); };  // Cao's method: Ctrl-C is noticed there
  return call([&] { return run_nonlinearity(in, params).report.json(); });
}

py::object density(const Array& parameter, const Array& value, const std::string& file, std::size_t parameter_column,
                   std::size_t value_column, const py::dict& p) {
  DensityParams params;
  read_parameters(p, params, density_parameters());
  check_density_params(params);
  const SeriesInput x = series(parameter, file, parameter_column, std::nullopt);
  const SeriesInput y = series(value, file, value_column, std::nullopt);
  return call([&] {
    return run_density(x.values, y.values, file, parameter_column, value_column, params).report.json();
  });
}

// chaos section: `columns` the data columns (each a float64 array, all of one length) with their
// 1-based numbers in params["columns"], `times` the time column (empty without one).
SectionParams section_params(const py::dict& p) {
  SectionParams params;
  read_parameters(p, params, section_parameters());
  check_section_params(params);  // before any input is read, as the command checks them
  return params;
}

py::object section(const py::list& columns, const Array& times, const std::string& file, const py::dict& p) {
  const SectionParams params = section_params(p);
  std::vector<Array> held;
  std::vector<std::span<const double>> data;
  for (const auto& c : columns) {
    held.push_back(c.cast<Array>());
    data.emplace_back(held.back().data(), static_cast<std::size_t>(held.back().size()));
  }
  const std::span<const double> t(times.data(), static_cast<std::size_t>(times.size()));
  // What the command's reader refuses in a file: no rows, NaN or infinity.
  if (!data.empty() && data.front().empty())
    throw chaos::InvalidInput(chaos::ErrorCode::empty, file + ": the series is empty (no samples)");
  const auto finite = [&](std::span<const double> x, std::size_t column) {
    for (std::size_t i = 0; i < x.size(); ++i)
      if (!std::isfinite(x[i]))
        throw chaos::InvalidInput(chaos::ErrorCode::non_finite, file + ": row " + std::to_string(i + 1) + ": column " +
                                                                    std::to_string(column) + ": " + number(x[i]) +
                                                                    " is not finite; NaN and infinity are refused");
  };
  for (std::size_t k = 0; k < data.size() && k < params.columns.size(); ++k) finite(data[k], params.columns[k]);
  if (params.time_column) finite(t, *params.time_column);
  return call([&] { return run_section(data, t, file, params).report.json(); });
}

// The columns of a file, read as `chaos section FILE -c ... -x -l --time-column` reads them:
// (columns read, their values, the times or an empty array).
py::tuple section_file_columns(const std::string& path, const py::dict& p, std::size_t skip,
                               std::optional<std::size_t> length) {
  SectionParams params = section_params(p);
  SectionColumns input;
  {
    py::gil_scoped_release release;
    input = read_section_columns(chaos::read_text(path), path, params, skip, length);
  }
  const auto array = [](const std::vector<double>& v) { return Array(static_cast<py::ssize_t>(v.size()), v.data()); };
  py::list values;
  for (const auto& c : input.columns) values.append(array(c));
  return py::make_tuple(params.columns, values, array(input.times));
}

// chaos validate: each case's result passed to `progress` (a callable taking the fraction of cases
// done, or None); Ctrl-C stops between cases.
py::object validate_cases_run(const py::dict& p, py::object progress) {
  ValidateParams params;
  read_parameters(p, params, validate_parameters());
  const std::size_t count = validate_cases(params).size();
  auto callback = std::make_shared<py::object>(std::move(progress));
  std::size_t done = 0;
  return call([&] {
    Report report = validate_report(params);
    run_validate(params, report, [&](const chaos::ValidationResult&) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) throw Interrupted{};
      ++done;
      if (!callback->is_none()) (*callback)(static_cast<double>(done) / static_cast<double>(count));
    });
    return report.json();
  });
}

// chaos validate --list: the selected cases' rows (id, quantity, value, low, high, source, kind).
py::list validate_list(const py::dict& p) {
  ValidateParams params;
  read_parameters(p, params, validate_parameters());
  py::list out;
  for (const chaos::Reference& r : validate_cases(params)) {
    py::dict row;
    row["id"] = r.id;
    row["system"] = r.system;
    row["quantity"] = r.quantity;
    row["value"] = r.value ? py::object(py::float_(*r.value)) : py::object(py::none());
    row["low"] = r.low;
    row["high"] = r.high;
    row["source"] = r.source;
    row["kind"] = r.kind;
    out.append(row);
  }
  return out;
}

// chaos zoo: the suite's data (run_zoo's JSON) and its Markdown report. `progress` (a callable or
// None) gets the fraction of cases done; Ctrl-C stops after the cases being run.
py::object zoo_run(const py::dict& p, py::object progress) {
  ZooParams params;
  read_parameters(p, params, zoo_parameters());
  auto callback = std::make_shared<py::object>(std::move(progress));
  return call([&] {
    ZooRun run = run_zoo(params, [&](std::size_t done, std::size_t total, const chaos::ZooCase&,
                                     const chaos::ZooCaseResult&) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) throw Interrupted{};
      if (!callback->is_none()) (*callback)(static_cast<double>(done) / static_cast<double>(total));
    });
    run.json["markdown"] = run.markdown;
    return run.json;
  });
}

// chaos zoo --series NAME: the JSON without the series, and the series as an array.
py::tuple zoo_series(const std::string& name, const py::dict& p) {
  ZooSeriesParams params;
  params.name = name;
  read_parameters(p, params, zoo_series_parameters());
  std::optional<ZooSeriesRun> run;
  {
    py::gil_scoped_release release;
    run.emplace(run_zoo_series(params));
  }
  nlohmann::ordered_json json = run->report.json();
  json.erase("x");
  return py::make_tuple(to_python(json), Array(static_cast<py::ssize_t>(run->x.size()), run->x.data()));
}

py::object spectrum(const std::string& system, const py::dict& p) {
  SpectrumParams params;
  params.system = system;
  read_parameters(p, params, spectrum_parameters());
  return call([&] { return run_spectrum(params).report.json(); });
}

// chaos generate: the JSON without the components, which come back as arrays (name, values) in the
// order the command writes them.
py::tuple generate(const std::string& system, const py::dict& p) {
  GenerateParams params;
  params.system = system;
  read_parameters(p, params, generate_parameters());
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

// study sweep: the spec as `study sweep` builds it from its options (scene text and source, --set,
// --axis, and the keyword arguments of its parameter table, study::sweep_parameters), run into `directory`
// on `threads` threads (ResultStore, run_sweep, assemble: the code behind the command), returning
// the command's summary (study::summary_json) and the scene's warnings. `progress` (a callable or None) gets the fraction of
// points done; Ctrl-C stops the sweep after the points being computed (a --resume finishes it).
py::tuple study_sweep(const std::string& toml, const std::string& source, const std::vector<std::string>& overrides,
                     const std::vector<std::string>& axes, const py::dict& p, const std::string& directory, bool resume,
                     std::size_t threads, py::object progress) {
  study::SweepParams params;
  read_parameters(p, params, study::sweep_parameters());
  if (!toml.empty()) {
    params.spec.scene_text = toml;
    params.spec.scene_source = source;
  }
  params.spec.overrides = overrides;
  std::vector<study::Axis> parsed;
  for (const auto& a : axes) parsed.push_back(study::parse_axis(a));
  params.spec.grid = study::Grid(std::move(parsed));
  const study::SweepSpec spec = study::sweep_spec(std::move(params));
  if (threads == 0) value_error("threads must be at least 1 (got 0)");
  auto callback = std::make_shared<py::object>(std::move(progress));
  study::SweepSummary summary;
  const auto start = std::chrono::steady_clock::now();
  {
    py::gil_scoped_release release;
    spec.validate();
    const study::ResultStore store(directory, spec, resume);
    study::SweepExecution exec;
    exec.threads = threads;
    exec.progress = [callback](const study::SweepProgress& at) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) throw Interrupted{};
      if (!callback->is_none() && at.to_do)
        (*callback)(static_cast<double>(at.done) / static_cast<double>(at.to_do));
    };
    study::SweepProgress done;
    try {
      done = study::run_sweep(spec, store, exec);
    } catch (const Interrupted&) {
      py::gil_scoped_acquire acquire;
      throw py::error_already_set();
    }
    store.assemble();
    summary = study::summarise_sweep(spec, store, done.done, done.skipped);
  }
  // The command's summary (study::summary_json), key for key; the scene's warnings beside it.
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::ordered_json json(study::summary_json(summary, directory, threads, 1, wall));
  return py::make_tuple(to_python(json), mechanism::scene_warnings(study::point_scene(spec, 0)));
}

// The time of the library's own work for one command, without the Python layer: the shared
// computation and its JSON, `repeats` times (scripts/measure/python_timing.py subtracts it from a call's time
// to get the call overhead).
double compute_seconds(const std::string& command, const Array& x, const py::dict& p, std::size_t repeats) {
  const SeriesInput in = series(x, ARRAY, 1, std::nullopt);
  std::function<void()> work;
  AutocorrelationParams a;
  MutualParams m;
  D2Params d;
  if (command == "autocorrelation") {
    read_parameters(p, a, autocorrelation_parameters());
    work = [&] { (void)run_autocorrelation(in, a).report.json().size(); };
  } else if (command == "mutual") {
    read_parameters(p, m, mutual_parameters());
    work = [&] { (void)run_mutual(in, m).report.json().size(); };
  } else if (command == "d2") {
    read_parameters(p, d, d2_parameters());
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
  m.def("parameters", &parameters);
  m.def("mutual", &mutual);
  m.def("autocorrelation", &autocorrelation);
  m.def("cao", &cao);
  m.def("fnn", &fnn);
  m.def("d2", &d2);
  m.def("lyapunov", &lyapunov);
  m.def("lyapunov_maps", &lyapunov_maps);
  m.def("analyze", &analyze);
  m.def("surrogates", &surrogates);
  m.def("generate", &generate);
  m.def("spectrum", &spectrum);
  m.def("density", &density);
  m.def("nonlinearity", &nonlinearity);
  m.def("section", &section);
  m.def("section_file_columns", &section_file_columns);
  m.def("check_section", [](const py::dict& p) { (void)section_params(p); });
  m.def("validate", &validate_cases_run);
  m.def("validate_list", &validate_list);
  m.def("zoo_series", &zoo_series);
  m.def("zoo", &zoo_run);
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
  m.def("study_sweep", &study_sweep);
  m.def("_compute_seconds", &compute_seconds);
  m.def("_last_input_address", [] { return static_cast<std::uintptr_t>(last_input_address); });
}
