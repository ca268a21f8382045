// chaos autocorrelation: r(k) by FFT, its first zero crossing and 1/e time.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "chaos/autocorrelation.hpp"
#include "chaos/format.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"
#include "plot.hpp"

namespace chaos::cli {

namespace {

struct AutocorrelationArgs {
  InputOptions input;
  OutputOptions output;
  AutocorrelationParams params;
  std::string plot;
};

// r(lag) against the lag (samples, or time units with --dt), the 1/e level and its crossing marked.
std::string plot_script(const AutocorrelationResult& result, const std::optional<double>& decay,
                        const std::optional<std::size_t>& zero, const std::optional<double>& dt) {
  const double scale = dt.value_or(1.0);
  const double level = std::exp(-1.0);
  std::ostringstream s;
  s << "set grid\nset key top right\nset xlabel '" << (dt ? "lag (time units)" : "lag (samples)")
    << "'\nset ylabel 'r(lag)'\nset yrange [-1:1]\nset title 'autocorrelation: 1/e time ";
  if (decay)
    s << format_number(*decay, Precision::title) << " samples" << (dt ? " = " + format_number(*decay * scale, Precision::title) + " time units" : std::string());
  else
    s << "none within the range";
  s << ", first zero crossing " << (zero ? std::to_string(*zero) : std::string("none")) << "' noenhanced\n";
  s << "set arrow 1 from graph 0, first " << level << " to graph 1, first " << level << " nohead dt 2\n";
  s << "set label 1 '1/e' at graph 0.01, first " << level + 0.05 << "\n";
  if (decay)
    s << "set arrow 2 from first " << *decay * scale << ", graph 0 to first " << *decay * scale
      << ", graph 1 nohead dt 2\n";
  s << "plot '-' using 1:2 with lines lw 2 title 'r(lag)'";
  if (decay) s << ", '-' using 1:2 with points pt 6 ps 2 lw 2 title '1/e crossing'";
  s << "\n";
  for (std::size_t k = 0; k < result.correlation.size(); ++k)
    s << static_cast<double>(k) * scale << " " << result.correlation[k] << "\n";
  s << "e\n";
  if (decay) s << *decay * scale << " " << level << "\ne\n";
  return s.str();
}

void run(const AutocorrelationArgs& args) {
  const Series series = load_series(args.input);
  auto [result, zero, decay, report] =
      run_autocorrelation({series.values, args.input.file, series.column, series.dt}, args.params, mode_of(args.output));
  if (!args.plot.empty()) render_plot(plot_script(result, decay, zero, series.dt), args.plot);
  std::ostream* table = report.open_table(args.output);
  if (!table) return;
  std::ostream& out = *table;
  out << "# first_zero_crossing = " << (zero ? std::to_string(*zero) : "none within the range") << "\n";
  out << "# decorrelation_time (1/e, samples) = " << (decay ? number(*decay) : "none within the range") << "\n";
  out << "# lag\tautocorrelation\n";
  for (std::size_t k = 0; k < result.correlation.size(); ++k) out << k << "\t" << number(result.correlation[k]) << "\n";
}

}  // namespace

void register_autocorrelation(CLI::App& app) {
  auto args = std::make_shared<AutocorrelationArgs>();
  CLI::App* command = app.add_subcommand("autocorrelation", "autocorrelation r(k), first zero crossing and 1/e time");
  add_quiet_option(*command);
  add_input_options(*command, args->input);
  add_options(*command, args->params, autocorrelation_parameters());
  add_plot_option(*command, args->plot, "draw r(lag) with the 1/e level and its crossing to FILE.png or FILE.svg");
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
