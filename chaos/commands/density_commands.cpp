// density: the computation and the JSON (commands.hpp).

#include <map>

#include "chaos/error.hpp"
#include "commands.hpp"
#include "report_parameters.hpp"

namespace chaos::cli {

void check_density_params(const DensityParams& a) {
  if (a.max_bins == 0) throw InvalidInput(ErrorCode::invalid_parameter, "density map: bins must be >= 1 (got --max-bins 0)");
  if (a.bandwidth && !a.kde) throw InvalidInput(ErrorCode::invalid_parameter, "--bandwidth applies to the kernel estimate: add --kde");
  if (a.low.has_value() != a.high.has_value()) throw InvalidInput(ErrorCode::invalid_parameter, "density map: give both --low and --high or neither");
}

DensityRun run_density(std::span<const double> parameter, std::span<const double> value, const std::string& file,
                       std::size_t parameter_column, std::size_t value_column, const DensityParams& a,
                       const OutputOptions& output) {
  check_density_params(a);
  if (parameter.size() != value.size())
    throw InvalidInput(ErrorCode::invalid_parameter, "density map: " + std::to_string(parameter.size()) +
                                                         " parameter values but " + std::to_string(value.size()) + " values");
  std::map<double, std::vector<double>> groups;  // ascending parameter values
  for (std::size_t i = 0; i < parameter.size(); ++i) groups[parameter[i]].push_back(value[i]);
  DensityRun run{{}, {}, {}, {}, Report("density", output)};
  for (auto& [p, v] : groups) {
    run.parameters.push_back(p);
    run.samples.push_back(std::move(v));
  }

  DensityMapOptions o;
  o.estimator = a.kde ? DensityEstimator::kernel : DensityEstimator::histogram;
  o.bin_rule = a.bins ? BinRule::fixed : BinRule::freedman_diaconis;
  o.bins = a.bins ? *a.bins : a.max_bins;
  o.low = a.low;
  o.high = a.high;
  o.padding = a.padding;
  o.bandwidth = a.bandwidth;
  run.map = density_map(run.parameters, run.samples, o);
  const DensityMap& m = run.map;
  run.method = a.kde ? "gaussian kernel, averaged over each bin" : "histogram";
  std::string rule;
  if (a.bins) rule = "fixed: " + std::to_string(*a.bins) + " bins (--bins)";
  else if (m.rule_bins) rule = "freedman-diaconis: width 2 IQR n^(-1/3) on the pooled values gives " + std::to_string(*m.rule_bins) + " bins" +
                               (*m.rule_bins > a.max_bins ? ", capped at --max-bins " + std::to_string(a.max_bins) : std::string());
  else rule = "freedman-diaconis: the pooled IQR is 0, so --max-bins " + std::to_string(a.max_bins);

  Report& report = run.report;
  report.parameter("file", file).parameter("parameter_column", parameter_column).parameter("value_column", value_column)
      .parameter("N", parameter.size()).parameter("parameters", run.parameters.size());
  report_parameters(report, a, density_parameters());
  report.parameter("method", run.method).parameter("bin_rule", rule).parameter("bins", m.centres.size())
      .parameter("low", m.edges.front()).parameter("high", m.edges.back())
      .parameter("range", std::string(a.low ? "given (--low, --high)" : "pooled min/max padded by " + number(a.padding) + " of the span on each side"));
  if (a.kde)
    report.parameter("bandwidth_rule", std::string(a.bandwidth ? "given (--bandwidth)"
                                                               : "Silverman: 0.9 min(s, IQR/1.34) n^(-1/5) per parameter value"));
  auto& j = report.json();
  j["parameter"] = m.parameters;
  j["bin_centre"] = m.centres;
  j["edges"] = m.edges;
  j["density"] = m.density;
  j["in_range"] = m.in_range;
  if (a.kde) {
    j["bandwidth"] = m.bandwidths;
    j["kernel_mass"] = m.kernel_mass;
  }
  return run;
}

}  // namespace chaos::cli
