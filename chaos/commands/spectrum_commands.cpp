// spectrum: the computation and the JSON (commands.hpp).

#include <cmath>

#include "chaos/error.hpp"
#include "chaos/models/zoo.hpp"
#include "commands.hpp"
#include "report_parameters.hpp"

namespace chaos::cli {

namespace {

void fill(const LyapunovSpectrum& s, Report& report) {
  auto& j = report.json();
  j["exponents"] = s.exponents;
  j["sum"] = s.sum;
  j["kaplan_yorke_dimension"] = s.kaplan_yorke_dimension;
  j["renormalisations"] = s.renormalisations;
  j["averaging_length"] = s.averaging_length;
  j["initial_state"] = s.initial_state;
}

// Options of the other kind of system would be silently ignored: refuse them instead.
void refuse_other_kind_options(const SpectrumParams& params, bool flow) {
  if (flow && (params.iterations || params.map_interval || params.map_transient))
    throw InvalidInput(ErrorCode::invalid_parameter, params.system + " is a flow: use --time, --step, --interval, --transient "
                                                                   "(in time units), not --iterations or --map-*");
  if (!flow && (params.time || params.step || params.flow_interval || params.flow_transient))
    throw InvalidInput(ErrorCode::invalid_parameter, params.system + " is a map: use --iterations, --map-interval, "
                                                                   "--map-transient, not --time, --step, --interval, --transient");
}

// A zoo system with its own equations (not one of the five reference systems of generate.hpp).
SpectrumRun run_zoo(const SpectrumParams& params, const ZooEntry& entry, const OutputOptions& output) {
  const bool flow = entry.kind == ZooKind::flow;
  refuse_other_kind_options(params, flow);
  if (params.delay_exponents && !entry.delay)
    throw InvalidInput(ErrorCode::invalid_parameter, "--exponents applies to delay systems only; " + params.system +
                                                         " has " + std::to_string(entry.dimension) + " exponents");
  const auto overrides = params.parameters;
  ZooSpectrumOptions options;
  options.seed = params.seed;
  FlowSpectrumOptions f = entry.flow_spectrum;
  MapSpectrumOptions m = entry.map_spectrum;
  if (params.time) f.time = *params.time;
  if (params.step) f.step = *params.step;
  if (params.flow_interval) f.renormalisation_interval = *params.flow_interval;
  if (params.flow_transient) f.transient = *params.flow_transient;
  if (params.iterations) m.iterations = *params.iterations;
  if (params.map_interval) m.renormalisation_interval = *params.map_interval;
  if (params.map_transient) m.transient = *params.map_transient;
  options.flow = f;
  options.map = m;
  if (entry.delay) {
    options.delay_exponents = params.delay_exponents.value_or(options.delay_exponents);
    // --step sets the delay grid: tau / step steps per delay.
    const auto p = zoo_parameters(entry, overrides);
    options.steps_per_delay = static_cast<std::size_t>(std::lround(p[3] / f.step));
  }
  const LyapunovSpectrum s = zoo_spectrum(entry, overrides, options);

  Report report("spectrum", output);
  report.parameter("system", params.system);
  report_parameters(report, params, spectrum_parameters());
  const auto values = zoo_parameters(entry, overrides);
  for (std::size_t i = 0; i < values.size(); ++i) report.parameter(entry.parameters[i].name, values[i]);
  if (flow) {
    const auto& used = std::get<FlowSpectrumOptions>(s.settings);
    report.parameter("step", used.step).parameter("renormalisation_interval", used.renormalisation_interval)
        .parameter("transient", used.transient).parameter("time", used.time)
        .parameter("units", std::string("per time unit"));
    if (entry.delay) report.parameter("exponents", options.delay_exponents);
  } else {
    report.parameter("renormalisation_interval", m.renormalisation_interval)
        .parameter("transient", m.transient).parameter("iterations", m.iterations)
        .parameter("units", std::string("per iteration"));
  }
  if (params.identity) {
    // What the sum must equal: the closed form when trace J (ln|det J|) is constant, otherwise its
    // average along the same orbit (zoo_mean_divergence).
    if (entry.delay || entry.name == "logistic")
      throw InvalidInput(ErrorCode::invalid_parameter, "--identity is not available for " + entry.name);
    const double target = entry.constant_divergence ? entry.divergence : zoo_mean_divergence(entry, overrides, options);
    report.json()["identity"] = {{"sum", target},
                                 {"kind", entry.constant_divergence ? "constant" : "mean along the orbit"}};
    report.parameter("identity_sum", target);
  }
  fill(s, report);
  return {s, std::move(report)};
}

}  // namespace

SpectrumRun run_spectrum(const SpectrumParams& params, const OutputOptions& output) {
  const auto kind = system_from_name(params.system);
  // The zoo's own options also apply to the reference systems it contains (lorenz, henon, ...).
  if ((params.identity || params.delay_exponents) && find_zoo_system(params.system)) {
    return run_zoo(params, *find_zoo_system(params.system), output);
  }
  if (!kind || !has_spectrum(*kind)) {
    if (const ZooEntry* entry = find_zoo_system(params.system)) {
      return run_zoo(params, *entry, output);
    }
    throw InvalidInput(ErrorCode::invalid_parameter, "no spectrum for system '" + params.system +
                                                         "': choose one of " + zoo_names());
  }
  if (params.delay_exponents || params.identity)
    throw InvalidInput(ErrorCode::invalid_parameter, "--exponents and --identity apply to zoo systems only; use the zoo "
                                                     "names (chaos generate --list)");
  SpectrumRequest request;
  request.system = *kind;
  request.parameters = params.parameters;
  request.seed = params.seed;
  const bool flow = is_flow(*kind);
  refuse_other_kind_options(params, flow);
  if (params.time) request.flow.time = *params.time;
  if (params.step) request.flow.step = *params.step;
  if (params.flow_interval) request.flow.renormalisation_interval = *params.flow_interval;
  if (params.flow_transient) request.flow.transient = *params.flow_transient;
  if (params.iterations) request.map.iterations = *params.iterations;
  if (params.map_interval) request.map.renormalisation_interval = *params.map_interval;
  if (params.map_transient) request.map.transient = *params.map_transient;
  const LyapunovSpectrum s = spectrum(request);

  Report report("spectrum", output);
  report.parameter("system", params.system);
  report_parameters(report, params, spectrum_parameters());
  for (const auto& p : system_parameters(*kind))
    if (p.name != "dt" && p.name != "step" && p.name != "transient") {
      const auto it = request.parameters.find(p.name);
      report.parameter(p.name, it == request.parameters.end() ? p.default_value : it->second);
    }
  if (flow) {
    report.parameter("step", request.flow.step).parameter("renormalisation_interval", request.flow.renormalisation_interval)
        .parameter("transient", request.flow.transient).parameter("time", request.flow.time)
        .parameter("units", std::string("per time unit"));
  } else {
    report.parameter("renormalisation_interval", request.map.renormalisation_interval)
        .parameter("transient", request.map.transient).parameter("iterations", request.map.iterations)
        .parameter("units", std::string("per iteration"));
    if (*kind == SystemKind::logistic) report.parameter("seed", params.seed);
  }
  fill(s, report);
  return {s, std::move(report)};
}

}  // namespace chaos::cli
