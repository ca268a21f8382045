// chaos density: the density map of a bifurcation diagram. Rows of (parameter, value), e.g. the
// section points of a sweep, become per-parameter densities on common bins, written as rows of
// (parameter, bin centre, density), one block per parameter value, and drawn as a colour map.

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "chaos/bifurcation.hpp"
#include "chaos/error.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"
#include "plot.hpp"

namespace chaos::cli {

namespace {

struct DensityArgs {
  InputOptions input;  // -c is the parameter column here
  std::size_t value_column = 2;
  DensityParams params;
  std::string plot;
  OutputOptions output;
};

// A colour map over (parameter, observed value) as the seed's Fig. 4b and 5; a single parameter
// value has no second axis to colour, so it is drawn as a curve.
std::string plot_script(const DensityMap& m, const std::string& method) {
  std::ostringstream s;
  s << "set xlabel 'parameter'\nset title 'density (" << method << ")' noenhanced\n";
  if (m.parameters.size() == 1) {
    s << "set xlabel 'value'\nset ylabel 'density'\nset grid\nplot '-' using 1:2 with steps notitle\n";
    for (std::size_t b = 0; b < m.centres.size(); ++b) s << m.centres[b] << " " << m.density[0][b] << "\n";
    s << "e\n";
    return s.str();
  }
  s << "set ylabel 'value'\nset cblabel 'density'\nset autoscale xfix\nset autoscale yfix\nset view map\nset pm3d map corners2color c1\nset palette rgb 21,22,23\n"
    << "splot '-' using 1:2:3 with pm3d notitle\n";
  for (std::size_t p = 0; p < m.parameters.size(); ++p) {
    for (std::size_t b = 0; b < m.centres.size(); ++b) s << m.parameters[p] << " " << m.centres[b] << " " << m.density[p][b] << "\n";
    s << "\n";
  }
  s << "e\n";
  return s.str();
}

void run(DensityArgs& a) {
  if (a.value_column == a.input.column) {
    throw InvalidInput(ErrorCode::invalid_parameter, "the value column (" + std::to_string(a.value_column) +
                                                         ") must differ from the parameter column (-c " + std::to_string(a.input.column) + ")");
  }
  check_density_params(a.params);
  // The input is read twice (parameter and value columns): standard input is kept in memory.
  std::string stdin_text;
  auto read = [&](std::size_t column) {
    InputOptions in = a.input;
    in.column = column;
    if (in.file != "-") return load_series(in).values;
    ReadOptions o;
    o.column = column;
    o.skip = in.skip;
    if (in.length) o.length = *in.length;
    std::istringstream text(stdin_text);
    return read_series(text, "<stdin>", o).values;
  };
  if (a.input.file == "-") {
    std::ostringstream all;
    all << std::cin.rdbuf();
    stdin_text = all.str();
  }
  const std::vector<double> parameter = read(a.input.column), value = read(a.value_column);

  auto run = run_density(parameter, value, a.input.file, a.input.column, a.value_column, a.params, mode_of(a.output));
  const DensityMap& m = run.map;
  const auto& samples = run.samples;
  if (!a.plot.empty()) render_plot(plot_script(m, run.method), a.plot);
  std::ostream* table = run.report.open_table(a.output);
  if (!table) return;
  std::ostream& out = *table;
  out << "# parameter\tbin_centre\tdensity\n";
  for (std::size_t p = 0; p < m.parameters.size(); ++p) {
    out << "# parameter = " << number(m.parameters[p]) << ": " << samples[p].size() << " values, " << m.in_range[p] << " in range";
    if (a.params.kde) out << ", bandwidth " << number(m.bandwidths[p]) << ", kernel mass in range " << number(m.kernel_mass[p]);
    out << "\n";
    for (std::size_t b = 0; b < m.centres.size(); ++b) out << number(m.parameters[p]) << "\t" << number(m.centres[b]) << "\t" << number(m.density[p][b]) << "\n";
    out << "\n";  // blank line between parameter values (gnuplot's scans)
  }
}

}  // namespace

void register_density(CLI::App& app) {
  auto a = std::make_shared<DensityArgs>();
  CLI::App* command = app.add_subcommand("density", "density map of a bifurcation diagram: rows of (parameter, value) -> (parameter, bin centre, density)");
  add_quiet_option(*command);
  a->input.column = 1;
  command->add_option("file", a->input.file, "input file, rows of parameter and value; - for stdin")->capture_default_str();
  command->add_option("-c,--column", a->input.column, "the parameter column (1-based)")->capture_default_str();
  command->add_option("-v,--value-column", a->value_column, "the value column (1-based)")->capture_default_str();
  command->add_option("-x,--skip", a->input.skip, "data rows to skip at the start")->capture_default_str();
  command->add_option("-l,--length", a->input.length, "data rows to use after the skip (default: all)");
  add_options(*command, a->params, density_parameters());
  add_plot_option(*command, a->plot, "draw the map as a colour map to FILE.png or FILE.svg");
  add_output_options(*command, a->output);
  command->callback([a] { run(*a); });
}

}  // namespace chaos::cli
