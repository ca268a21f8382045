#include "report.hpp"

#include <cstdio>
#include <iostream>

#include "chaos/error.hpp"
#include "chaos/format.hpp"
#include "chaos/series.hpp"
#include "chaos/time_scales.hpp"
#include "safe_output.hpp"

namespace chaos::cli {

std::string number(double value) { return format_number(value, Precision::result); }

std::string interval_text(const std::optional<Interval>& interval) {
  if (!interval) return "none";
  std::string text = "[";  // appended piece by piece: GCC 12's -Wstringop-overflow misreads "[" + string
  text += number(interval->low);
  text += ", ";
  text += number(interval->high);
  text += ']';
  return text;
}

Report::Report(std::string command, const OutputOptions& output) : command_(std::move(command)) {
  json_["command"] = command_;
  json_["parameters"] = nlohmann::ordered_json::object();
  open(output);
}

void Report::open(const OutputOptions& output) {
  output_ = output;
  file_ = output_.path.empty() ? nullptr : &safe_output::open_pending(output_.path).stream();
}

Report& Report::parameter(const std::string& name, const std::optional<double>& value) {
  json_["parameters"][name] = optional_json(value);
  set_header(name, value ? number(*value) : "none");
  return *this;
}

Report& Report::parameter(const std::string& name, const std::optional<std::size_t>& value) {
  json_["parameters"][name] = optional_json(value);
  set_header(name, value ? std::to_string(*value) : "none");
  return *this;
}

Report& Report::parameter_left_out(const std::string& name) {
  json_["parameters"][name] = nullptr;
  set_header(name, "none");
  return *this;
}

void Report::set_header(const std::string& name, std::string text) {
  for (auto& [n, t] : header_)
    if (n == name) {
      t = std::move(text);
      return;
    }
  header_.emplace_back(name, std::move(text));
}

std::ostream& Report::stream() { return file_ ? *file_ : std::cout; }

void Report::write_header(std::ostream& out) const {
  out << "# chaos " << command_ << "\n";
  for (const auto& [name, value] : header_) out << "# " << name << " = " << value << "\n";
}

void Report::write_json(std::ostream& out) const { out << json_.dump(2) << "\n"; }

std::ostream* Report::open_table(const OutputOptions& output) {
  open(output);
  return begin_table();
}

std::ostream* Report::begin_table() {
  std::ostream& out = stream();
  if (json_mode()) {
    write_json(out);
    return nullptr;
  }
  write_header(out);
  return &out;
}

nlohmann::ordered_json interval_json(const std::optional<Interval>& i) {
  return i ? nlohmann::ordered_json::array({i->low, i->high}) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json estimate_json(const Estimate& e) {
  return {{"value", optional_json(e.value)}, {"interval", interval_json(e.interval)}, {"status", to_string(e.status)},
          {"reason", e.reason}};
}

std::string estimate_text(const Estimate& e, const std::string& per) {
  std::string text = e.value ? number(*e.value) : "none";
  if (e.value && e.interval)
    text += " in [" + number(e.interval->low) + ", " + number(e.interval->high) + "]" + (per.empty() ? "" : " per " + per);
  return text + " (" + to_string(e.status) + ")";
}

Norm parse_norm(const std::string& name) {
  if (name == "max") return Norm::max;
  if (name == "euclidean") return Norm::euclidean;
  throw InvalidInput(ErrorCode::invalid_parameter, "norm must be 'max' or 'euclidean' (got '" + name + "')");
}

void check_series(std::span<const double> x, const std::string& what) {
  require_finite(x, what);
  require_scale(x, what);
}

}  // namespace chaos::cli
