// chaos spectrum SYSTEM: the full Lyapunov spectrum of a reference system from its equations
// (tangent dynamics with QR re-orthonormalisation) and the Kaplan-Yorke dimension.

#include <cmath>

#include "chaos/error.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/models/lyapunov_spectrum.hpp"
#include "chaos/models/zoo.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct SpectrumArgs {
  SpectrumParams params;
  std::vector<std::string> settings;
  OutputOptions output;
};

void run(SpectrumArgs& args) {
  args.params.parameters = parse_settings(args.settings);
  auto [s, report] = run_spectrum(args.params, args.output);
  std::ostream& out = report.stream();
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
  add_quiet_option(*command);
  command->add_option("system", args->params.system, "lorenz, rossler, henon, logistic, ikeda or any zoo system "
                                               "(chaos generate --list)")->required();
  command->add_option("-p,--parameter", args->settings, "model parameter name=value (repeatable), as in chaos generate");
  command->add_option("--time", args->params.time, "flows: averaging time (default 10000; zoo systems: their own)");
  command->add_option("--step", args->params.step, "flows: RK4 step (default 0.01; zoo systems: their own; delay: tau / step steps per delay)");
  command->add_option("--interval", args->params.flow_interval, "flows: time between QR factorisations (default 0.1)");
  command->add_option("--transient", args->params.flow_transient, "flows: time not averaged (default 100)");
  command->add_option("--iterations", args->params.iterations, "maps: iterations averaged (default 1000000)");
  command->add_option("--map-interval", args->params.map_interval, "maps: iterations between QR factorisations (default 1)");
  command->add_option("--map-transient", args->params.map_transient, "maps: iterations not averaged (default 1000)");
  command->add_flag("--identity", args->params.identity, "zoo systems: also give what the sum must equal (trace or ln|det J|)");
  command->add_option("--exponents", args->params.delay_exponents, "delay systems: how many leading exponents (1..8, default 6)");
  command->add_option("--seed", args->params.seed, "logistic map: seed of the initial condition")->capture_default_str();
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
