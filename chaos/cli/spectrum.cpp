// chaos spectrum SYSTEM: the full Lyapunov spectrum of a reference system from its equations
// (tangent dynamics with QR re-orthonormalisation) and the Kaplan-Yorke dimension.

#include <cmath>

#include "chaos/error.hpp"
#include "chaos/generate.hpp"
#include "chaos/lyapunov_spectrum.hpp"
#include "chaos/zoo.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct SpectrumArgs {
  std::string system;
  std::vector<std::string> settings;
  OutputOptions output;
  std::optional<double> time, step, flow_interval, flow_transient;
  std::optional<std::size_t> iterations, map_interval, map_transient;
  std::uint64_t seed = 1;
  std::optional<std::size_t> delay_exponents;
  bool identity = false;
};

void write(SpectrumArgs& args, const LyapunovSpectrum& s, Report& report) {
  std::ostream& out = report.stream();
  auto& j = report.json();
  j["exponents"] = s.exponents;
  j["sum"] = s.sum;
  j["kaplan_yorke_dimension"] = s.kaplan_yorke_dimension;
  j["renormalisations"] = s.renormalisations;
  j["averaging_length"] = s.averaging_length;
  j["initial_state"] = s.initial_state;
  if (report.json_mode()) {
    report.write_json(out);
    return;
  }
  report.write_header(out);
  out << "# sum = " << number(s.sum) << "\n# kaplan_yorke_dimension = " << number(s.kaplan_yorke_dimension) << "\n"
      << "# renormalisations = " << s.renormalisations << "\n# index\texponent\n";
  for (std::size_t i = 0; i < s.exponents.size(); ++i) out << i + 1 << "\t" << number(s.exponents[i]) << "\n";
  (void)args;
}

// Options of the other kind of system would be silently ignored: refuse them instead.
void refuse_other_kind_options(const SpectrumArgs& args, bool flow) {
  if (flow && (args.iterations || args.map_interval || args.map_transient))
    throw InvalidInput(ErrorCode::invalid_parameter, args.system + " is a flow: use --time, --step, --interval, --transient "
                                                                   "(in time units), not --iterations or --map-*");
  if (!flow && (args.time || args.step || args.flow_interval || args.flow_transient))
    throw InvalidInput(ErrorCode::invalid_parameter, args.system + " is a map: use --iterations, --map-interval, "
                                                                   "--map-transient, not --time, --step, --interval, --transient");
}

// A zoo system with its own equations (not one of the five reference systems of generate.hpp).
void run_zoo(SpectrumArgs& args, const ZooEntry& entry) {
  const bool flow = entry.kind == ZooKind::flow;
  refuse_other_kind_options(args, flow);
  if (args.delay_exponents && !entry.delay)
    throw InvalidInput(ErrorCode::invalid_parameter, "--exponents applies to delay systems only; " + args.system +
                                                         " has " + std::to_string(entry.dimension) + " exponents");
  const auto overrides = parse_settings(args.settings);
  ZooSpectrumOptions options;
  options.seed = args.seed;
  FlowSpectrumOptions f = entry.flow_spectrum;
  MapSpectrumOptions m = entry.map_spectrum;
  if (args.time) f.time = *args.time;
  if (args.step) f.step = *args.step;
  if (args.flow_interval) f.renormalisation_interval = *args.flow_interval;
  if (args.flow_transient) f.transient = *args.flow_transient;
  if (args.iterations) m.iterations = *args.iterations;
  if (args.map_interval) m.renormalisation_interval = *args.map_interval;
  if (args.map_transient) m.transient = *args.map_transient;
  options.flow = f;
  options.map = m;
  if (entry.delay) {
    options.delay_exponents = args.delay_exponents.value_or(options.delay_exponents);
    // --step sets the delay grid: tau / step steps per delay.
    const auto p = zoo_parameters(entry, overrides);
    options.steps_per_delay = static_cast<std::size_t>(std::lround(p[3] / f.step));
  }
  const LyapunovSpectrum s = zoo_spectrum(entry, overrides, options);

  Report report("spectrum", args.output);
  report.parameter("system", args.system);
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
  if (args.identity) {
    // What the sum must equal: the closed form when trace J (ln|det J|) is constant, otherwise its
    // average along the same orbit (zoo_mean_divergence).
    if (entry.delay || entry.name == "logistic")
      throw InvalidInput(ErrorCode::invalid_parameter, "--identity is not available for " + entry.name);
    const double target = entry.constant_divergence ? entry.divergence : zoo_mean_divergence(entry, overrides, options);
    report.json()["identity"] = {{"sum", target},
                                 {"kind", entry.constant_divergence ? "constant" : "mean along the orbit"}};
    report.parameter("identity_sum", target);
  }
  write(args, s, report);
}

