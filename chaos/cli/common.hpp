#pragma once
// What every `chaos` command shares: reading the series (TISEAN's -c -x -l and --dt), and writing
// the result either as a tab-separated table under a '#' header that records every parameter and
// N, or as one JSON object for scripts.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <type_traits>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "chaos/cao.hpp"
#include "chaos/norm.hpp"
#include "chaos/series.hpp"
#include "progress_bar.hpp"
#include "report.hpp"

namespace chaos::cli {

// Exit codes, documented in README.md.
enum ExitCode : int { ok = 0, internal_error = 1, usage_error = 2, invalid_input = 3, validation_failed = 4 };

struct InputOptions {
  std::string file = "-";
  std::size_t column = 1;
  std::string column_name;  // -c NAME: the column of that name in the file's header row
  std::size_t skip = 0;
  std::optional<std::size_t> length;
  std::optional<double> dt;
};

// Registers [file|-] -c -x -l --dt.
void add_input_options(CLI::App& command, InputOptions& input);
// -c,--column: a number (1-based) or the name of a column in the file's header row.
void add_column_option(CLI::App& command, InputOptions& input);
Series load_series(const InputOptions& input);

void add_output_options(CLI::App& command, OutputOptions& output);
// Registers --plot FILE.png|FILE.svg, refused while the command line is read when the extension is
// neither, or the file could not be written (output_path.hpp); register the input file first.
void add_plot_option(CLI::App& command, std::string& path, const std::string& description);

// What the long commands (d2, lyapunov, cao, fnn, surrogates, nonlinearity, analyze) say on
// standard error while they work: a hint before a job on more than long_run_points samples (what is
// slow, and the option that shortens it), and a progress line on a terminal (drawn after 2 s, so
// short runs show none); -q,--quiet, which add_quiet_option registers, silences both.
constexpr std::size_t long_run_points = 200'000;
void add_quiet_option(CLI::App& command, bool& quiet);
// -q,--quiet on a command that writes nothing to standard error but its errors: accepted, so a
// script can pass -q to every command alike.
void add_quiet_option(CLI::App& command);
class Progress {
 public:
  explicit Progress(bool quiet);
  // "chaos COMMAND: N = n samples: TEXT (-q silences this)" when n > long_run_points.
  void hint(const std::string& command, std::size_t n, const std::string& text) const;
  // For an options struct's `progress`: redraws the line with `step` as its detail (a new step
  // starts the time-left estimate afresh).
  std::function<void(double)> callback(const std::string& step);
  // For AutomaticAnalysisOptions::progress.
  std::function<void(const std::string&, double)> steps();

 private:
  void update(const std::string& step, double fraction);
  bool quiet_;
  cli_support::ProgressBar bar_;
  std::string step_;
};

// Writes samples as rows of full-precision numbers (%.17g, which reads back exactly), one column
// each, tab-separated, under a "# name1\tname2 ..." line: the series of `generate` and `zoo --series`.
void write_columns(std::ostream& out, const std::vector<std::string>& names,
                   const std::vector<std::span<const double>>& columns);

// Thrown by `validate` after its report is written, to leave with exit code 4.
struct ValidationFailed {};

// "3", or why there is no embedding dimension (stochastic, not saturated).
std::string describe_dimension(const CaoResult& result);

// "name=value" settings (-p): refused with the offending text when malformed or not a number.
std::map<std::string, double> parse_settings(const std::vector<std::string>& settings);

// Each command registers itself on the application.
void register_generate(CLI::App& app);
void register_mutual(CLI::App& app);
void register_autocorrelation(CLI::App& app);
void register_cao(CLI::App& app);
void register_fnn(CLI::App& app);
void register_d2(CLI::App& app);
void register_analyze(CLI::App& app);
void register_validate(CLI::App& app);
void register_zoo(CLI::App& app);
void register_lyapunov(CLI::App& app);
void register_lyapunov_maps(CLI::App& app);
void register_spectrum(CLI::App& app);
void register_section(CLI::App& app);
void register_density(CLI::App& app);
void register_surrogates(CLI::App& app);
void register_nonlinearity(CLI::App& app);
void register_neighbors(CLI::App& app);

}  // namespace chaos::cli
