// chaos generate SYSTEM: a reference series with its integrator, sampling and seed in the header.

#include <algorithm>
#include <iostream>
#include <sstream>

#include "chaos/error.hpp"
#include "chaos/generate.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct GenerateArgs {
  std::string system;
  std::size_t length = 10000;
  std::vector<std::string> settings;
  std::uint64_t seed = 1;
  std::string components = "all";
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
  return text;
}

void run(const GenerateArgs& args) {
  const auto kind = system_from_name(args.system);
  if (!kind) throw InvalidInput(ErrorCode::invalid_parameter, "unknown system '" + args.system + "'; see chaos generate --help");
  GenerateRequest request;
  request.system = *kind;
  request.length = args.length;
  request.seed = args.seed;
  request.parameters = parse_settings(args.settings);
  if (args.length == 0) throw InvalidInput(ErrorCode::invalid_parameter, "length -l must be at least 1 (got 0)");
  const Trajectory trajectory = generate(request);

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
  for (const auto& p : system_parameters(*kind)) {
    const auto it = request.parameters.find(p.name);
    report.parameter(p.name, it == request.parameters.end() ? p.default_value : it->second);
  }
  report.parameter("dt", trajectory.dt);
  std::ostream& out = report.stream();
  if (report.json_mode()) {
    for (const std::size_t k : chosen) report.json()["components"][trajectory.names[k]] = trajectory.components[k];
    report.write_json(out);
    return;
  }
  report.write_header(out);
  out << "#";
  for (std::size_t c = 0; c < chosen.size(); ++c) out << (c ? "\t" : " ") << trajectory.names[chosen[c]];
  out << "\n";
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    for (std::size_t c = 0; c < chosen.size(); ++c) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.17g", trajectory.components[chosen[c]][i]);
      out << (c ? "\t" : "") << buffer;
    }
    out << "\n";
  }
}

}  // namespace

void register_generate(CLI::App& app) {
  auto args = std::make_shared<GenerateArgs>();
  CLI::App* command = app.add_subcommand("generate", "write a series from a reference system (full precision)");
  command->add_option("system", args->system, "lorenz, rossler, henon, logistic, ikeda, mackey_glass, sine, quasi_periodic, white_noise, uniform_noise, ar1")
      ->required();
  command->add_option("-l,--length", args->length, "number of samples")->capture_default_str();
  command->add_option("-p,--parameter", args->settings, "system parameter name=value (repeatable)");
  command->add_option("--seed", args->seed, "seed of the stochastic systems and the logistic start")->capture_default_str();
  command->add_option("--components", args->components, "comma-separated components to write, or all")->capture_default_str();
  add_output_options(*command, args->output);
  command->footer(systems_help());
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
