#pragma once
// Runs a sweep's unfinished points on a pool of threads, and on MPI ranks when the caller has
// several: the work is split into units (a point for fresh initial conditions, a whole chain for
// continuation), unit u belongs to rank u % ranks, and a rank's threads take its units in order.
// Each finished point is written at once (ResultStore::write), so the only shared state is the
// counter of the next unit. Which thread or rank computes a point never changes its numbers.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <string>

#include "study/result_store.hpp"
#include "study/sweep.hpp"

namespace study {

struct SweepProgress {
  std::size_t done = 0;       // points finished by this process (this run)
  std::size_t to_do = 0;      // points this process had to run
  std::size_t skipped = 0;    // points already finished before this run (resume)
  std::size_t failed = 0;     // points whose simulation did not complete or ended energy_defect (still written)
};

struct SweepExecution {
  std::size_t threads = 1;
  std::size_t rank = 0, ranks = 1;  // MPI rank and size (1 without MPI)
  // Called after each point this process finishes (from the worker threads, serialised).
  std::function<void(const SweepProgress&)> progress;
};

// Runs this rank's share; the caller assembles once every rank is done.
SweepProgress run_sweep(const SweepSpec& spec, const ResultStore& store, const SweepExecution& execution);

// What a finished sweep says of itself, counted from the assembled tables so that every rank's
// points are in it. `study sweep` prints its JSON and study.sweep returns the same keys.
struct SweepSummary {
  std::size_t points = 0;
  std::size_t computed = 0, resumed_from_disk = 0;  // this run's, over every rank
  std::size_t failed = 0;             // points.tsv: a status other than completed
  std::size_t first_failed = 0;       // ... the first such point, and its status
  std::string first_failed_status;
  // analysis.tsv: the points analysed, and those where the estimators refused the series or the
  // options ("stopped at", "series too short"); a constant series or one without a mutual-information
  // minimum is an answer about the data, and a point not analysed is counted among the failed
  // simulations.
  std::size_t analysed = 0, analysis_failed = 0;
  std::string first_analysis_failure;
  // lyapunov.tsv: a period that could not be integrated (trajectory_failed) or a perturbation below
  // the point's floor (refused); not_computed follows a failed simulation, already counted, and
  // nonlinear, not_finite and invariant_subspace are answers with a warning.
  std::size_t lyapunov_failed = 0;
};
// `computed` and `resumed`: SweepProgress's done and skipped, summed over the ranks.
SweepSummary summarise_sweep(const SweepSpec& spec, const ResultStore& store, std::size_t computed,
                             std::size_t resumed);
// The summary as JSON: directory, points, computed, resumed_from_disk, failed, analysis_failed,
// lyapunov_failed, threads, ranks and wall_seconds.
nlohmann::json summary_json(const SweepSummary& summary, const std::string& directory, std::size_t threads,
                            std::size_t ranks, double wall_seconds);

}  // namespace study
