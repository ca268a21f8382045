#pragma once
// A command's options from its parameter table (parameters/parameter_table.hpp): a bool field is a
// flag, a map field repeatable name=value settings read by the tool's own parser, any other field
// an option taking a value; a value field that is not optional (nor a list) shows its default in
// the help, as CLI11's capture_default_str writes it.

#include <CLI/CLI.hpp>

#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "parameter_table.hpp"

namespace cli_support {

// Reads repeatable name=value settings into a map, refusing a malformed one with the tool's own
// error (chaos: `-p name=value`).
using SettingsParser = std::map<std::string, double> (*)(const std::vector<std::string>&);

template <class Params>
void add_option(CLI::App& command, Params& params, const Parameter<Params>& parameter,
                SettingsParser parse_settings = nullptr) {
  std::visit(
      [&](auto* target) {
        using T = std::remove_pointer_t<decltype(target)>;
        if constexpr (std::is_same_v<T, bool>) {
          command.add_flag(parameter.flags, *target, parameter.help);
        } else if constexpr (std::is_same_v<T, std::map<std::string, double>>) {
          if (parse_settings == nullptr)
            throw std::logic_error(parameter.flags + ": a settings parameter needs the tool's settings parser");
          command.add_option_function<std::vector<std::string>>(
              parameter.flags, [target, parse_settings](const std::vector<std::string>& settings) {
                *target = parse_settings(settings);
              },
              parameter.help);
        } else {
          CLI::Option* option = command.add_option(parameter.flags, *target, parameter.help);
          if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>)
            if (!parameter.default_described) option->capture_default_str();
          if (!parameter.type_name.empty()) option->type_name(parameter.type_name);
          if (parameter.delimiter != '\0') option->delimiter(parameter.delimiter);
        }
      },
      parameter.field(params));
}

// Registers every parameter of the table, in the table's order.
template <class Params>
void add_options(CLI::App& command, Params& params, const ParameterTable<Params>& table,
                 SettingsParser parse_settings = nullptr) {
  for (const auto& parameter : table) add_option(command, params, parameter, parse_settings);
}

}  // namespace cli_support
