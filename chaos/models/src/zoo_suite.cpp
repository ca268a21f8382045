#include "chaos/models/zoo_suite.hpp"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <map>
#include <utility>
#include <chrono>
#include <numbers>
#include <cmath>

#include "chaos/automatic_analysis.hpp"
#include "chaos/d2_answer.hpp"
#include "chaos/detail/parallel.hpp"
#include "chaos/format.hpp"
#include "chaos/lyapunov_answer.hpp"
#include "chaos/lyapunov_local_maps.hpp"
#include "chaos/models/control_signals.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/error.hpp"
#include "chaos/surrogates.hpp"
#include "chaos/models/systems.hpp"
#include "chaos/models/zoo.hpp"
#include "chaos/models/zoo_state_d2.hpp"

namespace chaos {

const char* to_string(ZooCaseKind kind) noexcept {
  switch (kind) {
    case ZooCaseKind::chaotic: return "chaotic";
    case ZooCaseKind::noise: return "noise";
    case ZooCaseKind::surrogate: return "surrogate";
    case ZooCaseKind::random_walk: return "random_walk";
    case ZooCaseKind::periodic: return "periodic";
    case ZooCaseKind::quasi_periodic: return "quasi_periodic";
    case ZooCaseKind::noisy_chaos: return "noisy_chaos";
    case ZooCaseKind::quantised: return "quantised";
    case ZooCaseKind::short_series: return "short_series";
  }
  return "unknown";
}

const char* to_string(ZooVerdict verdict) noexcept {
  switch (verdict) {
    case ZooVerdict::in_band: return "in_band";
    case ZooVerdict::wrong: return "WRONG";
    case ZooVerdict::unsure: return "unsure";
  }
  return "unknown";
}

ZooVerdict judge(const std::optional<double>& value, bool confident, const ZooBand& band) {
  if (!confident || !value) return ZooVerdict::unsure;
  for (const auto& i : band.accepted)
    if (*value >= i.low && *value <= i.high) return ZooVerdict::in_band;
  return ZooVerdict::wrong;
}

namespace {

constexpr std::size_t full_length = 100000;
constexpr std::size_t fast_length = 10000;
constexpr std::size_t short_length = 500;

std::string fmt(double v) { return format_number(v, Precision::title); }

// The series of a zoo system: its default component at its default sampling.
std::function<std::vector<double>(std::size_t)> system_series(const ZooEntry& e) {
  return [&e](std::size_t n) { return zoo_trajectory(e, n).components[e.component]; };
}

struct ChaoticReference {
  ZooBand d2, lambda;
  double lambda_equations, kaplan_yorke;
};

// Bands fixed from the equations and the cited literature, before anything is estimated.
ChaoticReference reference_bands(const ZooEntry& e) {
  ChaoticReference r;
  const LyapunovSpectrum s = zoo_spectrum(e);
  r.lambda_equations = s.exponents.front();
  r.kaplan_yorke = s.kaplan_yorke_dimension;
  r.lambda.accepted = {Interval{0.9 * r.lambda_equations, 1.1 * r.lambda_equations}};
  r.lambda.source = "lambda_1 = " + fmt(r.lambda_equations) + " from the equations, +-10%";
  if (e.literature.d2 == e.literature.d2) {
    r.d2.accepted = {Interval{e.literature.d2 - 0.1, e.literature.d2 + 0.1}};
    r.d2.source = "D2 = " + fmt(e.literature.d2) + " (" + e.literature.source + "), +-0.1";
  } else {
    r.d2.accepted = {Interval{0.0, r.kaplan_yorke + 0.1}};
    r.d2.source = "no cited D2: not above D_KY + 0.1 = " + fmt(r.kaplan_yorke + 0.1);
  }
  return r;
}

ZooCase chaotic_case(const ZooEntry& e, const ChaoticReference& ref, std::size_t length) {
  ZooCase c;
  c.name = e.name;
  c.kind = ZooCaseKind::chaotic;
  c.system = e.name;
  c.description = e.citation;
  c.length = length;
  if (e.kind == ZooKind::flow) c.dt = e.dt;
  c.series = system_series(e);
  if (!e.delay) c.state = [&e](std::size_t n) { return zoo_state(e, n); };
  c.d2_band = ref.d2;
  c.lambda_band = ref.lambda;
  c.lambda_equations = ref.lambda_equations;
  c.kaplan_yorke = ref.kaplan_yorke;
  c.literature_lambda = e.literature.lambda1();
  c.literature_d2 = e.literature.d2;
  c.dysts_lambda = e.dysts.lambda1();
  c.dysts_d2 = e.dysts.d2;
  c.grid = true;
  return c;
}

ZooBand nothing_right(const std::string& why) { return ZooBand{{}, why}; }
ZooBand torus(std::initializer_list<double> dimensions, const std::string& why) {
  ZooBand b;
  for (const double d : dimensions) b.accepted.push_back(Interval{d - 0.1, d + 0.1});
  b.source = why;
  return b;
}

ZooCase control(std::string name, ZooCaseKind kind, std::string description, std::size_t length,
                std::function<std::vector<double>(std::size_t)> series, ZooBand d2, ZooBand lambda) {
  ZooCase c;
  c.name = std::move(name);
  c.kind = kind;
  c.description = std::move(description);
  c.length = length;
  c.series = std::move(series);
  c.d2_band = std::move(d2);
  c.lambda_band = std::move(lambda);
  return c;
}

// Chaos seen through a transformation (noise, quantisation, shortness): the clean system's bands.
ZooCase derived(const ZooCase& clean, std::string name, ZooCaseKind kind, std::string description, std::size_t length,
                std::function<std::vector<double>(std::vector<double>)> transform) {
  ZooCase c = clean;
  c.name = std::move(name);
  c.kind = kind;
  c.description = std::move(description);
  c.length = length;
  c.grid = false;
  const auto source = clean.series;
  c.series = [source, transform](std::size_t n) { return transform(source(n)); };
  return c;
}

}  // namespace

std::vector<ZooCase> zoo_cases(const ZooSuiteOptions& options) {
  const std::size_t length = options.fast ? fast_length : full_length;
  const std::vector<std::string> fast_systems = {"lorenz", "henon", "rossler", "logistic"};
  std::vector<ZooCase> cases;
  const auto wanted = [&](const std::string& name) {
    return options.only.empty() || std::find(options.only.begin(), options.only.end(), name) != options.only.end();
  };
  std::optional<ZooCase> lorenz, henon;
  std::vector<const ZooEntry*> entries;
  for (const ZooEntry& e : zoo_systems()) {
    const bool needed = e.name == "lorenz" || e.name == "henon";
    if (options.fast && std::find(fast_systems.begin(), fast_systems.end(), e.name) == fast_systems.end()) continue;
    if (wanted(e.name) || needed) entries.push_back(&e);
  }
  // The spectra behind the bands, one entry per task (each is deterministic on its own).
  std::vector<std::optional<ChaoticReference>> references(entries.size());
  // Each task's failure is kept by entry, so the one rethrown is the first entry's whatever the threads.
  std::vector<std::exception_ptr> failures(entries.size());
  detail::parallel_tasks(options.threads, entries.size(), [&](std::size_t k, std::size_t) {
    try {
      references[k] = reference_bands(*entries[k]);
    } catch (...) {
      failures[k] = std::current_exception();
    }
  });
  for (const auto& f : failures)
    if (f) std::rethrow_exception(f);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const ZooEntry& e = *entries[k];
    const ZooCase c = chaotic_case(e, *references[k], length);
    if (e.name == "lorenz") lorenz = c;
    if (e.name == "henon") henon = c;
    if (wanted(e.name)) cases.push_back(c);
  }

