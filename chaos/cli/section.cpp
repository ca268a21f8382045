// chaos section: a Poincaré section of a multi-column series: every PERIOD-th row from a phase
// (stroboscopic), or the crossings of one column through a level with every column interpolated
// on the cubic through four rows and the return times (hyperplane).

#include <span>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"

namespace chaos::cli {

namespace {

struct SectionArgs {
  std::string file = "-";
  std::size_t skip = 0;
  std::optional<std::size_t> length;
  SectionParams params;
  OutputOptions output;
};

void run(SectionArgs& a) {
  check_section_params(a.params);
  // The whole input, read once, so that several columns can be taken from standard input.
  const std::string text = read_text(a.file), name = a.file == "-" ? "<stdin>" : a.file;
  const SectionColumns input = read_section_columns(text, name, a.params, a.skip, a.length);
  const std::vector<std::span<const double>> data(input.columns.begin(), input.columns.end());
  SectionRun run = run_section(data, input.times, a.file, a.params, a.output);
  std::ostream* table = run.report.begin_table();
  if (!table) return;
  std::ostream& out = *table;
  const bool hyperplane = a.params.hyperplane.has_value();
  if (hyperplane) out << "# return_time: since the previous crossing; none for the first\n";
  out << "# time";
  for (std::size_t c : a.params.columns) out << "\tcolumn_" << c;
  if (hyperplane) out << "\treturn_time";
  out << "\n";
  for (std::size_t j = 0; j < run.time.size(); ++j) {
    out << number(run.time[j]);
    for (double v : run.points[j]) out << "\t" << number(v);
    if (hyperplane) out << "\t" << (run.return_time[j] ? number(*run.return_time[j]) : std::string("none"));
    out << "\n";
  }
}

}  // namespace

void register_section(CLI::App& app) {
  auto a = std::make_shared<SectionArgs>();
  CLI::App* command = app.add_subcommand("section", "Poincaré section: stroboscopic (every PERIOD-th row) or hyperplane crossings with return times");
  add_quiet_option(*command);
  command->add_option("file", a->file, "input file, columns separated by blanks, tabs or commas; - for stdin")->capture_default_str();
  command->add_option("-x,--skip", a->skip, "data rows to skip at the start")->capture_default_str();
  command->add_option("-l,--length", a->length, "data rows to use after the skip (default: all)");
  add_options(*command, a->params, section_parameters());
  command->get_option("--stroboscopic")->excludes(command->get_option("--hyperplane"));
  add_output_options(*command, a->output);
  command->callback([a] { run(*a); });
}

}  // namespace chaos::cli
