// zoo: the regression suite's run, judgement and Markdown report (commands.hpp); zoo --series: a
// case's series and the JSON.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "chaos/detail/parallel.hpp"
#include "chaos/error.hpp"
#include "chaos/format.hpp"
#include "chaos/models/zoo_suite.hpp"
#include "commands.hpp"
#include "report_parameters.hpp"
#include "zoo_checkpoint.hpp"

namespace chaos::cli {

namespace {

// A number of the report, "-" where there is none.
std::string num(const std::optional<double>& v, Precision precision = Precision::title) {
  return v && *v == *v ? format_number(*v, precision) : "-";
}
std::string num(double v, Precision precision = Precision::title) { return num(std::optional<double>(v), precision); }

std::string estimate(const ZooEstimate& e) {
  std::string s = num(e.value);
  if (e.interval) s += " [" + num(e.interval->low, Precision::coarse) + ", " + num(e.interval->high, Precision::coarse) + "]";
  s += " " + e.status;
  if (e.dimension) s += " at m = " + std::to_string(*e.dimension);
  if (e.verdict == ZooVerdict::wrong) s += " **WRONG**";
  return s;
}

std::string bands(const ZooBand& b) {
  if (b.accepted.empty()) return "none";
  std::string s;
  for (const auto& i : b.accepted) {  // appended piece by piece: GCC 12's -Wrestrict misreads "[" + string
    if (!s.empty()) s += " or ";
    s += '[';
    s += num(i.low, Precision::coarse);
    s += ", ";
    s += num(i.high, Precision::coarse);
    s += ']';
  }
  return s;
}

std::string machine() {
  std::ifstream cpu("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpu, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

struct Tally {
  std::size_t in_band = 0, wrong = 0, unsure = 0;
  void add(ZooVerdict v) { (v == ZooVerdict::in_band ? in_band : v == ZooVerdict::wrong ? wrong : unsure)++; }
  std::string text() const {
    return std::to_string(in_band) + " / " + std::to_string(unsure) + " / " + std::to_string(wrong);
  }
};

nlohmann::ordered_json band_json(const ZooBand& b) {
  auto out = nlohmann::ordered_json::array();
  for (const auto& i : b.accepted) out.push_back({i.low, i.high});
  return out;
}

nlohmann::ordered_json estimate_json(const ZooEstimate& e) {
  return {{"value", optional_json(e.value)}, {"interval", interval_json(e.interval)}, {"status", e.status},
          {"verdict", to_string(e.verdict)}, {"dimension", optional_json(e.dimension)}};
}

}  // namespace

ZooRun run_zoo(const ZooParams& params,
               const std::function<void(std::size_t, std::size_t, const ZooCase&, const ZooCaseResult&)>& each) {
  if (params.threads == 0) throw InvalidInput(ErrorCode::invalid_parameter, "zoo: --threads must be at least 1 (got 0)");
  ZooSuiteOptions options;
  options.fast = params.fast;
  options.grid = params.grid;
  if (params.grid_points == 0 || params.grid_points > 12)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "zoo: --grid-points must be 1 to 12, the points of the grid (got " + std::to_string(params.grid_points) + ")");
  options.grid_points = params.grid_points;
  options.only = params.only;
  options.threads = params.threads;
  // Opened first, so that a refused file is reported before the spectra behind the bands are computed.
  std::optional<ZooCheckpoint> checkpoint;
  if (!params.checkpoint.empty()) checkpoint.emplace(params.checkpoint, params.fast, params.grid && !params.fast ? params.grid_points : 0);  // --fast has no grid
  const auto start = std::chrono::steady_clock::now();
  const std::vector<ZooCase> cases = zoo_cases(options);
  if (cases.empty()) throw InvalidInput(ErrorCode::invalid_parameter, "zoo: no case matches --only");

  // Cases a checkpoint holds are read, not run.
  std::vector<ZooCaseResult> results(cases.size());
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (checkpoint)
      if (const auto stored = checkpoint->results().find(cases[i].name); stored != checkpoint->results().end()) {
        results[i] = stored->second;
        results[i].case_index = i;
        continue;
      }
    order.push_back(i);
  }
  const std::size_t resumed = cases.size() - order.size();