  const ZooBand no_d2 = nothing_right("no invariant: any confident D2 is wrong");
  const ZooBand no_lambda = nothing_right("no exponential divergence: any confident lambda_1 is wrong");
  std::vector<ZooCase> controls;
  controls.push_back(control("white_noise", ZooCaseKind::noise, "Gaussian white noise, seed 11", length,
                             [](std::size_t n) { return white_noise(n, 11).components[0]; }, no_d2, no_lambda));
  controls.push_back(control("random_walk", ZooCaseKind::random_walk, "cumulative Gaussian steps, seed 12", length,
                             [](std::size_t n) { return random_walk(n, 12).components[0]; }, no_d2, no_lambda));
  controls.push_back(control("periodic_rational", ZooCaseKind::periodic, "sine at a period of 317/3 samples (317 distinct points)",
                             length, [](std::size_t n) { return periodic(n, RationalPeriod{317, 3}).components[0]; },
                             torus({1.0}, "a closed curve: D2 = 1 +- 0.1"), no_lambda));
  controls.push_back(control("torus2", ZooCaseKind::quasi_periodic, "two incommensurate frequencies (control_signals.hpp)",
                             length, [](std::size_t n) { return two_torus(n).components[0]; },
                             torus({2.0}, "a 2-torus: D2 = 2 +- 0.1"), no_lambda));
  if (!options.fast) {
    controls.push_back(control("ar1", ZooCaseKind::noise, "AR(1), phi = 0.9, seed 13", length,
                               [](std::size_t n) { return ar1(n, 0.9, 13).components[0]; }, no_d2, no_lambda));
    controls.push_back(control("pink_noise", ZooCaseKind::noise, "1/f noise (Timmer & Koenig 1995), seed 14", length,
                               [](std::size_t n) { return power_law_noise(n, 1.0, 14).components[0]; }, no_d2, no_lambda));
    controls.push_back(control("brown_noise", ZooCaseKind::noise, "1/f^2 noise (Timmer & Koenig 1995), seed 15", length,
                               [](std::size_t n) { return power_law_noise(n, 2.0, 15).components[0]; }, no_d2, no_lambda));
    controls.push_back(control("periodic_integer", ZooCaseKind::periodic, "sine at a period of 25 samples", length,
                               [](std::size_t n) { return periodic(n, RationalPeriod{25, 1}).components[0]; },
                               torus({1.0}, "a closed curve: D2 = 1 +- 0.1"), no_lambda));
    controls.push_back(control("periodic_irrational", ZooCaseKind::periodic, "sine at a period of 25 phi samples", length,
                               [](std::size_t n) { return periodic(n, 25.0 * std::numbers::phi).components[0]; },
                               torus({1.0}, "a closed curve: D2 = 1 +- 0.1"), no_lambda));
    controls.push_back(control("torus3", ZooCaseKind::quasi_periodic, "three incommensurate frequencies", length,
                               [](std::size_t n) { return three_torus(n).components[0]; },
                               torus({3.0}, "a 3-torus: D2 = 3 +- 0.1"), no_lambda));
    controls.push_back(control("torus2_rational_first", ZooCaseKind::quasi_periodic,
                               "two frequencies, the first at a period of exactly 25 samples", length,
                               [](std::size_t n) { return two_torus_rational_first(n).components[0]; },
                               torus({1.0, 2.0}, "25 closed curves on a torus: D2 = 1 at small scales, 2 at large (+- 0.1)"),
                               no_lambda));
  }
  for (auto& c : controls)
    if (wanted(c.name)) cases.push_back(std::move(c));

