// chaos section: a Poincaré section of a multi-column series: every PERIOD-th row from a phase
// (stroboscopic), or the crossings of one column through a level with every column interpolated
// on the cubic through four rows and the return times (hyperplane).

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string_view>

#include "chaos/error.hpp"
#include "chaos/poincare.hpp"
#include "chaos/section_stream.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct SectionArgs {
  std::string file = "-";
  std::vector<std::size_t> columns;  // empty: every column of the first data row (less the time column)
  std::size_t skip = 0;
  std::optional<std::size_t> length;
  double dt = 1.0;
  std::optional<std::size_t> time_column;
  std::optional<std::size_t> period;
  std::size_t phase = 0;
  std::optional<std::size_t> hyperplane;
  std::optional<double> level;
  std::string direction = "up";
  OutputOptions output;
};

CrossingDirection parse_direction(const std::string& name) {
  if (name == "up") return CrossingDirection::upward;
  if (name == "down") return CrossingDirection::downward;
  if (name == "both") return CrossingDirection::both;
  throw InvalidInput(ErrorCode::invalid_parameter, "direction must be up, down or both (got '" + name + "')");
}

std::vector<double> read_column(const std::string& text, const std::string& name, std::size_t column, const SectionArgs& a) {
  ReadOptions o;
  o.column = column;
  o.skip = a.skip;
  if (a.length) o.length = *a.length;
  std::istringstream in(text);
  return read_series(in, name, o).values;
}

void run(SectionArgs& a) {
  if (a.period.has_value() == a.hyperplane.has_value()) {
    throw InvalidInput(ErrorCode::invalid_parameter, "choose one section: --stroboscopic PERIOD or --hyperplane COLUMN --level C");
  }
  if (a.hyperplane && !a.level) throw InvalidInput(ErrorCode::invalid_parameter, "--hyperplane needs --level C (the plane is column = C)");
  if (!(a.dt > 0.0) || !std::isfinite(a.dt)) throw InvalidInput(ErrorCode::invalid_parameter, "dt must be finite and > 0 (got " + number(a.dt) + ")");
  const CrossingDirection direction = parse_direction(a.direction);
  // The whole input, read once, so that several columns can be taken from standard input.
  const std::string text = read_text(a.file), name = a.file == "-" ? "<stdin>" : a.file;
  if (a.columns.empty()) {
    std::istringstream in(text);
    const std::size_t n = count_columns(in);
    for (std::size_t c = 1; c <= n; ++c) {
      if (c != a.time_column) a.columns.push_back(c);
    }
    if (a.columns.empty()) throw InvalidInput(ErrorCode::empty, name + ": no data columns" + (n == 0 ? " (no data rows)" : " besides the time column"));
  }
  std::vector<std::vector<double>> data;
  for (std::size_t c : a.columns) data.push_back(read_column(text, name, c, a));
  const std::size_t n = data.front().size();
  std::vector<double> times(n);
  if (a.time_column) {
    times = read_column(text, name, *a.time_column, a);
  } else {
    for (std::size_t i = 0; i < n; ++i) times[i] = static_cast<double>(i) * a.dt;
  }

  std::vector<double> section_times, return_times;
  std::vector<std::vector<double>> points;
  std::vector<bool> has_return;
  std::size_t plane = 0;
  if (a.period) {
    if (*a.period == 0) throw InvalidInput(ErrorCode::invalid_parameter, "the stroboscopic period must be >= 1 row (got 0)");
    if (a.phase >= *a.period) {
      throw InvalidInput(ErrorCode::invalid_parameter, "the phase (" + std::to_string(a.phase) + ") must be below the period (" +
                                                           std::to_string(*a.period) + " rows)");
    }
    section_times = stroboscopic_section(times, *a.period, a.phase);
    std::vector<std::vector<double>> columns;
    for (const auto& x : data) columns.push_back(stroboscopic_section(x, *a.period, a.phase));
    for (std::size_t j = 0; j < section_times.size(); ++j) {
      std::vector<double> p;
      for (const auto& c : columns) p.push_back(c[j]);
      points.push_back(std::move(p));
    }
  } else {
    const auto it = std::find(a.columns.begin(), a.columns.end(), *a.hyperplane);
    if (it == a.columns.end()) {
      throw InvalidInput(ErrorCode::invalid_parameter, "the hyperplane column " + std::to_string(*a.hyperplane) +
                                                           " is not among the columns read (-c); add it there");
    }
    plane = static_cast<std::size_t>(it - a.columns.begin());
    HyperplaneOptions o;
    o.component = plane;
    o.level = *a.level;
    o.direction = direction;
    // The streaming detector: the same cubic as hyperplane_section, and it accepts a time column
    // with uneven steps (an adaptive integrator's output).
    HyperplaneCrossingDetector detector(data.size(), o);
    std::vector<double> row(data.size());
    auto keep = [&](const std::optional<SectionPoint>& s) {
      if (!s) return;
      section_times.push_back(s->time);
      points.push_back(s->point);
      has_return.push_back(s->return_time.has_value());
      return_times.push_back(s->return_time.value_or(0.0));
    };
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < data.size(); ++k) row[k] = data[k][i];
      keep(detector.push(times[i], row));
    }
    keep(detector.finish());
  }

  Report report("section", a.output);
  std::string column_list;
  for (std::size_t c : a.columns) column_list += (column_list.empty() ? "" : ",") + std::to_string(c);
  report.parameter("file", a.file).parameter("columns", column_list).parameter("N", n);
  if (a.time_column) report.parameter("time_column", *a.time_column);
  else report.parameter("dt", a.dt);
  if (a.period) {
    report.parameter("section", std::string("stroboscopic")).parameter("period", *a.period).parameter("phase", a.phase);
  } else {
    report.parameter("section", std::string("hyperplane")).parameter("hyperplane_column", *a.hyperplane).parameter("level", *a.level)
        .parameter("direction", a.direction).parameter("interpolation", std::string("cubic through 4 rows (linear in the first and last interval)"));
  }
  report.parameter("points", section_times.size());
  std::ostream& out = report.stream();
  if (report.json_mode()) {
    auto& j = report.json();
    j["time"] = section_times;
    j["points"] = points;
    if (a.hyperplane) {
      nlohmann::ordered_json r = nlohmann::ordered_json::array();
      for (std::size_t k = 0; k < return_times.size(); ++k) r.push_back(has_return[k] ? nlohmann::ordered_json(return_times[k]) : nullptr);
      j["return_time"] = r;
    }
    report.write_json(out);
    return;
  }
  report.write_header(out);
  if (a.hyperplane) out << "# return_time: since the previous crossing; none for the first\n";
  out << "# time";
  for (std::size_t c : a.columns) out << "\tcolumn_" << c;
  if (a.hyperplane) out << "\treturn_time";
  out << "\n";
  for (std::size_t j = 0; j < section_times.size(); ++j) {
    out << number(section_times[j]);
    for (double v : points[j]) out << "\t" << number(v);
    if (a.hyperplane) out << "\t" << (has_return[j] ? number(return_times[j]) : std::string("none"));
    out << "\n";
  }
}

}  // namespace

