#include "pipeline.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "gnuplot.hpp"
#include "outputs.hpp"
#include "safe_output.hpp"
#include "chaos/format.hpp"
#include "mechanism/simulate.hpp"
#include "study/error.hpp"
#include "study/grid.hpp"
#include "study/sweep.hpp"

namespace study::cli {

void add_pipeline_options(CLI::App& cmd, PipelineRequest& r) {
  cmd.add_option("scene", r.scene_file, "scene file (TOML); without one, the built-in seed scene");
  cmd.add_option("--set", r.overrides, "override a scene key (repeatable)");
  cmd.add_option("--periods", r.periods, "crank revolutions simulated; the analysed ones are the last");
  cmd.add_option("--analysis-periods", r.analysis.periods, "revolutions analysed (the seed: 5)");
  cmd.add_option("--analysis-interval", r.analysis.interval, "s between samples of the analysed series");
  cmd.add_option("--analysis-samples-per-period", r.analysis.samples_per_period,
                 "sample this many times per crank revolution instead of every --analysis-interval");
  cmd.add_option("--max-delay", r.analysis.max_delay, "largest mutual-information delay of the first search, samples (with no minimum there, the search goes on to two Theiler windows)");
  cmd.add_option("--max-dimension", r.analysis.max_dimension, "Cao and D2 up to this embedding dimension (the seed: 12)");
  cmd.add_option("--delay", r.analysis.given_delay, "use this delay (samples) instead of the mutual-information minimum");
  // Both refused before the run when they cannot be written, as study plot's -o.
  const CLI::Option* scene = cmd.get_option("scene");
  check_output(cmd.add_option("--plot", r.plot, "draw the six panels of the seed's Fig. 7 to FILE.png or FILE.svg"), "--plot",
               scene, true);
  check_output(cmd.add_option("--series", r.series_output, "also write t, slider_y, slider_vy of the analysed revolutions to FILE"),
               "--series", scene, false);
}

bool run_pipeline(const PipelineRequest& r) {
  if (r.analysis.periods == 0 || r.analysis.periods > r.periods)
    throw StudyError("--analysis-periods", std::to_string(r.analysis.periods),
                     "must be 1 .. --periods (" + std::to_string(r.periods) + ")");
  validate_analysis(r.analysis);
  std::string text;
  if (!r.scene_file.empty()) {
    if (std::filesystem::is_directory(r.scene_file)) throw StudyError("scene", r.scene_file, "is a directory, not a scene file");
    std::ifstream in(r.scene_file);
    if (!in) throw StudyError("scene", r.scene_file, "cannot be opened (missing or unreadable file)");
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  mechanism::Scene scene = mechanism::read_scene(text, r.overrides, r.scene_file.empty() ? "scene" : r.scene_file);
  for (const auto& w : mechanism::scene_warnings(scene)) std::cerr << "study: warning: " << w << "\n";
  const double period = scene.driver.period();
  AnalysisOptions analysis = r.analysis;
  if (analysis.samples_per_period) analysis.interval = period / static_cast<double>(analysis.samples_per_period);
  scene.run.transient = static_cast<double>(r.periods - r.analysis.periods) * period;
  scene.run.duration = static_cast<double>(r.analysis.periods) * period;
  scene.run.output_interval = analysis.interval;
  scene.run.stroboscopic = false;
  mechanism::SliderCrank system(scene);
  std::vector<double> t, y, vy;
  mechanism::SimulationObserver observer;
  observer.sample = [&](double time, const mechanism::State&, const mechanism::Evaluation& ev) {
    t.push_back(time);
    y.push_back(ev.slider_pose[1]);
    vy.push_back(ev.slider_velocity[1]);
  };
  const mechanism::SimulationSummary sim = mechanism::simulate(system, observer);
  nlohmann::json out = {{"simulation", {{"status", mechanism::to_string(sim.status)},
                                        {"message", sim.message},
                                        {"wall_seconds", sim.wall_seconds},
                                        {"steps", sim.steps},
                                        {"rejected_steps", sim.rejected_steps}}}};
  if (sim.status != mechanism::SimulationStatus::completed) {
    std::cout << out.dump(2) << "\n";
    return false;
  }
  if (!r.series_output.empty()) {
    safe_output::OutputFile file(r.series_output);
    std::ostream& f = file.stream();
    // Every digit, so that another tool reads the series the pipeline analysed.
    f << "# t\tslider_y\tslider_vy\n";
    using chaos::format_number, chaos::Precision;
    for (std::size_t i = 0; i < t.size(); ++i)
      f << format_number(t[i], Precision::round_trip) << '\t' << format_number(y[i], Precision::round_trip) << '\t'
        << format_number(vy[i], Precision::round_trip) << '\n';
    file.commit();
  }
  const SeriesAnalysis a = analyse_series_with_curves(y, analysis.interval, analysis);
  auto opt = [](const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  nlohmann::json d2m = nlohmann::json::array();
  for (const auto& d : a.d2_by_dimension) d2m.push_back(opt(d));
  out["analysis"] = {{"status", a.status},
                     {"samples", a.samples},
                     {"interval_seconds", a.interval},
                     {"delay_samples", opt(a.delay)},
                     {"delay_seconds", a.delay ? nlohmann::json(static_cast<double>(*a.delay) * a.interval) : nlohmann::json(nullptr)},
                     {"delay_source", r.analysis.given_delay ? "given (--delay)" : a.delay_source},
                     {"delay_searched", a.delay_searched},
                     {"theiler_samples", a.theiler},
                     {"theiler_source", a.theiler_source},
                     {"cao_dimension", opt(a.embedding_dimension)},
                     {"E1", a.E1},
                     {"E2", a.E2},
                     {"e2_deviation", a.e2_deviation},
                     {"d2_status", a.d2_status},
                     {"d2", opt(a.d2)},
                     {"d2_low", opt(a.d2_low)},
                     {"d2_high", opt(a.d2_high)},
                     {"d2_by_dimension", d2m}};
  std::cout << out.dump(2) << "\n";

  if (!r.plot.empty()) {
    std::ostringstream g;
    g << "set multiplot layout 3,2\nset grid\nunset key\n$series << EOD\n";
    for (std::size_t i = 0; i < y.size(); ++i) g << y[i] * 1e3 << ' ' << vy[i] << '\n';
    g << "EOD\nset title '(a) phase portrait'\nset xlabel 'slider y (mm)'\nset ylabel 'slider v_y (m/s)'\n"
      << "plot $series using 1:2 with lines lc rgb 'black'\n";
    g << "$mi << EOD\n";
    for (std::size_t k = 0; k < a.mutual_information.size(); ++k) g << k << ' ' << a.mutual_information[k] << '\n';
    g << "EOD\nset title " << cli_support::quoted("(b) mutual information" + (a.delay ? ", delay " + std::to_string(*a.delay) : std::string(", no minimum")))
      << "\nset xlabel 'delay (samples)'\nset ylabel 'I (nats)'\n";
    if (a.delay) g << "set arrow from " << *a.delay << ", graph 0 to " << *a.delay << ", graph 1 nohead dt 2\n";
    g << "plot $mi using 1:2 with linespoints pt 7 ps 0.3\nunset arrow\n";
    const std::size_t tau = a.delay.value_or(1);
    g << "$rec << EOD\n";
    for (std::size_t i = 0; i + tau < y.size(); ++i) g << y[i] * 1e3 << ' ' << y[i + tau] * 1e3 << '\n';
    g << "EOD\nset title " << cli_support::quoted("(c) reconstruction, tau = " + std::to_string(tau))
      << "\nset xlabel 'y(t) (mm)'\nset ylabel 'y(t + tau) (mm)'\nplot $rec using 1:2 with lines lc rgb 'black'\n";
    g << "$c << EOD\n";
    for (std::size_t m = 0; m < a.correlation_sum.size(); ++m) {
      for (std::size_t k = 0; k < a.radius.size(); ++k)
        if (a.correlation_sum[m][k] > 0) g << std::log10(a.radius[k] * 1e3) << ' ' << std::log10(a.correlation_sum[m][k]) << '\n';
      g << "\n\n";
    }
    g << "EOD\nset title '(d) correlation sums, m = 1.." << a.correlation_sum.size()
      << "'\nset xlabel 'log10 eps (mm)'\nset ylabel 'log10 C(eps)'\n";
    if (a.correlation_sum.empty()) g << "plot [0:1][0:1] NaN\n";
    else g << "plot for [i=0:" << a.correlation_sum.size() - 1 << "] $c index i using 1:2 with lines\n";
    g << "$d2 << EOD\n";
    for (std::size_t m = 0; m < a.d2_by_dimension.size(); ++m)
      if (a.d2_by_dimension[m]) g << m + 1 << ' ' << *a.d2_by_dimension[m] << '\n';
    g << "EOD\nset title " << cli_support::quoted("(e) D2 against m: " + a.d2_status + (a.d2 ? ", D2 = " + std::to_string(*a.d2) : std::string()))
      << "\nset xlabel 'embedding dimension m'\nset ylabel 'D2(m)'\n";
    const bool any_d2 = std::any_of(a.d2_by_dimension.begin(), a.d2_by_dimension.end(), [](const auto& d) { return d.has_value(); });
    g << (any_d2 ? "plot $d2 using 1:2 with linespoints pt 7\n" : "plot [0:1][0:1] NaN\n");
    g << "$cao << EOD\n";
    for (std::size_t k = 0; k < a.E1.size(); ++k) g << a.dimension[k] << ' ' << a.E1[k] << ' ' << a.E2[k] << '\n';
    g << "EOD\nset title " << cli_support::quoted("(f) Cao: E1 (saturation " +
                                                  (a.embedding_dimension ? std::to_string(*a.embedding_dimension) : std::string("none")) + "), E2")
      << "\nset xlabel 'm'\nset ylabel 'E1, E2'\nset key bottom right\n";
    g << (a.E1.empty() ? "plot [0:1][0:1] NaN\n" : "plot $cao using 1:2 with linespoints title 'E1', $cao using 1:3 with linespoints title 'E2'\n");
    g << "unset multiplot\n";
    try {
      cli_support::render(g.str(), r.plot);
    } catch (const cli_support::PlotError& e) {
      throw StudyError("--plot", r.plot, e.what());
    }
  }
  return true;
}

}  // namespace study::cli
