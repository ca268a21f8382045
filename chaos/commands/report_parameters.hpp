#pragma once
// A command's parameter table (parameter_table.hpp) written into its report (report.hpp). The command
// first writes what it chose for the parameters left out, each beside the rule that chose it
// (delay, delay_source), and the facts of the run (the file, N); report_parameters then adds every
// parameter of the table it has not written, under its Python name, with the value given (one left
// out, or a default that stands for "no limit" such as infinity: null, and "none" in the header). So
// the keys of a result's "parameters" include every keyword argument of its Python function, and
// neither front end writes that list.

#include <cmath>
#include <optional>
#include <type_traits>
#include <variant>

#include "parameter_table.hpp"
#include "report.hpp"

namespace chaos::cli {

template <class Params>
void report_parameters(Report& report, Params params, const ParameterTable<Params>& table) {
  for (const auto& parameter : table) {
    if (report.has_parameter(parameter.name)) continue;
    std::visit(
        [&](auto* value) {
          using T = std::remove_pointer_t<decltype(value)>;
          if constexpr (std::is_floating_point_v<T>) {
            if (std::isfinite(*value))
              report.parameter(parameter.name, *value);
            else
              report.parameter_left_out(parameter.name);
          } else if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string> ||
                        std::is_same_v<T, std::optional<double>> || std::is_same_v<T, std::optional<std::size_t>>) {
            report.parameter(parameter.name, *value);
          } else if (value->empty()) {  // a list or a map of settings
            report.parameter_left_out(parameter.name);
          } else {
            report.parameter(parameter.name, *value);
          }
        },
        parameter.field(params));
  }
}

}  // namespace chaos::cli
