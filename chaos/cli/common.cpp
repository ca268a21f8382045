#include "common.hpp"

#include <unistd.h>

#include "chaos/format.hpp"
#include "chaos/time_scales.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "chaos/autocorrelation.hpp"
#include "chaos/error.hpp"
#include "chaos/norm.hpp"
#include "gnuplot.hpp"
#include "output_path.hpp"

namespace chaos::cli {

void add_quiet_option(CLI::App& command, bool& quiet) {
  command.add_flag("-q,--quiet", quiet, "no progress line and no long-run hint on standard error");
}

void add_quiet_option(CLI::App& command) {
  command.add_flag("-q,--quiet")->description("accepted as by every command (this one writes only its errors to standard error)");
}

Progress::Progress(bool quiet) : quiet_(quiet), bar_(!quiet && isatty(fileno(stderr))) {}

void Progress::hint(const std::string& command, std::size_t n, const std::string& text) const {
  if (!quiet_ && n > long_run_points)
    std::cerr << "chaos " << command << ": N = " << n << " samples: " << text << " (-q silences this)\n";
}

void Progress::update(const std::string& step, double fraction) {
  if (step != step_) {
    step_ = step;
    bar_.restart();
  }
  bar_.update(fraction, step);
}

std::function<void(double)> Progress::callback(const std::string& step) {
  return [this, step](double fraction) { update(step, fraction); };
}

std::function<void(const std::string&, double)> Progress::steps() {
  return [this](const std::string& step, double fraction) { update(step, fraction); };
}

void write_columns(std::ostream& out, const std::vector<std::string>& names,
                   const std::vector<std::span<const double>>& columns) {
  out << "#";
  for (std::size_t c = 0; c < names.size(); ++c) out << (c ? "\t" : " ") << names[c];
  out << "\n";
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      out << (c ? "\t" : "") << format_number(columns[c][i], Precision::round_trip);
    }
    out << "\n";
  }
}

void add_input_options(CLI::App& command, InputOptions& input) {
  command.add_option("file", input.file, "input file, one value per row (columns separated by blanks or commas); - for stdin")
      ->capture_default_str();
  add_column_option(command, input);
  command.add_option("-x,--skip", input.skip, "data rows to skip at the start")->capture_default_str();
  command.add_option("-l,--length", input.length, "data rows to use after the skip (default: all)");
  command.add_option("--dt", input.dt, "sampling interval, to report delays and times in time units too");
}

void add_column_option(CLI::App& command, InputOptions& input) {
  command
      .add_option_function<std::string>(
          "-c,--column",
          [&input](const std::string& text) {
            if (!text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); })) {
              if (!CLI::detail::lexical_cast(text, input.column))
                throw CLI::ValidationError("--column", "'" + text + "' is larger than any column number");
              input.column_name.clear();
            } else if (!text.empty() && (text[0] == '-' || text[0] == '+')) {
              throw CLI::ValidationError("--column", "'" + text + "' is neither a column number (1, 2, ...) nor a name");
            } else {
              input.column_name = text;
            }
          },
          "column to read: its number (1-based) or its name in the file's header row")
      ->type_name("NUMBER|NAME")
      ->default_str("1");
}

Series load_series(const InputOptions& input) {
  ReadOptions options;
  options.column = input.column;
  options.column_name = input.column_name;
  options.skip = input.skip;
  if (input.length) options.length = *input.length;
  options.dt = input.dt;
  Series series = read_series(input.file, options);
  check_series(series.values, input.file);
  return series;
}

namespace {

// The command's input file, when it has one and it was given: -o and --plot must not name it.
std::string input_path(const CLI::Option* input) {
  return input && input->count() > 0 ? input->results().front() : std::string();
}

}  // namespace

void add_output_options(CLI::App& command, OutputOptions& output) {
  command.add_flag("--json", output.json, "write one JSON object instead of the table");
  // Checked while the command line is read, before any work (-o naming the input file
  // overwrote the data; an unwritable -o failed only after the whole computation). The input is
  // the command's "file" argument, when it has one.
  const CLI::Option* input = command.get_option_no_throw("file");
  command.add_option("-o,--output", output.path, "write to this file instead of standard output")
      ->check(CLI::Validator(
          [input](std::string& path) {
            if (const std::string why = cli_support::output_refusal("-o", path, input_path(input)); !why.empty())
              throw InvalidInput(ErrorCode::io, why);
            return std::string();
          },
          "", "writable file"));
}

void add_plot_option(CLI::App& command, std::string& path, const std::string& description) {
  // Checked while the command line is read, like -o (an unwritable --plot failed only
  // after the whole computation), and the extension with it.
  const CLI::Option* input = command.get_option_no_throw("file");
  command.add_option("--plot", path, description)
      ->check(CLI::Validator(
          [input](std::string& plot) {
            if (const std::string why = cli_support::plot_extension_refusal(plot); !why.empty())
              throw InvalidInput(ErrorCode::invalid_parameter, why);
            if (const std::string why = cli_support::output_refusal("--plot", plot, input_path(input)); !why.empty())
              throw InvalidInput(ErrorCode::io, why);
            return std::string();
          },
          "", "FILE.png|FILE.svg"));
}

std::string describe_dimension(const CaoResult& result) {
  if (result.embedding_dimension) return std::to_string(*result.embedding_dimension);
  if (result.stochastic)
    return std::string("none: E2 stays within its sampling error of 1 (stochastic series)") +
           (result.e1_saturation ? "; E1 alone would settle at m = " + std::to_string(*result.e1_saturation) : "");
  return "none: E1 does not settle within the range (not saturated)";
}

std::map<std::string, double> parse_settings(const std::vector<std::string>& settings) {
  std::map<std::string, double> out;
  for (const auto& setting : settings) {
    const auto eq = setting.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InvalidInput(ErrorCode::invalid_parameter, "parameter '" + setting + "' is not of the form name=value");
    double value = 0.0;
    try {
      std::size_t used = 0;
      value = std::stod(setting.substr(eq + 1), &used);
      if (used != setting.size() - eq - 1) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      throw InvalidInput(ErrorCode::invalid_parameter, "parameter '" + setting + "': the value is not a number");
    }
    out[setting.substr(0, eq)] = value;
  }
  return out;
}

}  // namespace chaos::cli
