// generate: the computation and the JSON (commands.hpp).

#include <algorithm>
#include <cmath>
#include <sstream>

#include "chaos/error.hpp"
#include "chaos/models/zoo.hpp"
#include "commands.hpp"
#include "report_parameters.hpp"

namespace chaos::cli {

GenerateRun run_generate(const GenerateParams& params, const OutputOptions& output, bool with_components) {
  if (params.system.empty()) throw InvalidInput(ErrorCode::invalid_parameter, "a system name is required (or --list)");
  // Every sample of every component is held in memory before it is written: 10^8 samples of a
  // three-component flow are 2.4 GB, and a larger -l is more likely a typo than a plan.
  constexpr std::size_t max_length = 100'000'000;
  if (params.length == 0 || params.length > max_length)
    throw InvalidInput(ErrorCode::invalid_parameter, "length -l must be in 1.." + std::to_string(max_length) +
                                                         " (got " + std::to_string(params.length) + ")");
  const auto kind = system_from_name(params.system);
  const ZooEntry* entry = kind ? nullptr : find_zoo_system(params.system);
  if (!kind && !entry)
    throw InvalidInput(ErrorCode::invalid_parameter, "unknown system '" + params.system + "' (valid: " +
                                                         std::string("sine, quasi_periodic, white_noise, uniform_noise, ar1, ") +
                                                         zoo_names() + "); see chaos generate --help");
  Trajectory trajectory;
  std::vector<std::pair<std::string, double>> parameters;
  const auto& settings = params.parameters;
  if (entry) {
    // A zoo system that is not one of the reference systems of generate.hpp.
    trajectory = zoo_trajectory(*entry, params.length, settings, params.seed);
    // Every model parameter and the sampling actually used, defaults included.
    const auto values = zoo_parameters(*entry, [&] {
      std::map<std::string, double> model;
      for (const auto& [name, value] : settings)
        if (std::find_if(entry->parameters.begin(), entry->parameters.end(),
                         [&](const ZooParameter& p) { return p.name == name; }) != entry->parameters.end())
          model[name] = value;
      return model;
    }());
    for (std::size_t i = 0; i < values.size(); ++i) parameters.emplace_back(entry->parameters[i].name, values[i]);
    const auto setting = [&](const std::string& name, double fallback) {
      const auto it = settings.find(name);
      return it == settings.end() ? fallback : it->second;
    };
    if (entry->kind == ZooKind::map) {
      parameters.emplace_back("transient", setting("transient", static_cast<double>(entry->map_transient)));
    } else if (entry->delay) {
      parameters.emplace_back("steps_per_delay",
                              setting("steps_per_delay", std::round(entry->parameters[3].value / entry->step)));
      parameters.emplace_back("transient", setting("transient", entry->transient));
    } else {
      parameters.emplace_back("step", setting("step", entry->step));
      parameters.emplace_back("transient", setting("transient", entry->transient));
    }
  } else {
    GenerateRequest request;
    request.system = *kind;
    request.length = params.length;
    request.seed = params.seed;
    request.parameters = settings;
    trajectory = generate(request);
    for (const auto& p : system_parameters(*kind)) {
      const auto it = request.parameters.find(p.name);
      parameters.emplace_back(p.name, it == request.parameters.end() ? p.default_value : it->second);
    }
  }

  std::vector<std::size_t> chosen;
  if (params.components == "all") {
    for (std::size_t k = 0; k < trajectory.names.size(); ++k) chosen.push_back(k);
  } else {
    std::stringstream list(params.components);
    for (std::string name; std::getline(list, name, ',');) {
      const auto it = std::find(trajectory.names.begin(), trajectory.names.end(), name);
      if (it == trajectory.names.end()) {
        std::string valid;
        for (const auto& n : trajectory.names) valid += (valid.empty() ? "" : ", ") + n;
        throw InvalidInput(ErrorCode::invalid_parameter,
                           "system " + params.system + " has no component '" + name + "' (components: " + valid + ")");
      }
      chosen.push_back(static_cast<std::size_t>(it - trajectory.names.begin()));
    }
  }

  Report report("generate", output);
  report.parameter("system", params.system);
  report_parameters(report, params, generate_parameters());
  for (const auto& [name, value] : parameters) report.parameter(name, value);
  report.parameter("dt", trajectory.dt);
  if (with_components)
    for (const std::size_t k : chosen) report.json()["components"][trajectory.names[k]] = trajectory.components[k];
  return {std::move(trajectory), std::move(chosen), std::move(report)};
}

}  // namespace chaos::cli
