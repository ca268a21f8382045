// chaos nonlinearity: the rank-order surrogate test for nonlinearity (null hypothesis: a linear
// Gaussian process seen through a static monotone function), with K surrogates, a seed and a
// choice of discriminating statistic.

#include "chaos/error.hpp"
#include "chaos/nonlinearity_test.hpp"
#include "chaos/surrogates.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"

namespace chaos::cli {

namespace {

struct NonlinearityArgs {
  InputOptions input;
  OutputOptions output;
  NonlinearityParams params;
  bool quiet = false;
};

void run(NonlinearityArgs& args) {
  const Series series = load_series(args.input);
  Progress progress(args.quiet);
  progress.hint("nonlinearity", series.values.size(),
                "each surrogate takes up to --max-iterations Fourier transforms of all the samples and may take "
                "long; -l 100000 tests the first 10^5 samples");
  args.params.choice_progress = progress.callback("Cao's method (the automatic dimension)");
  args.params.options.progress = progress.callback("surrogates");
  auto [r, report] = run_nonlinearity({series.values, args.input.file, series.column, series.dt}, args.params, args.output);
  std::ostream* table = report.begin_table();
  if (!table) return;
  std::ostream& out = *table;
  // Ties are what keep the data from rejecting when, counted as neither side, they are all that
  // stands between its value and the tested end of the order (nonlinearity_test.hpp, rank_test).
  const RankTest& t = r.test;
  const std::size_t count = r.surrogate_statistics.size();
  const bool low_but_tied = t.ties > 0 && t.above + t.ties == count;
  const bool high_but_tied = t.ties > 0 && t.below + t.ties == count;
  const Alternative alternative = r.options.alternative;
  const bool held_by_ties = alternative == Alternative::smaller  ? low_but_tied
                            : alternative == Alternative::larger ? high_but_tied
                                                                 : low_but_tied || high_but_tied;
  out << "# data_statistic = " << number(r.data_statistic) << "\n# rank = " << t.rank << " of " << count + 1
      << " (1 = lowest)\n# ties = " << t.ties << " (surrogate statistics within a relative "
      << number(rank_tie_relative) << " of the data's)\n# significance = " << number(t.significance) << "\n# rejected = ";
  if (t.rejected)
    out << "true: the data's statistic lies beyond every surrogate's: the series is not "
        << null_hypothesis(r.options.surrogate.method);
  else if (held_by_ties)
    out << "false: the data's statistic ties with " << t.ties << " of " << count << " surrogates: a tie cannot reject";
  else
    out << "false: the data are consistent with the null hypothesis";
  out << "\n# surrogates_not_converged = " << r.surrogates_not_converged << "\n";
  if (!r.value_ties.empty()) out << "# value_ties = " << r.value_ties << "\n";
  out << "# surrogate\tstatistic\titerations\n";
  for (std::size_t k = 0; k < r.surrogate_statistics.size(); ++k)
    out << k + 1 << "\t" << number(r.surrogate_statistics[k]) << "\t" << r.surrogate_iterations[k] << "\n";
}

}  // namespace

void register_nonlinearity(CLI::App& app) {
  auto args = std::make_shared<NonlinearityArgs>();
  CLI::App* command = app.add_subcommand("nonlinearity", "rank-order surrogate test for nonlinearity");
  add_input_options(*command, args->input);
  add_options(*command, args->params, nonlinearity_parameters());
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
