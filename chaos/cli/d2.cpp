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
#include "common.hpp"
#include "plot.hpp"
#include "plot_panels.hpp"

namespace chaos::cli {

namespace {

struct D2Args {
  InputOptions input;
  OutputOptions output;
  CorrelationSumOptions sums;
  CorrelationDimensionOptions dimension;
  std::optional<std::size_t> theiler;
  std::optional<double> r_min, r_max;
  std::size_t radii = 40;
  std::vector<double> radius_list;
  std::string norm = "max";
  std::string search = "box";
  std::string plot;
  bool halves = false;
  bool quiet = false;
};

CorrelationSearch parse_search(const std::string& name) {
  if (name == "box") return CorrelationSearch::box_assisted;
  if (name == "kd") return CorrelationSearch::kd_tree;
  if (name == "brute") return CorrelationSearch::brute_force;
  throw InvalidInput(ErrorCode::invalid_parameter, "search must be box, kd or brute (got '" + name + "')");
}

std::string interval_text(const std::optional<Interval>& i) {
  return i ? "[" + number(i->low) + ", " + number(i->high) + "]" : std::string("none");
}

nlohmann::ordered_json interval_json(const std::optional<Interval>& i) {
  return i ? nlohmann::ordered_json::array({i->low, i->high}) : nlohmann::ordered_json(nullptr);
}

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
  require_not_constant(x, args.input.file);
  args.sums.norm = parse_norm(args.norm);
  args.sums.search = parse_search(args.search);

  // Theiler window: given, or the autocorrelation's 1/e time (pairs closer in time than the
  // correlation time would otherwise pose as neighbours and bias D2 low).
  std::string theiler_source = "given (-t)";
  if (args.theiler) {
    args.sums.theiler = *args.theiler;
  } else {
    const CorrelationTime t = correlation_time(x);
    args.sums.theiler = t.samples;
    theiler_source = t.source;
  }
  // Radii: given, or from the data's range (TISEAN's -r range/1000; -R a quarter of the range,
  // beyond which C is near 1 and carries no scaling).
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double range = *hi - *lo;
  const double r_max = args.r_max.value_or(range / 4.0);
  const double r_min = args.r_min.value_or(range / 1000.0);
  args.sums.radii = args.radius_list.empty() ? log_radii(r_min, r_max, args.radii) : args.radius_list;

  // Exact sums over many points take minutes to hours (the pairs grow as N^2): the user is told
  // before the wait, with the option that shortens it.
  Progress progress(args.quiet);
  if (args.sums.reference_points == 0 && args.sums.pairs_per_radius == 0)
    progress.hint("d2", x.size(),
                  "the exact correlation sums count about " +
                      number(0.5 * static_cast<double>(x.size()) * static_cast<double>(x.size())) +
                      " pairs and may take long; --reference-points 20000 counts from a random subset of "
                      "reference points in a fraction of the time");
  args.sums.progress = progress.callback("correlation sums");
  const CorrelationSumResult sums = correlation_sum(x, args.sums);
  CorrelationDimensionResult d2 = correlation_dimension(sums, args.dimension);
  if (args.halves) {
    // The same sums over each half of the record (same radii): a saturated plateau must be reproduced.
    CorrelationSumOptions halves = args.sums;
    halves.progress = nullptr;  // the bar has shown the full record's sums
    check_record_halves(d2, x, halves, args.dimension);
  }
  if (!args.plot.empty()) render_plot(plot_script(sums, d2), args.plot);