  const auto surrogate = [](const ZooCase& clean, std::uint64_t seed) {
    ZooCase c = clean;
    c.name = clean.name + "_iaaft";
    c.kind = ZooCaseKind::surrogate;
    c.description = "IAAFT surrogate of " + clean.name + " (seed " + std::to_string(seed) + ")";
    c.grid = false;
    c.d2_band = nothing_right("a linear Gaussian process with the data's spectrum: any confident D2 is wrong");
    c.lambda_band = nothing_right("a linear stochastic process: any confident lambda_1 is wrong");
    const auto source = clean.series;
    c.series = [source, seed](std::size_t n) { return surrogates(source(n), 1, seed).front().values; };
    return c;
  };
  std::vector<ZooCase> more;
  if (lorenz) {
    more.push_back(derived(*lorenz, "lorenz_snr20", ZooCaseKind::noisy_chaos, "Lorenz x + Gaussian noise at 20 dB SNR",
                           length, [](std::vector<double> x) { return add_noise(x, 20.0, 21); }));
    if (!options.fast) {
      more.push_back(surrogate(*lorenz, 31));
      more.push_back(derived(*lorenz, "lorenz_snr10", ZooCaseKind::noisy_chaos, "Lorenz x + Gaussian noise at 10 dB SNR",
                             length, [](std::vector<double> x) { return add_noise(x, 10.0, 22); }));
      more.push_back(derived(*lorenz, "lorenz_quantised", ZooCaseKind::quantised, "Lorenz x rounded to 64 levels",
                             length, [](std::vector<double> x) { return quantise_levels(x, 64); }));
      more.push_back(derived(*lorenz, "lorenz_short", ZooCaseKind::short_series, "the first 500 samples of Lorenz x",
                             short_length, [](std::vector<double> x) { return x; }));
    }
  }
  if (henon && !options.fast) {
    more.push_back(surrogate(*henon, 32));
    more.push_back(derived(*henon, "henon_snr20", ZooCaseKind::noisy_chaos, "Henon x + Gaussian noise at 20 dB SNR",
                           length, [](std::vector<double> x) { return add_noise(x, 20.0, 23); }));
    more.push_back(derived(*henon, "henon_quantised", ZooCaseKind::quantised, "Henon x rounded to 64 levels", length,
                           [](std::vector<double> x) { return quantise_levels(x, 64); }));
    more.push_back(derived(*henon, "henon_short", ZooCaseKind::short_series, "the first 500 samples of Henon x",
                           short_length, [](std::vector<double> x) { return x; }));
  }
  for (auto& c : more)
    if (wanted(c.name)) cases.push_back(std::move(c));
  return cases;
}

