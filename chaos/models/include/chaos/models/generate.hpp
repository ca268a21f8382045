#pragma once
// One entry point to the reference systems of systems.hpp by name, for the command line and the
// reference table: `generate({SystemKind::lorenz, 10000, {{"rho", 28}}})`. Parameter names are the
// fields of each system's parameter struct; an unknown name is refused with the list of valid ones.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "chaos/models/systems.hpp"

namespace chaos {

enum class SystemKind { lorenz, rossler, henon, logistic, ikeda, mackey_glass, sine, quasi_periodic, white_noise, uniform_noise, ar1 };

const char* to_string(SystemKind system) noexcept;
std::optional<SystemKind> system_from_name(std::string_view name) noexcept;
std::vector<SystemKind> all_systems();

struct SystemParameter {
  std::string name;
  double default_value;
  std::string meaning;
};
// The parameters `generate` accepts for a system, with their defaults, in a stable order.
std::vector<SystemParameter> system_parameters(SystemKind system);

struct GenerateRequest {
  SystemKind system = SystemKind::lorenz;
  std::size_t length = 10000;
  std::map<std::string, double> parameters;  // overrides of system_parameters(); unknown names refused
  std::uint64_t seed = 1;                    // for the stochastic systems (and the logistic start)
};

Trajectory generate(const GenerateRequest& request);

}  // namespace chaos
