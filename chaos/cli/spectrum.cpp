// chaos spectrum SYSTEM: the full Lyapunov spectrum of a reference system from its equations
// (tangent dynamics with QR re-orthonormalisation) and the Kaplan-Yorke dimension.

#include <cmath>

#include "chaos/error.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/models/lyapunov_spectrum.hpp"
#include "chaos/models/zoo.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"

namespace chaos::cli {

namespace {

struct SpectrumArgs {
  SpectrumParams params;
  OutputOptions output;
};

void run(SpectrumArgs& args) {
  auto [s, report] = run_spectrum(args.params, args.output);
  std::ostream* table = report.begin_table();
  if (!table) return;
  std::ostream& out = *table;
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
  add_options(*command, args->params, spectrum_parameters(), parse_settings);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
