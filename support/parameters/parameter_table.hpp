#pragma once
// A command's parameter table: one entry per parameter that both the command line and the Python
// package take, the only place its Python name, command-line flags and help text are written, with
// the field of the command's parameters struct it sets. From the table the command line registers
// its options (support/parameter_options.hpp) and the Python package reads its keyword arguments
// and builds each function's signature (python/src/_core.cpp, python/src/chaos/__init__.py). A
// parameter's default is its field's value in a default-constructed parameters struct: it is
// written once, in the struct. The checks of the values stay in the shared computation (run_X in
// chaos/commands, study::sweep_spec for `study sweep`), which both front ends call. Standard
// library only: the Python module reads the tables without the command line's parser.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace cli_support {

static_assert(std::is_same_v<std::uint64_t, std::size_t>, "seeds and counts share the std::size_t field type");

// The field a parameter sets: one of the types both front ends read. An empty optional (or vector,
// or map) means "left out": the command chooses, and Python's default is None.
using ParameterField =
    std::variant<std::size_t*, std::optional<std::size_t>*, double*, std::optional<double>*, std::string*, bool*,
                 std::vector<double>*, std::vector<std::size_t>*, std::vector<std::string>*,
                 std::map<std::string, double>*>;

template <class Params>
struct Parameter {
  std::string name;   // the Python keyword argument
  std::string flags;  // the command-line names as CLI11 takes them: "-m,--min-dimension"; "!--no-x" clears a bool
  std::string help;
  std::function<ParameterField(Params&)> field;
  // The command line's type name in place of CLI11's own (e.g. "FLOAT|inf"); empty: CLI11's.
  std::string type_name = {};
  // Several values in one argument, split at this character ('\0': one value per argument).
  char delimiter = '\0';
  // The default is not a value to show (infinity for "no limit", which the help text describes): the
  // command line shows none and Python's default is None, which leaves the field as it is.
  bool default_described = false;
};

template <class Params>
using ParameterTable = std::vector<Parameter<Params>>;

namespace field_path {
template <class Object, class Member, class... Rest>
auto& follow(Object& object, Member member, Rest... rest) {
  if constexpr (sizeof...(Rest) == 0)
    return object.*member;
  else
    return follow(object.*member, rest...);
}
}  // namespace field_path

// The field reached by a path of member pointers: field(&CaoParams::options, &CaoOptions::min_dimension)
// is params.options.min_dimension.
template <class Params, class Member, class... Rest>
std::function<ParameterField(Params&)> field(Member Params::*member, Rest... rest) {
  return [=](Params& params) -> ParameterField { return &field_path::follow(params, member, rest...); };
}

}  // namespace cli_support
