#pragma once
// A command's options from its parameter table (commands/parameter_table.hpp): a bool field is a
// flag, a map field repeatable name=value settings (parse_settings), any other field an option
// taking a value; a value field that is not optional (nor a list) shows its default in the help, as
// CLI11's capture_default_str writes it.

#include <CLI/CLI.hpp>

#include <map>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "common.hpp"
#include "parameter_table.hpp"

namespace chaos::cli {

template <class Params>
void add_option(CLI::App& command, Params& params, const Parameter<Params>& parameter) {
  std::visit(
      [&](auto* target) {
        using T = std::remove_pointer_t<decltype(target)>;
        if constexpr (std::is_same_v<T, bool>) {
          command.add_flag(parameter.flags, *target, parameter.help);
        } else if constexpr (std::is_same_v<T, std::map<std::string, double>>) {
          command.add_option_function<std::vector<std::string>>(
              parameter.flags, [target](const std::vector<std::string>& settings) { *target = parse_settings(settings); },
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
void add_options(CLI::App& command, Params& params, const ParameterTable<Params>& table) {
  for (const auto& parameter : table) add_option(command, params, parameter);
}

}  // namespace chaos::cli
