// zoo --series: a case's series and the JSON (commands.hpp).

#include "chaos/error.hpp"
#include "chaos/zoo_suite.hpp"
#include "commands.hpp"

namespace chaos::cli {

ZooSeriesRun run_zoo_series(const ZooSeriesParams& params, const OutputOptions& output) {
  if (params.threads == 0) throw InvalidInput(ErrorCode::invalid_parameter, "zoo: --threads must be at least 1 (got 0)");
  ZooSuiteOptions options;
  options.fast = params.fast;
  options.only = {params.name};
  options.threads = params.threads;
  const std::vector<ZooCase> cases = zoo_cases(options);
  if (cases.empty())
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "zoo: no case is named '" + params.name + "' (the names are the first column of docs/zoo.md)");
  const ZooCase& c = cases.front();
  std::vector<double> x = c.series(c.length);
  Report report("zoo", output);
  report.parameter("case", c.name).parameter("kind", std::string(to_string(c.kind))).parameter("description", c.description)
      .parameter("N", x.size()).parameter("dt", c.dt);
  report.json()["x"] = x;
  return {std::move(x), std::move(report)};
}

}  // namespace chaos::cli
