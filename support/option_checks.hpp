#pragma once
// Refuses, while the command line is parsed, the numbers an option's type cannot hold. CLI11 2.1
// reads "-1" into an unsigned option as 2^64-1 (strtoull wraps it), an out-of-range whole number
// as its largest value, and "nan" or "inf" into a floating-point option. Every tool calls this
// once, after all its options are registered, so no command meets such a value: a negative
// count, a count past 2^64-1, a non-finite real. The message names the option and the value
// (exit code: the tool's usage error, like any other value not of the option's type).

#include <CLI/CLI.hpp>

#include <string>

namespace cli_support {

// Adds the checks to every option of `app` and of its subcommands, recursively.
void check_numeric_options(CLI::App& app);

// Makes every repeatable (vector) option take one value per occurrence (a comma-separated list
// still splits where the option has a delimiter). CLI11 lets such an option swallow every
// argument after it, so "--set k=v scene.toml" would read the scene as another --set; here
// the file is left to the positional argument, and several values need the option repeated.
void one_value_per_occurrence(CLI::App& app);

// When the first argument is neither an option nor one of `app`'s subcommands, the message that
// names it and lists the commands (CLI11 says only "A subcommand is required", and with --help
// after it prints the main help and exits 0); else empty. The caller exits with its usage error.
std::string unknown_subcommand(const CLI::App& app, int argc, const char* const* argv);

}  // namespace cli_support
