// The `mechanism` command: the slider-crank simulator from a scene file.
//   mechanism scene [--default] [scene.toml] [--set key=value]...
//   mechanism simulate [scene.toml] [--set key=value]... [--stroboscopic] [--signals a,b] [-o FILE] [--json]
//   mechanism lyapunov [scene.toml] [--set key=value]... [--method benettin|saltation] [--periods N] [--exponents K] [-o FILE] [--json] [--plot FILE]
//   mechanism impact-oscillator [--zeta Z] [--amplitude A] [--omega W] [--gap G] [--restitution R] [--periods N]
// Exit codes: 0 ok (simulation completed), 1 internal error, 2 usage, 3 invalid scene or output file
// (refused before the run, or a write that failed: a full disk, /dev/full), 5 the integration could
// not continue, or reached the end with its energy balance too far off to trust (status
// energy_defect; the summary says when and why).

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include "gnuplot.hpp"
#include "option_checks.hpp"
#include "output_path.hpp"
#include "progress_bar.hpp"
#include "safe_output.hpp"
#include "mechanism/error.hpp"
#include "mechanism/impact_oscillator.hpp"
#include "mechanism/scene.hpp"
#include "mechanism/scene_lyapunov.hpp"
#include "mechanism/signals.hpp"
#include "lyapunov_json.hpp"
#include "summary_json.hpp"
#include "mechanism/simulate.hpp"

