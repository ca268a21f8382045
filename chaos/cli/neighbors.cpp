// chaos neighbors: a benchmark of the neighbour searches on the user's own series and embedding:
// brute force, our kd-tree, our box-assisted grid and nanoflann (Euclidean norm only), each with its
// build time, query time, memory and whether its answers equal brute force's (docs/reference/neighbors.md).

#include <cstdio>
#include <map>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "plot.hpp"

namespace chaos::cli {

namespace {

struct NeighborsArgs {
  InputOptions input;
  OutputOptions output;
  NeighborsParams params;
  bool no_brute = false;
  std::string plot;
  bool quiet = false;
};

double micros_per_query(const NeighborsRow& r) {
  return r.queries ? 1e6 * r.query_seconds / static_cast<double>(r.queries) : 0.0;
}

// Time per query (top) and build time (bottom) against N, log-log, one line per structure and query.
std::string plot_script(const std::vector<NeighborsRow>& rows) {
  std::map<std::string, std::vector<const NeighborsRow*>> lines;  // "structure query" -> rows by N
  for (const auto& r : rows)
    if (r.ran) lines[r.structure + " " + r.query].push_back(&r);
  std::ostringstream s;
  s << "set multiplot layout 2,1\nset logscale xy\nset grid\nset key outside right\nset format y '%g'\nset xlabel 'N (samples)'\n";
  const auto panel = [&](const std::string& ylabel, const std::string& title, bool build) {
    s << "set ylabel '" << ylabel << "'\nset title '" << title << "'\nplot ";
    bool first = true;
    int colour = 0;  // fixed per line, so both panels agree
    for (const auto& [name, line] : lines) {
      ++colour;
      if (build && line.front()->structure == "brute_force") continue;  // nothing to build
      s << (first ? "" : ", ") << "'-' using 1:2 with linespoints pt 7 ps 0.6 lc " << colour << " title '" << name << "'";
      first = false;
    }
    if (first) s << "1/0 notitle";
    s << "\n";
    for (const auto& [name, line] : lines) {
      if (build && line.front()->structure == "brute_force") continue;
      for (const NeighborsRow* r : line) {
        const double y = build ? r->build_seconds : micros_per_query(*r);
        if (y > 0.0) s << r->n << " " << y << "\n";
      }
      s << "e\n";
    }
  };
  panel("microseconds per query", "query time (brute force: at the points it checks)", false);
  panel("seconds", "build time", true);
  s << "unset multiplot\n";
  return s.str();
}

void run(NeighborsArgs& args) {
  const Series series = load_series(args.input);
  args.params.brute = !args.no_brute;
  Progress progress(args.quiet);
  if (args.params.brute && !args.params.check_points)
    progress.hint("neighbors", series.values.size(),
                  "brute force compares every pair of points and may take long; --check-points 1000 checks "
                  "1000 evenly spaced query points, --no-brute none");
  args.params.progress = progress.callback("neighbour searches");
  auto [rows, all_equal, report] =
      run_neighbors({series.values, args.input.file, series.column, series.dt}, args.params, mode_of(args.output));
  if (!args.plot.empty()) render_plot(plot_script(rows), args.plot);
  report.open(args.output);
  std::ostream& out = report.stream();
  // A structure that disagrees with brute force is a wrong answer: after the report, exit 4 (as
  // validate and zoo do), so a script cannot take the timings of a broken search for good ones.
  if (report.json_mode()) {
    report.write_json(out);
    if (!all_equal) throw ValidationFailed{};
    return;
  }
  report.write_header(out);
  out << "# all_equal = " << (all_equal ? "yes" : "no") << "\n";
  out << "# N\tpoints\tstructure\tquery\tbuild_seconds\tquery_seconds\tqueries\tmicroseconds_per_query\tmemory_bytes"
         "\tchecked\tmismatches\ttie_swaps\tequal\tnote\n";
  for (const auto& r : rows) {
    out << r.n << "\t" << r.points << "\t" << r.structure << "\t" << r.query << "\t";
    if (r.ran)
      out << number(r.build_seconds) << "\t" << number(r.query_seconds) << "\t" << r.queries << "\t"
          << number(micros_per_query(r)) << "\t" << r.memory_bytes;
    else
      out << "none\tnone\t0\tnone\tnone";
    out << "\t" << r.checked << "\t" << r.mismatches << "\t" << r.tie_swaps << "\t" << r.equal << "\t" << r.note << "\n";
  }
  if (!all_equal) throw ValidationFailed{};
}

}  // namespace

void register_neighbors(CLI::App& app) {
  auto args = std::make_shared<NeighborsArgs>();
  CLI::App* command = app.add_subcommand(
      "neighbors", "benchmark of the neighbour searches (brute force, kd-tree, box grid, nanoflann) on this series");
  add_input_options(*command, args->input);
  command->add_option("-m,--dimension", args->params.dimension, "embedding dimension")->capture_default_str();
  command->add_option("-d,--delay", args->params.delay, "delay tau in samples")->capture_default_str();
  command->add_option("-t,--theiler", args->params.theiler, "Theiler window in samples (|i-j| <= t excluded)")
      ->capture_default_str();
  command->add_option("-r,--radius", args->params.radius, "count the neighbours closer than this radius (strict)");
  command->add_option("-k,--neighbors", args->params.k, "find the k nearest neighbours (default 1 when -r is not given)");
  command->add_option("--norm", args->params.norm, "max or euclidean (nanoflann runs only for euclidean)")
      ->capture_default_str();
  command->add_option("--sizes", args->params.sizes, "comma-separated sizes N: each run on the series' first N samples")
      ->delimiter(',');
  auto* no_brute = command->add_flag("--no-brute", args->no_brute, "no brute force: times only, nothing checked");
  command
      ->add_option("--check-points", args->params.check_points,
                   "brute force at K evenly spaced query points only; every structure is checked there "
                   "(default: at every point)")
      ->excludes(no_brute);
  add_plot_option(*command, args->plot, "draw time per query and build time against N (log-log) to FILE.png or FILE.svg");
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
