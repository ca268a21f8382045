// chaos generate SYSTEM: a reference series with its integrator, sampling and seed in the header.

#include <algorithm>
#include <cmath>
#include <map>
#include <iostream>
#include <sstream>

#include "chaos/error.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/models/zoo.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "parameter_options.hpp"

namespace chaos::cli {

namespace {

struct GenerateArgs {
  GenerateParams params;
  bool list = false;
  OutputOptions output;
};

std::string systems_help() {
  std::string text = "Systems and their parameters (set with -p name=value):\n";
  for (const SystemKind kind : all_systems()) {
    text += "  " + std::string(to_string(kind)) + ":";
    const auto parameters = system_parameters(kind);
    if (parameters.empty()) text += " (no parameters; --seed)";
    for (const auto& p : parameters) text += " " + p.name + "=" + number(p.default_value);
    text += "\n";
  }
  text += "Zoo systems (chaos generate --list shows their parameters): " + zoo_names() + "\n";
  return text;
}

// One line per zoo system: name, kind, dimension, parameters with defaults, default sampling.
void list_zoo(std::ostream& out) {
  out << "# name\tkind\tdimension\tparameters\tsampling\tcitation\n";
  for (const ZooEntry& e : zoo_systems()) {
    std::string parameters;
    for (const auto& p : e.parameters) parameters += (parameters.empty() ? "" : " ") + p.name + "=" + number(p.value);
    const std::string sampling = e.kind == ZooKind::map ? "transient=" + std::to_string(e.map_transient)
                                                        : "dt=" + number(e.dt) + " step=" + number(e.step) +
                                                              " transient=" + number(e.transient);
    out << e.name << "\t" << to_string(e.kind) << (e.delay ? " (delay)" : e.forced ? " (forced)" : "") << "\t"
        << e.dimension << "\t" << (parameters.empty() ? "-" : parameters) << "\t" << sampling << "\t" << e.citation
        << "\n";
  }
}

void run(const GenerateArgs& args) {
  if (args.list) {
    list_zoo(std::cout);
    return;
  }
  auto [trajectory, chosen, report] = run_generate(args.params, args.output, args.output.json);
  std::ostream* table = report.begin_table();
  if (!table) return;
  std::ostream& out = *table;
  std::vector<std::string> names;
  std::vector<std::span<const double>> columns;
  for (const std::size_t k : chosen) {
    names.push_back(trajectory.names[k]);
    columns.emplace_back(trajectory.components[k]);
  }
  write_columns(out, names, columns);
}

}  // namespace

void register_generate(CLI::App& app) {
  auto args = std::make_shared<GenerateArgs>();
  CLI::App* command = app.add_subcommand("generate", "write a series from a reference system (full precision)");
  add_quiet_option(*command);
  command->add_option("system", args->params.system, "lorenz, rossler, henon, logistic, ikeda, mackey_glass, sine, quasi_periodic, "
                                               "white_noise, uniform_noise, ar1, or a zoo system (--list)");
  command->add_flag("--list", args->list, "list the zoo systems with their parameters, sampling and citation");
  add_options(*command, args->params, generate_parameters(), parse_settings);
  add_output_options(*command, args->output);
  command->footer(systems_help());
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
