// chaos lyapunov: the largest Lyapunov exponent from a series, by Rosenstein's or Kantz's divergence
// curve with its linear region found automatically; per sample, and per time unit with --dt.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "chaos/automatic_analysis.hpp"
#include "chaos/error.hpp"
#include "chaos/lyapunov.hpp"
#include "common.hpp"
#include "plot.hpp"

namespace chaos::cli {

namespace {

struct LyapunovArgs {
  InputOptions input;
  OutputOptions output;
  LyapunovOptions options;
  LyapunovFitOptions fit;
  std::optional<std::size_t> theiler, steps, period;
  std::string method = "rosenstein";
  std::string norm = "max";
  std::string plot;
  bool quiet = false;
};

LyapunovMethod parse_method(const std::string& name) {
  if (name == "rosenstein") return LyapunovMethod::rosenstein;
  if (name == "kantz") return LyapunovMethod::kantz;
  throw InvalidInput(ErrorCode::invalid_parameter, "method must be rosenstein or kantz (got '" + name + "')");
}

nlohmann::ordered_json interval_json(const std::optional<Interval>& i) {
  return i ? nlohmann::ordered_json::array({i->low, i->high}) : nlohmann::ordered_json(nullptr);
}

std::string interval_text(const std::optional<Interval>& i) {
  return i ? "[" + number(i->low) + ", " + number(i->high) + "]" : std::string("none");
}

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
  const std::vector<double>& x = series.values;
  require_not_constant(x, args.input.file);
  args.options.method = parse_method(args.method);
  args.options.norm = parse_norm(args.norm);

  // Defaults from the data's own time scales (time_scales.hpp): the Theiler window covers the
  // autocorrelation time and half a period of a dominant oscillation (as in d2); the curve is
  // followed for 20 of the longer of the two (at least 20 steps, at most N/10), long enough for a
  // flow's separation to grow to the attractor's size; the local slopes span a whole period.
  // (20 of them: the linear region must rise by LyapunovFitOptions::min_rise after the transient.)
  const CorrelationTime correlation = correlation_time(x);
  std::string theiler_source = "given (-t)", steps_source = "given (-s)", period_source = "given (--period)";
  if (args.theiler) {
    args.options.theiler = *args.theiler;
  } else {
    args.options.theiler = correlation.samples;
    theiler_source = correlation.source;
  }
  if (!args.period) {
    args.fit.period = correlation.period;
    period_source = correlation.period ? "twice the first autocorrelation minimum" : "no dominant oscillation";
  } else {
    args.fit.period = *args.period;
  }
  if (args.steps) {
    args.options.steps = *args.steps;
  } else {
    args.options.steps = automatic_lyapunov_steps(correlation.samples, args.fit.period, x.size());
    steps_source = "20 correlation times or periods, at least 20, at most N/10";
  }
  Progress progress(args.quiet);
  if (args.options.reference_points == 0)
    progress.hint("lyapunov", x.size(),
                  "the divergence curve follows the neighbours of every one of the points and may take long; "
                  "--reference-points 10000 averages over evenly spaced reference points in a fraction of the time");
  args.options.progress = progress.callback(std::string("divergence curve (") + to_string(args.options.method) + ")");
  const LyapunovResult r = largest_lyapunov(x, args.options, args.fit, series.dt);
  if (!args.plot.empty()) render_plot(plot_script(r), args.plot);