namespace {

ZooEstimate d2_estimate(const CorrelationDimensionResult& r, const ZooBand& band) {
  ZooEstimate e;
  e.value = r.d2;
  e.interval = r.d2_interval;
  e.status = to_string(r.status);
  e.verdict = judge(r.d2, r.status == D2Status::saturated, band);
  return e;
}

// An answer (estimate.hpp) judged: confident values against the band.
ZooEstimate answer_estimate(const Estimate& a, const ZooBand& band) {
  ZooEstimate e;
  e.value = a.value;
  e.interval = a.interval;
  e.status = to_string(a.status);
  e.verdict = judge(a.value, a.status == EstimateStatus::confident, band);
  return e;
}

ZooEstimate lambda_estimate(const LyapunovFit& fit, std::optional<double> dt, const ZooBand& band) {
  ZooEstimate e;
  const double scale = dt.value_or(1.0);
  if (fit.lambda) e.value = *fit.lambda / scale;
  if (fit.lambda_interval) e.interval = Interval{fit.lambda_interval->low / scale, fit.lambda_interval->high / scale};
  e.status = to_string(fit.status);
  e.verdict = judge(e.value, fit.status == LyapunovStatus::linear_region, band);
  return e;
}


ZooEstimate local_maps_estimate(const LocalMapResult& r, const ZooBand& band) {
  ZooEstimate e;
  e.value = r.dt ? r.lambda_per_time : r.lambda;
  e.interval = r.dt ? r.lambda_per_time_interval : r.lambda_interval;
  e.status = to_string(r.status);
  e.verdict = judge(e.value, r.status == LocalMapStatus::consistent, band);
  return e;
}

// lambda_1 from local linear maps at (m, tau, w) with the pipeline's settings, or the refusal (a
// series too short for the embedding), which the row reports as not_run. The grid runs m only (the
// pipeline retries m + 1 where m is inconsistent), so a grid row's slopes need a confirmation at m.
struct LocalMaps {
  std::optional<LocalMapResult> result;
  std::string refusal;
};

LocalMaps local_maps_at(std::span<const double> x, std::size_t m, std::size_t tau, std::size_t w,
                        std::optional<double> dt) {
  LocalMaps out;
  try {
    out.result = largest_lyapunov_local_maps(x, choose_local_map_options(m, tau, w), dt);
  } catch (const InvalidInput& error) {
    out.refusal = error.what();
  }
  return out;
}

ZooEstimate not_run(const std::string& why) {
  ZooEstimate e;
  e.status = why;
  return e;
}

// The D2 references of a row at N = n for each Theiler window: the plateau of the state's own
// correlation sums over its first n samples (zoo_state_d2.hpp), with the band they give (within 0.1
// of the reference's interval). Where the state gives no value, or where another coding of the same
// samples (state_codings) reads more than 0.1 away or no plateau at all, the case's band from the
// literature or D_KY.
struct D2Reference {
  ZooEstimate reference;
  ZooBand band;
};

std::vector<D2Reference> d2_references(const std::vector<std::vector<double>>& state, bool map, std::size_t n,
                                       const std::vector<std::size_t>& windows, const ZooBand& fallback) {
  std::vector<D2Reference> out(windows.size(), D2Reference{not_run("none: no state vector"), fallback});
  if (state.empty()) return out;
  std::vector<std::vector<double>> prefix;
  for (const auto& c : state) prefix.emplace_back(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(n));
  // A cap of 10^6 pairs per radius: exact sums of the state cost 50-90 s per system at N = 10^5, the
  // capped ones 3-10 s, with the same reference to 0.01 on Lorenz, Rossler, Henon and Duffing.
  const auto references = [&](const std::vector<std::vector<double>>& components) {
    std::vector<Estimate> e;
    for (const CorrelationSumResult& sums :
         state_correlation_sums(components, state_radii(components), windows, 1000000))
      e.push_back(state_d2_reference(sums));
    return e;
  };
  const std::vector<Estimate> own = references(prefix);
  std::vector<std::pair<std::string, std::vector<Estimate>>> others;
  for (const StateCoding& coding : state_codings(prefix, map)) others.emplace_back(coding.name, references(coding.components));
  for (std::size_t q = 0; q < windows.size(); ++q) {
    const Estimate& e = own[q];
    out[q].reference.value = e.value;
    out[q].reference.interval = e.interval;
    out[q].reference.status = to_string(e.status);
    if (!e.value) {
      out[q].band.source = "the state shows no plateau (" + e.reason + "); " + fallback.source;
      continue;
    }
    std::string readings = "own " + fmt(*e.value);
    bool depends = false;
    for (const auto& [name, estimates] : others) {
      const Estimate& o = estimates[q];
      readings += ", " + name + " " + (o.value ? fmt(*o.value) : std::string("no plateau"));
      if (!o.value || std::abs(*o.value - *e.value) > 0.1) depends = true;
    }
    if (depends) {
      out[q].reference = not_run("none: the state's D2 depends on its coordinates (" + readings + ")");
      out[q].band.source = "the state's D2 depends on its coordinates at N = " + std::to_string(n) + ", w = " +
                           std::to_string(windows[q]) + " (" + readings + "); " + fallback.source;
      continue;
    }
    // The reference is the plateau with its own interval: within 0.1 of that interval.
    const Interval i = e.interval.value_or(Interval{*e.value, *e.value});
    out[q].band.accepted = {Interval{i.low - 0.1, i.high + 0.1}};
    out[q].band.source = "the state's own D2 = " + fmt(*e.value) + " [" + fmt(i.low) + ", " + fmt(i.high) + "] (" +
                         to_string(e.status) + ") at N = " + std::to_string(n) + ", w = " + std::to_string(windows[q]) +
                         " (" + readings + "), +-0.1";
  }
  return out;
}

// D2 from the sums of dimensions 1..top only (the saturation test then uses the three highest).
CorrelationSumResult truncated(const CorrelationSumResult& sums, std::size_t top) {
  CorrelationSumResult t = sums;
  std::size_t keep = 0;
  while (keep < sums.dimension.size() && sums.dimension[keep] <= top) ++keep;
  t.dimension.resize(keep);
  t.correlation_sum.resize(keep);
  t.pairs.resize(keep);
  t.examined.resize(keep);
  return t;
}

// Exact sums of one series at the grid's Theiler windows, counted together at the first request
// (correlation_sums_over_theiler_windows: one walk of the pairs, the same counts as one call per
// window). If that refuses some window, each request is counted alone by correlation_sum, so a
// window is answered or refused exactly as a call per window would answer or refuse it.
class SumsOverWindows {
 public:
  SumsOverWindows(std::span<const double> x, const CorrelationSumOptions& options, std::vector<std::size_t> windows)
      : x_(x), options_(options), windows_(std::move(windows)) {}

