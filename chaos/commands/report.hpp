#pragma once
// The output of a `chaos` command, shared by the command line (chaos/cli/) and the Python package
// (python/): the parameters of a run, collected in order, written as '#' header lines or as the
// "parameters" object of the JSON output, and the JSON object of the result. A command's whole
// JSON is built here once (commands.hpp), so `chaos X --json` and the Python result's to_dict()
// cannot drift apart.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "chaos/estimate.hpp"
#include "chaos/norm.hpp"
#include "chaos/scaling_region.hpp"

namespace chaos::cli {

struct OutputOptions {
  bool json = false;
  std::string path;  // -o; empty: standard output
};

// The output mode without the file: what a command's shared computation is given when the command
// line opens the file itself afterwards (Report::open).
inline OutputOptions mode_of(const OutputOptions& output) { return {output.json, std::string()}; }

// Formats a double with enough digits to round-trip the estimate's meaningful precision.
std::string number(double value);
// "[low, high]" with number()'s digits, or "none".
std::string interval_text(const std::optional<Interval>& interval);

// Collects the parameters of a run in the order they are added, then writes them as '#' lines or
// as the "parameters" object of the JSON output. A parameter written again keeps its place and takes
// the new value.
class Report {
 public:
  explicit Report(std::string command, const OutputOptions& output = {});
  template <class T>
  Report& parameter(const std::string& name, const T& value) {
    json_["parameters"][name] = value;
    set_header(name, to_text(value));
    return *this;
  }
  Report& parameter(const std::string& name, const std::optional<double>& value);
  Report& parameter(const std::string& name, const std::optional<std::size_t>& value);
  // A parameter left out, with nothing chosen for it: null, and "none" in the header.
  Report& parameter_left_out(const std::string& name);
  bool has_parameter(const std::string& name) const { return json_["parameters"].contains(name); }
  // Sends the output to output.path from now on: a temporary file beside it, renamed over it when
  // the command line commits its outputs after the command succeeded (safe_output.hpp's
  // commit_pending), so a failed write or a later error (a plot refused) leaves the file untouched.
  void open(const OutputOptions& output);
  nlohmann::ordered_json& json() { return json_; }
  const nlohmann::ordered_json& json() const { return json_; }
  bool json_mode() const { return output_.json; }
  // Writes the header lines (text mode) or nothing (JSON mode) to `out`.
  void write_header(std::ostream& out) const;
  // Writes the JSON object (JSON mode) to `out`.
  void write_json(std::ostream& out) const;
  std::ostream& stream();
  // The command line's output step: in JSON mode writes the JSON object and returns null (the
  // command is done), else writes the '#' header lines and returns the stream the command writes
  // its table to.
  std::ostream* begin_table();
  // open(output), then begin_table().
  std::ostream* open_table(const OutputOptions& output);

 private:
  template <class T>
  static std::string to_text(const T& value) {
    if constexpr (std::is_same_v<T, bool>) {
      return value ? "true" : "false";
    } else if constexpr (std::is_floating_point_v<T>) {
      return number(value);
    } else if constexpr (std::is_arithmetic_v<T>) {
      return std::to_string(value);
    } else if constexpr (std::is_convertible_v<T, std::string>) {
      return std::string(value);
    } else {  // a list, or a map of name=value settings; appended piece by piece (GCC 12's
              // -Wstringop-overflow misreads a chain of string additions here)
      std::string text;
      for (const auto& item : value) {
        if (!text.empty()) text += ',';
        if constexpr (requires { item.second; }) {
          text += item.first;
          text += '=';
          text += to_text(item.second);
        } else {
          text += to_text(item);
        }
      }
      return text.empty() ? std::string("none") : text;
    }
  }
  void set_header(const std::string& name, std::string text);
  std::string command_;
  OutputOptions output_;
  nlohmann::ordered_json json_;
  std::vector<std::pair<std::string, std::string>> header_;
  std::ostream* file_ = nullptr;  // the pending file's stream (safe_output.hpp), or standard output
};

// JSON null for an empty optional.
template <class T>
nlohmann::ordered_json optional_json(const std::optional<T>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

// [low, high], or null.
nlohmann::ordered_json interval_json(const std::optional<Interval>& i);
// An answer (estimate.hpp) as {"value", "interval", "status", "reason"}: the one shape every
// command and the Python package give an estimate in.
nlohmann::ordered_json estimate_json(const Estimate& e);
// The same as text: "value in [low, high] per PER (status)", or "none (status)"; with no unit
// (PER empty, as for D2) "value in [low, high] (status)".
std::string estimate_text(const Estimate& e, const std::string& per = "");

Norm parse_norm(const std::string& name);

// The series a command analyses, wherever it came from: a file read by the command line, or an
// array handed over by the Python package (`file` then names it as such). The values are viewed,
// not copied.
struct SeriesInput {
  std::span<const double> values;
  std::string file = "-";
  std::size_t column = 1;
  std::optional<double> dt;
};

// The checks every command applies to a series it reads (finite values, a usable scale).
void check_series(std::span<const double> x, const std::string& what);

}  // namespace chaos::cli
