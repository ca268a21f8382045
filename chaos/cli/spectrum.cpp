// chaos spectrum SYSTEM: the full Lyapunov spectrum of a reference system from its equations
// (tangent dynamics with QR re-orthonormalisation) and the Kaplan-Yorke dimension.

#include "chaos/error.hpp"
#include "chaos/generate.hpp"
#include "chaos/lyapunov_spectrum.hpp"
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
};

void run(SpectrumArgs& args) {
  const auto kind = system_from_name(args.system);
  if (!kind || !has_spectrum(*kind))
    throw InvalidInput(ErrorCode::invalid_parameter, "no spectrum for system '" + args.system +
                                                         "': choose lorenz, rossler, henon, logistic or ikeda");
  SpectrumRequest request;
  request.system = *kind;
  request.parameters = parse_settings(args.settings);
  request.seed = args.seed;
  const bool flow = is_flow(*kind);
  // Options of the other kind of system would be silently ignored: refuse them instead.
  if (flow && (args.iterations || args.map_interval || args.map_transient))
    throw InvalidInput(ErrorCode::invalid_parameter, args.system + " is a flow: use --time, --step, --interval, --transient "
                                                                   "(in time units), not --iterations or --map-*");
  if (!flow && (args.time || args.step || args.flow_interval || args.flow_transient))
    throw InvalidInput(ErrorCode::invalid_parameter, args.system + " is a map: use --iterations, --map-interval, "
                                                                   "--map-transient, not --time, --step, --interval, --transient");
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
}

}  // namespace

void register_spectrum(CLI::App& app) {
  auto args = std::make_shared<SpectrumArgs>();
  CLI::App* command = app.add_subcommand("spectrum", "Lyapunov spectrum of a reference system from its equations, with "
                                                     "the Kaplan-Yorke dimension");
  command->add_option("system", args->system, "lorenz, rossler, henon, logistic or ikeda")->required();
  command->add_option("-p,--parameter", args->settings, "model parameter name=value (repeatable), as in chaos generate");
  command->add_option("--time", args->time, "flows: averaging time (default 10000)");
  command->add_option("--step", args->step, "flows: RK4 step (default 0.01)");
  command->add_option("--interval", args->flow_interval, "flows: time between QR factorisations (default 0.1)");
  command->add_option("--transient", args->flow_transient, "flows: time not averaged (default 100)");
  command->add_option("--iterations", args->iterations, "maps: iterations averaged (default 1000000)");
  command->add_option("--map-interval", args->map_interval, "maps: iterations between QR factorisations (default 1)");
  command->add_option("--map-transient", args->map_transient, "maps: iterations not averaged (default 1000)");
  command->add_option("--seed", args->seed, "logistic map: seed of the initial condition")->capture_default_str();
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
