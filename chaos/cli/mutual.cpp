// chaos mutual: average mutual information I(tau) and its first minimum (the delay).

#include <sstream>

#include "chaos/mutual_information.hpp"
#include "chaos/error.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"
#include "plot.hpp"
#include "plot_panels.hpp"

namespace chaos::cli {

namespace {

struct MutualArgs {
  InputOptions input;
  OutputOptions output;
  MutualParams params;
  std::string plot;
};

// I(tau) against tau (samples, or time units with --dt) with the first minimum marked.
std::string plot_script(const MutualInformationResult& result, const std::optional<std::size_t>& minimum,
                        const std::optional<double>& dt) {
  std::ostringstream s;
  s << "set grid\n";
  mutual_information_panel(
      s, result, minimum, "first minimum",
      "average mutual information: first minimum " +
          (minimum ? "at tau = " + std::to_string(*minimum) +
                         (dt ? " samples = " + number(static_cast<double>(*minimum) * *dt) : std::string())
                   : std::string("none within the range")),
      dt);
  return s.str();
}

void run(MutualArgs& args) {
  const Series series = load_series(args.input);
  auto [result, minimum, no_minimum, report] =
      run_mutual({series.values, args.input.file, series.column, series.dt}, args.params, mode_of(args.output));
  if (!args.plot.empty()) render_plot(plot_script(result, minimum, series.dt), args.plot);
  std::ostream* table = report.open_table(args.output);
  if (!table) return;
  std::ostream& out = *table;
  const double dt = series.dt.value_or(1.0);
  out << "# first_minimum = " << (minimum ? std::to_string(*minimum) : "none: " + no_minimum) << "\n";
  if (minimum && series.dt) out << "# first_minimum_time = " << number(static_cast<double>(*minimum) * dt) << "\n";
  out << (series.dt ? "# delay\tdelay_time\tmutual_information\n" : "# delay\tmutual_information\n");
  for (std::size_t k = 0; k < result.delay.size(); ++k) {
    out << result.delay[k];
    if (series.dt) out << "\t" << number(static_cast<double>(result.delay[k]) * dt);
    out << "\t" << number(result.information[k]) << "\n";
  }
}

}  // namespace

void register_mutual(CLI::App& app) {
  auto args = std::make_shared<MutualArgs>();
  CLI::App* command = app.add_subcommand("mutual", "average mutual information I(tau) in nats and its first minimum");
  add_quiet_option(*command);
  add_input_options(*command, args->input);
  add_options(*command, args->params, mutual_parameters());
  add_plot_option(*command, args->plot, "draw I(tau) with the first minimum marked to FILE.png or FILE.svg");
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
