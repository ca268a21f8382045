// chaos cao: Cao's E1(m) and E2(m) and the embedding dimension where E1 saturates.

#include <sstream>

#include "chaos/cao.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"
#include "plot.hpp"
#include "plot_panels.hpp"

namespace chaos::cli {

namespace {

struct CaoArgs {
  InputOptions input;
  OutputOptions output;
  CaoParams params;
  std::string plot;
  bool quiet = false;
};

// E1(m) and E2(m) against m, the level 1 and the saturation dimension marked.
std::string plot_script(const CaoResult& result) {
  std::ostringstream s;
  s << "set grid\n";
  cao_panel(s, result,
            "Cao's method: " + (result.embedding_dimension ? "E1 saturates at m = " + std::to_string(*result.embedding_dimension)
                                : result.stochastic      ? std::string("none, E2 stays near 1 (stochastic)")
                                                         : std::string("none, E1 does not settle (not saturated)")));
  return s.str();
}

void run(CaoArgs& args) {
  const Series series = load_series(args.input);
  Progress progress(args.quiet);
  progress.hint("cao", series.values.size(),
                "a nearest-neighbour search from every point in each dimension may take long; -l 100000 uses "
                "the first 10^5 samples, a smaller -M fewer dimensions");
  args.params.options.progress = progress.callback("Cao's method");
  auto [result, report] = run_cao({series.values, args.input.file, series.column, series.dt}, args.params, mode_of(args.output));
  if (!args.plot.empty()) render_plot(plot_script(result), args.plot);
  std::ostream* table = report.open_table(args.output);
  if (!table) return;
  std::ostream& out = *table;
  out << "# embedding_dimension = " << describe_dimension(result) << "\n";
  out << "# max_E2_deviation = " << number(result.max_E2_deviation) << "\n";
  if (!result.value_ties.empty()) out << "# value_ties = " << result.value_ties << "\n";
  out << "# dimension\tE1\tE2\tE2_standard_error\tE\tE_star\n";
  for (std::size_t k = 0; k < result.dimension.size(); ++k)
    out << result.dimension[k] << "\t" << number(result.E1[k]) << "\t" << number(result.E2[k]) << "\t"
        << number(result.E2_standard_error[k]) << "\t" << number(result.E[k]) << "\t" << number(result.E_star[k]) << "\n";
}

}  // namespace

void register_cao(CLI::App& app) {
  auto args = std::make_shared<CaoArgs>();
  CLI::App* command = app.add_subcommand("cao", "Cao's method: E1(m), E2(m) and the minimum embedding dimension");
  add_input_options(*command, args->input);
  add_options(*command, args->params, cao_parameters());
  add_plot_option(*command, args->plot, "draw E1(m) and E2(m) with the saturation dimension to FILE.png or FILE.svg");
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