  const bool per_time = r.dt.has_value();
  const std::optional<double> lambda = per_time ? r.lambda_per_time : r.fit.lambda;
  const std::optional<Interval> lambda_interval = per_time ? r.lambda_per_time_interval : r.fit.lambda_interval;
  Report report("lyapunov", args.output);
  report.parameter("file", args.input.file).parameter("column", series.column).parameter("N", x.size())
      .parameter("dt", series.dt).parameter("method", args.method).parameter("dimension", args.options.dimension)
      .parameter("delay", args.options.delay).parameter("theiler", args.options.theiler)
      .parameter("theiler_source", theiler_source).parameter("steps", args.options.steps)
      .parameter("steps_source", steps_source).parameter("norm", args.norm);
  if (args.options.method == LyapunovMethod::kantz)
    report.parameter("radius", r.curve.radius)
        .parameter("radius_source", std::string(args.options.radius ? "given (-r)"
                                                                     : "data range / 1000 times a power of two: half "
                                                                       "the reference points have a neighbour, at most "
                                                                       "20 on average"))
        .parameter("min_neighbours", args.options.min_neighbours);
  report.parameter("reference_points", args.options.reference_points).parameter("threads", args.options.threads)
      .parameter("tolerance", args.fit.tolerance).parameter("half_width", r.fit.half_width)
      .parameter("min_steps", r.fit.min_steps).parameter("period", args.fit.period)
      .parameter("period_source", period_source).parameter("dimensions", args.fit.dimensions);
  std::ostream& out = report.stream();
  auto& j = report.json();
  j["lambda"] = optional_json(lambda);
  j["lambda_interval"] = interval_json(lambda_interval);
  j["per"] = per_time ? "time" : "sample";
  j["lambda_per_sample"] = optional_json(r.fit.lambda);
  j["lambda_per_sample_interval"] = interval_json(r.fit.lambda_interval);
  j["status"] = to_string(r.fit.status);
  j["explanation"] = r.fit.explanation;
  j["region"] = r.fit.first_step ? nlohmann::ordered_json::array({*r.fit.first_step, *r.fit.last_step})
                                 : nlohmann::ordered_json(nullptr);
  j["region_time"] = interval_json(r.fit_range_time);
  j["dimensions"] = r.dimensions;
  j["lambda_by_dimension"] = r.fit.lambda_by_curve;
  j["step"] = r.curve.step;
  if (per_time) {
    std::vector<double> time(r.curve.step.size());
    for (std::size_t k = 0; k < time.size(); ++k) time[k] = static_cast<double>(r.curve.step[k]) * *r.dt;
    j["time"] = time;
  }
  auto divergence = nlohmann::ordered_json::array(), slope = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < r.curve.step.size(); ++k) {
    divergence.push_back(optional_json(r.curve.divergence[k]));
    slope.push_back(optional_json(r.fit.local_slope[k]));
  }
  j["divergence"] = divergence;
  j["local_slope"] = slope;
  j["terms"] = r.curve.terms;
  j["zero_distances"] = r.curve.zero_distances;
  j["points"] = r.curve.points;
  j["reference_points_examined"] = r.curve.reference_points;
  j["references_used"] = r.curve.references_used;
  j["mean_neighbours"] = r.curve.mean_neighbours;
  if (report.json_mode()) {
    report.write_json(out);
    return;
  }
  report.write_header(out);
  out << "# status = " << to_string(r.fit.status) << ": " << r.fit.explanation << "\n";
  out << "# lambda = " << (lambda ? number(*lambda) : "none") << "  interval " << interval_text(lambda_interval)
      << "  per " << (per_time ? "time unit" : "sample") << "\n";
  if (per_time)
    out << "# lambda_per_sample = " << (r.fit.lambda ? number(*r.fit.lambda) : "none") << "  interval "
        << interval_text(r.fit.lambda_interval) << "\n";
  if (r.fit_range_time)
    out << "# fitted over t = " << number(r.fit_range_time->low) << " .. " << number(r.fit_range_time->high)
        << " time units\n";
  out << "# references_used = " << r.curve.references_used << " of " << r.curve.reference_points
      << "  mean_neighbours = " << number(r.curve.mean_neighbours) << "\n";
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
  args->fit.dimensions = 3;  // m, m+1, m+2 must agree: a transient that looks straight in one m is refused
  CLI::App* command =
      app.add_subcommand("lyapunov", "largest Lyapunov exponent from a series (Rosenstein 1993 or Kantz 1994)");
  add_input_options(*command, args->input);
  command->add_option("--method", args->method, "rosenstein (mean log distance of nearest neighbours) or kantz "
                                                "(log of the mean distance in an eps-neighbourhood)")
      ->capture_default_str();
  command->add_option("-m,--dimension", args->options.dimension, "embedding dimension")->capture_default_str();
  command->add_option("-d,--delay", args->options.delay, "delay tau in samples")->capture_default_str();
  command->add_option("-t,--theiler", args->theiler, "Theiler window in samples (default: the autocorrelation 1/e "
                                                     "time or half the dominant oscillation period, the longer)");
  command->add_option("-s,--steps", args->steps,
                      "steps the divergence is followed (default: 20 correlation times or periods, 20..N/10)");
  command->add_option("--period", args->period, "oscillation period in samples: local slopes span a whole period "
                                                "(default: twice the first autocorrelation minimum; 0: none)");
  command->add_option("--dimensions", args->fit.dimensions, "embedding dimensions m, m+1, ... whose curves must "
                                                            "share the linear region and agree on its slope")
      ->capture_default_str();
  command->add_option("-r,--radius", args->options.radius, "Kantz: neighbourhood radius eps (default: data range / 1000, scaled by powers of 2 so that half the "
                      "reference points have a neighbour and at most 20 on average)");
  command->add_option("-k,--min-neighbours", args->options.min_neighbours,
                      "Kantz: reference points with fewer neighbours are skipped")
      ->capture_default_str();
  command->add_option("--reference-points", args->options.reference_points,
                      "use this many evenly spaced reference points (0: all)")
      ->capture_default_str();
  command->add_option("--norm", args->norm, "max or euclidean")->capture_default_str();
  command->add_option("--threads", args->options.threads, "threads (results identical for any number)")
      ->capture_default_str();
  command->add_option("--tolerance", args->fit.tolerance, "relative flatness of the local slopes in the linear region")
      ->capture_default_str();
  command->add_option("--half-width", args->fit.half_width, "local-slope half width in steps (0: max(2, steps/25, period/2))")
      ->capture_default_str();
  command->add_option("--min-steps", args->fit.min_steps, "steps in a linear region, at least (0: 3 half widths + 1, and a period + 1)")
      ->capture_default_str();
  command->add_option("--min-rise", args->fit.min_rise, "e-folds the curve must rise across the linear region")
      ->capture_default_str();
  add_plot_option(*command, args->plot, "draw the divergence curve with the fitted region to FILE.png or FILE.svg");
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
