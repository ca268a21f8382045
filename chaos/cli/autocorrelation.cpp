// chaos autocorrelation: r(k) by FFT, its first zero crossing and 1/e time.

#include <algorithm>

#include "chaos/autocorrelation.hpp"
#include "common.hpp"

namespace chaos::cli {

namespace {

struct AutocorrelationArgs {
  InputOptions input;
  OutputOptions output;
  std::optional<std::size_t> max_lag;
};

void run(const AutocorrelationArgs& args) {
  const Series series = load_series(args.input);
  const std::size_t n = series.values.size();
  // Default: a tenth of the series, at most 1000 lags, at least 1.
  const std::size_t max_lag = args.max_lag.value_or(std::max<std::size_t>(1, std::min<std::size_t>(1000, n / 10)));
  const AutocorrelationResult result = autocorrelation(series.values, max_lag);
  const auto zero = first_zero_crossing(result);
  const auto decay = decorrelation_time(result);

  Report report("autocorrelation", args.output);
  report.parameter("file", args.input.file).parameter("column", series.column).parameter("N", n)
      .parameter("dt", series.dt).parameter("max_lag", max_lag);
  std::ostream& out = report.stream();
  const double dt = series.dt.value_or(1.0);
  if (report.json_mode()) {
    auto& j = report.json();
    std::vector<std::size_t> lags(result.correlation.size());
    for (std::size_t k = 0; k < lags.size(); ++k) lags[k] = k;
    j["lag"] = lags;
    j["autocorrelation"] = result.correlation;
    j["first_zero_crossing"] = optional_json(zero);
    j["decorrelation_time"] = optional_json(decay);
    if (series.dt) j["decorrelation_time_units"] = decay ? nlohmann::ordered_json(*decay * dt) : nullptr;
    report.write_json(out);
    return;
  }
  report.write_header(out);
  out << "# first_zero_crossing = " << (zero ? std::to_string(*zero) : "none within the range") << "\n";
  out << "# decorrelation_time (1/e, samples) = " << (decay ? number(*decay) : "none within the range") << "\n";
  out << "# lag\tautocorrelation\n";
  for (std::size_t k = 0; k < result.correlation.size(); ++k) out << k << "\t" << number(result.correlation[k]) << "\n";
}

}  // namespace

void register_autocorrelation(CLI::App& app) {
  auto args = std::make_shared<AutocorrelationArgs>();
  CLI::App* command = app.add_subcommand("autocorrelation", "autocorrelation r(k), first zero crossing and 1/e time");
  add_input_options(*command, args->input);
  command->add_option("-D,--max-lag", args->max_lag, "largest lag (default N/10, at most 1000)");
  add_output_options(*command, args->output);
  command->callback([args] { run(*args); });
}

}  // namespace chaos::cli