  CorrelationSumResult at(std::size_t q) {
    if (!tried_) {
      tried_ = true;
      try {
        together_ = correlation_sums_over_theiler_windows(x_, options_, windows_);
      } catch (const InvalidInput&) {
        together_.clear();
      }
    }
    if (!together_.empty()) return together_[q];
    CorrelationSumOptions alone = options_;
    alone.theiler = windows_[q];
    return correlation_sum(x_, alone);
  }

 private:
  std::span<const double> x_;
  CorrelationSumOptions options_;
  std::vector<std::size_t> windows_;
  bool tried_ = false;
  std::vector<CorrelationSumResult> together_;
};

}  // namespace

std::vector<ZooGridPoint> zoo_grid_points(std::size_t n, const std::string& name, std::size_t sample) {
  constexpr std::size_t windows = 3, extras = 4, all = windows * extras;
  std::vector<std::size_t> chosen;
  if (n <= 10000 || sample >= all) {
    for (std::size_t p = 0; p < all; ++p) chosen.push_back(p);
  } else {
    std::uint64_t hash = 14695981039346656037ull;
    for (const unsigned char ch : name) hash = (hash ^ ch) * 1099511628211ull;
    for (std::size_t j = 0; j < sample; ++j) chosen.push_back((hash % all + j * all / sample) % all);
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  }
  std::vector<ZooGridPoint> points;
  for (const std::size_t p : chosen) points.push_back(ZooGridPoint{p / extras, p % extras});
  return points;
}

