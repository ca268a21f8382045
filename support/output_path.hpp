#pragma once
// Refuses, before any work, a file a command would write its result to (-o, --plot): it is the
// command's input file (writing there destroys the data), a directory, in a directory that does
// not exist, or not writable. Issue 16: `-o` naming the input overwrote it, and an unwritable -o
// or --plot failed only after the whole computation. Checked without creating the file.

#include <string>

namespace cli_support {

// Why `path`, given to `option`, cannot take the output, or empty. `input` is the command's input
// file ("" or "-" when there is none to protect).
std::string output_refusal(const std::string& option, const std::string& path, const std::string& input = "");

}  // namespace cli_support
