// chaos d2: correlation sums C(eps, m) for m = min..max in one pass, local slopes, the scaling
// region chosen automatically, D2 per m and saturated with intervals, and a Takens-Theiler check.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "chaos/automatic_analysis.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/error.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"
#include "plot.hpp"
#include "plot_panels.hpp"

namespace chaos::cli {

namespace {

struct D2Args {
  InputOptions input;
  OutputOptions output;
  D2Params params;
  std::string plot;
  bool quiet = false;
};

// log C against log eps per m (top) and the local slopes with the chosen region and D2 (bottom).
std::string plot_script(const CorrelationSumResult& sums, const CorrelationDimensionResult& d2) {
  std::ostringstream s;
  s << "set multiplot layout 2,1\nset logscale x\nset logscale y\nset grid\nset key outside right\n"
    << "set xlabel 'eps'\nset ylabel 'C(eps, m)'\nset title 'correlation sums'\n";
  s << "plot ";
  for (std::size_t d = 0; d < sums.dimension.size(); ++d)
    s << (d ? ", " : "") << "'-' using 1:2 with linespoints pt 7 ps 0.4 title 'm=" << sums.dimension[d] << "'";
  s << "\n";
  for (std::size_t d = 0; d < sums.dimension.size(); ++d) {
    for (std::size_t k = 0; k < sums.radius.size(); ++k)
      if (sums.correlation_sum[d][k] > 0.0) s << sums.radius[k] << " " << sums.correlation_sum[d][k] << "\n";
    s << "e\n";
  }
  local_slopes_panel(s, d2,
                     std::string(to_string(d2.status)) +
                         (d2.d2 ? ": D2 = " + number(*d2.d2) + " in " + interval_text(d2.d2_interval) : std::string()));
  s << "unset multiplot\n";
  return s.str();
}

void run(D2Args& args) {
  const Series series = load_series(args.input);
  const std::vector<double>& x = series.values;
  const CorrelationSumOptions& sums_options = args.params.sums;
  // Exact sums over many points take minutes to hours (the pairs grow as N^2): the user is told
  // before the wait, with the option that shortens it.
  Progress progress(args.quiet);
  if (sums_options.reference_points == 0 && sums_options.pairs_per_radius == 0 && !args.params.fast)
    progress.hint("d2", x.size(),
                  "the exact correlation sums count about " +
                      number(0.5 * static_cast<double>(x.size()) * static_cast<double>(x.size())) +
                      " pairs and may take long; --reference-points 20000 counts from a random subset of "
                      "reference points in a fraction of the time");
  D2Params params = args.params;
  params.sums.progress = progress.callback("correlation sums");
  params.halves_progress = progress.callback("correlation sums of the record's halves");
  auto [sums, d2, estimate, report, run_fast] = run_d2({x, args.input.file, series.column, series.dt}, std::move(params), mode_of(args.output));
  if (!args.plot.empty()) render_plot(plot_script(sums, d2), args.plot);
  std::ostream* table = report.open_table(args.output);
  if (!table) return;
  std::ostream& out = *table;
  out << "# D2 = " << estimate_text(estimate) << ": " << estimate.reason << "\n";
  out << "# status = " << to_string(d2.status) << ": " << d2.explanation << "\n";
  out << "# d2 = " << (d2.d2 ? number(*d2.d2) : "none") << "  interval " << interval_text(d2.d2_interval)
      << "  scaling region eps in " << interval_text(d2.scaling_region) << "\n";
  for (const auto& p : d2.other_plateaus)
    out << "# other_plateau = " << number(p.slope) << " for eps in " << interval_text(p.radii)
        << " (another reading of the same dimensions, not judged)\n";
  if (run_fast)
    out << "# fast: " << run_fast->explanation << "\n";
  if (d2.d2_standard_error)
    out << "# d2_standard_error = " << number(*d2.d2_standard_error) << " (jackknife over " << sums.group_pairs.size()
        << " groups of reference points)\n";
  if (d2.takens_theiler)
    out << "# takens_theiler = " << number(*d2.takens_theiler) << " +- " << number(*d2.takens_theiler_error) << "\n";
  out << "# eckmann_ruelle_limit = " << number(d2.eckmann_ruelle_limit) << (d2.exceeds_eckmann_ruelle ? " (exceeded)" : "")
      << "\n# m\td2\tinterval\tregion\n";
  for (std::size_t d = 0; d < sums.dimension.size(); ++d)
    out << "# " << sums.dimension[d] << "\t" << (d2.d2_by_dimension[d] ? number(*d2.d2_by_dimension[d]) : "none") << "\t"
        << interval_text(d2.d2_by_dimension_interval[d]) << "\t" << interval_text(d2.region_by_dimension[d]) << "\n";
  out << "# m\tradius\tcorrelation_sum\tpairs\tlocal_slope\n";
  for (std::size_t d = 0; d < sums.dimension.size(); ++d) {
    for (std::size_t k = 0; k < sums.radius.size(); ++k)
      out << sums.dimension[d] << "\t" << number(sums.radius[k]) << "\t" << number(sums.correlation_sum[d][k]) << "\t"
          << sums.pairs[d][k] << "\t" << (d2.local_slope[d][k] ? number(*d2.local_slope[d][k]) : "none") << "\n";
    out << "\n";  // blank line between dimensions (gnuplot's index)
  }
}

}  // namespace

void register_d2(CLI::App& app) {
  auto args = std::make_shared<D2Args>();
  CLI::App* command = app.add_subcommand("d2", "correlation sums and the correlation dimension D2 with its scaling region");
  add_input_options(*command, args->input);
  add_options(*command, args->params, d2_parameters());
  add_quiet_option(*command, args->quiet);
  add_plot_option(*command, args->plot, "draw log C and the local slopes with the region to FILE.png or FILE.svg");
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
