#pragma once
// Refuses, before any work, a file a command would write its result to (-o, --plot): it is the
// command's input file (writing there destroys the data), a directory, in a directory that does
// not exist, or cannot be written (a temporary file is created beside it and removed again, as
// safe_output.hpp will write it). Unchecked, `-o` naming the input would overwrite it, and an
// unwritable -o or --plot would fail only after the whole computation.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace cli_support {

// Why `path`, given to `option`, cannot take the output, or empty. `input` is the command's input
// file ("" or "-" when there is none to protect).
std::string output_refusal(const std::string& option, const std::string& path, const std::string& input = "");

// Checks `option` (called `name` in messages) while the command line is read: for a plot the
// extension first (gnuplot.hpp), then output_refusal against the value of `input` (null or not
// given: none). `refuse` gets the reason, and whether it is about the file system (false: the
// extension), and throws the tool's own error, for its exit code.
void check_output_option(CLI::Option* option, const std::string& name, const CLI::Option* input, bool plot,
                         std::function<void(const std::string& why, bool io)> refuse);

}  // namespace cli_support