  // Cases are handed out largest first (grids before single points) and stored by index, so the
  // report is the same for any thread count.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return cases[a].grid * cases[a].length > cases[b].grid * cases[b].length;
  });
  // An exception from a case or from `each` stops the others after their case and is rethrown.
  std::mutex progress;
  std::size_t done = resumed;
  detail::parallel_tasks(params.threads, order.size(), [&](std::size_t k, std::size_t) {
    const std::size_t i = order[k];
    results[i] = run_zoo_case(cases[i], i, options);
    const std::lock_guard<std::mutex> lock(progress);
    if (checkpoint) checkpoint->append(cases[i].name, results[i]);
    ++done;
    if (each) each(done, cases.size(), cases[i], results[i]);
  });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // The lambda_1 answers over every chaotic row (automatic and grid): how many are confident and in
  // band, how often the interval holds lambda_1 from the equations (confident and rough rows), and how
  // many confident ones lie farther from it than twice their half-width.
  struct AnswerTally {
    std::size_t rows = 0, confident = 0, in_band = 0, stated = 0, held = 0, beyond = 0;
  };
  std::map<std::size_t, AnswerTally> answers, d2_answers;  // by N; automatic rows only
  AnswerTally all_answers, all_d2_answers;                 // every row
  const auto tally_answer = [](AnswerTally& t, const ZooEstimate& e, double reference) {
    ++t.rows;
    if (!e.value || !std::isfinite(reference)) return;
    if (e.status != "confident" && e.status != "rough") return;
    ++t.stated;
    if (e.interval && e.interval->low <= reference && reference <= e.interval->high) ++t.held;
    if (e.status != "confident") return;
    ++t.confident;
    t.in_band += e.verdict == ZooVerdict::in_band;
    const double half = e.interval ? 0.5 * (e.interval->high - e.interval->low) : 0.0;
    t.beyond += std::abs(*e.value - reference) > 2.0 * half;
  };
  // Judgement.
  std::size_t wrong = 0, chaotic = 0, d2_covered = 0, lambda_covered = 0;
  std::vector<std::string> wrong_rows;
  std::map<ZooCaseKind, Tally> control_d2, control_lambda;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const ZooCase& c = cases[i];
    for (const ZooRow& r : results[i].rows)
      for (const auto* e : {&r.d2, &r.d2_answer, &r.lyapunov, &r.rosenstein, &r.kantz, &r.local_maps})
        if (e->verdict == ZooVerdict::wrong) {
          ++wrong;
          const bool is_d2 = e == &r.d2 || e == &r.d2_answer;
          const std::string what = e == &r.d2           ? "D2"
                                   : e == &r.d2_answer  ? "D2 (the answer)"
                                   : e == &r.lyapunov   ? "lambda_1 (the answer)"
                                   : e == &r.rosenstein ? "lambda (Rosenstein)"
                                   : e == &r.kantz      ? "lambda (Kantz)"
                                                        : "lambda (local maps)";
          wrong_rows.push_back(c.name + ": " + what + " = " + num(e->value) + " with status " + e->status + " at N = " +
                               std::to_string(r.n) + ", w = " + std::to_string(r.theiler) + ", m = " +
                               std::to_string(r.dimension) + "; band " + bands(is_d2 ? r.d2_band : c.lambda_band) +
                               (is_d2 ? " (" + r.d2_band.source + ")" : std::string()));
        }
    if (results[i].rows.empty()) continue;
    const ZooRow& base = results[i].rows.back().automatic ? results[i].rows.back() : *std::find_if(
        results[i].rows.rbegin(), results[i].rows.rend(), [](const ZooRow& r) { return r.automatic; });
    if (c.kind == ZooCaseKind::chaotic) {
      for (const ZooRow& r : results[i].rows) {
        tally_answer(all_answers, r.lyapunov, c.lambda_equations);
        if (r.automatic) tally_answer(answers[r.n], r.lyapunov, c.lambda_equations);
        // D2 answers are held to the state's own D2 where it has one (the rows without are left out).
        if (!r.d2_reference.value) continue;
        tally_answer(all_d2_answers, r.d2_answer, *r.d2_reference.value);
        if (r.automatic) tally_answer(d2_answers[r.n], r.d2_answer, *r.d2_reference.value);
      }
      ++chaotic;
      d2_covered += base.d2_answer.verdict == ZooVerdict::in_band;
      lambda_covered += base.lyapunov.verdict == ZooVerdict::in_band;
    } else {
      control_d2[c.kind].add(base.d2.verdict);
      control_d2[c.kind].add(base.d2_answer.verdict);
      control_lambda[c.kind].add(base.rosenstein.verdict);
      control_lambda[c.kind].add(base.kantz.verdict);
      control_lambda[c.kind].add(base.local_maps.verdict);
      control_lambda[c.kind].add(base.lyapunov.verdict);
    }
  }

  std::ostringstream md;
  md << "# The zoo: out-of-sample regression of the automatic estimates\n\n"
     << "Made by `chaos zoo" << (params.fast ? " --fast" : "") << (!params.grid ? " --no-grid" : "")
     << (params.grid && !params.fast && params.grid_points != 2 ? " --grid-points " + std::to_string(params.grid_points) : "")
     << " --threads " << params.threads << "` (chaos/cli/zoo.cpp, rules in chaos/models/include/chaos/models/zoo_suite.hpp and "
     << "automatic_analysis.hpp). Machine: " << machine() << ". Wall time: " << num(wall) << " s on "
     << params.threads << " thread(s)";
  if (resumed > 0) {
    double sum = 0.0;
    for (const auto& r : results) sum += r.seconds;
    md << ", running " << cases.size() - resumed << " of the " << cases.size() << " cases; the other " << resumed
       << " were read from a checkpoint written by earlier runs of the same build (`--checkpoint`). The cases' own "
       << "times sum to " << num(sum) << " s";
  }
  md << ".\n\n"
     << "Bands, fixed before any run (zoo_suite.hpp): D2 within 0.1 of the attractor's own D2 and its interval at the same N, "
     << "Theiler window and scales (the plateau of the full state's correlation sums from the equations, "
     << "zoo_state_d2.hpp; why a finite record is held to it and not to a zero-scale value: "
     << "docs/notes/zoo-state-space.md; where another coding of the same samples, each component scaled to a common "
     << "range or, for a map, each state beside its image, reads more than 0.1 away or no plateau, the reading belongs "
     << "to the coordinates and is no reference: this rule was added after the first full run under the state "
     << "reference, for the reason measured there), else within +-0.1 of a cited literature D2, else not above "
     << "D_KY + 0.1 (D_KY from the equations); lambda_1 within 10% of lambda_1 from the equations (`chaos spectrum`); "
     << "noise, surrogates and random walks: no confident value at all; periodic and quasi-periodic signals: "
     << "D2 equal to the torus dimension +-0.1 and no confident lambda_1. A confident value is a D2 with status "
     << "`saturated`, a D2 or lambda_1 answer with status `confident`, or a lambda_1 with status `linear_region` (Rosenstein, Kantz) or `consistent` (local maps); every other "
     << "status is *unsure*. "
     << "What the remaining wrong rows have in common, and what was measured about them, is in docs/notes/zoo-notes.md.\n\n"
     << "## Summary\n\n"
     << "- Confident and wrong: **" << wrong << "** over every row ("
     << (params.grid && !params.fast ? "automatic choices and grid" : "automatic choices only: no grid in this run") << ").\n";
  if (chaotic > 0)
    md << "- Coverage with the automatic choices at N = " << (params.fast ? "10^4" : "10^5") << ": D2 confident and in band for **"
       << d2_covered << " of " << chaotic << "** chaotic systems (the D2 answer; " << num(100.0 * static_cast<double>(d2_covered) / static_cast<double>(chaotic), Precision::coarse)
       << "%); lambda_1 confident and in band for **" << lambda_covered << " of " << chaotic << "** (the lambda_1 answer; "
       << num(100.0 * static_cast<double>(lambda_covered) / static_cast<double>(chaotic), Precision::coarse)
       << "%). The goals are 90% for D2 and 85% for lambda_1.\n";
  const auto answer_text = [](const AnswerTally& t, const std::string& reference) {
    std::ostringstream a;
    a << t.confident << " confident of " << t.rows << ", " << t.in_band << " of them in band; the interval holds "
      << reference << " in " << t.held << " of " << t.stated << " confident or rough answers; " << t.beyond
      << " confident farther from it than twice their half-width";
    return a.str();
  };
  const std::string lambda_reference = "lambda_1 from the equations", d2_reference = "the state's own D2";
  for (const auto& [n, t] : answers)
    md << "- lambda_1 answers (lyapunov_answer.hpp), automatic choices at N = " << n << ": " << answer_text(t, lambda_reference) << ".\n";
  if (all_answers.rows > 0) md << "- lambda_1 answers over every chaotic row: " << answer_text(all_answers, lambda_reference) << ".\n";
  for (const auto& [n, t] : d2_answers)
    md << "- D2 answers (d2_answer.hpp), automatic choices at N = " << n << ", rows with a state reference: "
       << answer_text(t, d2_reference) << ".\n";
  if (all_d2_answers.rows > 0)
    md << "- D2 answers over every chaotic row with a state reference: " << answer_text(all_d2_answers, d2_reference) << ".\n";
  md << "- Controls (in band / unsure / wrong; lambda counts the answer and the three methods):";
  for (const auto& [kind, t] : control_d2) md << " " << to_string(kind) << " D2 " << t.text() << ", lambda " << control_lambda[kind].text() << ";";
  md << "\n\n";
  if (!wrong_rows.empty()) {
    md << "### Confident and wrong\n\n";
    for (const auto& w : wrong_rows) md << "- " << w << "\n";
    md << "\n";
  }
  md << "## Chaotic systems, automatic choices\n\n"
     << "tau, m and w are the pipeline's choices (MI minimum, Cao, the longer of the 1/e time and half the period, at least tau); lambda per time unit "
     << "for flows, per iteration for maps, with the range of the local slopes over the fitted stretch (Rosenstein, "
     << "Kantz) or of the estimator's variants (local maps).\n\n"
     << "| system | N | tau | m | w | D2 answer | D2 | D2 of the state | D2 band | lambda_1 answer | lambda Rosenstein | lambda Kantz | lambda local maps | lambda_1 eq. | D_KY eq. | literature lambda_1 / D2 | dysts lambda_1 / D2 | s |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const ZooCase& c = cases[i];
    if (c.kind != ZooCaseKind::chaotic) continue;
    for (const ZooRow& r : results[i].rows) {
      if (!r.automatic) continue;
      md << "| " << c.name << " | " << r.n << " | " << r.delay << " | " << r.dimension << " | " << r.theiler << " | "
         << estimate(r.d2_answer) << " | " << estimate(r.d2) << " | " << estimate(r.d2_reference) << " | "
         << bands(r.d2_band) << " | " << estimate(r.lyapunov) << " | " << estimate(r.rosenstein)
         << " | " << estimate(r.kantz) << " | " << estimate(r.local_maps) << " | " << num(c.lambda_equations) << " | " << num(c.kaplan_yorke) << " | " << num(c.literature_lambda) << " / "
         << num(c.literature_d2) << " | " << num(c.dysts_lambda) << " / " << num(c.dysts_d2) << " | "
         << num(results[i].seconds, Precision::coarse) << " |\n";
    }
    if (!results[i].error.empty()) md << "| " << c.name << " | error: " << results[i].error << " |||||||||||||||||\n";
  }
  md << "\n## Controls, automatic choices\n\n"
     << "| case | kind | what | N | D2 answer | D2 | D2 band | lambda_1 answer | lambda Rosenstein | lambda Kantz | lambda local maps | note |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const ZooCase& c = cases[i];
    if (c.kind == ZooCaseKind::chaotic) continue;
    for (const ZooRow& r : results[i].rows)
      md << "| " << c.name << " | " << to_string(c.kind) << " | " << c.description << " | " << r.n << " | "
         << estimate(r.d2_answer) << " | " << estimate(r.d2) << " | " << bands(r.d2_band) << " | " << estimate(r.lyapunov)
         << " | " << estimate(r.rosenstein) << " | " << estimate(r.kantz) << " | " << estimate(r.local_maps) << " | "
         << r.note << " |\n";
    if (!results[i].error.empty()) md << "| " << c.name << " | error: " << results[i].error << " |||||||||||\n";
  }
  bool any_grid = false;
  for (const auto& r : results) any_grid = any_grid || r.rows.size() > 2;
  if (any_grid) {
    md << "\n## The neighbourhood grid\n\n"
       << "Each chaotic system at w = 1, 2, 3 times the automatic window and m from Cao's to Cao's + 3 "
       << "(D2: the highest dimension of the saturation test; lambda: the lowest of the three fitted together; local "
       << "maps: m itself): all 12 points at N = 10^4, and at N = 10^5 "
       << (params.grid_points >= 12 ? std::string("all 12")
                                    : std::to_string(params.grid_points) + " of them, chosen by the system's name (`--grid-points`)")
       << ". Counts are in band / unsure / wrong over the grid points run.\n\n"
       << "| system | D2 answer | D2 | lambda_1 answer | lambda Rosenstein | lambda Kantz | lambda local maps |\n"
       << "|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < cases.size(); ++i) {
      if (!cases[i].grid) continue;
      Tally d2_answer, d2, lambda_answer, r, k, l;
      for (const ZooRow& row : results[i].rows)
        if (!row.automatic) {
          d2_answer.add(row.d2_answer.verdict);
          d2.add(row.d2.verdict);
          lambda_answer.add(row.lyapunov.verdict);
          r.add(row.rosenstein.verdict);
          k.add(row.kantz.verdict);
          l.add(row.local_maps.verdict);
        }
      md << "| " << cases[i].name << " | " << d2_answer.text() << " | " << d2.text() << " | " << lambda_answer.text() << " | " << r.text() << " | " << k.text() << " | " << l.text()
         << " |\n";
    }
  }

  ZooRun run;
  run.wall_seconds = wall;
  run.resumed = resumed;
  run.wrong = wrong;
  run.chaotic = chaotic;
  run.d2_covered = d2_covered;
  run.lambda_covered = lambda_covered;
  run.markdown = md.str();
  auto& j = run.json;
  j["command"] = "zoo";
  Report parameters("zoo");
  report_parameters(parameters, params, zoo_parameters());
  j["parameters"] = parameters.json()["parameters"];
  j["wrong"] = wrong;
  j["chaotic"] = chaotic;
  j["d2_covered"] = d2_covered;
  j["lambda_covered"] = lambda_covered;
  j["wall_seconds"] = wall;
  j["resumed"] = resumed;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (const ZooRow& r : results[i].rows)
      rows.push_back({{"case", cases[i].name}, {"kind", to_string(cases[i].kind)}, {"n", r.n},
                      {"automatic", r.automatic}, {"delay", r.delay}, {"dimension", r.dimension},
                      {"theiler", r.theiler}, {"theiler_factor", r.theiler_factor}, {"d2", estimate_json(r.d2)},
                      {"d2_answer", estimate_json(r.d2_answer)}, {"d2_reference", estimate_json(r.d2_reference)},
                      {"d2_band", {{"accepted", band_json(r.d2_band)}, {"source", r.d2_band.source}}},
                      {"rosenstein", estimate_json(r.rosenstein)}, {"kantz", estimate_json(r.kantz)},
                      {"local_maps", estimate_json(r.local_maps)}, {"lyapunov", estimate_json(r.lyapunov)},
                      {"note", r.note}, {"seconds", results[i].seconds}, {"error", results[i].error}});
  j["rows"] = std::move(rows);
  run.cases = cases;
  run.results = std::move(results);
  return run;
}

ZooSeriesRun run_zoo_series(const ZooSeriesParams& params, const OutputOptions& output) {
  if (params.threads == 0) throw InvalidInput(ErrorCode::invalid_parameter, "zoo: --threads must be at least 1 (got 0)");
  ZooSuiteOptions options;
  options.fast = params.fast;
  options.only = {params.name};
  options.threads = params.threads;
  const std::vector<ZooCase> cases = zoo_cases(options);
  if (cases.empty())
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "zoo: no case is named '" + params.name + "' (the names are the first column of docs/validation/zoo.md)");
  const ZooCase& c = cases.front();
  std::vector<double> x = c.series(c.length);
  Report report("zoo", output);
  report.parameter("case", c.name);
  report_parameters(report, params, zoo_series_parameters());
  report.parameter("kind", std::string(to_string(c.kind))).parameter("description", c.description)
      .parameter("N", x.size()).parameter("dt", c.dt);
  report.json()["x"] = x;
  return {std::move(x), std::move(report)};
}

}  // namespace chaos::cli