void run(SpectrumArgs& args) {
  const auto kind = system_from_name(args.system);
  // The zoo's own options also apply to the reference systems it contains (lorenz, henon, ...).
  if ((args.identity || args.delay_exponents) && find_zoo_system(args.system)) {
    run_zoo(args, *find_zoo_system(args.system));
    return;
  }
  if (!kind || !has_spectrum(*kind)) {
    if (const ZooEntry* entry = find_zoo_system(args.system)) {
      run_zoo(args, *entry);
      return;
    }
    throw InvalidInput(ErrorCode::invalid_parameter, "no spectrum for system '" + args.system +
                                                         "': choose one of " + zoo_names());
  }
  if (args.delay_exponents || args.identity)
    throw InvalidInput(ErrorCode::invalid_parameter, "--exponents and --identity apply to zoo systems only; use the zoo "
                                                     "names (chaos generate --list)");
  SpectrumRequest request;
  request.system = *kind;
  request.parameters = parse_settings(args.settings);
  request.seed = args.seed;
  const bool flow = is_flow(*kind);
  refuse_other_kind_options(args, flow);
  if (args.time) request.flow.time = *args.time;
  if (args.step) request.flow.step = *args.step;
  if (args.flow_interval) request.flow.renormalisation_interval = *args.flow_interval;
  if (args.flow_transient) request.flow.transient = *args.flow_transient;
  if (args.iterations) request.map.iterations = *args.iterations;
  if (args.map_interval) request.map.renormalisation_interval = *args.map_interval;
  if (args.map_transient) request.map.transient = *args.map_transient;
  const LyapunovSpectrum s = spectrum(request);

  Report report("spectrum", args.output);
  report.parameter("system", args.system);
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
    if (*kind == SystemKind::logistic) report.parameter("seed", args.seed);
  }
  write(args, s, report);
}

}  // namespace

void register_spectrum(CLI::App& app) {
  auto args = std::make_shared<SpectrumArgs>();
  CLI::App* command = app.add_subcommand("spectrum", "Lyapunov spectrum of a reference system from its equations, with "
                                                     "the Kaplan-Yorke dimension");
  command->add_option("system", args->system, "lorenz, rossler, henon, logistic, ikeda or any zoo system "
                                               "(chaos generate --list)")->required();
  command->add_option("-p,--parameter", args->settings, "model parameter name=value (repeatable), as in chaos generate");
  command->add_option("--time", args->time, "flows: averaging time (default 10000; zoo systems: their own)");
  command->add_option("--step", args->step, "flows: RK4 step (default 0.01; zoo systems: their own; delay: tau / step steps per delay)");
  command->add_option("--interval", args->flow_interval, "flows: time between QR factorisations (default 0.1)");
  command->add_option("--transient", args->flow_transient, "flows: time not averaged (default 100)");
  command->add_option("--iterations", args->iterations, "maps: iterations averaged (default 1000000)");
  command->add_option("--map-interval", args->map_interval, "maps: iterations between QR factorisations (default 1)");
  command->add_option("--map-transient", args->map_transient, "maps: iterations not averaged (default 1000)");
  command->add_flag("--identity", args->identity, "zoo systems: also give what the sum must equal (trace or ln|det J|)");
  command->add_option("--exponents", args->delay_exponents, "delay systems: how many leading exponents (1..8, default 6)");
  command->add_option("--seed", args->seed, "logistic map: seed of the initial condition")->capture_default_str();
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