  Report report("d2", args.output);
  report.parameter("file", args.input.file).parameter("column", series.column).parameter("N", x.size())
      .parameter("dt", series.dt).parameter("delay", args.sums.delay).parameter("min_dimension", args.sums.min_dimension)
      .parameter("max_dimension", args.sums.max_dimension).parameter("theiler", args.sums.theiler)
      .parameter("theiler_source", theiler_source).parameter("norm", args.norm).parameter("search", args.search)
      .parameter("r_min", args.sums.radii.front()).parameter("r_max", args.sums.radii.back())
      .parameter("radii", args.sums.radii.size())
      .parameter("pairs_per_radius", args.sums.pairs_per_radius).parameter("reference_points", args.sums.reference_points)
      .parameter("seed", args.sums.seed).parameter("threads", args.sums.threads)
      .parameter("tolerance", args.dimension.region.tolerance).parameter("min_points", args.dimension.region.min_points)
      .parameter("saturation_dimensions", args.dimension.saturation_dimensions)
      .parameter("min_pairs", args.dimension.min_pairs)
      .parameter("max_region_radius", d2.max_region_radius)
      .parameter("points", sums.points);
  std::ostream& out = report.stream();
  auto& j = report.json();
  j["dimension"] = sums.dimension;
  j["radius"] = sums.radius;
  j["correlation_sum"] = sums.correlation_sum;
  j["pairs"] = sums.pairs;
  auto slopes = nlohmann::ordered_json::array();
  for (const auto& row : d2.local_slope) {
    auto line = nlohmann::ordered_json::array();
    for (const auto& v : row) line.push_back(optional_json(v));
    slopes.push_back(line);
  }
  j["local_slope"] = slopes;
  auto by_m = nlohmann::ordered_json::array(), by_m_interval = nlohmann::ordered_json::array();
  for (std::size_t d = 0; d < sums.dimension.size(); ++d) {
    by_m.push_back(optional_json(d2.d2_by_dimension[d]));
    by_m_interval.push_back(interval_json(d2.d2_by_dimension_interval[d]));
  }
  j["d2_by_dimension"] = by_m;
  j["d2_by_dimension_interval"] = by_m_interval;
  j["d2"] = optional_json(d2.d2);
  j["d2_interval"] = interval_json(d2.d2_interval);
  j["scaling_region"] = interval_json(d2.scaling_region);
  auto plateaus = nlohmann::ordered_json::array();
  for (const auto& p : d2.plateaus)
    plateaus.push_back({{"radii", interval_json(p.radii)}, {"slope", p.slope}, {"slopes", interval_json(p.slopes)}});
  j["plateaus"] = plateaus;
  if (d2.first_half_status) {
    j["first_half"] = {{"status", to_string(*d2.first_half_status)}, {"d2", optional_json(d2.first_half_d2)}};
    j["second_half"] = {{"status", to_string(*d2.second_half_status)}, {"d2", optional_json(d2.second_half_d2)}};
  }
  j["saturated"] = d2.status == D2Status::saturated;
  j["status"] = to_string(d2.status);
  j["explanation"] = d2.explanation;
  j["takens_theiler"] = optional_json(d2.takens_theiler);
  j["takens_theiler_error"] = optional_json(d2.takens_theiler_error);
  j["eckmann_ruelle_limit"] = d2.eckmann_ruelle_limit;
  j["exceeds_eckmann_ruelle"] = d2.exceeds_eckmann_ruelle;
  if (report.json_mode()) {
    report.write_json(out);
    return;
  }
  report.write_header(out);
  out << "# status = " << to_string(d2.status) << ": " << d2.explanation << "\n";
  out << "# d2 = " << (d2.d2 ? number(*d2.d2) : "none") << "  interval " << interval_text(d2.d2_interval)
      << "  scaling region eps in " << interval_text(d2.scaling_region) << "\n";
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
  args->sums.max_dimension = 10;
  CLI::App* command = app.add_subcommand("d2", "correlation sums and the correlation dimension D2 with its scaling region");
  add_input_options(*command, args->input);
  command->add_option("-d,--delay", args->sums.delay, "delay tau in samples")->capture_default_str();
  command->add_option("-m,--min-dimension", args->sums.min_dimension, "smallest embedding dimension")->capture_default_str();
  command->add_option("-M,--max-dimension", args->sums.max_dimension, "largest embedding dimension")->capture_default_str();
  command->add_option("-t,--theiler", args->theiler, "Theiler window in samples (default: autocorrelation 1/e time)");
  command->add_option("-r,--min-radius", args->r_min, "smallest radius (default: data range / 1000)");
  command->add_option("-R,--max-radius", args->r_max, "largest radius (default: data range / 4)");
  command->add_option("-#,--radii", args->radii, "number of log-spaced radii")->capture_default_str();
  command->add_option("--radius-list", args->radius_list, "explicit increasing radii (comma-separated), instead of -r -R -#")
      ->delimiter(',');
  command->add_option("--norm", args->norm, "max or euclidean")->capture_default_str();
  command->add_option("--search", args->search, "box (box-assisted, the fastest), kd (kd-tree, often tens of times slower) or brute (the definition, slowest)")->capture_default_str();
  command->add_option("-N,--pairs-per-radius", args->sums.pairs_per_radius,
                      "stop counting a radius after this many close pairs (0: exact)")
      ->capture_default_str();
  command->add_option("--reference-points", args->sums.reference_points, "random subset of reference points (0: all)")
      ->capture_default_str();
  command->add_option("--seed", args->sums.seed, "seed of the reference order and subset")->capture_default_str();
  command->add_option("--threads", args->sums.threads, "threads (results identical for any number)")->capture_default_str();
  command->add_option("--tolerance", args->dimension.region.tolerance, "relative flatness of the local slopes in the region")
      ->capture_default_str();
  command->add_option("--min-points", args->dimension.region.min_points, "radii in a scaling region, at least")
      ->capture_default_str();
  command->add_option("--saturation-dimensions", args->dimension.saturation_dimensions,
                      "highest dimensions that must share the plateau")
      ->capture_default_str();
  command->add_option("--min-pairs", args->dimension.min_pairs, "radii with fewer close pairs are left out")
      ->capture_default_str();
  command->add_option("--max-region-fraction", args->dimension.max_region_fraction,
                      "a region ends at or below this fraction of the data range (Eckmann-Ruelle take 0.1; default: no limit)");
  add_quiet_option(*command, args->quiet);
  command->add_flag("--halves", args->halves,
                    "a saturated D2 must be reproduced by the first and the second half of the record (as in chaos analyze)");
  add_plot_option(*command, args->plot, "draw log C and the local slopes with the region to FILE.png or FILE.svg");
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
