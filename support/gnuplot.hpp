#pragma once
// Plots through gnuplot (Debian's gnuplot-nox), shared by the `chaos` and `mechanism` commands
// (an internal library of the command-line tools; neither analysis library links it). The caller
// writes a self-contained gnuplot script with the data inline; this sets the terminal from the
// file's extension (PNG through pngcairo, or SVG), runs gnuplot and reports failure.

#include <stdexcept>
#include <string>

namespace cli_support {

class PlotError : public std::runtime_error {
 public:
  enum class Kind { bad_extension, gnuplot_failed };
  PlotError(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  Kind kind() const noexcept { return kind_; }

 private:
  Kind kind_;
};

// Why `path` cannot be a plot (it ends neither in .png nor in .svg), or empty: for the commands
// to refuse it before any work, with the message render would give.
std::string plot_extension_refusal(const std::string& path, const std::string& option = "--plot");

// Runs `script` (which must not set the terminal or output) into `path` (.png or .svg). The image is
// written through safe_output::write_file: a file that cannot be written throws its WriteError.
void render(const std::string& script, const std::string& path);

// Single quotes in gnuplot strings are doubled.
std::string quoted(const std::string& s);

}  // namespace cli_support
