// chaos generate SYSTEM: a reference series with its integrator, sampling and seed in the header.

#include <algorithm>
#include <cmath>
#include <map>
#include <iostream>
#include <sstream>

#include "chaos/error.hpp"
#include "chaos/generate.hpp"
#include "chaos/zoo.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct GenerateArgs {
  std::string system;
  std::size_t length = 10000;
  std::vector<std::string> settings;
  std::uint64_t seed = 1;
  std::string components = "all";
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

// A zoo system that is not one of the reference systems of generate.hpp.
Trajectory generate_zoo(const ZooEntry& entry, const GenerateArgs& args, const std::map<std::string, double>& settings) {
  return zoo_trajectory(entry, args.length, settings, args.seed);
}

void run_zoo(const ZooEntry& entry, const GenerateArgs& args);
void write(const GenerateArgs& args, const Trajectory& trajectory,
           const std::vector<std::pair<std::string, double>>& parameters);

void run(const GenerateArgs& args) {
  if (args.list) {
    list_zoo(std::cout);
    return;
  }
  if (args.system.empty()) throw InvalidInput(ErrorCode::invalid_parameter, "a system name is required (or --list)");
  // Every sample of every component is held in memory before it is written: 10^8 samples of a
  // three-component flow are 2.4 GB, and a larger -l is more likely a typo than a plan.
  constexpr std::size_t max_length = 100'000'000;
  if (args.length == 0 || args.length > max_length)
    throw InvalidInput(ErrorCode::invalid_parameter, "length -l must be in 1.." + std::to_string(max_length) +
                                                         " (got " + std::to_string(args.length) + ")");
  const auto kind = system_from_name(args.system);
  const ZooEntry* entry = kind ? nullptr : find_zoo_system(args.system);
  if (!kind && !entry)
    throw InvalidInput(ErrorCode::invalid_parameter, "unknown system '" + args.system + "' (valid: " +
                                                         std::string("sine, quasi_periodic, white_noise, uniform_noise, ar1, ") +
                                                         zoo_names() + "); see chaos generate --help");
  if (entry) {
    run_zoo(*entry, args);
    return;
  }
  GenerateRequest request;
  request.system = *kind;
  request.length = args.length;
  request.seed = args.seed;
  request.parameters = parse_settings(args.settings);
  const Trajectory trajectory = generate(request);
  std::vector<std::pair<std::string, double>> parameters;
  for (const auto& p : system_parameters(*kind)) {
    const auto it = request.parameters.find(p.name);
    parameters.emplace_back(p.name, it == request.parameters.end() ? p.default_value : it->second);
  }
  write(args, trajectory, parameters);
}

void write(const GenerateArgs& args, const Trajectory& trajectory,
           const std::vector<std::pair<std::string, double>>& parameters) {
  std::vector<std::size_t> chosen;
  if (args.components == "all") {
    for (std::size_t k = 0; k < trajectory.names.size(); ++k) chosen.push_back(k);
  } else {
    std::stringstream list(args.components);
    for (std::string name; std::getline(list, name, ',');) {
      const auto it = std::find(trajectory.names.begin(), trajectory.names.end(), name);
      if (it == trajectory.names.end()) {
        std::string valid;
        for (const auto& n : trajectory.names) valid += (valid.empty() ? "" : ", ") + n;
        throw InvalidInput(ErrorCode::invalid_parameter,
                           "system " + args.system + " has no component '" + name + "' (components: " + valid + ")");
      }
      chosen.push_back(static_cast<std::size_t>(it - trajectory.names.begin()));
    }
  }

  Report report("generate", args.output);
  report.parameter("system", args.system).parameter("length", args.length).parameter("seed", args.seed);
  for (const auto& [name, value] : parameters) report.parameter(name, value);
  report.parameter("dt", trajectory.dt);
  std::ostream& out = report.stream();
  if (report.json_mode()) {
    for (const std::size_t k : chosen) report.json()["components"][trajectory.names[k]] = trajectory.components[k];
    report.write_json(out);
    return;
  }
  report.write_header(out);
  std::vector<std::string> names;
  std::vector<std::span<const double>> columns;
  for (const std::size_t k : chosen) {
    names.push_back(trajectory.names[k]);
    columns.emplace_back(trajectory.components[k]);
  }
  write_columns(out, names, columns);
}

void run_zoo(const ZooEntry& entry, const GenerateArgs& args) {
  const auto settings = parse_settings(args.settings);
  const Trajectory trajectory = generate_zoo(entry, args, settings);
  // Every model parameter and the sampling actually used, defaults included.
  const auto values = zoo_parameters(entry, [&] {
    std::map<std::string, double> model;
    for (const auto& [name, value] : settings)
      if (std::find_if(entry.parameters.begin(), entry.parameters.end(),
                       [&](const ZooParameter& p) { return p.name == name; }) != entry.parameters.end())
        model[name] = value;
    return model;
  }());
  std::vector<std::pair<std::string, double>> parameters;
  for (std::size_t i = 0; i < values.size(); ++i) parameters.emplace_back(entry.parameters[i].name, values[i]);
  const auto setting = [&](const std::string& name, double fallback) {
    const auto it = settings.find(name);
    return it == settings.end() ? fallback : it->second;
  };
  if (entry.kind == ZooKind::map) {
    parameters.emplace_back("transient", setting("transient", static_cast<double>(entry.map_transient)));
  } else if (entry.delay) {
    parameters.emplace_back("steps_per_delay", setting("steps_per_delay", std::round(entry.parameters[3].value / entry.step)));
    parameters.emplace_back("transient", setting("transient", entry.transient));
  } else {
    parameters.emplace_back("step", setting("step", entry.step));
    parameters.emplace_back("transient", setting("transient", entry.transient));
  }
  write(args, trajectory, parameters);
}

}  // namespace

void register_generate(CLI::App& app) {
  auto args = std::make_shared<GenerateArgs>();
  CLI::App* command = app.add_subcommand("generate", "write a series from a reference system (full precision)");
  command->add_option("system", args->system, "lorenz, rossler, henon, logistic, ikeda, mackey_glass, sine, quasi_periodic, "
                                               "white_noise, uniform_noise, ar1, or a zoo system (--list)");
  command->add_flag("--list", args->list, "list the zoo systems with their parameters, sampling and citation");
  command->add_option("-l,--length", args->length, "number of samples")->capture_default_str();
  command->add_option("-p,--parameter", args->settings, "system parameter name=value (repeatable)");
  command->add_option("--seed", args->seed, "seed of the stochastic systems and the logistic start")->capture_default_str();
  command->add_option("--components", args->components, "comma-separated components to write, or all")->capture_default_str();
  add_output_options(*command, args->output);
  command->footer(systems_help());
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
