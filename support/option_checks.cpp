#include "option_checks.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace cli_support {

namespace {

std::string first_non_blank(const std::string& s) {
  const auto at = s.find_first_not_of(" \t\n\r\f\v");
  return at == std::string::npos ? std::string() : s.substr(at, 1);
}

// Empty: accepted (or left to CLI11's own conversion, which refuses what is not a number).
std::string check_unsigned(const std::string& text) {
  if (first_non_blank(text) == "-") return "'" + text + "' is negative; this option takes a whole number >= 0";
  errno = 0;
  char* end = nullptr;
  std::strtoull(text.c_str(), &end, 0);
  if (errno == ERANGE) return "'" + text + "' is larger than 18446744073709551615, the largest whole number this option holds";
  return {};
}

std::string check_signed(const std::string& text) {
  errno = 0;
  char* end = nullptr;
  std::strtoll(text.c_str(), &end, 0);
  if (errno == ERANGE) return "'" + text + "' is outside the whole numbers this option holds (|n| < 2^63)";
  return {};
}

std::string check_real(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return {};  // not a number at all: CLI11's conversion says so
  if (!std::isfinite(value)) return "'" + text + "' is not a finite number (NaN, infinity, or beyond 1.8e308)";
  return {};
}

}  // namespace

void check_numeric_options(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type == "UINT") option->check(CLI::Validator(check_unsigned, "", "whole number >= 0"));
    else if (type == "INT") option->check(CLI::Validator(check_signed, "", "whole number"));
    else if (type == "FLOAT") option->check(CLI::Validator(check_real, "", "finite number"));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) check_numeric_options(*sub);
}

void one_value_per_occurrence(CLI::App& app) {
  for (CLI::Option* option : app.get_options())
    if (!option->get_positional() && option->get_expected_max() > 1)
      option->expected(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) one_value_per_occurrence(*sub);
}

std::string unknown_subcommand(const CLI::App& app, int argc, const char* const* argv) {
  if (argc < 2 || argv[1][0] == '-') return {};
  const std::string name = argv[1];
  std::string names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->check_name(name)) return {};
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return "unknown command '" + name + "'; the commands are: " + names;
}

}  // namespace cli_support