void register_section(CLI::App& app) {
  auto a = std::make_shared<SectionArgs>();
  CLI::App* command = app.add_subcommand("section", "Poincaré section: stroboscopic (every PERIOD-th row) or hyperplane crossings with return times");
  command->add_option("file", a->file, "input file, columns separated by blanks, tabs or commas; - for stdin")->capture_default_str();
  command->add_option("-c,--columns", a->columns, "columns to read, 1-based, comma separated (default: every column but the time column)")
      ->delimiter(',');
  command->add_option("-x,--skip", a->skip, "data rows to skip at the start")->capture_default_str();
  command->add_option("-l,--length", a->length, "data rows to use after the skip (default: all)");
  command->add_option("--dt", a->dt, "time between rows, when there is no time column")->capture_default_str();
  command->add_option("--time-column", a->time_column, "column holding the time (increasing; steps may be uneven)");
  auto* strobe = command->add_option("--stroboscopic", a->period, "stroboscopic section: every PERIOD-th row");
  command->add_option("--phase", a->phase, "stroboscopic: the first row taken, 0 <= K < PERIOD")->capture_default_str();
  auto* plane = command->add_option("--hyperplane", a->hyperplane, "hyperplane section: crossings of this column (1-based)");
  command->add_option("--level", a->level, "hyperplane: the plane is column = C");
  command->add_option("--direction", a->direction, "hyperplane: up, down or both")->capture_default_str();
  strobe->excludes(plane);
  add_output_options(*command, a->output);
  command->callback([a] { run(*a); });
}

}  // namespace chaos::cli
