// The `study` command: the seed paper's parameter studies over the simulator, with the chaos
// analysis of each point (docs/reference/study.md).
//   study sweep [scene.toml] [--set k=v]... [--axis key=from:to:count]... -o DIR [--resume] ...
//   study pipeline [scene.toml] [--set k=v]... [--plot FILE]   (seed Fig. 7 for one scene)
//   study plot DIR --figure bifurcation|density|portrait|d2|e2|d2map -o FILE.png|svg
// Exit codes: 0 ok, 1 internal error, 2 usage, 3 invalid scene or sweep, 4 input/output (an output
// refused before the work, or a write that failed: standard output, a table, a plot, a point file),
// 5 the sweep finished but some points' simulations did not complete or ended energy_defect (their
// status says why), or the analysis failed at every analysed point, or the pipeline's simulation
// did not complete.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "mechanism/error.hpp"
#include "memory_policy.hpp"
#include "mpi_session.hpp"
#include "option_checks.hpp"
#include "parameter_options.hpp"
#include "pipeline.hpp"
#include "progress_bar.hpp"
#include "plots.hpp"
#include "safe_output.hpp"
#include "study/error.hpp"
#include "study/run_sweep.hpp"
#include "sweep_parameters.hpp"

namespace {

enum ExitCode : int { ok = 0, internal_error = 1, usage_error = 2, invalid_request = 3, io_error = 4, points_failed = 5 };

std::string read_text(const std::string& path) {
  // A directory opens as a stream that reads nothing: it ran the built-in scene.
  if (std::filesystem::is_directory(path)) throw study::StudyError("scene", path, "is a directory, not a scene file");
  std::ifstream in(path);
  if (!in) throw study::StudyError("scene", path, "cannot be opened (missing or unreadable file)");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int run(int argc, char** argv) {
  study::cli::MpiSession mpi(argc, argv);
  const bool root = mpi.rank() == 0;
  CLI::App app{"study: parameter sweeps of the slider-crank simulator with the chaos analysis of each point"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "study 0.1.0");

  study::SweepParams params;
  std::string scene_file, out_dir;
  std::vector<std::string> axes;
  bool resume = false, quiet = false;
  std::size_t threads = 0;
  auto* sweep = app.add_subcommand("sweep", "run a one- or two-dimensional sweep over scene keys into a result directory");
  sweep->add_option("scene", scene_file, "scene file (TOML); without one, the built-in seed scene");
  sweep->add_option("--set", params.spec.overrides, "override a scene key for every point: --set joint.slider.friction.sigma1_velocity=1e-3");
  sweep->add_option("--axis", axes, "a swept key: key=from:to:count or key=v1,v2,... (at most two; the first varies fastest)");
  cli_support::add_options(*sweep, params, study::sweep_parameters());
  sweep->add_option("--threads", threads, "worker threads (default: the cores available, divided among MPI ranks)");
  sweep->add_option("-o,--output", out_dir, "result directory (docs/reference/study.md lists its files)")->required();
  sweep->add_flag("--resume", resume, "continue the sweep already in the directory (its spec must match)");
  sweep->add_flag("-q,--quiet", quiet, "no progress bar and no warnings about the scene");

  study::cli::PipelineRequest pipeline;
  auto* pipeline_cmd = app.add_subcommand("pipeline", "the correlation-dimension pipeline of one scene, with the six panels of the seed's Fig. 7");
  study::cli::add_pipeline_options(*pipeline_cmd, pipeline);

  study::cli::PlotRequest plot;
  auto* plot_cmd = app.add_subcommand("plot", "draw a figure from a result directory");
  study::cli::add_plot_options(*plot_cmd, plot);
  cli_support::check_numeric_options(app);
  cli_support::one_value_per_occurrence(app);
  if (const std::string unknown = cli_support::unknown_subcommand(app, argc, argv); !unknown.empty()) {
    if (root) std::cerr << "study: " << unknown << "\n";
    return usage_error;
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (root) app.exit(e);
    return e.get_exit_code() == 0 ? ok : usage_error;
  } catch (const study::StudyError& e) {  // an output file refused while parsing is of kind io (outputs.hpp)
    if (root) std::cerr << "study: " << e.what() << "\n";
    return e.kind() == study::StudyError::Kind::io ? io_error : invalid_request;
  }
  try {
    if (pipeline_cmd->parsed()) {
      if (!root) return ok;
      return study::cli::run_pipeline(pipeline) ? ok : points_failed;
    }
    if (plot_cmd->parsed()) {
      if (root) study::cli::draw(plot);
      return ok;
    }
    if (!scene_file.empty()) {
      params.spec.scene_text = read_text(scene_file);
      params.spec.scene_source = scene_file;
    }
    std::vector<study::Axis> parsed;
    for (const auto& a : axes) parsed.push_back(study::parse_axis(a));
    params.spec.grid = study::Grid(std::move(parsed));
    const study::SweepSpec spec = study::sweep_spec(std::move(params));
    spec.validate();
    if (root && !quiet)
      for (const auto& w : mechanism::scene_warnings(study::point_scene(spec, 0))) std::cerr << "study: warning: " << w << "\n";

    // Rank 0 creates the directory; the others open it once it exists (as a resume of the same spec).
    // Every collective call is reached by every rank: a rank's failure is reported, not thrown past them.
    std::unique_ptr<study::ResultStore> store;
    int store_failure = invalid_request;  // io_error where a file of the directory could not be written
    auto open_store = [&](bool as_resume) {
      try {
        // Rank 0's lock covers the other ranks, which open the directory only after it.
        store = std::make_unique<study::ResultStore>(out_dir, spec, as_resume, root);
        for (const auto& d : store->discarded()) std::cerr << "study: recomputing " << d << "\n";
        return true;
      } catch (const std::exception& e) {
        if (const auto* s = dynamic_cast<const study::StudyError*>(&e); s && s->kind() == study::StudyError::Kind::io)
          store_failure = io_error;
        std::cerr << "study: " << e.what() << "\n";
        return false;
      }
    };
    if (!mpi.all_succeeded(root ? open_store(resume) : true)) return store_failure;
    if (!mpi.all_succeeded(root ? true : open_store(true))) return store_failure;

    study::SweepExecution exec;
    exec.rank = mpi.rank();
    exec.ranks = mpi.size();
    exec.threads = threads ? threads : std::max<std::size_t>(1, std::thread::hardware_concurrency() / mpi.size());
    // Points done out of this run's share, the time left from this run's rate.
    cli_support::ProgressBar bar(root && !quiet && isatty(fileno(stderr)));
    exec.progress = [&](const study::SweepProgress& p) {
      if (p.to_do)
        bar.update(static_cast<double>(p.done) / static_cast<double>(p.to_do),
                   std::to_string(p.done) + "/" + std::to_string(p.to_do) + " points");
    };
    const auto wall0 = std::chrono::steady_clock::now();
    int failure = ok;
    study::SweepProgress progress;
    try {
      progress = study::run_sweep(spec, *store, exec);
    } catch (const study::StudyError& e) {
      std::cerr << "study: rank " << mpi.rank() << ": " << e.what() << "\n";
      failure = e.kind() == study::StudyError::Kind::io ? io_error : invalid_request;
    } catch (const std::exception& e) {
      std::cerr << "study: internal error on rank " << mpi.rank() << ": " << e.what() << "\n";
      failure = internal_error;
    }
    if (!mpi.all_succeeded(failure == ok)) return failure == ok ? internal_error : failure;
    const std::size_t computed = mpi.sum(progress.done), resumed = mpi.sum(progress.skipped);
    if (!root) return ok;
    store->assemble();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const study::SweepSummary summary = study::summarise_sweep(spec, *store, computed, resumed);
    std::cout << study::summary_json(summary, store->dir().string(), exec.threads, mpi.size(), wall).dump(2) << "\n";
    // Every analysis failing says the options do not fit the series (exit 0 with no
    // analysis at all); some failing is a per-point answer that analysis.tsv gives.
    const bool no_analysis = summary.analysed > 0 && summary.analysis_failed == summary.analysed;
    // Exit 5 says why, also under -q (a corrupt-file run of the tier exited 5 with no word).
    if (summary.failed)
      std::cerr << "study: " << summary.failed << " of " << summary.points << " points did not complete (the first: point "
                << summary.first_failed << ", " << summary.first_failed_status
                << "); points.tsv's status and message columns say why\n";
    if (no_analysis)
      std::cerr << "study: the analysis failed at all " << summary.analysed << " analysed points (the first: "
                << summary.first_analysis_failure
                << "); --max-delay, --max-dimension and the analysed series (--analysis-periods, "
                   "--analysis-interval) decide what it needs\n";
    return summary.failed || no_analysis ? points_failed : ok;
  } catch (const study::StudyError& e) {
    std::cerr << "study: " << e.what() << "\n";
    return e.kind() == study::StudyError::Kind::io ? io_error : invalid_request;
  } catch (const mechanism::InvalidParameter& e) {
    std::cerr << "study: invalid scene: " << e.what() << "\n";
    return invalid_request;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "study: " << e.what() << "\n";
    return io_error;
  } catch (const safe_output::WriteError& e) {
    std::cerr << "study: " << e.what() << "\n";
    return io_error;
  } catch (const std::exception& e) {
    std::cerr << "study: internal error: " << e.what() << "\n";
    return internal_error;
  }
}

}  // namespace

int main(int argc, char** argv) {
  cli_support::keep_freed_memory_in_heap();
  safe_output::StandardOutput out;
  const int code = run(argc, argv);
  if (const std::string why = out.finish(); !why.empty()) {
    std::cerr << "study: " << why << "\n";
    return code == ok ? io_error : code;
  }
  return code;
}
