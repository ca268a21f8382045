// chaos lyapunov-maps: the largest Lyapunov exponent from local linear maps fitted to the delay
// embedding (lyapunov_local_maps.hpp), checked over a neighbourhood of the estimator's own choices;
// per sample, and per time unit with --dt.

#include "chaos/lyapunov_local_maps.hpp"
#include "commands.hpp"
#include "common.hpp"

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
  report.open(args.output);
  std::ostream& out = report.stream();
  if (report.json_mode()) {
    report.write_json(out);
    return;
  }
  report.write_header(out);
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
  command->add_option("-m,--dimension", args->params.dimension, "embedding dimension (default: automatic, where Cao's E1 saturates)");
  command->add_option("-d,--delay", args->params.delay, "delay tau in samples (default: automatic, the first mutual-information minimum or the rule that stands in for it; the output names the rule)");
  command->add_option("-t,--theiler", args->params.theiler, "Theiler window in samples (default: automatic, the longer of the autocorrelation 1/e time and half the dominant oscillation period, at least the delay)");
  command->add_option("--step", args->params.options.step, "samples the local maps advance (0: max(1, round(tau/2)))")
      ->capture_default_str();
  command->add_option("-k,--neighbours", args->params.options.neighbours, "neighbours per local map (0: 5 m)")
      ->capture_default_str();
  command->add_option("--cutoff", args->params.options.cutoff,
                      "singular values of a neighbourhood below this fraction of the largest are not fitted")
      ->capture_default_str();
  command->add_option("--tolerance", args->params.tolerance, "agreement required of every variant, relative to the base")
      ->capture_default_str();
  command->add_option("--max-residual", args->params.options.max_residual,
                      "a map leaving more of its neighbourhood's image spread unexplained is not averaged; more than half "
                      "such maps: not_deterministic")
      ->capture_default_str();
  command->add_option("--norm", args->params.norm, "max or euclidean (neighbour search)")->capture_default_str();
  command->add_option("--threads", args->params.options.threads, "threads (results identical for any number)")
      ->capture_default_str();
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
