#include "gnuplot.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

namespace cli_support {

namespace {
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string plot_extension_refusal(const std::string& path, const std::string& option) {
  if (ends_with(path, ".png") || ends_with(path, ".svg")) return {};
  return option + ": the file must end in .png or .svg (got '" + path + "')";
}

void render(const std::string& script, const std::string& path) {
  std::string terminal;
  if (ends_with(path, ".png")) {
    terminal = "pngcairo size 1000,800 font 'sans,10'";
  } else if (ends_with(path, ".svg")) {
    terminal = "svg size 1000,800 dynamic font 'sans,10'";
  } else {
    throw PlotError(PlotError::Kind::bad_extension, plot_extension_refusal(path));
  }
  const auto script_path = std::filesystem::temp_directory_path() /
                           ("plot-" + std::to_string(std::hash<std::string>{}(path + script)) + ".gp");
  {
    std::ofstream out(script_path);
    if (!out) throw PlotError(PlotError::Kind::io, "--plot: cannot write the gnuplot script " + script_path.string());
    // Plain text everywhere: names such as not_saturated or crank_conrod are not subscripts.
    out << "set terminal " << terminal << "\nset termoption noenhanced\nset output " << quoted(path) << "\n"
        << script << "\nunset output\n";
  }
  const std::string command = "gnuplot " + quoted(script_path.string()) + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string messages;
  int status = -1;
  if (pipe) {
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe)) messages += buffer;
    status = pclose(pipe);
  }
  std::filesystem::remove(script_path);
  if (status != 0) {
    throw PlotError(PlotError::Kind::gnuplot_failed,
                    "--plot: gnuplot failed (is the gnuplot-nox package installed?)" +
                        (messages.empty() ? std::string() : ": " + messages));
  }
}

}  // namespace cli_support
