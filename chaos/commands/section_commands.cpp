// section: the computation and the JSON (commands.hpp).

#include <algorithm>
#include <cmath>
#include <sstream>

#include "chaos/error.hpp"
#include "chaos/poincare.hpp"
#include "chaos/section_stream.hpp"
#include "commands.hpp"
#include "report_parameters.hpp"

namespace chaos::cli {

namespace {

CrossingDirection parse_direction(const std::string& name) {
  if (name == "up") return CrossingDirection::upward;
  if (name == "down") return CrossingDirection::downward;
  if (name == "both") return CrossingDirection::both;
  throw InvalidInput(ErrorCode::invalid_parameter, "direction must be up, down or both (got '" + name + "')");
}

std::vector<double> read_column(const std::string& text, const std::string& name, std::size_t column, std::size_t skip,
                                std::optional<std::size_t> length) {
  ReadOptions o;
  o.column = column;
  o.skip = skip;
  if (length) o.length = *length;
  std::istringstream in(text);
  return read_series(in, name, o).values;
}

}  // namespace

void check_section_params(const SectionParams& p) {
  if (p.period.has_value() == p.hyperplane.has_value()) {
    throw InvalidInput(ErrorCode::invalid_parameter, "choose one section: --stroboscopic PERIOD or --hyperplane COLUMN --level C");
  }
  if (p.hyperplane && !p.level) throw InvalidInput(ErrorCode::invalid_parameter, "--hyperplane needs --level C (the plane is column = C)");
  if (!(p.dt > 0.0) || !std::isfinite(p.dt)) throw InvalidInput(ErrorCode::invalid_parameter, "dt must be finite and > 0 (got " + number(p.dt) + ")");
  (void)parse_direction(p.direction);
}

SectionColumns read_section_columns(const std::string& text, const std::string& name, SectionParams& params,
                                    std::size_t skip, std::optional<std::size_t> length) {
  if (params.columns.empty()) {
    std::istringstream in(text);
    const std::size_t n = count_columns(in);
    for (std::size_t c = 1; c <= n; ++c) {
      if (c != params.time_column) params.columns.push_back(c);
    }
    if (params.columns.empty()) throw InvalidInput(ErrorCode::empty, name + ": no data columns" + (n == 0 ? " (no data rows)" : " besides the time column"));
  }
  SectionColumns out;
  for (std::size_t c : params.columns) out.columns.push_back(read_column(text, name, c, skip, length));
  if (params.time_column) out.times = read_column(text, name, *params.time_column, skip, length);
  return out;
}

SectionRun run_section(const std::vector<std::span<const double>>& data, std::span<const double> given_times,
                       const std::string& file, const SectionParams& params, const OutputOptions& output) {
  check_section_params(params);
  if (data.empty() || data.size() != params.columns.size())
    throw InvalidInput(ErrorCode::invalid_parameter, "section: one data column per column read (" +
                                                         std::to_string(params.columns.size()) + " named, " +
                                                         std::to_string(data.size()) + " given)");
  const CrossingDirection direction = parse_direction(params.direction);
  const std::size_t n = data.front().size();
  std::vector<double> times(n);
  if (params.time_column) {
    if (given_times.size() != n) throw InvalidInput(ErrorCode::invalid_parameter, "section: the time column must have one value per row");
    std::copy(given_times.begin(), given_times.end(), times.begin());
  } else {
    for (std::size_t i = 0; i < n; ++i) times[i] = static_cast<double>(i) * params.dt;
  }

  std::vector<double> section_times;
  std::vector<std::vector<double>> points;
  std::vector<std::optional<double>> return_times;
  if (params.period) {
    if (*params.period == 0) throw InvalidInput(ErrorCode::invalid_parameter, "the stroboscopic period must be >= 1 row (got 0)");
    if (params.phase >= *params.period) {
      throw InvalidInput(ErrorCode::invalid_parameter, "the phase (" + std::to_string(params.phase) + ") must be below the period (" +
                                                           std::to_string(*params.period) + " rows)");
    }
    section_times = stroboscopic_section(times, *params.period, params.phase);
    std::vector<std::vector<double>> columns;
    for (const auto& x : data) columns.push_back(stroboscopic_section(x, *params.period, params.phase));
    for (std::size_t j = 0; j < section_times.size(); ++j) {
      std::vector<double> p;
      for (const auto& c : columns) p.push_back(c[j]);
      points.push_back(std::move(p));
    }
  } else {
    const auto it = std::find(params.columns.begin(), params.columns.end(), *params.hyperplane);
    if (it == params.columns.end()) {
      throw InvalidInput(ErrorCode::invalid_parameter, "the hyperplane column " + std::to_string(*params.hyperplane) +
                                                           " is not among the columns read (-c); add it there");
    }
    HyperplaneOptions o;
    o.component = static_cast<std::size_t>(it - params.columns.begin());
    o.level = *params.level;
    o.direction = direction;
    // The streaming detector: the same cubic as hyperplane_section, and it accepts a time column
    // with uneven steps (an adaptive integrator's output).
    HyperplaneCrossingDetector detector(data.size(), o);
    std::vector<double> row(data.size());
    auto keep = [&](const std::optional<SectionPoint>& s) {
      if (!s) return;
      section_times.push_back(s->time);
      points.push_back(s->point);
      return_times.push_back(s->return_time);
    };
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < data.size(); ++k) row[k] = data[k][i];
      keep(detector.push(times[i], row));
    }
    keep(detector.finish());
  }

  Report report("section", output);
  report.parameter("file", file);
  report_parameters(report, params, section_parameters());
  report.parameter("N", n).parameter("section", std::string(params.period ? "stroboscopic" : "hyperplane"));
  if (!params.period)
    report.parameter("interpolation", std::string("cubic through 4 rows (linear in the first and last interval)"));
  report.parameter("points", section_times.size());
  auto& j = report.json();
  j["time"] = section_times;
  j["points"] = points;
  if (params.hyperplane) {
    nlohmann::ordered_json r = nlohmann::ordered_json::array();
    for (const auto& t : return_times) r.push_back(optional_json(t));
    j["return_time"] = r;
  }
  return {std::move(section_times), std::move(points), std::move(return_times), n, std::move(report)};
}

}  // namespace chaos::cli
