// chaos lyapunov-maps: the largest Lyapunov exponent from local linear maps fitted to the delay
// embedding (lyapunov_local_maps.hpp), checked over a neighbourhood of the estimator's own choices;
// per sample, and per time unit with --dt.

#include "chaos/lyapunov_local_maps.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"

namespace chaos::cli {

namespace {

struct LyapunovMapsArgs {
  InputOptions input;
  OutputOptions output;
  LyapunovMapsParams params;
};

void run(const LyapunovMapsArgs& args) {
  const Series series = load_series(args.input);  // checked there: finite, with a scale
  auto [r, report] =
      run_lyapunov_maps({series.values, args.input.file, series.column, series.dt}, args.params, mode_of(args.output));
  std::ostream* table = report.open_table(args.output);
  if (!table) return;
  std::ostream& out = *table;
  const bool per_time = r.dt.has_value();
  const double scale = per_time ? 1.0 / *r.dt : 1.0;
  const auto lambda = per_time ? r.lambda_per_time : r.lambda;
  const auto interval = per_time ? r.lambda_per_time_interval : r.lambda_interval;
  out << "# status = " << to_string(r.status) << ": " << r.explanation << "\n";
  out << "# lambda = " << (lambda ? number(*lambda) : "none") << "  interval "
      << (interval ? "[" + number(interval->low) + ", " + number(interval->high) + "]" : std::string("none"))
      << "  per " << (per_time ? "time unit" : "sample") << "\n";
  out << "# median_residual = " << number(r.base.median_residual) << "  mean_rank = " << number(r.base.mean_rank)
      << "  maps = " << r.base.maps << "  poor_fits = " << r.base.poor_fits << "  restarts = " << r.base.restarts << "\n";
  out << "# variant\tdimension\tdelay\tneighbours\tlambda (per " << (per_time ? "time unit" : "sample") << ")\n";
  for (const auto& v : r.variants)
    out << v.name << "\t" << v.dimension << "\t" << v.delay << "\t" << v.neighbours << "\t" << number(v.lambda * scale) << "\n";
}

}  // namespace

void register_lyapunov_maps(CLI::App& app) {
  auto args = std::make_shared<LyapunovMapsArgs>();
  CLI::App* command = app.add_subcommand(
      "lyapunov-maps", "largest Lyapunov exponent from local linear maps (Eckmann-Ruelle 1985, Sano-Sawada 1985), "
                       "reported only when it holds over the estimator's choices");
  add_quiet_option(*command);
  add_input_options(*command, args->input);
  add_options(*command, args->params, lyapunov_maps_parameters());
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
