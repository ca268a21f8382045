// chaos surrogates: FT, AAFT or IAAFT surrogates of a series, one column per surrogate, with an
// explicit seed (surrogate k uses the k-th draw of the seed's stream, so it does not depend on
// --count) and optional end matching (TISEAN's advice: trim rather than zero-pad).

#include <cstdio>

#include "chaos/format.hpp"
#include "chaos/error.hpp"
#include "chaos/surrogates.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"

namespace chaos::cli {

namespace {

struct SurrogatesArgs {
  InputOptions input;
  OutputOptions output;
  SurrogatesParams params;
  bool quiet = false;
};

void run(SurrogatesArgs& args) {
  const Series series = load_series(args.input);
  Progress progress(args.quiet);
  progress.hint("surrogates", series.values.size(),
                "each surrogate takes up to --max-iterations Fourier transforms of all the samples and may take "
                "long; -l 100000 uses the first 10^5 samples");
  args.params.options.progress = progress.callback("surrogates");
  auto [made, match, length, report] =
      run_surrogates({series.values, args.input.file, series.column, series.dt}, args.params, args.output);
  std::ostream* table = report.begin_table();
  if (!table) return;
  std::ostream& out = *table;
  const auto& j = report.json();
  const auto status = j["status"].get<std::vector<std::string>>();
  const auto iterations = j["iterations"].get<std::vector<std::size_t>>();
  const auto deviation = j["spectral_deviation"].get<std::vector<double>>();
  out << "# surrogate\tstatus\titerations\tspectral_deviation\n";
  for (std::size_t k = 0; k < made.size(); ++k)
    out << "# " << k + 1 << "\t" << status[k] << "\t" << iterations[k] << "\t" << number(deviation[k]) << "\n";
  out << "#";
  for (std::size_t k = 0; k < made.size(); ++k) out << (k ? "\t" : " ") << "s" << k + 1;
  out << "\n";
  // Full precision: IAAFT and AAFT surrogates are permutations of the data, and the output keeps
  // them so.
  for (std::size_t i = 0; i < length; ++i) {
    for (std::size_t k = 0; k < made.size(); ++k) {
      out << (k ? "\t" : "") << format_number(made[k].values[i], Precision::round_trip);
    }
    out << "\n";
  }
}

}  // namespace

void register_surrogates(CLI::App& app) {
  auto args = std::make_shared<SurrogatesArgs>();
  CLI::App* command = app.add_subcommand("surrogates", "FT, AAFT or IAAFT surrogate series, one column per surrogate");
  add_input_options(*command, args->input);
  add_options(*command, args->params, surrogates_parameters());
  add_quiet_option(*command, args->quiet);
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
