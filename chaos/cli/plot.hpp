#pragma once
// Plots through gnuplot (Debian's gnuplot-nox): the command writes a self-contained gnuplot script
// with the data inline and runs it. PNG (pngcairo) or SVG, chosen by the file's extension.

#include <string>

namespace chaos::cli {

// Runs `script` (which must not set the terminal or output) into `path`; throws InvalidInput with
// the reason when the extension is neither .png nor .svg, or gnuplot is missing or fails.
void render_plot(const std::string& script, const std::string& path);

}  // namespace chaos::cli
