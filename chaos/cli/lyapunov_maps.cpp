// chaos lyapunov-maps: the largest Lyapunov exponent from local linear maps fitted to the delay
// embedding (lyapunov_local_maps.hpp), checked over a neighbourhood of the estimator's own choices;
// per sample, and per time unit with --dt.

#include <string>

#include "chaos/lyapunov_local_maps.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct LyapunovMapsArgs {
  InputOptions input;
  OutputOptions output;
  LocalMapOptions options;
  std::optional<std::size_t> theiler;
  std::string norm = "max";
  double tolerance = 0.05;
};

void run(LyapunovMapsArgs& args) {
  const Series series = load_series(args.input);
  const std::span<const double> x = series.values;
  check_series(x, args.input.file);
  args.options.norm = parse_norm(args.norm);
  std::string theiler_source = "given (-t)";
  if (args.theiler) {
    args.options.theiler = *args.theiler;
  } else {
    const CorrelationTime correlation = correlation_time(x);
    args.options.theiler = correlation.samples;
    theiler_source = correlation.source;
  }
  const LocalMapResult r =
      largest_lyapunov_local_maps(x, args.options, series.dt, args.tolerance);
  const bool per_time = r.dt.has_value();
  Report report("lyapunov-maps", mode_of(args.output));
  report.parameter("file", args.input.file).parameter("column", series.column).parameter("N", x.size())
      .parameter("dt", series.dt).parameter("dimension", args.options.dimension)
      .parameter("delay", args.options.delay).parameter("theiler", args.options.theiler)
      .parameter("theiler_source", theiler_source).parameter("step", r.base.step)
      .parameter("neighbours", r.base.neighbours).parameter("cutoff", args.options.cutoff)
      .parameter("norm", args.norm).parameter("tolerance", r.tolerance).parameter("max_residual", args.options.max_residual)
      .parameter("threads", args.options.threads);
  auto& j = report.json();
  const double scale = per_time ? 1.0 / *r.dt : 1.0;
  j["lambda"] = optional_json(per_time ? r.lambda_per_time : r.lambda);
  j["lambda_interval"] = interval_json(per_time ? r.lambda_per_time_interval : r.lambda_interval);
  j["per"] = per_time ? "time" : "sample";
  j["lambda_per_sample"] = optional_json(r.lambda);
  j["status"] = to_string(r.status);
  j["explanation"] = r.explanation;
  auto variants = nlohmann::ordered_json::array();
  for (const auto& v : r.variants)
    variants.push_back({{"name", v.name}, {"dimension", v.dimension}, {"neighbours", v.neighbours},
                        {"lambda", v.lambda * scale}});
  j["variants"] = variants;
  j["median_residual"] = r.base.median_residual;
  j["residual_q90"] = r.base.residual_q90;
  j["residual_q99"] = r.base.residual_q99;
  j["mean_rank"] = r.base.mean_rank;
  j["maps"] = r.base.maps;
  j["restarts"] = r.base.restarts;
  j["poor_fits"] = r.base.poor_fits;

  report.open(args.output);
  std::ostream& out = report.stream();
  if (report.json_mode()) {
    report.write_json(out);
    return;
  }
  report.write_header(out);
  const auto lambda = per_time ? r.lambda_per_time : r.lambda;
  const auto interval = per_time ? r.lambda_per_time_interval : r.lambda_interval;
  out << "# status = " << to_string(r.status) << ": " << r.explanation << "\n";
  out << "# lambda = " << (lambda ? number(*lambda) : "none") << "  interval "
      << (interval ? "[" + number(interval->low) + ", " + number(interval->high) + "]" : std::string("none"))
      << "  per " << (per_time ? "time unit" : "sample") << "\n";
  out << "# median_residual = " << number(r.base.median_residual) << "  mean_rank = " << number(r.base.mean_rank)
      << "  maps = " << r.base.maps << "  poor_fits = " << r.base.poor_fits << "  restarts = " << r.base.restarts << "\n";
  out << "# variant\tdimension\tneighbours\tlambda (per " << (per_time ? "time unit" : "sample") << ")\n";
  for (const auto& v : r.variants)
    out << v.name << "\t" << v.dimension << "\t" << v.neighbours << "\t" << number(v.lambda * scale) << "\n";
}

}  // namespace

void register_lyapunov_maps(CLI::App& app) {
  auto args = std::make_shared<LyapunovMapsArgs>();
  CLI::App* command = app.add_subcommand(
      "lyapunov-maps", "largest Lyapunov exponent from local linear maps (Eckmann-Ruelle 1985, Sano-Sawada 1985), "
                       "reported only when it holds over the estimator's choices");
  add_input_options(*command, args->input);
  command->add_option("-m,--dimension", args->options.dimension, "embedding dimension")->capture_default_str();
  command->add_option("-d,--delay", args->options.delay, "delay tau in samples")->capture_default_str();
  command->add_option("-t,--theiler", args->theiler, "Theiler window in samples (default: the autocorrelation 1/e "
                                                     "time or half the dominant oscillation period, the longer)");
  command->add_option("--step", args->options.step, "samples the local maps advance (0: max(1, round(tau/2)))")
      ->capture_default_str();
  command->add_option("-k,--neighbours", args->options.neighbours, "neighbours per local map (0: 5 m)")
      ->capture_default_str();
  command->add_option("--cutoff", args->options.cutoff,
                      "singular values of a neighbourhood below this fraction of the largest are not fitted")
      ->capture_default_str();
  command->add_option("--tolerance", args->tolerance, "agreement required of every variant, relative to the base")
      ->capture_default_str();
  command->add_option("--max-residual", args->options.max_residual,
                      "a map leaving more of its neighbourhood's image spread unexplained is not averaged; more than half "
                      "such maps: not_deterministic")
      ->capture_default_str();
  command->add_option("--norm", args->norm, "max or euclidean (neighbour search)")->capture_default_str();
  command->add_option("--threads", args->options.threads, "threads (results identical for any number)")
      ->capture_default_str();
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
