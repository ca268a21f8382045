// chaos analyze: the embedding parameters of a series chosen and justified, then its invariants, by
// the library's automatic pipeline (automatic_analysis.hpp, the one `chaos zoo` validates): the
// Theiler window from the autocorrelation's 1/e time or half the dominant oscillation period (a
// series too short for its own correlation time is reported non-stationary, with advice); the delay
// 1 for a series decorrelated within a sample, else the first mutual-information minimum; the
// dimension where Cao's E1 saturates, corroborated by false nearest neighbours; then D2, the largest
// Lyapunov exponent by Rosenstein and by Kantz (each with a status), and the surrogate test for
// nonlinearity. With no file it analyses a built-in Lorenz x series, the project's default
// demonstration.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "chaos/format.hpp"
#include "chaos/automatic_analysis.hpp"
#include "chaos/autocorrelation.hpp"
#include "chaos/cao.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/error.hpp"
#include "chaos/fnn.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/nonlinearity_test.hpp"
#include "chaos/surrogates.hpp"
#include "chaos/time_scales.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"
#include "plot.hpp"
#include "plot_panels.hpp"

namespace chaos::cli {

namespace {

struct AnalyzeArgs {
  InputOptions input;
  OutputOptions output;
  AnalyzeParams params;
  std::string plot;
  bool quiet = false;
};

// `text` inside a gnuplot single-quoted string (a quote is doubled).
std::string gnuplot_text(const std::string& text) {
  std::string out;
  for (const char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out;
}

// An empty panel that says why it has nothing to show.
void empty_panel(std::ostringstream& s, const std::string& title, const std::string& why) {
  s << "set title '" << title << "'\nunset border\nunset tics\nunset xlabel\nunset ylabel\nunset grid\n"
    << "set label 1 'not run: " << gnuplot_text(why.size() > 60 ? why.substr(0, 57) + "..." : why)
    << "' at graph 0.5, graph 0.5 center\n"
    << "plot [0:1] [0:1] 2 notitle\n"
    << "set border\nset tics\nset grid\n";
}

// One figure of the evidence, a panel each: I(tau) with the delay chosen, Cao's E1 and E2 with the
// dimension, the false-neighbour fraction, and the local slopes of the correlation sums with the
// scaling region and D2.
// lambda_1's evidence: the local slopes of Rosenstein's and Kantz's divergence curves against the
// time followed (in time units with dt), the answer as a dashed line inside its interval, shaded.
void lyapunov_panel(std::ostringstream& s, const AutomaticAnalysis& a, const std::optional<double>& dt) {
  const double scale = dt.value_or(1.0);
  const std::string per = dt ? "time unit" : "sample";
  std::string title = "lambda_1: none";
  if (a.lyapunov) {
    const Estimate e = a.lyapunov->per_time();
    if (e.value) title = "lambda_1 = " + format_number(*e.value, Precision::title) + " per " + per;
    title += " (" + std::string(to_string(e.status)) + ")";
    if (e.interval)
      s << "set object 1 rect from graph 0, first " << e.interval->low << " to graph 1, first " << e.interval->high
        << " fc rgb '#dddddd' fs solid 0.5 behind\n";
    if (e.value) s << "set arrow 1 from graph 0, first " << *e.value << " to graph 1, first " << *e.value << " nohead dt 2\n";
  }
  s << "set key top right\nset xlabel '" << (dt ? "time followed (time units)" : "steps followed (samples)")
    << "'\nset ylabel 'local slope (per " << per << ")'\nset title '" << gnuplot_text(title) << "' noenhanced\n";
  std::vector<std::pair<const LyapunovResult*, const char*>> curves;
  if (a.rosenstein) curves.emplace_back(&*a.rosenstein, "Rosenstein");
  if (a.kantz) curves.emplace_back(&*a.kantz, "Kantz");
  s << "plot ";
  for (std::size_t c = 0; c < curves.size(); ++c)
    s << (c ? ", " : "") << "'-' using 1:2 with linespoints pt 7 ps 0.3 title '" << curves[c].second << "'";
  s << "\n";
  for (const auto& [r, name] : curves) {
    bool any = false;
    for (std::size_t k = 0; k < r->fit.local_slope.size(); ++k)
      if (r->fit.local_slope[k]) {
        s << static_cast<double>(k) * scale << " " << *r->fit.local_slope[k] / scale << "\n";
        any = true;
      }
    if (!any) s << "NaN NaN\n";
    s << "e\n";
  }
}

std::string plot_script(const AutomaticAnalysis& a, const std::optional<MutualInformationResult>& mi,
                        const std::optional<FnnResult>& fnn, double fnn_threshold, const std::optional<double>& dt) {
  std::ostringstream s;
  const std::string stopped = a.scales.stationary ? a.stopped : "non-stationary series (see stationarity)";
  const auto reset = [&s] {
    s << "unset arrow\nunset label\nunset object\nunset logscale\nset autoscale\nset xtics autofreq\nset offsets 0, 0, 0, 0\n";
  };
  s << "set multiplot layout 3,2 title 'chaos analyze: the evidence'\nset grid\n";
  // Mutual information, against the delay in time units when dt is known.
  if (mi)
    mutual_information_panel(s, *mi, a.delay, "delay",
                             "mutual information: delay " +
                                 (a.delay ? std::to_string(*a.delay) + " samples" +
                                                (dt ? " (" + format_number(static_cast<double>(*a.delay) * *dt, Precision::title) +
                                                          " time units)"
                                                    : std::string())
                                          : std::string("none")),
                             dt, 0.4);
  else
    empty_panel(s, "mutual information", stopped);
  reset();
  // Cao.
  if (a.cao) {
    const CaoResult& c = *a.cao;
    cao_panel(s, c,
              "Cao: m = " + (c.embedding_dimension ? std::to_string(*c.embedding_dimension)
                                                   : std::string(c.stochastic ? "none (stochastic)" : "none (not saturated)")),
              0.6);
  } else {
    empty_panel(s, "Cao", stopped);
  }
  reset();
  // False nearest neighbours.
  if (fnn)
    fnn_panel(s, *fnn, fnn_threshold,
              "false nearest neighbours: m = " +
                  (fnn->embedding_dimension ? std::to_string(*fnn->embedding_dimension) : std::string("none")),
              0.6);
  else
    empty_panel(s, "false nearest neighbours", stopped);
  reset();
  // D2: local slopes.
  bool slopes = false;
  if (a.d2)
    for (const auto& row : a.d2->local_slope)
      slopes = slopes || std::any_of(row.begin(), row.end(), [](const auto& v) { return v.has_value(); });
  if (slopes) {
    const CorrelationDimensionResult& d = *a.d2;
    std::string title = to_string(d.status);
    if (d.d2) title += ": D2 = " + format_number(*d.d2, Precision::title);
    local_slopes_panel(s, d, title, 0.3);
  } else {
    empty_panel(s, "correlation dimension", a.d2 ? std::string("no local slopes") : stopped);
  }
  reset();
  // The largest Lyapunov exponent.
  if (a.rosenstein || a.kantz)
    lyapunov_panel(s, a, dt);
  else
    empty_panel(s, "largest Lyapunov exponent", stopped);
  s << "unset multiplot\n";
  return s.str();
}

void run(AnalyzeArgs& args) {
  const bool builtin = args.input.file.empty();
  const Series series = builtin ? builtin_series(args.params.builtin_length) : load_series(args.input);
  const std::vector<double>& x = series.values;
  AnalyzeParams params = args.params;
  params.mutual_curve = !args.plot.empty();
  Progress progress(args.quiet);
  progress.hint("analyze", x.size(),
                "the correlation sums, false neighbours and divergence curves on all the samples may take long "
                "(Cao's method reads the first 10^5); -l 100000 analyses the first 10^5 samples, --threads "
                "shares the work");
  params.progress = progress.steps();
  AnalyzeRun run = run_analyze({x, builtin ? std::string(builtin_series_name) : args.input.file, series.column, series.dt},
                               params, mode_of(args.output));
  const AutomaticAnalysis& a = run.analysis;
  const TimeScales& scales = a.scales;
  const std::string& theiler_source = run.theiler_source;
  // Why a step did not run: said once in full (stationarity), then referred to.
  const std::string not_run = scales.stationary ? a.stopped : "non-stationary series: see stationarity";
  const std::optional<FnnResult>& fnn = run.fnn;
  const FnnOptions& fnn_options = run.fnn_options;
  const std::optional<NonlinearityTestResult>& nonlinear = run.nonlinear;
  const std::optional<EndMatch>& segment = run.segment;
  if (!args.plot.empty()) render_plot(plot_script(a, run.mutual, fnn, fnn_options.threshold, series.dt), args.plot);
  std::ostream* table = run.report.open_table(args.output);
  if (!table) return;
  std::ostream& out = *table;
  const bool per_time = series.dt.has_value();
  const auto in_time = [&](std::size_t samples) {
    return series.dt ? " (" + number(static_cast<double>(samples) * *series.dt) + " time units)" : std::string();
  };
  if (!scales.stationary) out << "stationarity\tnon-stationary\t[" << scales.stationarity_explanation << "]\n";
  out << "delay\t" << (a.delay ? std::to_string(*a.delay) + " samples" + in_time(*a.delay) : "none") << "\t["
      << (a.delay ? a.delay_source : not_run) << "]\n";
  out << "theiler_window\t" << a.theiler << " samples" << in_time(a.theiler) << "\t[" << theiler_source << "]\n";
  if (a.cao)
    out << "embedding_dimension\t" << describe_dimension(*a.cao) << "\t[Cao: E1 >= 0.8 and steps <= 0.1 from there on"
        << (a.cao_samples < series.values.size() ? ", over the first " + std::to_string(a.cao_samples) + " samples" : "")
        << "]\n";
  if (fnn)
    out << "fnn_embedding_dimension\t" << (fnn->embedding_dimension ? std::to_string(*fnn->embedding_dimension) : "none")
        << "\t[false fraction <= " << number(fnn_options.threshold) << "]\n";
  if (a.cao)
    out << "determinism\t" << run.determinism << ": max|E2-1| = " << number(a.cao->max_E2_deviation) << "\t["
        << run.determinism_explanation << "]\n";
  out << "correlation_dimension\t";
  if (a.d2 && a.d2_estimate) {
    out << estimate_text(*a.d2_estimate) << "\t[" << to_string(a.d2->status) << ": " << a.d2_estimate->reason << "]\n";
  } else {
    out << "not run\t[" << not_run << "]\n";
  }
  const std::string per = per_time ? "time unit" : "sample";
  out << "largest_lyapunov_exponent\t";
  if (a.lyapunov) {
    const Estimate e = a.lyapunov->per_time();
    out << estimate_text(e, per) << "\t[" << (a.lyapunov->source.empty() ? "" : a.lyapunov->source + ": ") << e.reason << "]\n";
  } else {
    out << "not run\t[" << not_run << "]\n";
  }
  // The evidence: each estimator's own answer, with its detailed status.
  const auto lambda_text = [&](const std::optional<LyapunovResult>& l, const char* method) {
    out << "largest_lyapunov_exponent_" << method << "\t";
    if (!l) {
      out << "not run\t[" << not_run << "]\n";
      return;
    }
    const Estimate e = l->estimate_per_time();
    out << estimate_text(e, per) << "\t[" << l->options.steps << " steps, m = " << l->dimensions.front() << ".."
        << l->dimensions.back() << "; " << to_string(l->fit.status) << ": " << l->fit.explanation;
    if (e.status != EstimateStatus::confident && !e.reason.empty()) out << "; answer: " << e.reason;
    out << "]\n";
  };
  lambda_text(a.rosenstein, "rosenstein");
  lambda_text(a.kantz, "kantz");
  out << "largest_lyapunov_exponent_local_maps\t";
  if (a.local_maps) {
    const LocalMapResult& l = *a.local_maps;
    const auto lambda = per_time ? l.lambda_per_time : l.lambda;
    const auto range = per_time ? l.lambda_per_time_interval : l.lambda_interval;
    if (lambda)
      out << number(*lambda) << " in [" << number(range->low) << ", " << number(range->high) << "] per "
          << (per_time ? "time unit" : "sample");
    else
      out << "none";
    out << "\t[m = " << l.variants.front().dimension << ", s = " << l.base.step << ", k = " << l.base.neighbours << "; "
        << to_string(l.status) << ": " << l.explanation << "]\n";
  } else {
    out << "not run\t[" << (a.local_maps_refusal.empty() ? not_run : a.local_maps_refusal) << "]\n";
  }
  if (nonlinear) {
    const std::size_t ties = nonlinear->test.ties;
    out << "nonlinearity\t"
        << (nonlinear->test.rejected
                ? std::string("rejected (not ") + null_hypothesis(nonlinear->options.surrogate.method) + ")"
                : std::string("not rejected"))
        << ": rank "
        << nonlinear->test.rank << " of " << nonlinear->surrogate_statistics.size() + 1
        << (ties ? ", tied with " + std::to_string(ties) + " surrogates" : std::string()) << ", significance "
        << number(nonlinear->test.significance) << "\t[prediction error " << number(nonlinear->data_statistic)
        << " vs " << nonlinear->surrogate_statistics.size() << " IAAFT surrogates, samples " << segment->offset << ".."
        << segment->offset + segment->length - 1 << " (end-matched)]\n";
  } else {
    out << "nonlinearity\tnot run\t[no embedding]\n";
  }
  if (a.cao && fnn) {
    out << "#\n# evidence: Cao and false nearest neighbours\n# m\tE1\tE2\tfalse_fraction\n";
    for (std::size_t k = 0; k < a.cao->dimension.size(); ++k)
      out << a.cao->dimension[k] << "\t" << number(a.cao->E1[k]) << "\t" << number(a.cao->E2[k]) << "\t"
          << number(fnn->false_fraction[k]) << "\n";
  }
}

}  // namespace

void register_analyze(CLI::App& app) {
  auto args = std::make_shared<AnalyzeArgs>();
  args->input.file.clear();  // no file: the built-in Lorenz series
  CLI::App* command = app.add_subcommand("analyze", "choose and justify delay, Theiler window and embedding dimension; "
                                                    "then D2, the largest Lyapunov exponent and a nonlinearity test");
  command->add_option("file", args->input.file, "input file or - for stdin (default: built-in Lorenz x series)");
  add_column_option(*command, args->input);
  command->add_option("-x,--skip", args->input.skip, "data rows to skip")->capture_default_str();
  command->add_option("-l,--length", args->input.length, "data rows to use");
  command->add_option("--dt", args->input.dt, "sampling interval");
  add_options(*command, args->params, analyze_parameters());
  add_plot_option(*command, args->plot,
                  "draw the evidence (mutual information, Cao, false neighbours, D2 local slopes) to FILE.png or FILE.svg");
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
