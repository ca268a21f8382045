#include "chaos/models/validation.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

#include "numeric.hpp"

#include "chaos/cao.hpp"
#include "chaos/choose.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/error.hpp"
#include "chaos/fnn.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/models/lyapunov_spectrum.hpp"
#include "chaos/mutual_information.hpp"
#include "chaos/time_scales.hpp"

namespace chaos {

namespace {

const char kReferenceTable[] =
#include "reference_table.inc"
    ;

std::vector<std::string> split(std::string_view text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    parts.emplace_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return parts;
}

double parse_number(const std::string& token, const std::string& where) {
  if (token == "inf") return std::numeric_limits<double>::infinity();
  if (token == "-inf") return -std::numeric_limits<double>::infinity();
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(token, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != token.size())
    throw InvalidInput(ErrorCode::parse, where + ": '" + token + "' is not a number");
  return value;
}

// "key=value;key=value" -> map; an empty field or "-" is an empty map.
std::map<std::string, std::string> parse_pairs(const std::string& field, const std::string& where) {
  std::map<std::string, std::string> out;
  if (field.empty() || field == "-") return out;
  for (const auto& item : split(field, ';')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InvalidInput(ErrorCode::parse, where + ": '" + item + "' is not of the form key=value");
    out[item.substr(0, eq)] = item.substr(eq + 1);
  }
  return out;
}

struct Conditions {
  const Reference& ref;
  std::string text(const std::string& key, const std::string& fallback) const {
    const auto it = ref.conditions.find(key);
    return it == ref.conditions.end() ? fallback : it->second;
  }
  std::size_t count(const std::string& key, std::size_t fallback) const {
    const auto it = ref.conditions.find(key);
    if (it == ref.conditions.end()) return fallback;
    const double v = parse_number(it->second, ref.id + ": condition " + key);
    if (v < 0 || v != std::floor(v))
      throw InvalidInput(ErrorCode::parse, ref.id + ": condition " + key + " must be a whole number");
    return static_cast<std::size_t>(v);
  }
  // "lo..hi" ranges, used for the embedding dimensions.
  std::pair<std::size_t, std::size_t> range(const std::string& key, std::size_t lo, std::size_t hi) const {
    const auto it = ref.conditions.find(key);
    if (it == ref.conditions.end()) return {lo, hi};
    const auto dots = it->second.find("..");
    if (dots == std::string::npos) {
      const std::size_t v = count(key, lo);
      return {v, v};
    }
    return {static_cast<std::size_t>(parse_number(it->second.substr(0, dots), ref.id)),
            static_cast<std::size_t>(parse_number(it->second.substr(dots + 2), ref.id))};
  }
};

std::vector<double> make_series(const Reference& ref, const Conditions& c) {
  const auto system = system_from_name(ref.system);
  if (!system) throw InvalidInput(ErrorCode::parse, ref.id + ": unknown system '" + ref.system + "'");
  GenerateRequest request;
  request.system = *system;
  request.length = c.count("N", 10000);
  request.parameters = ref.parameters;
  request.seed = c.count("seed", 1);
  Trajectory trajectory = generate(request);
  for (std::size_t k = 0; k < trajectory.names.size(); ++k) {
    if (trajectory.names[k] != ref.component) continue;
    std::vector<double> x = std::move(trajectory.components[k]);
    // Quantisation on request, to test the tie rules: values rounded to multiples of `quantum`.
    if (const auto quantum = c.text("quantum", ""); !quantum.empty()) {
      const double q = parse_number(quantum, ref.id + ": condition quantum");
      for (double& v : x) v = q * std::round(v / q);
    }
    return x;
  }
  throw InvalidInput(ErrorCode::parse, ref.id + ": system " + ref.system + " has no component '" + ref.component + "'");
}

// The delay: a number of samples, or "mi" for the automatic delay (choose_delay: the first
// mutual-information minimum within 100 samples, or the rule that stands in for it), the way a user
// without a hand-picked delay gets it.
std::size_t delay_of(const Conditions& c, const std::vector<double>& x) {
  if (c.text("tau", "") != "mi") return c.count("tau", 1);
  const DelayChoice choice = choose_delay(x, time_scales(x));
  if (!choice.delay) throw InvalidInput(ErrorCode::invalid_parameter, c.ref.id + ": " + choice.stopped);
  return *choice.delay;
}

std::string describe(const std::optional<std::size_t>& v, const char* none) {
  return v ? std::to_string(*v) : std::string(none);
}

// Spectra from the equations: no series; the row's parameters are the model parameters and the
// conditions the integration settings (time, step, interval, transient for flows; iterations,
// interval, transient for maps).
void validate_spectrum(const Reference& ref, const Conditions& c, ValidationResult& result, std::ostringstream& text) {
  const auto system = system_from_name(ref.system);
  if (!system) throw InvalidInput(ErrorCode::parse, ref.id + ": unknown system '" + ref.system + "'");
  SpectrumRequest request;
  request.system = *system;
  request.parameters = ref.parameters;
  request.seed = c.count("seed", 1);
  const auto real = [&](const char* key, double fallback) {
    const std::string value = c.text(key, "");
    return value.empty() ? fallback : parse_number(value, ref.id + ": condition " + key);
  };
  if (is_flow(*system)) {
    request.flow.step = real("step", request.flow.step);
    request.flow.renormalisation_interval = real("interval", request.flow.renormalisation_interval);
    request.flow.transient = real("transient", request.flow.transient);
    request.flow.time = real("time", request.flow.time);
  } else {
    request.map.renormalisation_interval = c.count("interval", request.map.renormalisation_interval);
    request.map.transient = c.count("transient", request.map.transient);
    request.map.iterations = c.count("iterations", request.map.iterations);
  }
  const LyapunovSpectrum s = spectrum(request);
  text << "exponents";
  for (const double e : s.exponents) text << " " << detail::format_number(e);
  text << ", sum " << detail::format_number(s.sum) << ", D_KY " << s.kaplan_yorke_dimension << " over "
         << s.averaging_length << (is_flow(*system) ? " time units" : " iterations");
  if (ref.quantity == "lyapunov_spectrum.exponent") {
    const std::size_t index = c.count("index", 1);
    if (index < 1 || index > s.exponents.size())
      throw InvalidInput(ErrorCode::parse, ref.id + ": condition index must be 1.." + std::to_string(s.exponents.size()));
    result.measured = s.exponents[index - 1];
  } else if (ref.quantity == "lyapunov_spectrum.sum") {
    result.measured = s.sum;
  } else if (ref.quantity == "lyapunov_spectrum.kaplan_yorke_dimension") {
    result.measured = s.kaplan_yorke_dimension;
  } else {
    throw InvalidInput(ErrorCode::parse, ref.id + ": unknown quantity " + ref.quantity);
  }
}

// The largest exponent from the series: conditions method (rosenstein | kantz), tau, m, w, steps,
// eps (Kantz; default range/1000), references (0: all). Per time unit when the row samples a flow
// (its parameters give dt), per iteration otherwise.
void validate_lyapunov(const Reference& ref, const Conditions& c, const std::vector<double>& x, ValidationResult& result,
                       std::ostringstream& text) {
  LyapunovOptions options;
  const std::string method = c.text("method", "rosenstein");
  if (method == "kantz") options.method = LyapunovMethod::kantz;
  else if (method != "rosenstein") throw InvalidInput(ErrorCode::parse, ref.id + ": unknown method " + method);
  options.delay = delay_of(c, x);
  options.dimension = c.count("m", options.dimension);
  options.theiler = c.count("w", 0);
  options.steps = c.count("steps", options.steps);
  options.reference_points = c.count("references", 0);
  if (const std::string eps = c.text("eps", ""); !eps.empty()) options.radius = parse_number(eps, ref.id + ": condition eps");
  std::optional<double> dt;
  if (const auto it = ref.parameters.find("dt"); it != ref.parameters.end()) dt = it->second;
  const LyapunovResult r = largest_lyapunov(x, options, {}, dt);
  text << method << ", tau = " << options.delay << ", status " << to_string(r.fit.status);
  if (r.fit.lambda)
    text << ", lambda = " << *r.fit.lambda << " per sample in [" << r.fit.lambda_interval->low << ", "
           << r.fit.lambda_interval->high << "] over steps " << *r.fit.first_step << ".." << *r.fit.last_step;
  if (r.lambda_per_time) text << ", " << *r.lambda_per_time << " per time unit";
  text << ": " << r.fit.explanation;
  if (ref.quantity == "lyapunov.lambda") {
    result.measured = dt ? r.lambda_per_time : r.fit.lambda;
  } else if (ref.quantity == "lyapunov.no_linear_region") {
    result.measured = r.fit.lambda ? 0.0 : 1.0;
  } else {
    throw InvalidInput(ErrorCode::parse, ref.id + ": unknown quantity " + ref.quantity);
  }
}

}  // namespace

std::vector<Reference> parse_reference_table(std::string_view text, const std::string& origin) {
  static const std::vector<std::string> kColumns{"id", "system", "parameters", "component", "quantity", "value",
                                                 "low", "high", "conditions", "source", "kind", "note"};
  std::vector<Reference> table;
  std::size_t line_number = 0;
  bool header_seen = false;
  for (const auto& raw : split(text, '\n')) {
    ++line_number;
    const std::string where = origin + ":" + std::to_string(line_number);
    if (raw.empty() || raw.front() == '#') continue;
    auto fields = split(raw, '\t');
    if (!header_seen) {
      if (fields != kColumns) throw InvalidInput(ErrorCode::parse, where + ": header must be the columns id..note");
      header_seen = true;
      continue;
    }
    if (fields.size() != kColumns.size())
      throw InvalidInput(ErrorCode::parse, where + ": expected " + std::to_string(kColumns.size()) + " tab-separated fields, got " +
                                               std::to_string(fields.size()));
    Reference r;
    r.id = fields[0];
    r.system = fields[1];
    for (const auto& [key, value] : parse_pairs(fields[2], where)) r.parameters[key] = parse_number(value, where + " " + key);
    r.component = fields[3];
    r.quantity = fields[4];
    if (fields[5] != "-") r.value = parse_number(fields[5], where + " value");
    r.low = parse_number(fields[6], where + " low");
    r.high = parse_number(fields[7], where + " high");
    if (!(r.low <= r.high)) throw InvalidInput(ErrorCode::parse, where + ": band low > high");
    r.conditions = parse_pairs(fields[8], where);
    r.source = fields[9];
    r.kind = fields[10];
    if (r.kind != "analytic" && r.kind != "literature" && r.kind != "peer-output")
      throw InvalidInput(ErrorCode::parse, where + ": kind must be analytic, literature or peer-output");
    r.note = fields[11];
    for (const auto& other : table)
      if (other.id == r.id) throw InvalidInput(ErrorCode::parse, where + ": duplicate id " + r.id);
    table.push_back(std::move(r));
  }
  return table;
}

const std::vector<Reference>& reference_table() {
  static const std::vector<Reference> table = parse_reference_table(kReferenceTable, "references/references.tsv");
  return table;
}

ValidationResult validate(const Reference& ref) {
  const auto start = std::chrono::steady_clock::now();
  ValidationResult result{ref, std::nullopt, false, "", 0.0};
  const Conditions c{ref};
  std::ostringstream detail;
  const auto finish = [&] {
    result.passed = result.measured && *result.measured >= ref.low && *result.measured <= ref.high;
    result.detail = detail.str();
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
  if (ref.quantity.rfind("lyapunov_spectrum.", 0) == 0) {
    validate_spectrum(ref, c, result, detail);
    return finish();
  }
  const std::vector<double> x = make_series(ref, c);

  if (ref.quantity.rfind("lyapunov.", 0) == 0) {
    validate_lyapunov(ref, c, x, result, detail);
  } else if (ref.quantity == "mutual_information.first_minimum") {
    MutualInformationOptions options;
    options.boxes = c.count("boxes", options.boxes);
    options.max_delay = c.count("max_delay", options.max_delay);
    const std::string estimator = c.text("estimator", "equal_width");
    if (estimator == "equiprobable") options.estimator = MutualInformationEstimator::equiprobable;
    else if (estimator != "equal_width") throw InvalidInput(ErrorCode::parse, ref.id + ": unknown estimator " + estimator);
    const auto minimum = first_minimum(mutual_information(x, options));
    if (minimum) result.measured = static_cast<double>(*minimum);
    detail << "first minimum of I(tau): " << describe(minimum, "none within the range");
  } else if (ref.quantity.rfind("cao.", 0) == 0) {
    CaoOptions options;
    options.delay = delay_of(c, x);
    options.theiler = c.count("w", 0);
    std::tie(options.min_dimension, options.max_dimension) = c.range("m", 1, 10);
    const CaoResult cao_result = cao(x, options);
    if (ref.quantity == "cao.embedding_dimension") {
      if (cao_result.embedding_dimension) result.measured = static_cast<double>(*cao_result.embedding_dimension);
      detail << "E1 saturates at m = " << describe(cao_result.embedding_dimension, "none (not saturated)");
    } else if (ref.quantity == "cao.max_E2_deviation") {
      result.measured = cao_result.max_E2_deviation;
      detail << "max |E2(m) - 1| over m = " << options.min_dimension << ".." << options.max_dimension << ": "
             << cao_result.max_E2_deviation;
    } else if (ref.quantity == "cao.stochastic") {
      result.measured = cao_result.stochastic ? 1.0 : 0.0;
      detail << (cao_result.stochastic ? "every |E2(m) - 1| within " : "some |E2(m) - 1| beyond ") << options.stochastic_sigmas
             << " standard errors";
    } else if (ref.quantity == "cao.all_finite") {
      bool finite = true;
      for (std::size_t k = 0; k < cao_result.E1.size(); ++k)
        finite = finite && std::isfinite(cao_result.E1[k]) && std::isfinite(cao_result.E2[k]);
      result.measured = finite ? 1.0 : 0.0;
      detail << (finite ? "every E1(m) and E2(m) finite" : "a non-finite E1 or E2");
    } else {
      throw InvalidInput(ErrorCode::parse, ref.id + ": unknown quantity " + ref.quantity);
    }
  } else if (ref.quantity.rfind("d2", 0) == 0) {
    CorrelationSumOptions options;
    options.delay = delay_of(c, x);
    options.theiler = c.count("w", 0);
    std::tie(options.min_dimension, options.max_dimension) = c.range("m", 1, 10);
    options.radii = log_radii(parse_number(c.text("r", ""), ref.id + ": condition r"),
                              parse_number(c.text("R", ""), ref.id + ": condition R"), c.count("radii", 40));
    const CorrelationDimensionResult d2 = correlation_dimension(correlation_sum(x, options));
    if (ref.quantity == "d2") {
      result.measured = d2.d2;
      detail << "tau = " << options.delay << ", status " << to_string(d2.status);
      if (d2.d2) detail << ", D2 = " << *d2.d2 << " in [" << d2.d2_interval->low << ", " << d2.d2_interval->high
                        << "], region eps in [" << d2.scaling_region->low << ", " << d2.scaling_region->high << "]";
      detail << ": " << d2.explanation;
    } else if (ref.quantity == "d2.at_dimension") {
      const std::size_t at = c.count("at", options.max_dimension);
      for (std::size_t k = 0; k < d2.dimension.size(); ++k)
        if (d2.dimension[k] == at) result.measured = d2.d2_by_dimension[k];
      detail << "D2(m = " << at << ") over its own scaling region";
    } else if (ref.quantity == "d2.not_saturated") {
      result.measured = d2.status == D2Status::not_saturated ? 1.0 : 0.0;
      detail << "status " << to_string(d2.status) << ": " << d2.explanation;
    } else {
      throw InvalidInput(ErrorCode::parse, ref.id + ": unknown quantity " + ref.quantity);
    }
  } else if (ref.quantity == "fnn.embedding_dimension") {
    FnnOptions options;
    options.delay = c.count("tau", 1);
    options.theiler = c.count("w", 0);
    std::tie(options.min_dimension, options.max_dimension) = c.range("m", 1, 10);
    const FnnResult fnn = false_nearest_neighbors(x, options);
    if (fnn.embedding_dimension) result.measured = static_cast<double>(*fnn.embedding_dimension);
    detail << "false fraction falls to " << options.threshold << " at m = "
           << describe(fnn.embedding_dimension, "none within the range");
  } else {
    throw InvalidInput(ErrorCode::parse, ref.id + ": unknown quantity " + ref.quantity);
  }

  return finish();
}

}  // namespace chaos
