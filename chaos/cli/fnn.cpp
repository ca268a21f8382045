// chaos fnn: the fraction of false nearest neighbours against m (Kennel et al. 1992).

#include <sstream>

#include "chaos/fnn.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"
#include "plot.hpp"
#include "plot_panels.hpp"

namespace chaos::cli {

namespace {

struct FnnArgs {
  InputOptions input;
  OutputOptions output;
  FnnParams params;
  std::string plot;
  bool quiet = false;
};

// The false-neighbour fraction against m, the threshold and the chosen dimension marked.
std::string plot_script(const FnnResult& result, double threshold) {
  std::ostringstream s;
  s << "set grid\n";
  fnn_panel(s, result, threshold,
            "false nearest neighbours: " +
                (result.embedding_dimension
                     ? "fraction <= " + number(threshold) + " from m = " + std::to_string(*result.embedding_dimension)
                     : "fraction stays above " + number(threshold)));
  return s.str();
}

void run(FnnArgs& args) {
  const Series series = load_series(args.input);
  Progress progress(args.quiet);
  progress.hint("fnn", series.values.size(),
                "a nearest-neighbour search from every point in each dimension may take long; -l 100000 uses "
                "the first 10^5 samples, a smaller -M fewer dimensions");
  args.params.options.progress = progress.callback("false nearest neighbours");
  auto [result, report] = run_fnn({series.values, args.input.file, series.column, series.dt}, args.params, mode_of(args.output));
  if (!args.plot.empty()) render_plot(plot_script(result, args.params.options.threshold), args.plot);
  std::ostream* table = report.open_table(args.output);
  if (!table) return;
  std::ostream& out = *table;
  out << "# embedding_dimension = "
      << (result.embedding_dimension ? std::to_string(*result.embedding_dimension) : "none (fraction stays above threshold)")
      << "\n";
  if (!result.value_ties.empty()) out << "# value_ties = " << result.value_ties << "\n";
  out << "# dimension\tfalse_fraction\n";
  for (std::size_t k = 0; k < result.dimension.size(); ++k)
    out << result.dimension[k] << "\t" << number(result.false_fraction[k]) << "\n";
}

}  // namespace

void register_fnn(CLI::App& app) {
  auto args = std::make_shared<FnnArgs>();
  CLI::App* command = app.add_subcommand("fnn", "false nearest neighbours against the embedding dimension");
  add_input_options(*command, args->input);
  add_options(*command, args->params, fnn_parameters());
  add_plot_option(*command, args->plot, "draw the false fraction against m to FILE.png or FILE.svg");
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