namespace {

enum ExitCode : int { ok = 0, internal_error = 1, usage_error = 2, invalid_scene = 3, integration_failed = 5 };

// An output file refused while the command line is read (exit 3, as a scene refused).
struct OutputRefused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Refuses -o and --plot before the run (-o naming the input overwrote it, and an
// unwritable -o or --plot failed only after the whole simulation): output_path.hpp's rules, the
// scene file as the input.
void check_output(CLI::Option* option, const char* name, const CLI::Option* scene, bool plot) {
  cli_support::check_output_option(option, name, scene, plot, [](const std::string& why, bool) { throw OutputRefused(why); });
}

struct SceneOptions {
  std::string file;
  std::vector<std::string> overrides;
  bool quiet = false;  // simulate -q: no progress bar and no scene warnings
};

void add_scene_options(CLI::App& cmd, SceneOptions& o) {
  cmd.add_option("scene", o.file, "scene file (TOML); without one, the built-in seed scene");
  cmd.add_option("--set", o.overrides, "override a key: --set joint.slider.clearance=0.2e-3 (repeatable)");
}

mechanism::Scene load_scene(const SceneOptions& o) {
  std::string text;
  if (!o.file.empty()) {
    // A directory opens as a stream that reads nothing: it ran the built-in scene.
    if (std::filesystem::is_directory(o.file)) throw mechanism::InvalidParameter("scene", o.file, "is a directory, not a scene file");
    std::ifstream in(o.file);
    if (!in) throw mechanism::InvalidParameter("scene", o.file, "cannot be opened (missing or unreadable file)");
    std::stringstream buffer;
    buffer << in.rdbuf();
    text = buffer.str();
  }
  mechanism::Scene scene = mechanism::read_scene(text, o.overrides, o.file.empty() ? "scene" : o.file);
  if (!o.quiet)
    for (const auto& w : mechanism::scene_warnings(scene)) std::cerr << "mechanism: warning: " << w << "\n";
  return scene;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// The scene in a few lines: the keys that differ from the built-in scene, which with it determine
// the scene in full (`mechanism scene` with the same file and --set prints every key).
void write_scene_header(std::ostream& out, const mechanism::Scene& scene, const SceneOptions& o) {
  const std::vector<std::string> changed = mechanism::scene_differences(scene);
  out << "# scene: " << (o.file.empty() ? std::string("the built-in seed scene") : "the file " + o.file + " on the built-in scene");
  if (changed.empty()) {
    out << ", no key changed\n";
    return;
  }
  out << ", with these keys changed (every key: `mechanism scene` with the same file and --set):\n";
  for (const auto& line : changed) out << "#   " << line << "\n";
}

// The slider's trajectory (seed Fig. 3: its centre's height against the crank angle and its
// path in the guide) and, for each revolute clearance joint, the journal centre's path relative
// to the bearing inside the clearance circle (seed Fig. 13).
struct PlotData {
  std::vector<double> angle_deg, slider_x, slider_y;
  std::vector<std::vector<std::array<double, 2>>> journals;
};

void plot_trajectories(const PlotData& d, const mechanism::Scene& scene, const std::vector<std::string>& journals,
                       const std::string& path) {
  std::ostringstream g;
  const int panels = 2 + static_cast<int>(journals.size());
  g << "set multiplot layout " << (panels + 1) / 2 << ",2\nset grid\nunset key\n";
  auto block = [&](const char* name, auto&& rows) {
    g << "$" << name << " << EOD\n";
    rows();
    g << "EOD\n";
  };
  block("slider", [&] {
    for (std::size_t i = 0; i < d.slider_y.size(); ++i)
      g << d.angle_deg[i] << ' ' << d.slider_x[i] * 1e3 << ' ' << d.slider_y[i] * 1e3 << '\n';
  });
  const double c = scene.slider_guide.clearance * 1e3;
  g << "set title 'slider height against crank angle'\nset xlabel 'crank angle (deg, mod 360)'\n"
    << "set ylabel 'slider y (mm)'\nset xrange [0:360]\n";
  if (scene.slider_guide.kind == mechanism::JointKind::clearance)
    g << "set arrow from 0," << c << " to 360," << c << " nohead dt 2\nset arrow from 0," << -c << " to 360," << -c
      << " nohead dt 2\n";
  g << "plot $slider using 1:3 with dots\nunset arrow\nset xrange [*:*]\n";
  g << "set title 'slider centre in the guide'\nset xlabel 'slider x (mm)'\nset ylabel 'slider y (mm)'\n"
    << "plot $slider using 2:3 with lines\n";
  for (std::size_t j = 0; j < journals.size(); ++j) {
    const std::string name = "journal" + std::to_string(j);
    block(name.c_str(), [&] {
      for (const auto& e : d.journals[j]) g << e[0] * 1e3 << ' ' << e[1] * 1e3 << '\n';
    });
    const mechanism::RevoluteJoint& joint = journals[j] == "crank_ground"   ? scene.crank_ground
                                            : journals[j] == "crank_conrod" ? scene.crank_conrod
                                                                            : scene.conrod_slider;
    g << "set title " << cli_support::quoted("journal centre relative to the bearing: " + journals[j]) << "\n"
      << "set xlabel 'x (mm)'\nset ylabel 'y (mm)'\nset size ratio -1\nset parametric\nset trange [0:2*pi]\n"
      << "plot $" << name << " using 1:2 with lines, " << joint.clearance * 1e3 << "*cos(t), " << joint.clearance * 1e3
      << "*sin(t) lw 2 lc rgb 'black' dt 2\nunset parametric\nset size noratio\n";
  }
  g << "unset multiplot\n";
  try {
    cli_support::render(g.str(), path);
  } catch (const cli_support::PlotError& e) {
    throw mechanism::InvalidParameter("--plot", path, e.what());
  }
}


// The running means against the periods averaged: how the estimate converged.
void plot_convergence(const mechanism::SceneLyapunov& r, const std::string& path) {
  const std::size_t k = r.periods ? r.running.size() / r.periods : 0;  // also after a failed run
  std::ostringstream g;
  g << "$run << EOD\n";
  for (std::size_t p = 0; p < r.periods; ++p) {
    g << p + 1;
    for (std::size_t j = 0; j < k; ++j) {
      const double v = r.running[p * k + j];
      g << ' ' << (std::isfinite(v) ? number(v) : std::string("NaN"));
    }
    g << '\n';
  }
  g << "EOD\nset grid\nset key outside right\nset title 'Lyapunov exponents: running means'\n"
    << "set xlabel 'crank periods averaged'\nset ylabel 'lambda (1/s)'\nplot ";
  for (std::size_t j = 0; j < k; ++j)
    g << (j ? ", " : "") << "$run using 1:" << j + 2 << " with lines title 'lambda_" << j + 1 << "'";
  g << "\n";
  try {
    cli_support::render(g.str(), path);
  } catch (const cli_support::PlotError& e) {
    throw mechanism::InvalidParameter("--plot", path, e.what());
  }
}

int run(int argc, char** argv) {
  CLI::App app{"mechanism: planar slider-crank with translational and revolute clearance joints"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "mechanism 0.1.0");

  SceneOptions scene_opts;
  bool print_default = false;
  auto* scene_cmd = app.add_subcommand("scene", "print the resolved scene (every key, defaults included)");
  add_scene_options(*scene_cmd, scene_opts);
  scene_cmd->add_flag("--default", print_default, "print the built-in seed scene with a comment on every key");

  SceneOptions sim_opts;
  bool json = false, strobe = false;
  std::string out_path, signals, plot_path;
  auto* sim = app.add_subcommand("simulate", "integrate the scene and write the chosen signals");
  add_scene_options(*sim, sim_opts);
  sim->add_flag("--stroboscopic", strobe, "write one row per crank revolution (with a revolution column) instead of the time series");
  sim->add_option("--signals", signals, "comma-separated columns to write (default: all; a name the scene lacks is answered with the list it has)");
  check_output(sim->add_option("-o,--output", out_path, "write the table to FILE (default: standard output)"), "-o",
               sim->get_option("scene"), false);
  sim->add_flag("--json", json, "write a JSON summary to standard output (the table then goes only to -o FILE)");
  sim->add_flag("-q,--quiet", sim_opts.quiet, "no progress bar and no warnings about the scene");
  check_output(sim->add_option("--plot", plot_path,
                               "draw the slider's trajectory (seed Fig. 3) and each journal's path in its bearing (Fig. 13) to FILE.png or FILE.svg"),
               "--plot", sim->get_option("scene"), true);
  SceneOptions lyap_opts;
  mechanism::SceneLyapunovOptions lyap;
  bool lyap_json = false;
  std::string lyap_out, lyap_plot;
  auto* lyap_cmd = app.add_subcommand(
      "lyapunov",
      "Lyapunov exponents from the equations of motion (Benettin on the crank-period map: finite differences, or "
      "variational equations with saltation matrices)");
  add_scene_options(*lyap_cmd, lyap_opts);
  std::string lyap_method = "benettin";
  lyap_cmd
      ->add_option("--method", lyap_method,
                   "benettin: finite differences of k + 1 trajectories; saltation: variational equations with "
                   "Mueller's jump matrices at contact onsets and releases (RK4 scenes without Coulomb friction)")
      ->check(CLI::IsMember({"benettin", "saltation"}))
      ->default_val(lyap_method);
  bool lyap_drop_latched = false;
  lyap_cmd->add_flag("--drop-latched-variations", lyap_drop_latched,
                     "saltation only: zero the latched impact velocities' variations at every renormalisation, as "
                     "Benettin's companions do (each restarts with the reference's memory), to measure that difference");
  lyap_cmd->add_option("--periods", lyap.periods, "crank periods averaged (>= 10)")->default_val(lyap.periods);
  lyap_cmd->add_option("--transient-periods", lyap.transient_periods,
                       "periods that align the directions before averaging (after run.transient)")
      ->default_val(lyap.transient_periods);
  lyap_cmd->add_option("--intervals-per-period", lyap.intervals_per_period,
                       "renormalisations per crank period (the separations must stay small in between)")
      ->default_val(lyap.intervals_per_period);
  lyap_cmd->add_option("-k,--exponents", lyap.exponents, "leading exponents to compute (0: all)")->default_val(lyap.exponents);
  lyap_cmd->add_option("--perturbation", lyap.perturbation,
                       "separation relative to each coordinate's scale (refused below the scene's floor, 1e3 x epsilon x "
                       "steps per interval x the largest |coordinate| / scale)")
      ->default_val(lyap.perturbation);
  lyap_cmd->add_option("--seed", lyap.seed, "seed of the initial directions")->default_val(lyap.seed);
  check_output(lyap_cmd->add_option("-o,--output", lyap_out, "write the convergence table to FILE (default: standard output)"),
               "-o", lyap_cmd->get_option("scene"), false);
  lyap_cmd->add_flag("--json", lyap_json, "write the result as JSON to standard output (the table then goes only to -o FILE)");
  lyap_cmd->add_flag("-q,--quiet", lyap_opts.quiet, "no progress bar and no warnings about the scene");
  check_output(lyap_cmd->add_option("--plot", lyap_plot, "draw the running means to FILE.png or FILE.svg"), "--plot",
               lyap_cmd->get_option("scene"), true);
  mechanism::ImpactOscillator osc;
  mechanism::ImpactLyapunovOptions osc_opt;
  osc_opt.perturbation = 1e-8;
  auto* osc_cmd = app.add_subcommand(
      "impact-oscillator",
      "the closed-form benchmark: a forced linear oscillator against a rigid stop, its exponents three ways");
  osc_cmd->add_option("--zeta", osc.zeta, "damping ratio, in [0, 1)")->default_val(osc.zeta);
  osc_cmd->add_option("--amplitude", osc.amplitude, "forcing amplitude")->default_val(osc.amplitude);
  osc_cmd->add_option("--omega", osc.omega, "forcing frequency (natural frequency 1)")->default_val(osc.omega);
  osc_cmd->add_option("--gap", osc.gap, "the stop's position")->default_val(osc.gap);
  osc_cmd->add_option("--restitution", osc.restitution, "Newton's restitution at the stop, in (0, 1]")
      ->default_val(osc.restitution);
  osc_cmd->add_option("--periods", osc_opt.periods, "forcing periods averaged (>= 10)")->default_val(osc_opt.periods);
  osc_cmd->add_option("--transient-periods", osc_opt.transient, "periods before averaging")->default_val(osc_opt.transient);
  osc_cmd->add_option("--perturbation", osc_opt.perturbation, "finite differences: the separation")
      ->default_val(osc_opt.perturbation);
  cli_support::check_numeric_options(app);
  cli_support::one_value_per_occurrence(app);
  if (const std::string unknown = cli_support::unknown_subcommand(app, argc, argv); !unknown.empty()) {
    std::cerr << "mechanism: " << unknown << "\n";
    return usage_error;
  }

  try {
    app.parse(argc, argv);
    if (scene_cmd->parsed()) {
      if (print_default) {
        std::cout << mechanism::default_scene_toml();
      } else {
        std::cout << mechanism::to_toml(load_scene(scene_opts));
      }
      return ok;
    }
    if (osc_cmd->parsed()) {
      try {
        osc.validate();
        osc_opt.validate();
      } catch (const mechanism::InvalidParameter& e) {
        std::cerr << "mechanism: impact-oscillator: " << e.what() << "\n";
        return invalid_scene;
      }
      const double T = osc.period();
      const auto orbits = mechanism::period_one_orbits(osc);
      std::cout << "# mechanism impact-oscillator: x'' + 2 zeta x' + x = A cos(omega t) for x < gap, x' -> -r x' at the "
                   "stop (docs/reference/mechanism/lyapunov.md, \"A closed-form benchmark\")\n"
                << "# zeta " << number(osc.zeta) << ", A " << number(osc.amplitude) << ", omega " << number(osc.omega)
                << ", gap " << number(osc.gap) << ", r " << number(osc.restitution) << "; T " << number(T) << "; "
                << osc_opt.periods << " periods after " << osc_opt.transient << ", perturbation "
                << number(osc_opt.perturbation) << "\n";
      std::array<double, 2> start{osc.gap - osc.amplitude, 0.0};
      const mechanism::PeriodOneOrbit* stable = nullptr;
      for (const auto& o : orbits) {
        std::cout << "# period-1 orbit: impact at t = " << number(o.impact_time) << " mod T, speed " << number(o.impact_velocity)
                  << ", multipliers " << number(o.multipliers[0].real()) << (o.multipliers[0].imag() < 0 ? " - " : " + ")
                  << number(std::abs(o.multipliers[0].imag())) << "i, " << number(o.multipliers[1].real())
                  << (o.multipliers[1].imag() < 0 ? " - " : " + ") << number(std::abs(o.multipliers[1].imag())) << "i ("
                  << (o.stable ? "stable" : "unstable") << ")\n";
        if (o.stable && !stable) stable = &o;
      }
      if (orbits.empty()) std::cout << "# no period-1 impacting orbit\n";
      // On the stable orbit when there is one (its state at t = T, which is its state at 0).
      if (stable) start = mechanism::exact_flow(osc, stable->impact_time, {osc.gap, -osc.restitution * stable->impact_velocity}, T);
      std::cout << "# start (x, x') = (" << number(start[0]) << ", " << number(start[1]) << ") at t = 0"
                << (stable ? ", on the stable period-1 orbit" : "") << "\n";
      std::cout << "method\tlambda_1\tse_1\tlambda_2\tse_2\n";
      for (const auto& o : orbits)
        std::cout << (o.stable ? "closed_form" : "closed_form_unstable") << "\t" << number(o.exponents[0]) << "\t0\t"
                  << number(o.exponents[1]) << "\t0\n";
      int code = ok;
      for (int method = 0; method < 2; ++method) {
        const mechanism::ImpactLyapunov r = method == 0 ? mechanism::saltation_lyapunov(osc, start, osc_opt)
                                                        : mechanism::finite_difference_impact_lyapunov(osc, start, osc_opt);
        const char* name = method == 0 ? "saltation" : "finite_differences";
        if (r.status != "completed") {
          std::cerr << "mechanism: " << name << ": " << r.message << "\n";
          code = integration_failed;
          continue;
        }
        std::cout << name << "\t" << number(r.exponents[0]) << "\t" << number(r.standard_error[0]) << "\t"
                  << number(r.exponents[1]) << "\t" << number(r.standard_error[1]) << "\n";
      }
      return code;
    }
    if (lyap_cmd->parsed()) {
      const mechanism::Scene scene = load_scene(lyap_opts);
      lyap.method = lyap_method == "saltation" ? mechanism::LyapunovMethod::saltation : mechanism::LyapunovMethod::benettin;
      if (lyap_drop_latched && lyap.method != mechanism::LyapunovMethod::saltation) {
        std::cerr << "mechanism: lyapunov: --drop-latched-variations needs --method saltation (Benettin's companions "
                     "always drop them)\n";
        return usage_error;
      }
      lyap.carry_latched_variations = !lyap_drop_latched;
      // An option outside its domain is the command's error, not the scene's (refused before -o is opened).
      try {
        lyap.validate();
      } catch (const mechanism::InvalidParameter& e) {
        std::cerr << "mechanism: lyapunov: " << e.what() << "\n";
        return invalid_scene;
      }
      cli_support::ProgressBar bar(!lyap_opts.quiet && isatty(fileno(stderr)));
      lyap.progress = [&](double f) { bar.update(f, std::to_string(static_cast<int>(100 * f)) + "%"); };
      std::ostream* file = lyap_out.empty() ? nullptr : &safe_output::open_pending(lyap_out).stream();
      mechanism::SceneLyapunov r;
      try {
        r = mechanism::scene_lyapunov(scene, lyap);
      } catch (const mechanism::InvalidParameter& e) {  // a setting the loaded scene cannot meet
        std::cerr << "mechanism: lyapunov: " << e.what() << "\n";
        return invalid_scene;
      }
      bar.update(1.0, "done");
      std::ostream* out = file ? file : (lyap_json ? nullptr : &std::cout);
      if (out) {
        const bool saltation = r.method == "saltation";
        *out << (saltation ? "# mechanism lyapunov: Benettin on the crank-period map, variational equations with "
                             "saltation matrices (docs/reference/mechanism/saltation.md)\n"
                           : "# mechanism lyapunov: finite-difference Benettin on the crank-period map "
                             "(docs/reference/mechanism/lyapunov.md)\n")
             << "# status: " << r.status << (r.message.empty() ? "" : " (" + r.message + ")") << "\n"
             << "# period " << number(r.period) << " s, " << r.periods << " periods averaged, ";
        if (saltation)
          *out << "J v by central differences of step " << number(r.perturbation) << " of each coordinate's scale, "
               << "latched impact velocities' variations "
               << (r.latched_variations_carried ? "carried" : "dropped at each renormalisation") << "\n";
        else
          *out << "perturbation " << number(r.perturbation) << " (floor " << number(r.perturbation_floor)
               << ": 1e3 x epsilon x " << r.steps_per_interval << " steps per interval x "
               << number(r.largest_scaled_coordinate) << ", " << r.largest_scaled_name << "), largest separation "
               << number(r.largest_separation) << "\n";
        for (std::size_t j = 0; j < r.exponents.size(); ++j)
          *out << "# lambda_" << j + 1 << " = " << number(r.exponents[j]) << " +- " << number(r.standard_error[j])
               << " 1/s (" << number(r.exponents_per_period[j]) << " per period)\n";
        *out << "# exponents near or below " << number(r.resolution_limit)
             << " 1/s contract past double precision within one interval: bounds, not values\n";
        if (std::isfinite(r.kaplan_yorke))
          *out << "# Kaplan-Yorke dimension: " << number(r.kaplan_yorke) << " (section " << number(r.kaplan_yorke_section)
               << ")\n";
        else
          *out << "# Kaplan-Yorke dimension: none (the exponents computed do not bound it, or the run failed)\n";
        write_scene_header(*out, scene, lyap_opts);
        const std::size_t k = r.periods ? r.running.size() / r.periods : 0;  // also after a failed run
        *out << "# period";
        for (std::size_t j = 0; j < k; ++j) *out << "\tlambda_" << j + 1 << " [1/s]";
        *out << "\n";
        for (std::size_t p = 0; p < r.periods; ++p) {
          *out << p + 1;
          for (std::size_t j = 0; j < k; ++j) *out << "\t" << number(r.running[p * k + j]);
          *out << "\n";
        }
      }
      if (lyap_json) std::cout << mechanism::scene_lyapunov_json(r).dump(2) << "\n";
      if (!lyap_plot.empty() && r.periods > 0) plot_convergence(r, lyap_plot);
      if (r.status == "trajectory_failed") {
        std::cerr << "mechanism: the exponents could not be computed: " << r.message << "\n";
        return integration_failed;
      }
      if (r.status != "completed" && !lyap_opts.quiet) std::cerr << "mechanism: warning: " << r.message << "\n";
      return ok;
    }
    // simulate
    mechanism::Scene scene = load_scene(sim_opts);
    if (strobe) scene.run.stroboscopic = true;
    mechanism::SliderCrank system(scene);
    const mechanism::SignalTable table = mechanism::signal_table(system);
    std::vector<std::size_t> columns;
    if (signals.empty()) {
      for (std::size_t i = 0; i < table.names.size(); ++i) columns.push_back(i);
    } else {
      std::stringstream list(signals);
      for (std::string name; std::getline(list, name, ',');) {
        auto it = std::find(table.names.begin(), table.names.end(), name);
        if (it == table.names.end()) {
          std::string all;
          for (const auto& n : table.names) all += " " + n;
          throw mechanism::InvalidParameter("--signals", name, "is not a signal of this scene; it has:" + all);
        }
        columns.push_back(static_cast<std::size_t>(it - table.names.begin()));
      }
    }
    std::ostream* out = nullptr;
    if (!out_path.empty()) {
      out = &safe_output::open_pending(out_path).stream();
    } else if (!json) {
      out = &std::cout;
    }
    if (out) {
      *out << "# mechanism simulate: " << (scene.run.stroboscopic ? "one row per crank revolution" : "time series")
           << "\n";
      write_scene_header(*out, scene, sim_opts);
      *out << "#";
      if (scene.run.stroboscopic) *out << " revolution";
      for (std::size_t c : columns) *out << (c == columns.front() && !scene.run.stroboscopic ? " " : "\t") << table.names[c] << " [" << table.units[c] << "]";
      *out << "\n";
    }
    std::vector<double> values;
    auto write_row = [&](const std::string& prefix, double t, const mechanism::State& x, const mechanism::Evaluation& ev) {
      if (!out) return;
      mechanism::signal_values(system, t, x, ev, values);
      *out << prefix;
      for (std::size_t i = 0; i < columns.size(); ++i) *out << (i || !prefix.empty() ? "\t" : "") << number(values[columns[i]]);
      *out << "\n";
    };
    PlotData plot;
    plot.journals.resize(system.journal_names().size());
    auto keep_for_plot = [&](const mechanism::Evaluation& ev) {
      if (plot_path.empty()) return;
      plot.angle_deg.push_back(std::fmod(ev.crank_angle * 180.0 / M_PI, 360.0));
      plot.slider_x.push_back(ev.slider_pose[0]);
      plot.slider_y.push_back(ev.slider_pose[1]);
      for (std::size_t j = 0; j < plot.journals.size(); ++j) plot.journals[j].push_back(ev.eccentricity[j]);
    };
    mechanism::SimulationObserver observer;
    if (scene.run.stroboscopic) {
      observer.stroboscopic = [&](std::size_t rev, double t, const mechanism::State& x, const mechanism::Evaluation& ev) {
        write_row(std::to_string(rev), t, x, ev);
        keep_for_plot(ev);
      };
    } else {
      observer.sample = [&](double t, const mechanism::State& x, const mechanism::Evaluation& ev) {
        write_row("", t, x, ev);
        keep_for_plot(ev);
      };
    }
    cli_support::ProgressBar bar(!sim_opts.quiet && isatty(fileno(stderr)));
    observer.progress = [&](double f) { bar.update(f, std::to_string(static_cast<int>(100 * f)) + "%"); };
    const mechanism::SimulationSummary s = mechanism::simulate(system, observer);
    if (json) {
      const nlohmann::ordered_json j = mechanism::simulation_summary_json(s, system);
      std::cout << j.dump(2) << "\n";
    }
    if (!plot_path.empty()) {
      if (plot.slider_y.empty()) {
        std::cerr << "mechanism: no plot: the run wrote no samples to draw (it stopped at t = " << number(s.end_time)
                  << " s, before the transient of " << number(scene.run.transient) << " s ended)\n";
      } else {
        plot_trajectories(plot, scene, system.journal_names(), plot_path);
      }
    }
    if (s.status == mechanism::SimulationStatus::energy_defect) {
      std::cerr << "mechanism: the run reached its end but is not to be trusted: " << s.message << "\n";
      return integration_failed;
    }
    if (s.status != mechanism::SimulationStatus::completed) {
      std::cerr << "mechanism: the integration stopped: " << s.message << "\n";
      return integration_failed;
    }
    return ok;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return usage_error;
  } catch (const mechanism::InvalidParameter& e) {
    std::cerr << "mechanism: invalid scene: " << e.what() << "\n";
    return invalid_scene;
  } catch (const OutputRefused& e) {
    std::cerr << "mechanism: " << e.what() << "\n";
    return invalid_scene;
  } catch (const safe_output::WriteError& e) {
    std::cerr << "mechanism: " << e.what() << "\n";
    return invalid_scene;
  } catch (const std::exception& e) {
    std::cerr << "mechanism: internal error: " << e.what() << "\n";
    return internal_error;
  }
}

}  // namespace

int main(int argc, char** argv) {
  safe_output::StandardOutput out;
  int code = run(argc, argv);
  // The -o file is renamed into place once the run has ended, also one that stopped (exit 5: the
  // table holds the samples up to the stop, as the summary says).
  try {
    if (code == ok || code == integration_failed) safe_output::commit_pending();
  } catch (const safe_output::WriteError& e) {
    std::cerr << "mechanism: " << e.what() << "\n";
    code = invalid_scene;
  }
  safe_output::discard_pending();
  if (const std::string why = out.finish(); !why.empty()) {
    std::cerr << "mechanism: " << why << "\n";
    if (code == ok) code = invalid_scene;
  }
  return code;
}