ZooCaseResult run_zoo_case(const ZooCase& c, std::size_t case_index, const ZooSuiteOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ZooCaseResult result;
  result.case_index = case_index;
  try {
    const std::vector<double> full = c.series(c.length);
    const std::vector<std::vector<double>> state = c.state ? c.state(c.length) : std::vector<std::vector<double>>{};
    std::vector<std::size_t> lengths{c.length};
    const bool grid = c.grid && options.grid && !options.fast;
    if (grid && c.length > 10000) lengths = {10000, c.length};
    for (const std::size_t n : lengths) {
      const std::span<const double> x(full.data(), n);
      const AutomaticAnalysis a = analyse_series(x, c.dt);
      ZooRow base;
      base.n = n;
      base.theiler = a.theiler;
      base.delay = a.delay.value_or(0);
      base.dimension = a.dimension.value_or(0);
      base.note = a.stopped;
      const std::vector<std::size_t> windows{a.theiler, 2 * a.theiler, 3 * a.theiler};
      const bool grid_point = grid && a.dimension && a.delay;
      const std::vector<ZooGridPoint> points =
          grid_point ? zoo_grid_points(n, c.name, options.grid_points) : std::vector<ZooGridPoint>{};
      // The windows the rows need: the automatic one first (the base row's reference), then those of
      // the grid points run at this length.
      std::vector<std::size_t> used{0};
      for (const ZooGridPoint& g : points)
        if (std::find(used.begin(), used.end(), g.window) == used.end()) used.push_back(g.window);
      std::vector<std::size_t> used_windows;
      for (const std::size_t wi : used) used_windows.push_back(windows[wi]);
      const auto slot = [&](std::size_t wi) {
        return static_cast<std::size_t>(std::find(used.begin(), used.end(), wi) - used.begin());
      };
      const std::vector<D2Reference> references =
          c.kind == ZooCaseKind::chaotic
              ? d2_references(state, !c.dt.has_value(), n, used_windows, c.d2_band)
              : std::vector<D2Reference>(used.size(), D2Reference{not_run("none: not a chaotic system"), c.d2_band});
      base.d2_reference = references.front().reference;
      base.d2_band = references.front().band;
      base.d2 = a.d2 ? d2_estimate(*a.d2, base.d2_band) : not_run("not_run");
      base.d2_answer = a.d2_estimate ? answer_estimate(*a.d2_estimate, base.d2_band) : not_run("not_run");
      base.rosenstein = a.rosenstein ? lambda_estimate(a.rosenstein->fit, c.dt, c.lambda_band) : not_run("not_run");
      base.kantz = a.kantz ? lambda_estimate(a.kantz->fit, c.dt, c.lambda_band) : not_run("not_run");
      base.local_maps = a.local_maps                   ? local_maps_estimate(*a.local_maps, c.lambda_band)
                        : !a.local_maps_refusal.empty() ? not_run("not_run: " + a.local_maps_refusal)
                                                        : not_run("not_run");
      if (a.local_maps && a.local_maps->variants.front().dimension != base.dimension)
        base.local_maps.dimension = a.local_maps->variants.front().dimension;
      base.lyapunov = a.lyapunov ? answer_estimate(a.lyapunov->per_time(), c.lambda_band) : not_run("not_run");
      result.rows.push_back(base);
      if (!grid_point) continue;

      const std::size_t m0 = *a.dimension;
      const CorrelationSumOptions sum_options = choose_correlation_sum_options(x, *a.delay, a.theiler, m0 + 3);
      SumsOverWindows whole(x, sum_options, used_windows);
      const auto [first_half, second_half] = record_halves(x);
      SumsOverWindows first_sums(first_half, sum_options, used_windows), second_sums(second_half, sum_options, used_windows);
      const LyapunovFitOptions fit = choose_lyapunov_fit(a.scales);
      // Divergence curves for m0 .. m0 + 5 at each window, and the same on each half of the record,
      // computed the first time a grid point needs them: the fit at grid dimension m uses m, m+1, m+2.
      using HalfCurves = std::pair<DivergenceCurve, DivergenceCurve>;
      struct Curves {
        std::vector<std::optional<DivergenceCurve>> whole = std::vector<std::optional<DivergenceCurve>>(6);
        std::vector<std::optional<HalfCurves>> halves = std::vector<std::optional<HalfCurves>>(6);
      };
      std::map<std::pair<std::size_t, LyapunovMethod>, Curves> curves;
      std::string curve_error;
      for (const ZooGridPoint& point : points) {
        const std::size_t wi = point.window, ws = slot(wi);
        const double factor = static_cast<double>(wi + 1);
        const std::size_t w = windows[wi];
        const CorrelationSumResult sums = whole.at(ws);
        // The halves check, as in the pipeline (automatic_correlation_dimension), counted only when
        // some dimension saturates.
        std::optional<std::pair<CorrelationSumResult, CorrelationSumResult>> halves;
        const auto d2_at = [&](std::size_t m) {
          CorrelationDimensionResult d2 = correlation_dimension(truncated(sums, m));
          if (d2.status != D2Status::saturated) return d2;
          try {
            if (!halves) halves.emplace(first_sums.at(ws), second_sums.at(ws));
            require_reproduced_by_halves(d2, correlation_dimension(truncated(halves->first, m)),
                                         correlation_dimension(truncated(halves->second, m)));
          } catch (const InvalidInput&) {
            require_reproduced_by_halves(d2, CorrelationDimensionResult{}, CorrelationDimensionResult{});
          }
          return d2;
        };
        const auto curve = [&](LyapunovMethod method, std::size_t j) -> const std::optional<DivergenceCurve>& {
          std::optional<DivergenceCurve>& cached = curves[{wi, method}].whole[j];
          if (!cached) {
            try {
              cached = divergence_curve(x, choose_lyapunov_options(a.scales, n, m0 + j, *a.delay, w, method));
            } catch (const InvalidInput& e) {
              curve_error = e.what();
            }
          }
          return cached;
        };
        // The halves check of a linear region, as in the pipeline (check_record_halves).
        const auto check_halves = [&](LyapunovFit& f, LyapunovMethod method, std::size_t k) {
          if (f.status != LyapunovStatus::linear_region) return;
          auto& cache = curves[{wi, method}].halves;
          const auto [first, second] = record_halves(x);
          try {
            std::vector<DivergenceCurve> one, two;
            for (std::size_t j = k; j < k + 3; ++j) {
              if (!cache[j]) {
                const LyapunovOptions o = choose_lyapunov_options(a.scales, n, m0 + j, *a.delay, w, method);
                cache[j].emplace(divergence_curve(first, o), divergence_curve(second, o));
              }
              one.push_back(cache[j]->first);
              two.push_back(cache[j]->second);
            }
            require_reproduced_by_halves(f, fit_divergence(one, fit), fit_divergence(two, fit), fit.tolerance);
          } catch (const InvalidInput& e) {
            require_reproduced_by_halves(f, LyapunovFit{}, LyapunovFit{}, fit.tolerance);
            f.explanation += std::string(" (a half cannot be analysed: ") + e.what() + ")";
          }
        };
        const std::size_t m = m0 + point.extra;
        ZooRow row;
        row.n = n;
        row.theiler_factor = factor;
        row.theiler = w;
        row.delay = *a.delay;
        row.dimension = m;
        row.automatic = false;
        row.d2_reference = references[ws].reference;
        row.d2_band = references[ws].band;
        const CorrelationDimensionResult d2 = d2_at(m);
        row.d2 = d2_estimate(d2, row.d2_band);
        row.d2_answer = answer_estimate(d2_answer(d2), row.d2_band);
        const std::size_t k = m - m0;
        const auto fit_of = [&](LyapunovMethod method) -> std::optional<LyapunovFit> {
          std::vector<DivergenceCurve> three;
          for (std::size_t j = k; j < k + 3; ++j)
            if (const auto& curve_j = curve(method, j)) three.push_back(*curve_j);
          if (three.size() < 3) return std::nullopt;
          return fit_divergence(three, fit);
        };
        // As in the pipeline: each fit is checked against the record's halves, against the other
        // fit and against a consistent local-map exponent (cross_check).
        std::optional<LyapunovFit> r = fit_of(LyapunovMethod::rosenstein), q = fit_of(LyapunovMethod::kantz);
        if (r) check_halves(*r, LyapunovMethod::rosenstein, k);
        if (q) check_halves(*q, LyapunovMethod::kantz, k);
        if (r && q) cross_check(*r, *q, fit.tolerance);
        const LocalMaps maps = local_maps_at(x, m, *a.delay, w, c.dt);
        if (maps.result) {
          if (r) cross_check(*r, LyapunovMethod::rosenstein, *maps.result, fit.tolerance);
          if (q) cross_check(*q, LyapunovMethod::kantz, *maps.result, fit.tolerance);
        } else {
          if (r) cross_check_without_local_maps(*r, LyapunovMethod::rosenstein, maps.refusal);
          if (q) cross_check_without_local_maps(*q, LyapunovMethod::kantz, maps.refusal);
        }
        row.rosenstein = r ? lambda_estimate(*r, c.dt, c.lambda_band) : not_run("not_run: " + curve_error);
        row.kantz = q ? lambda_estimate(*q, c.dt, c.lambda_band) : not_run("not_run: " + curve_error);
        row.local_maps = maps.result ? local_maps_estimate(*maps.result, c.lambda_band) : not_run("not_run: " + maps.refusal);
        row.lyapunov = answer_estimate(combine_lyapunov(r ? &r->estimate : nullptr, q ? &q->estimate : nullptr,
                                                        maps.result ? &*maps.result : nullptr, c.dt)
                                           .per_time(),
                                       c.lambda_band);
        result.rows.push_back(row);
      }
    }
  } catch (const std::exception& e) {
    result.error = e.what();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace chaos
