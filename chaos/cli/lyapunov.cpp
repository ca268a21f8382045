// chaos lyapunov: the largest Lyapunov exponent from a series, by Rosenstein's or Kantz's divergence
// curve with its linear region found automatically; per sample, and per time unit with --dt.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "chaos/automatic_analysis.hpp"
#include "chaos/error.hpp"
#include "chaos/lyapunov.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"
#include "plot.hpp"

namespace chaos::cli {

namespace {

struct LyapunovArgs {
  InputOptions input;
  OutputOptions output;
  LyapunovParams params;
  std::string plot;
  bool quiet = false;
};

// The divergence curve with the fitted line over the region (top) and the local slopes with the
// region shaded and lambda dashed (bottom); x in time units when dt is known.
std::string plot_script(const LyapunovResult& r) {
  const double scale = r.dt.value_or(1.0);
  const auto& c = r.curve;
  std::ostringstream s;
  s << "set multiplot layout 2,1\nset grid\nset key top left\n"
    << "set xlabel '" << (r.dt ? "time" : "step (samples)") << "'\n"
    << "set ylabel '" << (c.method == LyapunovMethod::rosenstein ? "<ln d(k)>" : "S(k) = <ln <d(k)>_U>") << "'\n"
    << "set title '" << to_string(c.method) << " divergence: " << to_string(r.fit.status);
  if (r.fit.lambda)
    s << ", lambda = " << number(r.lambda_per_time.value_or(*r.fit.lambda)) << (r.dt ? " per time unit" : " per sample");
  s << "' noenhanced\n";  // status names contain underscores, not subscripts
  if (r.fit.first_step)
    s << "set object 1 rect from " << static_cast<double>(*r.fit.first_step) * scale << ", graph 0 to "
      << static_cast<double>(*r.fit.last_step) * scale << ", graph 1 fc rgb '#dddddd' fs solid 0.5 behind\n";
  s << "plot '-' using 1:2 with linespoints pt 7 ps 0.4 title 'divergence'";
  // The fitted line through the region's mean point.
  double intercept = 0.0;
  if (r.fit.lambda) {
    double sx = 0.0, sy = 0.0;
    std::size_t n = 0;
    for (std::size_t k = *r.fit.first_step; k <= *r.fit.last_step; ++k)
      if (c.divergence[k]) {
        sx += static_cast<double>(k);
        sy += *c.divergence[k];
        ++n;
      }
    intercept = sy / static_cast<double>(n) - *r.fit.lambda * sx / static_cast<double>(n);
    s << ", '-' using 1:2 with lines lw 2 title 'fit'";
  }
  s << "\n";
  for (std::size_t k = 0; k < c.step.size(); ++k)
    if (c.divergence[k]) s << static_cast<double>(k) * scale << " " << *c.divergence[k] << "\n";
  s << "e\n";
  if (r.fit.lambda) {
    for (const std::size_t k : {*r.fit.first_step, *r.fit.last_step})
      s << static_cast<double>(k) * scale << " " << intercept + *r.fit.lambda * static_cast<double>(k) << "\n";
    s << "e\n";
  }
  s << "set ylabel 'local slope (per " << (r.dt ? "time unit" : "sample") << ")'\nset title 'local slopes'\n";
  if (r.fit.lambda) {
    const double lambda = r.lambda_per_time.value_or(*r.fit.lambda);
    s << "set arrow 1 from graph 0, first " << lambda << " to graph 1, first " << lambda << " nohead dt 2\n";
  }
  s << "plot '-' using 1:2 with linespoints pt 7 ps 0.4 notitle\n";
  for (std::size_t k = 0; k < c.step.size(); ++k)
    if (r.fit.local_slope[k]) s << static_cast<double>(k) * scale << " " << *r.fit.local_slope[k] / scale << "\n";
  s << "e\nunset multiplot\n";
  return s.str();
}

void run(LyapunovArgs& args) {
  const Series series = load_series(args.input);
  Progress progress(args.quiet);
  if (args.params.reference_points && *args.params.reference_points == 0)
    progress.hint("lyapunov", series.values.size(),
                  "the divergence curves follow the neighbours of every one of the points, and the local maps the "
                  "whole chain, and may take long; --reference-points 10000 bounds every part (the curves, their "
                  "halves and cross-checks average over that many evenly spaced points, the local maps follow at "
                  "most 10 maps per point) in a fraction of the time");
  else
    progress.hint("lyapunov", series.values.size(),
                  "the neighbour searches run over all the samples and may take long; the rest is bounded by "
                  "--reference-points (at most 10^4 by default: the curves, their halves and cross-checks average "
                  "over that many evenly spaced points, the local maps follow at most 10 maps per point), the "
                  "automatic dimension reads the first 10^5 samples, and --threads shares the searches");
  args.params.choice_progress = progress.callback("Cao's method (the automatic dimension)");
  args.params.options.progress = progress.callback("divergence curve (" + args.params.method + ")");
  args.params.check_progress =
      progress.callback(std::string("cross-check (") + (args.params.method == "kantz" ? "rosenstein" : "kantz") + ")");
  args.params.maps_progress = progress.callback("cross-check (local maps)");
  auto [r, check, maps, maps_refusal, estimate, answer, report] = run_lyapunov({series.values, args.input.file, series.column, series.dt}, args.params, mode_of(args.output));
  if (!args.plot.empty()) render_plot(plot_script(r), args.plot);
  std::ostream* table = report.open_table(args.output);
  if (!table) return;
  std::ostream& out = *table;
  const bool per_time = r.dt.has_value();
  const std::optional<double> lambda = per_time ? r.lambda_per_time : r.fit.lambda;
  const std::optional<Interval> lambda_interval = per_time ? r.lambda_per_time_interval : r.fit.lambda_interval;
  // The answers first, then the strict fit behind them.
  const std::string per = per_time ? "time unit" : "sample";
  if (answer) {
    const Estimate e = answer->per_time();
    out << "# lambda_1 = " << estimate_text(e, per) << ": " << e.reason << " [" << answer->source << "]\n";
  }
  out << "# estimate = " << estimate_text(estimate, per) << ": " << estimate.reason << " [" << args.params.method << "]\n";
  out << "# status = " << to_string(r.fit.status) << ": " << r.fit.explanation << "\n";
  out << "# lambda = " << (lambda ? number(*lambda) : "none") << "  interval " << interval_text(lambda_interval)
      << "  per " << (per_time ? "time unit" : "sample") << "\n";
  if (per_time)
    out << "# lambda_per_sample = " << (r.fit.lambda ? number(*r.fit.lambda) : "none") << "  interval "
        << interval_text(r.fit.lambda_interval) << "\n";
  if (check) {
    const std::optional<double> other = per_time ? check->lambda_per_time : check->fit.lambda;
    out << "# cross_check = " << to_string(check->options.method) << ": " << to_string(check->fit.status)
        << ", lambda = " << (other ? number(*other) : "none") << "\n";
  }
  if (maps) {
    const std::optional<double> value = maps->dt ? maps->lambda_per_time : maps->lambda;
    out << "# local_maps = " << to_string(maps->status) << " at m = " << maps->variants.front().dimension
        << ", lambda = " << (value ? number(*value) : "none") << "\n";
  } else if (args.params.cross_check) {
    out << "# local_maps = not_run: " << maps_refusal << "\n";
  }
  if (r.fit_range_time)
    out << "# fitted over t = " << number(r.fit_range_time->low) << " .. " << number(r.fit_range_time->high)
        << " time units\n";
  out << "# references_used = " << r.curve.references_used << " of " << r.curve.reference_points
      << "  mean_neighbours = " << number(r.curve.mean_neighbours) << "\n";
  const std::size_t capped = r.curve.capped_neighbourhoods + (check ? check->curve.capped_neighbourhoods : 0);
  if (capped > 0)
    out << "# capped_neighbourhoods = " << capped << " (Kantz neighbourhoods represented by --max-neighbours = "
        << args.params.options.max_neighbours << " of their members)\n";
  out << (per_time ? "# step\ttime\tdivergence\tlocal_slope\tterms\n" : "# step\tdivergence\tlocal_slope\tterms\n");
  for (std::size_t k = 0; k < r.curve.step.size(); ++k) {
    out << r.curve.step[k];
    if (per_time) out << "\t" << number(static_cast<double>(r.curve.step[k]) * *r.dt);
    out << "\t" << (r.curve.divergence[k] ? number(*r.curve.divergence[k]) : "none") << "\t"
        << (r.fit.local_slope[k] ? number(*r.fit.local_slope[k]) : "none") << "\t" << r.curve.terms[k] << "\n";
  }
}

}  // namespace

void register_lyapunov(CLI::App& app) {
  auto args = std::make_shared<LyapunovArgs>();
  CLI::App* command =
      app.add_subcommand("lyapunov", "largest Lyapunov exponent from a series: one answer with its interval from Rosenstein's and Kantz's divergence curves and local linear maps (with the default checks); --method picks the curve shown");
  add_input_options(*command, args->input);
  add_options(*command, args->params, lyapunov_parameters());
  add_plot_option(*command, args->plot, "draw the divergence curve with the fitted region to FILE.png or FILE.svg");
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
