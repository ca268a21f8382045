#pragma once
// The files `study pipeline` and `study plot` write (--plot, --series, -o), refused while the
// command line is read (cli_support's output_path.hpp; an unwritable one failed only
// after the work): a file-system reason is a StudyError of kind io (exit 4, docs/reference/study.md), a plot's
// extension a StudyError (exit 3).

#include <CLI/CLI.hpp>

#include <string>

#include "output_path.hpp"
#include "study/error.hpp"

namespace study::cli {

inline void check_output(CLI::Option* option, const std::string& name, const CLI::Option* input, bool plot) {
  cli_support::check_output_option(option, name, input, plot, [](const std::string& why, bool io) {
    if (io) throw StudyError(why, StudyError::Kind::io);
    throw StudyError(why);
  });
}

}  // namespace study::cli
